"""Where a simulated step's time goes: sensing, clearance, the robot, the planner, the trace.

Run from the project root: ``python benchmarks/bench_step_profile.py`` (``--help`` for
options). For each world and sensor it runs one episode of the planner with
:func:`ifgm_ref.sim.simulator.simulate` and times it per step; then it times each part of the
step again, on the same episode, one part at a time:

* ``scan``: :meth:`ifgm_ref.sim.sensor.IRSensor.scan` at every pose the robot was at;
* ``clearance``: :meth:`ifgm_ref.sim.collision.ClearanceChecker.segment_clearance` of every move;
* ``robot``: :func:`ifgm_ref.sim.robot.advance` of every command;
* ``planner``: a fresh planner replayed through the episode's observations
  (:func:`ifgm_ref.core.recording.replay`), open loop;
* ``trace``: the :class:`~ifgm_ref.sim.simulator.TraceStep` of every step.

``rest`` is the whole step less the parts: the simulator's own loop (the stall and lap
rules, odometry and actuation, the observation). Times are microseconds per step, the median
of ``--repeats`` passes. It measures, it asserts nothing.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import statistics
import sys
import time
from collections.abc import Callable
from itertools import pairwise
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one core, as the benchmark workers use
if importlib.util.find_spec("ifgm_ref") is None:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Pose
from ifgm_ref.core.recording import RecordingPlanner, replay
from ifgm_ref.io import barn
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.collision import ClearanceChecker
from ifgm_ref.sim.robot import advance
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.simulator import TraceStep, simulate
from ifgm_ref.sim.world import World
from ifgm_ref.sim.worldgen.classes import random_world

#: The episodes profiled: a name, how to build the world, the simulation settings.
CASES: dict[str, Callable[[], tuple[World, SimParams]]] = {
    "scenario2 (paper IR)": lambda: (resolve_world("scenario2"), SimParams()),
    "u_trap (paper IR)": lambda: (resolve_world("u_trap"), SimParams()),
    "mixed drawn world 0 (paper IR)": lambda: (random_world("mixed", 0), SimParams()),
}


def _barn_case(number: int) -> Callable[[], tuple[World, SimParams]]:
    def build() -> tuple[World, SimParams]:
        task = barn.gazebo_task(
            f"barn:{number}", folder=None, sensor=barn.DEFAULT_SENSOR, start=None, goal=None
        )
        assert task is not None
        return task.world, task.sim

    return build


for _number in (1, 100, 200):
    CASES[f"barn:{_number} (Jackal LiDAR)"] = _barn_case(_number)


def _per_step(seconds: list[float], steps: int) -> float:
    return statistics.median(seconds) / max(steps, 1) * 1e6


def profile(world: World, sim: SimParams, planner: str, repeats: int) -> dict[str, float]:
    """The microseconds per step of the whole step and of each part (module docstring)."""
    whole: list[float] = []
    for _ in range(repeats):
        begin = time.perf_counter()
        run = simulate(world, make_planner(planner), sim)
        whole.append(time.perf_counter() - begin)
    recorder = RecordingPlanner(make_planner(planner))
    simulate(world, recorder, sim)
    recording = recorder.recording()
    trace, steps = run.trace, run.result.steps
    poses = [Pose(s.x, s.y, s.theta) for s in trace]
    commands = [command for _, command in recording.steps][:steps]
    parts: dict[str, Callable[[], object]] = {
        "scan": lambda: [sensor.scan(p) for p in poses[:steps]],
        "clearance": lambda: [checker.segment_clearance(a, b) for a, b in pairwise(poses)],
        "robot": lambda: [
            advance(p, c, world.robot, sim.dt) for p, c in zip(poses, commands, strict=False)
        ],
        "planner": lambda: list(replay(recording, make_planner(planner))),
        "trace": lambda: [TraceStep(**s.__dict__) for s in trace[:steps]],
    }
    result = {"steps": float(steps), "step": _per_step(whole, steps)}
    for name, part in parts.items():
        times = []
        for _ in range(repeats):
            sensor, checker = IRSensor(world), ClearanceChecker(world, world.robot.radius)
            begin = time.perf_counter()
            part()
            times.append(time.perf_counter() - begin)
        result[name] = _per_step(times, steps)
    result["rest"] = result["step"] - sum(result[name] for name in parts)
    return result


def main() -> None:
    """Profile every case and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--planner", default="ifgm", help="planner name (ifgm)")
    parser.add_argument("--repeats", type=int, default=3, help="passes per part (3)")
    args = parser.parse_args()
    print(f"machine: {machine()}; planner {args.planner}; us per step, median of {args.repeats}")
    columns = ("step", "scan", "clearance", "robot", "planner", "trace", "rest")
    print(f"{'episode':<31} {'steps':>6} " + " ".join(f"{c:>9}" for c in columns))
    for name, build in CASES.items():
        world, sim = build()
        found = profile(world, sim, args.planner, args.repeats)
        cells = " ".join(f"{found[c]:>9.1f}" for c in columns)
        print(f"{name:<31} {int(found['steps']):>6} {cells}")


if __name__ == "__main__":
    main()
