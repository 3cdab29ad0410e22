"""How near the simulator's lap rule comes to firing where it must not, and what it saves.

Run from the project root: ``python benchmarks/bench_stall.py`` (``--help`` for options; 4
min on 2 processes with the defaults, on a quiet machine). The lap rule
(:mod:`ifgm_ref.sim.laps`) ends an episode ``stalled`` when the robot is back within ``rho`` of
a place, travelling the same way, after ``K`` laps of at least ``L`` each, its best distance
to the goal no better than at the first lap's start by more than ``eps``. This script
measures its thresholds as the disc rule's were measured (:mod:`ifgm_ref.sim.simulator`): every
planner in every built-in world, ``--worlds`` generated worlds per class, BARN's sample
worlds in ``tests/worlds/barn`` and the test worlds in ``tests/worlds`` (the cases issues
found: livelocks, false ``goal_unreachable``), each to the oracle's time bound (BARN's:
100 s), first with the lap rule off (the disc rule on, as by default). ``--draws``,
``--barn DIR`` and ``--noise`` add or replace worlds and conditions.

Each trace is then replayed through the rule's own code (:class:`ifgm_ref.sim.laps.LapLog`, the
path lengths summed as the simulator sums them, so the replay fires at the step the
simulator would), and the script prints:

* for the episodes that reach the goal, how near they come to firing: the least progress
  over ``K`` laps at any step (the rule fires once ``eps`` reaches it), as a multiple of the
  chosen ``eps``, for ``K`` = 1, 2 and 3, and with ``rho`` and ``L`` varied; and the most
  laps in a row closed without ``eps`` of progress;
* for those that run to the time limit, when the rule fires instead and the time saved, for
  several ``eps``; and for the other stops (the disc rule, a planner's ``goal_unreachable``,
  a collision) whether the lap rule would have come first;
* the rule's cost per step against the whole simulation step.

Then every episode runs again with both rules on (the defaults; BARN's episodes, which run
without the lap rule, with it here): the script checks that each one that reached the goal
runs exactly as before (same result, same trace), that each one the replay says the rule
ends stops ``stalled`` by it at the step predicted, and that nothing else changes.
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import dataclasses
import functools
import json
import math
import statistics
import time
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from tqdm import tqdm

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.apps.bench.tasks import (
    barn_specs,
    builtin_specs,
    folder_specs,
    generated_specs,
    noise_seed,
)
from ifgm_ref.core.formulas import Scale
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import distance
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.io import barn
from ifgm_ref.planners import PLANNERS, make_planner
from ifgm_ref.sim.convergence import time_bound
from ifgm_ref.sim.laps import LapLog, LapRule
from ifgm_ref.sim.noise import NoiseLevels
from ifgm_ref.sim.simulator import Run, StopReason, simulate
from ifgm_ref.sim.world import World
from ifgm_ref.sim.worldgen.classes import GENERATORS, random_world

TEST_WORLDS = Path(__file__).resolve().parent.parent / "tests" / "worlds"
#: ``(rho, L)`` as multiples of the defaults (``r`` and ``2 pi r``): the default first.
VARIANTS: tuple[tuple[float, float], ...] = (
    (1.0, 1.0), (0.5, 1.0), (0.75, 1.0), (1.25, 1.0), (1.5, 1.0), (2.0, 1.0), (1.0, 0.5),
    (1.0, 0.75), (1.0, 1.5), (1.0, 2.0),
)  # fmt: skip
#: ``eps`` as multiples of the default (``v dt``) for the time saved.
EPS_FACTORS = (0.0, 1.0, 2.0, 4.0)
#: The most laps counted back from a step.
MOST_LAPS = 8


@dataclass
class Margin:
    """How near one episode came to the lap rule with one ``(rho, L)``.

    ``least[k]`` is the least progress (``best(i1) - best(n)``, in multiples of ``eps``) over
    ``k + 1`` laps at any step; ``laps`` the most laps closed in a row with less than ``eps``
    of progress; ``fires[e]`` the first step where ``K`` laps bring no more than
    ``EPS_FACTORS[e] * eps`` of progress (``None``: never).
    """

    least: list[float] = field(default_factory=lambda: [math.inf] * 3)
    laps: int = 0
    fires: list[int | None] = field(default_factory=lambda: [None] * len(EPS_FACTORS))


@dataclass
class Episode:
    """One planner in one world: the run without the lap rule, its margins, and the rerun."""

    planner: str
    world: str
    kind: str
    stop: str
    steps: int
    dt: float
    margins: list[Margin]
    replay_s: float
    simulate_s: float
    rerun_stop: str | None = None
    rerun_steps: int | None = None
    rerun_detail: str | None = None
    rerun_same: bool | None = None


def _episode(data: dict[str, Any]) -> Episode:
    """An :class:`Episode` read back from JSON."""
    margins = [Margin(**m) for m in data.pop("margins")]
    return Episode(margins=margins, **data)


def replay(run: Run, goal: tuple[float, float], rule: LapRule) -> Margin:
    """The lap rule's margins over ``run``'s trace (see :class:`Margin`)."""
    log = LapLog(rule.radius, rule.length, goal)
    margin, path, prev = Margin(), 0.0, None
    for n, step in enumerate(run.trace):
        here = (step.x, step.y)
        if prev is not None:
            path += distance(prev, here)
        prev = here
        visit = log.log(here, path)
        starts = log.laps(visit, MOST_LAPS)
        progress = [(s - visit.best) / rule.progress for s in starts]
        for k, p in enumerate(progress[:3]):
            margin.least[k] = min(margin.least[k], p)
        margin.laps = max(margin.laps, sum(1 for p in progress if p <= 1.0))
        if len(progress) >= rule.laps:
            for e, factor in enumerate(EPS_FACTORS):
                if margin.fires[e] is None and progress[rule.laps - 1] <= factor:
                    margin.fires[e] = n
    return margin


@dataclass(frozen=True)
class Task:
    """One episode to measure: a world (its name, kind and builder), a planner, the noise
    (``--noise`` levels, seeded per world as the benchmark seeds them; ``""``: none) and
    whether to run it again with the defaults."""

    name: str
    kind: str
    build: Callable[[], World]
    planner: str
    noise: str = ""
    rerun: bool = True


def measure(task: Task) -> Episode:
    """Run one planner in one world with the lap rule off, replay it, and (``rerun``) run it
    again with the defaults."""
    world = task.build()
    if task.noise:
        world = NoiseLevels.parse(task.noise).apply(world, noise_seed(0, task.name))
    sim = barn.SIM if task.kind == "barn" else SimParams(max_time=time_bound(world))
    begin = time.process_time()
    run = simulate(world, make_planner(task.planner), dataclasses.replace(sim, stall_laps=None))
    simulate_s = time.process_time() - begin
    default = LapRule.of(Scale.of(EpisodeParams(world.robot, world.sensor, sim.dt)), 2)
    margins = []
    begin = time.process_time()
    for rho, length in VARIANTS:
        rule = dataclasses.replace(
            default, radius=rho * default.radius, length=length * default.length
        )
        margins.append(replay(run, (world.goal.x, world.goal.y), rule))
    replay_s = time.process_time() - begin
    episode = Episode(
        task.planner, task.name, task.kind, run.result.stop_reason, run.result.steps, sim.dt,
        margins, replay_s / len(VARIANTS), simulate_s,
    )  # fmt: skip
    if task.rerun:  # with the lap rule on, even in BARN's episodes (where it is off)
        on = dataclasses.replace(sim, stall_laps=SimParams().stall_laps)
        again = simulate(world, make_planner(task.planner), on)
        episode.rerun_stop, episode.rerun_steps = again.result.stop_reason, again.result.steps
        episode.rerun_detail = again.result.detail
        episode.rerun_same = again.trace == run.trace and again.result == run.result
    return episode


def _draws(text: str) -> list[tuple[str, int]]:
    """``CLASS:FIRST-LAST`` as ``(class, seed)`` pairs, e.g. ``open:5000-5039``."""
    world_class, _, seeds = text.partition(":")
    first, _, last = seeds.partition("-")
    if world_class not in GENERATORS or not first.isdigit() or not (last or first).isdigit():
        raise argparse.ArgumentTypeError(f"expected CLASS:FIRST-LAST, e.g. open:5000-5039: {text}")
    return [(world_class, seed) for seed in range(int(first), int(last or first) + 1)]


def _worlds(args: argparse.Namespace) -> list[tuple[str, str, Callable[[], World]]]:
    """The worlds asked for: name, kind and builder."""
    specs = generated_specs(list(GENERATORS), args.worlds, args.seed)
    if args.fixed:
        specs = builtin_specs() + specs + folder_specs(TEST_WORLDS)
    if args.barn:
        specs += barn_specs(args.barn)
    worlds = [(spec.name, spec.kind, spec.build) for spec in specs]
    for draws in args.draws:
        worlds += [
            (f"{c}-seed{seed}", c, functools.partial(random_world, c, seed)) for c, seed in draws
        ]
    return worlds


def _run_all(tasks: Sequence[Task], jobs: int) -> list[Episode]:
    with cf.ProcessPoolExecutor(max_workers=jobs) as pool:
        return list(tqdm(pool.map(measure, tasks), total=len(tasks), unit="episode"))


def _print_reached(episodes: list[Episode]) -> None:
    reached = [e for e in episodes if e.stop == StopReason.GOAL_REACHED]
    print(f"\nEpisodes that reached the goal: {len(reached)}")
    print("least progress over K laps, in eps (the rule with K laps fires once eps reaches it):")
    for v, (rho, length) in enumerate(VARIANTS):
        cells = []
        for k in range(3):
            worst = min(reached, key=lambda e: e.margins[v].least[k])
            least = worst.margins[v].least[k]
            fire = sum(e.margins[v].least[k] <= 1.0 for e in reached)
            cells.append(f"K={k + 1}: {least:.3g} ({worst.planner} in {worst.world}; {fire} fire)")
        laps = max(e.margins[v].laps for e in reached)
        print(f"  rho={rho:g} r, L={length:g}*2 pi r: {'; '.join(cells)}; most laps {laps}")
    print("  by planner, the default rho and L, K=2 (least progress in eps, the episode):")
    for planner in sorted({e.planner for e in reached}):
        mine = [e for e in reached if e.planner == planner]
        worst = min(mine, key=lambda e: e.margins[0].least[1])
        laps = Counter(e.margins[0].laps for e in mine)
        print(
            f"    {planner:8} {len(mine):4} episodes; least {worst.margins[0].least[1]:.3g} "
            f"({worst.world}); laps without progress: {dict(sorted(laps.items()))}"
        )


def _print_others(episodes: list[Episode]) -> None:
    limited = [e for e in episodes if e.stop == StopReason.TIME_LIMIT]
    print(f"\nEpisodes that ran to the time limit: {len(limited)}")
    for e in limited:
        fires = [
            "never" if n is None else f"{n * e.dt:.1f} s (saves {(e.steps - n) * e.dt:.0f} s)"
            for n in e.margins[0].fires
        ]
        eps = ", ".join(f"eps={f:g}: {s}" for f, s in zip(EPS_FACTORS, fires, strict=True))
        print(f"  {e.planner:8} {e.world:12} limit {e.steps * e.dt:.0f} s; fires at {eps}")
        varied = ", ".join(
            f"rho={rho:g} L={length:g}: " + ("never" if n is None else f"{n * e.dt:.1f} s")
            for (rho, length), m in zip(VARIANTS[1:], e.margins[1:], strict=True)
            for n in (m.fires[1],)
        )
        print(f"    with rho and L varied (eps=1): {varied}")
    ends = (StopReason.GOAL_REACHED, StopReason.TIME_LIMIT)
    other = [e for e in episodes if e.stop not in ends]
    first = [(e, n) for e in other if (n := e.margins[0].fires[1]) is not None and n < e.steps]
    stops = dict(Counter(e.stop for e in other))
    print(f"\nOther stops: {stops}; the lap rule would come first in {len(first)}:")
    for e, n in first:
        print(
            f"  {e.planner:8} {e.world:12} {e.stop} at {e.steps * e.dt:.1f} s; "
            f"the lap rule at {n * e.dt:.1f} s"
        )


def _print_rerun(episodes: list[Episode]) -> None:
    print("\nRe-run with both rules on:")
    reached = [e for e in episodes if e.stop == StopReason.GOAL_REACHED]
    same = sum(bool(e.rerun_same) for e in reached)
    print(f"  reached the goal before: {len(reached)}; the same result and trace: {same}")
    changed = [e for e in episodes if not e.rerun_same]
    for (planner, before), n in sorted(Counter((e.planner, e.stop) for e in changed).items()):
        print(f"  {planner:8} {before} -> stalled by the lap rule: {n}")
    wrong = [
        e for e in changed
        if e.margins[0].fires[1] != e.rerun_steps or not (e.rerun_detail or "").startswith("lap")
    ]  # fmt: skip
    print(f"  changed, but not stalled by the lap rule at the replay's step: {len(wrong)}")
    for e in wrong:
        print(f"    {e.planner} in {e.world}: {e.stop} -> {e.rerun_stop} ({e.rerun_detail})")


def _print_cost(episodes: list[Episode]) -> None:
    per_step = [e.replay_s / max(e.steps, 1) * 1e6 for e in episodes]
    sim_step = [e.simulate_s / max(e.steps, 1) * 1e6 for e in episodes]
    print(
        f"\nCost per step (CPU, rule off: laps logged for ever): the rule's replay median "
        f"{statistics.median(per_step):.0f} us, max {max(per_step):.0f} us; the simulation "
        f"step median {statistics.median(sim_step):.0f} us"
    )


def main() -> None:
    """Measure the lap rule's margins; print them."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--worlds", type=int, default=20, help="worlds per class (default 20)")
    parser.add_argument("--seed", type=int, default=0, help="world seed (default 0)")
    parser.add_argument(
        "--no-fixed", dest="fixed", action="store_false", help="skip the built-in and test worlds"
    )
    parser.add_argument(
        "--barn", default=str(TEST_WORLDS / "barn"), help="BARN folder ('': none; default: "
        "the samples in tests/worlds/barn)"
    )  # fmt: skip
    parser.add_argument(
        "--draws", type=_draws, action="append", default=[], metavar="CLASS:FIRST-LAST",
        help="also random_world(CLASS, SEED) for these seeds (repeatable)",
    )  # fmt: skip
    parser.add_argument("--noise", default="", help="noise levels for every world, e.g. range=0.05")
    parser.add_argument("--jobs", type=int, default=2, help="worker processes (default 2)")
    parser.add_argument(
        "--planner", type=lambda text: text.split(","), action="extend",
        help="planners, comma-separated or repeated (default: every one)",
    )  # fmt: skip
    parser.add_argument("--no-rerun", action="store_true", help="skip the re-run with the rule on")
    parser.add_argument("--out", type=Path, help="also write every episode's figures (JSON)")
    parser.add_argument("--load", type=Path, help="print the figures of an --out file, run nothing")
    args = parser.parse_args()
    begin = time.perf_counter()
    if args.load is not None:
        episodes = [_episode(e) for e in json.loads(args.load.read_text())]
    else:
        planners = args.planner or list(PLANNERS)
        NoiseLevels.parse(args.noise)  # a bad level fails here, not in a worker
        worlds = _worlds(args)
        print(f"machine: {machine()}; jobs={args.jobs}")
        print(f"{len(worlds)} worlds x {len(planners)} planners; noise: {args.noise or 'none'}")
        tasks = [
            Task(name, kind, build, planner, args.noise, not args.no_rerun)
            for name, kind, build in worlds
            for planner in planners
        ]
        episodes = _run_all(tasks, args.jobs)
        if args.out is not None:
            args.out.write_text(json.dumps([dataclasses.asdict(e) for e in episodes]))
    print(f"stops without the lap rule: {dict(Counter(e.stop for e in episodes))}")
    _print_reached(episodes)
    _print_others(episodes)
    if episodes and episodes[0].rerun_stop is not None:
        _print_rerun(episodes)
    _print_cost(episodes)
    print(f"\nwall time {time.perf_counter() - begin:.0f} s; machine: {machine()}")


if __name__ == "__main__":
    main()
