"""Every stall of a BARN benchmark run on the mujoco engine, examined: where the robot's
odometry was, and whether the robot stalls again when its odometry is exact.

Run from the project root after ``ifgm-ref bench --barn --engine mujoco ... --out DIR``:
``python benchmarks/bench_stalls.py DIR/results.csv --planners ifgm --out DIR/stalls.csv``
(``--help`` for options). Each stall of ``results.csv`` (the simulator's disc or lap rule) is
run again twice, with the row's world, planner, sensor, engine and robot:

- as it ran, to read how far the pose the planner was told (the odometry: the IMU's heading,
  the wheels' encoder distance) was from the true pose when the robot stalled, and how often
  the planner's commanded heading reversed (by more than a right angle) in the stall's last
  seconds, a robot dithering between two ways round;
- with the odometry exact (the engine's true pose told instead), everything else the same:
  whether the robot then arrives.

A stall that the exact odometry turns into an arrival is the planner's memory of obstacle
points misplaced by the wheels slipping (the mujoco Jackal's tyres slip at every hard start and
stop); one that stays a stall is the planner's own, in that world, on that robot. It writes one
row per stall and prints the count of each kind per planner. It measures, it asserts nothing.
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

import itertools

from ifgm_ref.apps.bench.report import Row, read_rows
from ifgm_ref.core.params import robot_changes
from ifgm_ref.core.pose import wrap_angle
from ifgm_ref.io.barn import gazebo_task
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.physics.mujoco import MujocoEngine
from ifgm_ref.sim.simulator import Run, simulate

FIELDS = (
    "world",
    "planner",
    "robot",
    "detail",
    "time_s",
    "odometry_error_m",
    "reversals",
    "branch",
    "exact_odometry",
    "kind",
)
#: The stall's last seconds, where heading reversals are counted: the disc rule's 6 s.
WINDOW_S = 6.0


def _episode(row: Row, sensor: str, exact: bool) -> Run:
    """The row's episode again; with ``exact``, its odometry the true pose."""
    task = gazebo_task(f"barn:{int(row.world.removeprefix('barn-'))}", sensor=sensor)
    assert task is not None
    world = task.world
    if row.robot not in (None, "none"):
        world = world.with_robot(robot_changes(row.robot))
    sim = dataclasses.replace(task.sim, engine=row.engine)
    told = MujocoEngine.odometry
    if exact:
        MujocoEngine.odometry = lambda self, pose: self.true_pose()  # type: ignore[method-assign]
    try:
        return simulate(world, make_planner(row.planner), sim)
    finally:
        MujocoEngine.odometry = told  # type: ignore[method-assign]


def examine(row: Row, sensor: str) -> dict[str, object]:
    """One stall's row of ``stalls.csv``."""
    run = _episode(row, sensor, exact=False)
    last = run.trace[-1]
    error = math.hypot(last.x - (last.believed_x or last.x), last.y - (last.believed_y or last.y))
    window = [s for s in run.trace if s.t >= last.t - WINDOW_S and s.heading_cmd is not None]
    reversals = sum(
        abs(wrap_angle((b.heading_cmd or 0.0) - (a.heading_cmd or 0.0))) > math.pi / 2
        for a, b in itertools.pairwise(window)
    )
    exact = _episode(row, sensor, exact=True).result.stop_reason
    return {
        "world": row.world,
        "planner": row.planner,
        "robot": row.robot,
        "detail": run.result.detail,
        "time_s": run.result.time_s,
        "odometry_error_m": round(error, 4),
        "reversals": reversals,
        "branch": window[-1].branch if window else None,
        "exact_odometry": exact,
        "kind": "odometry" if exact == "goal_reached" else "planner",
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", help="a bench run's results.csv (BARN, mujoco engine)")
    parser.add_argument("--planners", default="ifgm", help="comma-separated (default ifgm)")
    parser.add_argument("--sensor", default="jackal_lidar", help="the run's sensor preset")
    parser.add_argument("--out", help="write one row per stall here (CSV)")
    parser.add_argument("--limit", type=int, help="the first N stalls only (in world order)")
    args = parser.parse_args(argv)
    planners = args.planners.split(",")
    rows = [r for r in read_rows(args.results) if r.planner in planners]
    stalls = [r for r in rows if r.stop_reason == "stalled" and r.engine == "mujoco"]
    stalls = stalls[: args.limit]
    found = []
    for k, row in enumerate(stalls, 1):
        found.append(examine(row, args.sensor))
        print(f"{k}/{len(stalls)} {row.planner} {row.world}: {found[-1]['kind']}", file=sys.stderr)
    if args.out:
        with Path(args.out).open("w", newline="") as sink:
            writer = csv.DictWriter(sink, FIELDS, lineterminator="\n")
            writer.writeheader()
            writer.writerows(found)
    counts = Counter((str(f["planner"]), str(f["kind"])) for f in found)
    for (planner, kind), count in sorted(counts.items()):
        print(f"{planner:6} {kind:10} {count}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
