"""What the invariance checks reject, and what they cost: the same examples for every planner.

Run from the project root: ``python benchmarks/bench_invariance.py`` (``--help`` for options).
For each planner -- the reference IFGM, every broken variant of :mod:`ifgm_ref.oracle.mutants`
(which a check may rightly reject) and every faithful one of :mod:`ifgm_ref.oracle.variants`
(which no check may reject), all offered with IFGM's promises, and any built-in planner or
``cmd:PROGRAM`` named with ``--planners`` -- it runs ``rigid_motion_invariant`` and
``scale_invariant`` on the same examples and prints how many each check rejects, the first
rejection's message, and what an example costs: the simulations and open-loop replays it
runs, the planner steps in each, and its seconds (mean), of which simulating.

The examples do not come from Hypothesis, whose draws depend on the literals of the modules
loaded (``docs/oracle.md``) and so on the oracle's own code: example ``k`` is drawn from
``numpy.random.default_rng([seed, k])`` with the world generators of
:mod:`ifgm_ref.sim.worldgen.classes` (a class of the planner's promised ones, uniformly; a
placement from :func:`~ifgm_ref.sim.worldgen.classes.placement`; a scale factor from the check's
``EXACT_SCALES + ROUNDED_SCALES``), and each is handed to the check's test function. The
script uses only names that exist before and after issue 24 changed the checks, so the same
command measures both (``PYTHONPATH=<old tree> python benchmarks/bench_invariance.py``).

``--quick`` runs each check as the oracle does instead, through Hypothesis (the quick
profile's derandomized draws, without shrinking), and prints each verdict and the runs to
it. ``--margins`` (open-loop checks only) replays every example to its end and prints the
largest differences between the answers and the transformed recorded ones: how close
faithful planners come to the tolerances.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from typing import Any

import numpy as np

import ifgm_ref
import ifgm_ref.oracle.checks as checks
from ifgm_ref.apps.bench.report import machine
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner
from ifgm_ref.oracle.check_types import CheckFailed, Recorder
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.invariance import EXACT_SCALES, ROUNDED_SCALES
from ifgm_ref.oracle.mutants import MUTANTS
from ifgm_ref.oracle.profiles import Profile
from ifgm_ref.oracle.runner import run_check
from ifgm_ref.oracle.variants import VARIANTS
from ifgm_ref.sim.simulator import Run
from ifgm_ref.sim.worldgen.classes import GENERATORS, placement
from ifgm_ref.sim.worldgen.draws import RandomDraw

#: The two checks measured.
CHECKS = ("rigid_motion_invariant", "scale_invariant")
#: Planners run by default: the reference, then the broken and the faithful variants.
DEFAULT_PLANNERS = ("ifgm", *MUTANTS, *VARIANTS)


class _Counting:
    """A planner that counts its episodes and steps (in this process)."""

    episodes = 0
    steps = 0

    def __init__(self, planner: Planner) -> None:
        self.planner = planner
        self.name = planner.name

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        _Counting.episodes += 1
        self.planner.reset(start, goal, params)

    def step(self, observation: Observation) -> Command:
        _Counting.steps += 1
        return self.planner.step(observation)


_simulate = checks.simulate
_simulated = [0.0, 0.0, 0.0]  # simulations, their steps, their seconds


def _counted_simulate(*args: Any, **kwargs: Any) -> Run:
    steps, started = _Counting.steps, time.perf_counter()
    run = _simulate(*args, **kwargs)
    _simulated[0] += 1
    _simulated[1] += _Counting.steps - steps
    _simulated[2] += time.perf_counter() - started
    return run


checks.simulate = _counted_simulate  # type: ignore[assignment]


def _implementation(name: str) -> tuple[Implementation, Callable[[], None]]:
    """The planner ``name``, counting its episodes and steps, and how to stop it."""
    if name.startswith("cmd:"):  # a program: cmd:PATH [ARGS], offered as IFGM
        impl = Implementation.from_command(name[4:], timeout=60.0, promises="ifgm")
    elif name in MUTANTS:
        impl = Implementation(MUTANTS[name], name, promises_of("ifgm"))
    elif name in VARIANTS:
        impl = Implementation(VARIANTS[name], name, promises_of("ifgm"))
    else:
        impl = Implementation.from_spec(name)
    make: Callable[[], Planner] = impl.factory
    counted = Implementation(lambda: _Counting(make()), impl.label, impl.promises)
    return counted, impl.close


def example(check: str, impl: Implementation, seed: int, k: int) -> tuple[Any, ...]:
    """Example ``k`` of ``check`` for ``impl``: a world of a promised class, and a placement
    or a scale factor."""
    draw = RandomDraw(np.random.default_rng([seed, k]))
    classes = [c for c in GENERATORS if c in impl.promises.converges_in] or ["open"]
    world = GENERATORS[draw.choice(classes, "class")](draw)
    if check == "rigid_motion_invariant":
        return world, placement(draw)
    return world, draw.choice(EXACT_SCALES + ROUNDED_SCALES, "scale")


@dataclass(frozen=True)
class Outcome:
    """One example's verdict and cost."""

    planner: str
    check: str
    k: int
    failure: str | None
    simulations: int
    simulated_steps: int
    episodes: int
    steps: int
    seconds: float
    simulated_seconds: float
    #: With ``--margins``: the largest heading (rad) and speed (fraction of top speed)
    #: differences over the whole replay, and the step of the larger heading's.
    heading: float = 0.0
    speed: float = 0.0
    at: int = -1


_worst = [0.0, 0.0, -1]


def _measure(impl: Implementation, expected: Any, how: str, where: str, rec: Recorder) -> None:
    """In place of ``compare_answers``: replay to the end, keep the largest differences."""
    from ifgm_ref.oracle.invariance import answer_errors  # issue 24's open-loop checks

    for error in answer_errors(impl, expected, where):
        if error.heading > _worst[0]:
            _worst[0], _worst[2] = error.heading, error.step
        _worst[1] = max(_worst[1], error.speed)


def _run(task: tuple[str, str, int, int, bool]) -> Outcome:
    name, check, seed, k, margins = task
    if margins:
        checks.compare_answers = _measure  # type: ignore[attr-defined]
        _worst[:] = [0.0, 0.0, -1]
    impl, close = _implementation(name)
    drawn = example(check, impl, seed, k)
    before = (_Counting.episodes, _Counting.steps, *_simulated)
    started = time.perf_counter()
    failure = None
    try:
        if checks.CHECKS[check].applies(impl) is None:
            checks.CHECKS[check].test(impl, drawn, Recorder())
    except CheckFailed as err:
        failure = str(err).split("\n")[0]
    finally:
        close()
    seconds = time.perf_counter() - started
    episodes, steps = _Counting.episodes - before[0], _Counting.steps - before[1]
    sims, sim_steps = int(_simulated[0] - before[2]), int(_simulated[1] - before[3])
    counts = (sims, sim_steps, episodes, steps, seconds, _simulated[2] - before[4])
    return Outcome(name, check, k, failure, *counts, _worst[0], _worst[1], int(_worst[2]))


def _verdict(task: tuple[str, str, int]) -> tuple[str, str, bool, int, float, str]:
    """One check of one planner through Hypothesis: the quick profile's draws, no shrinking."""
    name, check, examples = task
    impl, close = _implementation(name)
    try:
        profile = Profile("quick", examples, shrink=False)
        result = run_check(checks.CHECKS[check], impl, profile, artifacts=None)
    finally:
        close()
    return name, check, result.ok, result.examples, result.seconds, result.message


def _print_quick(names: list[str], wanted: list[str], examples: int, jobs: int) -> None:
    tasks = [(n, c, examples) for n in names for c in wanted]
    with ProcessPoolExecutor(jobs) as pool:
        verdicts = list(pool.map(_verdict, tasks))
    print("planner             check                   verdict   runs  seconds")
    for name, check, ok, runs, seconds, message in verdicts:
        print(f"{name:19} {check:23} {'passed' if ok else 'REJECTED':8} {runs:5}  {seconds:7.1f}")
        if not ok:
            print(f"    {message[:300]}")


def main() -> None:
    """Run both checks on the same examples for every planner; print the table."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--examples", type=int, default=20, help="examples per check (20)")
    parser.add_argument("--seed", type=int, default=0, help="the examples' seed (0)")
    parser.add_argument(
        "--planners",
        default=",".join(DEFAULT_PLANNERS),
        help="comma-separated: built-in names, mutant or variant names, or cmd:PROGRAM for a "
        "JSON-lines program offered as IFGM (default: ifgm, every mutant, every variant)",
    )
    parser.add_argument("--checks", default=",".join(CHECKS), help="comma-separated")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="processes")
    parser.add_argument(
        "--margins",
        action="store_true",
        help="instead of verdicts, replay every example to its end and print the largest "
        "answer differences (needs the open-loop checks of issue 24)",
    )
    parser.add_argument(
        "--quick",
        action="store_true",
        help="run each check through Hypothesis as the oracle does (the quick profile's "
        "draws, --examples of them, no shrinking) and print the verdicts",
    )
    args = parser.parse_args()
    names = args.planners.split(",")
    wanted = args.checks.split(",")
    unknown = [c for c in wanted if c not in CHECKS]
    if unknown:
        parser.error(f"unknown check(s) {', '.join(unknown)}; known: {', '.join(CHECKS)}")
    if args.quick:
        print(f"machine: {machine()}; jobs={args.jobs}; quick profile, {args.examples} examples")
        print(f"ifgm_ref from {os.path.dirname(ifgm_ref.__file__)}")
        _print_quick(names, wanted, args.examples, args.jobs)
        return
    tasks = [
        (n, c, args.seed, k, args.margins)
        for n in names
        for c in wanted
        for k in range(args.examples)
    ]
    print(f"machine: {machine()}; jobs={args.jobs}; {args.examples} examples, seed {args.seed}")
    print(f"ifgm_ref from {os.path.dirname(ifgm_ref.__file__)}")
    started = time.perf_counter()
    with ProcessPoolExecutor(args.jobs) as pool:
        outcomes = list(pool.map(_run, tasks))
    print(f"wall time {time.perf_counter() - started:.0f} s")
    if args.margins:
        _print_margins(names, wanted, outcomes)
    else:
        _print_verdicts(names, wanted, outcomes)


def _print_verdicts(names: list[str], wanted: list[str], outcomes: list[Outcome]) -> None:
    print(
        "planner             check                   rejected  sims/ex  replays/ex  "
        "steps/ex (sim+replay)  s/ex  of which simulating"
    )
    for name in names:
        for check in wanted:
            mine = [o for o in outcomes if o.planner == name and o.check == check]
            failed = [o for o in mine if o.failure is not None]
            sims = statistics.mean(o.simulations for o in mine)
            replays = statistics.mean(o.episodes - o.simulations for o in mine)
            sim_steps = statistics.mean(o.simulated_steps for o in mine)
            replay_steps = statistics.mean(o.steps - o.simulated_steps for o in mine)
            seconds = statistics.mean(o.seconds for o in mine)
            simulating = statistics.mean(o.simulated_seconds for o in mine)
            print(
                f"{name:19} {check:23} {len(failed):3} of {len(mine):<3} {sims:7.2f}  "
                f"{replays:10.2f}  {sim_steps:9.0f}+{replay_steps:<9.0f}   {seconds:6.2f}  "
                f"{simulating:6.2f}"
            )
            if failed:
                print(f"    first: example {failed[0].k}: {failed[0].failure[:300]}")


def _print_margins(names: list[str], wanted: list[str], outcomes: list[Outcome]) -> None:
    print(
        "planner             check                   replayed  longest  max heading (rad) "
        " (example, step)  max speed (of top)  examples over 1e-3 rad"
    )
    for name in names:
        for check in wanted:
            mine = [o for o in outcomes if o.planner == name and o.check == check]
            replayed = [o for o in mine if o.episodes > o.simulations]
            if not replayed:
                print(f"{name:19} {check:23} none replayed")
                continue
            worst = max(replayed, key=lambda o: o.heading)
            longest = max(o.steps - o.simulated_steps for o in replayed)
            over = sum(o.heading > 1e-3 for o in replayed)
            print(
                f"{name:19} {check:23} {len(replayed):3} of {len(mine):<3} {longest:7}  "
                f"{worst.heading:17.3g}  ({worst.k:3}, {worst.at:5})  "
                f"{max(o.speed for o in replayed):18.3g}  {over:3}"
            )


if __name__ == "__main__":
    main()
