"""Every miss of a BARN benchmark run, sorted by its kind (its collisions simulated again).

Run from the project root after ``ifgm-ref bench --barn ... --out DIR``:
``python benchmarks/bench_misses.py DIR/results.csv --out DIR/misses.csv`` (``--help`` for
options). Each collision of ``results.csv`` is run again (the same world, planner, sensor,
engine and robot: ``ifgm-ref simulate barn:N --planner P --engine E --robot R`` gives the same
episode) and given its kind from the trace; every other miss takes its kind from its row:

``collision while braking``
    From some decision up to the contact, every decision asked for less speed than the robot
    had (IFGM's stop-and-turn, a Bug planner's stop at a wall): the kinematic robot would have
    stopped at the first of them. The row gives the robot's speed ``u`` and clearance there,
    and the stopping distance ``u^2 / (2 mu g)`` of a robot braking at the friction limit
    (tyre friction ``mu``): a robot that skids while it turns needs more.
``collision while driving``
    Any other collision: the robot drove into the obstacle at the speed it was asked for (a
    gap the planner judged wide enough, the disc's side touching while it turns).
``stall: disc rule`` / ``stall: lap rule``
    The simulator's stall rules (:mod:`ifgm_ref.sim.simulator`).
``time_limit``, ``goal_unreachable``
    Still going at BARN's 100 s; the planner's own verdict (IBA after a full circuit).

It writes one row per miss (``world, planner, engine, sensor, stop_reason, kind, branch,
speed_at_decision, clearance_at_decision, stopping_distance``) and prints the count of each
kind per planner and engine. It measures, it asserts nothing.
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import importlib.util
import math
import sys
from collections import Counter
from pathlib import Path

if importlib.util.find_spec("ifgm_ref") is None:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from ifgm_ref.apps.bench.report import Row, read_rows
from ifgm_ref.core.params import SimParams, robot_changes
from ifgm_ref.core.pose import Pose
from ifgm_ref.io.barn import gazebo_task
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.collision import ClearanceChecker
from ifgm_ref.sim.physics.bodies import body_for, body_named
from ifgm_ref.sim.simulator import Run, TraceStep, simulate

FIELDS = (
    "world",
    "planner",
    "engine",
    "sensor",
    "stop_reason",
    "kind",
    "branch",
    "speed_at_decision",
    "clearance_at_decision",
    "stopping_distance",
)


def _rerun(row: Row, sensor: str) -> tuple[Run, SimParams, float, ClearanceChecker]:
    """The episode of ``row`` again, its settings, ``mu g`` of its body (infinite for the
    kinematic robot, which stops at once) and a clearance checker of its world."""
    number = int(row.world.removeprefix("barn-"))
    task = gazebo_task(f"barn:{number}", sensor=sensor)
    assert task is not None
    world = task.world
    if row.robot not in (None, "none"):  # ifgm-ref bench --robot / --speed
        world = world.with_robot(robot_changes(row.robot))
    sim = dataclasses.replace(task.sim, engine=row.engine)
    run = simulate(world, make_planner(row.planner), sim)
    if row.engine == "kinematic":
        return run, sim, math.inf, ClearanceChecker(world, world.robot.radius)
    body = body_named(sim.body) if sim.body else body_for(world.robot)
    told = body.told(world.robot)  # the disc the planners keep clear (the box's)
    return run, sim, body.friction * body.gravity, ClearanceChecker(world, told.radius)


def _speed(trace: list[TraceStep], k: int, dt: float) -> float:
    """The robot's speed over the step before sample ``k``."""
    if k == 0:
        return 0.0
    a, b = trace[k - 1], trace[k]
    return math.hypot(b.x - a.x, b.y - a.y) / dt


def classify(
    row: Row, run: Run, sim: SimParams, mu_g: float, checker: ClearanceChecker
) -> dict[str, object]:
    """The miss ``row``, its re-run ``run``, as one output row (module docstring)."""
    trace = run.trace
    last = len(trace) - 2  # the last sample with a command: its step ends in the contact
    out: dict[str, object] = {
        "world": row.world,
        "planner": row.planner,
        "engine": row.engine,
        "stop_reason": run.result.stop_reason,
        "branch": trace[last].branch or "",
    }
    if run.result.stop_reason != "collision":
        return out | {"kind": _end_kind(str(run.result.stop_reason), run.result.detail)}
    # The braking before the contact: the decisions, back from it, that each asked for less
    # speed than the robot had; the first of them is where the robot was asked to slow.
    start = last
    while start > 0 and (trace[start - 1].speed_cmd or 0.0) < _speed(trace, start - 1, sim.dt):
        start -= 1
    speed = _speed(trace, start, sim.dt)
    if (trace[start].speed_cmd or 0.0) >= speed:
        return out | {"kind": "collision while driving"}
    at = trace[start]
    clearance = checker.pose_clearance(Pose(at.x, at.y, at.theta))
    stopping = speed * speed / (2.0 * mu_g)
    return out | {
        "kind": "collision while braking",
        "branch": at.branch or "",
        "speed_at_decision": round(speed, 4),
        "clearance_at_decision": round(clearance, 4),
        "stopping_distance": round(stopping, 4),
    }


def _end_kind(stop_reason: str, detail: str | None) -> str:
    """The kind of a miss other than a collision: the stall's rule, or the stop reason."""
    if stop_reason == "stalled":
        return f"stall: {(detail or '').split(':')[0]}"
    return stop_reason


def _unrun(row: Row) -> dict[str, object]:
    """A miss other than a collision, from its row alone (no branch: it was not run again)."""
    kind = _end_kind(row.stop_reason, row.detail)
    return {"world": row.world, "planner": row.planner, "engine": row.engine,
            "stop_reason": row.stop_reason, "kind": kind}  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", type=Path, help="an `ifgm-ref bench --barn` results.csv")
    parser.add_argument("--out", type=Path, required=True, help="the misses' CSV to write")
    parser.add_argument("--sensor", default="jackal_lidar", help="the run's --sensor")
    parser.add_argument("--planners", help="only these planners' misses, e.g. ifgm,dwa")
    args = parser.parse_args(argv)
    chosen = None if args.planners is None else set(args.planners.split(","))
    rows = [
        r
        for r in read_rows(args.results)
        if not r.reached and (chosen is None or r.planner in chosen)
    ]
    found: list[dict[str, object]] = []
    for index, row in enumerate(rows, 1):
        if row.stop_reason != "collision":  # the row says it all: no need to run it again
            found.append(_unrun(row) | {"sensor": args.sensor})
            continue
        run, sim, mu_g, checker = _rerun(row, args.sensor)
        if run.result.stop_reason != row.stop_reason:
            print(f"{row.world} {row.planner}: re-run ended {run.result.stop_reason}, "
                  f"the bench said {row.stop_reason}", file=sys.stderr)  # fmt: skip
        found.append(classify(row, run, sim, mu_g, checker) | {"sensor": args.sensor})
        print(
            f"{index}/{len(rows)} {row.world} {row.planner}: {found[-1]['kind']}", file=sys.stderr
        )
    with args.out.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, FIELDS, lineterminator="\n")
        writer.writeheader()
        writer.writerows(found)
    counts = Counter((str(f["planner"]), str(f["engine"]), str(f["kind"])) for f in found)
    for (planner, engine, kind), count in sorted(counts.items()):
        print(f"{planner:6} {engine:10} {kind:28} {count}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
