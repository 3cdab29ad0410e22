"""The cost of one LiDAR scan in BARN's worlds: every (cylinder, ray) pair against the facing
pairs only, in one run.

Run from the project root: ``python benchmarks/bench_barn_scan.py`` (``--help`` for options).

BARN's worlds hold some 240 cylinders, all within the Jackal LiDAR's 30 m of one another, so
culling by range keeps them all and a 720-ray scan computed every one of the 170,000 or so
(cylinder, ray) pairs. :mod:`ifgm_ref.sim.raycast` now tests a cylinder only against the rays
that face it (``_facing_pairs``) once there are ``_PAIRS_FROM`` pairs or more; this script
times :meth:`ifgm_ref.sim.sensor.IRSensor.scan` both ways, by setting ``_PAIRS_FROM`` beyond
reach (``every pair``, the code before) and back (``facing pairs``), on the same poses: a
walk from BARN's start through each world's cylinders. It prints the median scan of each
world, their ratio, and whether the two gave the same ranges to the bit (they must: it
measures, it asserts nothing else).
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one core, as the benchmark workers use
if importlib.util.find_spec("ifgm_ref") is None:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.core.pose import Pose
from ifgm_ref.io import barn
from ifgm_ref.sim import raycast
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.world import World

#: The bundled worlds timed by default: a spread of BARN's difficulty ranking (0 to 299).
WORLDS = (1, 50, 100, 151, 200, 250, 299)


def poses(world: World, count: int) -> list[Pose]:
    """``count`` poses from the start towards the goal, turning as they go (the scans of a
    robot on its way; a pose inside a cylinder reads 0 everywhere, as it would)."""
    start, goal = world.start, world.goal
    return [
        Pose(
            start.x + (goal.x - start.x) * k / count,
            start.y + (goal.y - start.y) * k / count,
            start.theta + 0.05 * k,
        )
        for k in range(count)
    ]


def timed_scans(world: World, walk: list[Pose], pairs_from: float) -> tuple[float, list[bytes]]:
    """The median scan time (s) along ``walk`` with ``_PAIRS_FROM = pairs_from``, and every
    scan's ranges as bytes."""
    raycast._PAIRS_FROM = pairs_from  # type: ignore[assignment]
    sensor = IRSensor(world)
    seconds, ranges = [], []
    for pose in walk:
        begin = time.perf_counter()
        scan = sensor.scan(pose)
        seconds.append(time.perf_counter() - begin)
        ranges.append(scan.ranges.tobytes())
    return statistics.median(seconds), ranges


def main() -> None:
    """Time the scans of each world both ways and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--worlds", type=int, nargs="+", default=WORLDS, help="BARN world numbers")
    parser.add_argument("--poses", type=int, default=400, help="scans per world and way (400)")
    args = parser.parse_args()
    default = raycast._PAIRS_FROM
    print(f"machine: {machine()}")
    print(f"{'world':<9} {'cylinders':>9} {'every pair ms':>14} {'facing ms':>10} {'ratio':>6} "
          "same bits")  # fmt: skip
    ratios = []
    for number in args.worlds:
        task = barn.gazebo_task(
            f"barn:{number}", folder=None, sensor=barn.DEFAULT_SENSOR, start=None, goal=None
        )
        assert task is not None
        walk = poses(task.world, args.poses)
        before, old = timed_scans(task.world, walk, math.inf)
        after, new = timed_scans(task.world, walk, default)
        ratios.append(before / after)
        print(f"barn:{number:<4} {len(task.world.obstacles):>9} {before * 1e3:>14.3f} "
              f"{after * 1e3:>10.3f} {before / after:>6.1f} {old == new}")  # fmt: skip
    raycast._PAIRS_FROM = default
    print(f"median ratio {statistics.median(ratios):.1f}x over {len(ratios)} worlds")


if __name__ == "__main__":
    main()
