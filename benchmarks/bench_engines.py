"""What the MuJoCo engine costs against the kinematic one: the same episodes, side by side.

Run from the project root: ``python benchmarks/bench_engines.py`` (``--help`` for options);
the mujoco engine needs the ``physics`` extra (``pip install -e ".[physics]"``).

For each world and planner it runs the episode :func:`ifgm_ref.sim.simulator.simulate` runs for
``ifgm-ref simulate WORLD --planner P --engine E``, in both engines (:mod:`ifgm_ref.sim.engine`):

* the paper's worlds ``u_trap`` and ``scenario1`` with the paper's robot and IR sensor
  (``SimParams()``: ``dt`` 0.1 s; the mujoco engine's ``paper`` body);
* BARN's worlds 1 and 100 of the bundled set, with BARN's robot, the Jackal LiDAR (720 rays)
  and BARN's settings (``ifgm_ref.io.barn.SIM``: ``dt`` 0.05 s, 100 s; the ``jackal`` body).

An episode's wall time includes building its engine (the kinematic engine's sensor and
checker; the MuJoCo model compiled from the world), as ``ifgm-ref bench`` pays it once per
episode. Each pass runs every episode once in each engine, the engines alternating, so that a
change of the machine's load falls on both; the table gives the median of ``--repeats``
passes: simulated steps per second of wall time (``steps / s``), wall seconds per episode
(``s / ep``), and the ratios mujoco / kinematic of the wall time per step and per episode.
The two engines' episodes differ (a robot with mass does not follow the kinematic one's path
exactly), so the steps and the stop reasons of both are printed: the per-step ratio is the
one that compares like with like. It measures, it asserts nothing.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib.util
import os
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one core, as the benchmark workers use
if importlib.util.find_spec("ifgm_ref") is None:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.core.params import ENGINES, SimParams
from ifgm_ref.io import barn
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.engine import require_physics
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import World

#: The planners run by default.
PLANNERS = ("ifgm", "iba")


def _barn_case(number: int) -> Callable[[], tuple[World, SimParams]]:
    def build() -> tuple[World, SimParams]:
        task = barn.gazebo_task(f"barn:{number}", sensor=barn.DEFAULT_SENSOR)
        assert task is not None
        return task.world, task.sim

    return build


#: The worlds: a name, and how to build the world and its simulation settings.
CASES: dict[str, Callable[[], tuple[World, SimParams]]] = {
    "u_trap": lambda: (resolve_world("u_trap"), SimParams()),
    "scenario1": lambda: (resolve_world("scenario1"), SimParams()),
    "barn:1": _barn_case(1),
    "barn:100": _barn_case(100),
}


class Episode(NamedTuple):
    """One world, planner and engine: its steps, how it ended, its wall times (s)."""

    steps: int
    stop_reason: str
    seconds: list[float]

    @property
    def per_episode(self) -> float:
        """Median wall seconds per episode."""
        return statistics.median(self.seconds)

    @property
    def steps_per_s(self) -> float:
        """Simulated steps per second of wall time, at the median episode."""
        return self.steps / self.per_episode


def run_once(world: World, sim: SimParams, planner: str) -> tuple[int, str, float]:
    """One episode: its steps, its stop reason and its wall time, s (the engine's build
    included)."""
    begin = time.perf_counter()
    result = simulate(world, make_planner(planner), sim).result
    return result.steps, str(result.stop_reason), time.perf_counter() - begin


def measure(world: World, sim: SimParams, planner: str, repeats: int) -> dict[str, Episode]:
    """Each engine's :class:`Episode` of ``planner`` in ``world``, the engines alternating."""
    seconds: dict[str, list[float]] = {engine: [] for engine in ENGINES}
    ends: dict[str, tuple[int, str]] = {}
    for _ in range(repeats):
        for engine in ENGINES:
            steps, stop, wall = run_once(world, dataclasses.replace(sim, engine=engine), planner)
            seconds[engine].append(wall)
            ends[engine] = (steps, stop)  # deterministic: every pass ends the same way
    return {engine: Episode(*ends[engine], seconds[engine]) for engine in ENGINES}


def _row(world: str, planner: str, found: dict[str, Episode]) -> str:
    kinematic, mujoco = found["kinematic"], found["mujoco"]
    per_step = (mujoco.per_episode / mujoco.steps) / (kinematic.per_episode / kinematic.steps)
    cells = [f"{world:<10} {planner:<7}"]
    for episode in (kinematic, mujoco):
        cells.append(
            f"{episode.steps:>6} {episode.stop_reason:<13} {episode.steps_per_s:>8,.0f} "
            f"{episode.per_episode:>7.2f}"
        )
    ratio = mujoco.per_episode / kinematic.per_episode
    cells.append(f"{per_step:>7.1f}x {ratio:>7.1f}x")
    return " | ".join(cells)


def main() -> None:
    """Measure every world and planner in both engines and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--planners", default=",".join(PLANNERS), help="planners (ifgm,iba)")
    parser.add_argument("--worlds", default=",".join(CASES), help=f"worlds ({','.join(CASES)})")
    parser.add_argument("--repeats", type=int, default=3, help="passes; the median (3)")
    args = parser.parse_args()
    if args.repeats < 1:
        parser.error(f"--repeats must be at least 1, got {args.repeats}")
    unknown = sorted(set(args.worlds.split(",")) - set(CASES))
    if unknown:
        parser.error(f"unknown world(s) {', '.join(unknown)}; choose from {', '.join(CASES)}")
    require_physics()
    import ifgm_ref.sim.physics.mujoco  # noqa: F401 -- MuJoCo's import, outside the timing

    print(f"machine: {machine()}")
    print(f"median of {args.repeats} passes, engines alternating; wall time, build included")
    episode = f"{'steps':>6} {'stop':<13} {'steps/s':>8} {'s/ep':>7}"
    print(f"{'':<18} | {'kinematic':<37} | {'mujoco':<37} | mujoco / kinematic")
    print(f"{'world':<10} {'planner':<7} | {episode} | {episode} | {'s/step':>8} {'s/ep':>8}")
    begin = time.perf_counter()
    for name in args.worlds.split(","):
        world, sim = CASES[name]()
        for planner in args.planners.split(","):
            print(_row(name, planner, measure(world, sim, planner, args.repeats)), flush=True)
    load = " ".join(f"{v:.2f}" for v in os.getloadavg())
    print(f"total {time.perf_counter() - begin:.1f} s; load average at the end {load}")


if __name__ == "__main__":
    main()
