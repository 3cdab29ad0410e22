"""Throughput of the simulation core: range scans and simulator steps per second.

Run from the project root: ``python benchmarks/bench_core.py`` (``--help`` for options).

The world
---------
25 random quadrilaterals (100 edges) in a 60 x 60 ft field, from a fixed seed: each is a star
around a centre drawn uniformly in the field, with one vertex in each quarter turn at a radius
of 1 to 3 ft (so it is simple and convex-ish, about the size of the paper's simple obstacles).
They may overlap, as world obstacles may. The robot poses are drawn uniformly in the field
(heading uniform in [-pi, pi)), keeping only those whose centre is outside every obstacle.

The measurements
----------------
* ``scan``: :meth:`ifgm_ref.sim.sensor.IRSensor.scan` with the default sensor -- 135 degrees,
  76 rays, ``range_max`` 15 ft -- so culling leaves the edges near the robot (about 18 of
  100 on average).
* ``scan, no culling``: the same with ``range_max`` 100 ft, beyond the field's diagonal
  (85 ft): every edge survives culling, the worst case of this world.
* ``ray cast only``: :meth:`ifgm_ref.sim.raycast.RayCaster.cast_fan` alone, the kernel under
  ``scan`` (the difference is the ``LaserScan`` built around each result).
* ``simulator step``: :func:`ifgm_ref.sim.simulator.simulate` with the ``straight`` planner in a
  corridor world of 20 obstacles (10 boxes either side of the straight line, all within
  sensor range of it), timed over a whole 300 s episode: each step scans, decides, moves,
  checks the swept disc for collision and records the trace.

Each is timed as ``--repeats`` passes over ``--poses`` poses; the report gives the median pass
(and the best, which is what the machine can do when nothing else runs). Timings are
wall-clock on one core: OpenBLAS is held to one thread. Add a measurement by writing a function
``(setup: Setup) -> Rate`` and listing it in ``MEASUREMENTS``.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import os
import statistics
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import NamedTuple

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy loads BLAS: one core
if importlib.util.find_spec("ifgm_ref") is None:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np
import shapely

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.core.params import SensorParams, SimParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.planners.straight import StraightPlanner
from ifgm_ref.sim.raycast import RayCaster, RayFan
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.shapes import rectangle
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import Polygon, World

#: Side of the square field, ft.
FIELD_FT = 60.0
#: Number of quadrilateral obstacles (4 edges each).
QUADS = 25
#: Radius range of a quadrilateral's vertices around its centre, ft.
QUAD_RADIUS_FT = (1.0, 3.0)
#: Range that keeps every edge of the field within reach (> the diagonal, 84.9 ft), ft.
NO_CULLING_RANGE_FT = 100.0


@dataclass(frozen=True)
class Setup:
    """What every measurement gets: the world, the poses and the timing settings."""

    world: World
    poses: tuple[Pose, ...]
    repeats: int


class Rate(NamedTuple):
    """A measured throughput: operations per second, median and best of the repeats."""

    label: str
    unit: str
    median: float
    best: float
    detail: str


def benchmark_world(seed: int = 0) -> World:
    """The benchmark world: ``QUADS`` random quadrilaterals in the ``FIELD_FT`` square."""
    rng = np.random.default_rng(seed)
    obstacles = []
    for _ in range(QUADS):
        center = rng.uniform(0.0, FIELD_FT, 2)
        # One vertex per quarter turn: the gaps between vertex angles stay below pi, so the
        # star around the centre is a simple polygon.
        angles = (np.arange(4) + rng.uniform(0.0, 1.0, 4)) * (math.pi / 2)
        radii = rng.uniform(*QUAD_RADIUS_FT, 4)
        vertices = center + np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])
        obstacles.append(Polygon(vertices=tuple(map(tuple, vertices.tolist()))))
    # Start and goal only need to be valid; they play no part in the timing.
    return World(start=Pose(-5.0, -5.0, 0.0), goal=Point(-10.0, -10.0), obstacles=tuple(obstacles))


def random_poses(world: World, count: int, seed: int = 1) -> tuple[Pose, ...]:
    """``count`` poses uniform in the field whose centre is outside every obstacle."""
    rng = np.random.default_rng(seed)
    solid = shapely.union_all([ob.geometry for ob in world.obstacles])
    shapely.prepare(solid)
    poses: list[Pose] = []
    while len(poses) < count:
        x, y = rng.uniform(0.0, FIELD_FT, 2)
        theta = rng.uniform(-math.pi, math.pi)
        if not solid.intersects(shapely.Point(x, y)):
            poses.append(Pose(float(x), float(y), float(theta)))
    return tuple(poses)


def time_passes(run: Callable[[], object], operations: int, repeats: int) -> tuple[float, float]:
    """Call ``run`` ``repeats`` times; return (median, best) of ``operations`` per second."""
    run()  # warm-up: caches, lazy imports
    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        seconds.append(time.perf_counter() - start)
    return operations / statistics.median(seconds), operations / min(seconds)


def _scan_rate(setup: Setup, label: str, params: SensorParams) -> Rate:
    sensor = IRSensor(setup.world, params)
    scan, poses = sensor.scan, setup.poses
    kept = _mean_edges_in_reach(setup, params.range_max)

    def run() -> None:
        for pose in poses:
            scan(pose)

    median, best = time_passes(run, len(poses), setup.repeats)
    detail = (
        f"{math.degrees(params.fov):g} deg, {params.rays} rays, range {params.range_max:g} ft, "
        f"{kept:.1f} of {len(setup.world.segments)} edges kept on average"
    )
    return Rate(label, "scans/s", median, best, detail)


def scan_rate(setup: Setup) -> Rate:
    """Scans per second with the world's default sensor (135 deg, 76 rays, 15 ft)."""
    return _scan_rate(setup, "scan", setup.world.sensor)


def scan_rate_no_culling(setup: Setup) -> Rate:
    """Scans per second with a range reaching every edge: culling keeps all of them."""
    params = replace(setup.world.sensor, range_max=NO_CULLING_RANGE_FT)
    return _scan_rate(setup, "scan, no culling", params)


def cast_rate(setup: Setup) -> Rate:
    """Casts per second of the kernel alone, as ``scan`` calls it (without the LaserScan)."""
    world, params = setup.world, setup.world.sensor
    caster = RayCaster(world.segments, world.circle_centers, world.circle_radii, params.range_max)
    cast, fan = caster.cast_fan, RayFan.of(IRSensor(world).angles)
    jobs = [((p.x, p.y), p.theta) for p in setup.poses]

    def run() -> None:
        for origin, heading in jobs:
            cast(origin, heading, fan)

    median, best = time_passes(run, len(jobs), setup.repeats)
    return Rate("ray cast only", "casts/s", median, best, "RayCaster.cast_fan, default sensor")


def _mean_edges_in_reach(setup: Setup, max_range: float) -> float:
    """Mean number of edges whose bounding circle comes within ``max_range`` of the robot."""
    segs = setup.world.segments
    mids = 0.5 * (segs[:, 0] + segs[:, 1])
    reach = max_range + 0.5 * np.hypot(*(segs[:, 1] - segs[:, 0]).T)
    xy = np.array([(p.x, p.y) for p in setup.poses])
    gaps = np.hypot(*(mids[None, :, :] - xy[:, None, :]).transpose(2, 0, 1))
    return float((gaps <= reach).sum(axis=1).mean())


def corridor_world() -> World:
    """20 boxes, 10 either side of the line y = 0, 4 to 9 ft from it, along 400 ft."""
    boxes = tuple(
        rectangle((20.0 + 40.0 * i, side * (5.0 + 2.0 * (i % 3))), 6.0, 2.0)
        for i in range(10)
        for side in (-1.0, 1.0)
    )
    return World(start=Pose(0.0, 0.0, 0.0), goal=Point(500.0, 0.0), obstacles=boxes)


def sim_step_rate(setup: Setup) -> Rate:
    """Simulator steps per second: ``straight`` through the 20-box corridor for 300 s."""
    world, sim = corridor_world(), SimParams(max_time=300.0)
    steps = simulate(world, StraightPlanner(), sim).result.steps

    def run() -> None:
        simulate(world, StraightPlanner(), sim)

    median, best = time_passes(run, steps, max(3, setup.repeats // 3))
    detail = f"straight planner, {len(world.obstacles)} obstacles, {steps} steps per episode"
    return Rate("simulator step", "steps/s", median, best, detail)


#: The measurements ``main`` runs, in order.
MEASUREMENTS: tuple[Callable[[Setup], Rate], ...] = (
    scan_rate,
    scan_rate_no_culling,
    cast_rate,
    sim_step_rate,
)


def main(argv: Sequence[str] | None = None) -> int:
    """Print every measurement of ``MEASUREMENTS``; return the exit status."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--poses", type=int, default=2000, help="poses per pass (2000)")
    parser.add_argument("--repeats", type=int, default=15, help="timed passes (15)")
    parser.add_argument("--seed", type=int, default=0, help="world seed (0)")
    args = parser.parse_args(argv)
    world = benchmark_world(args.seed)
    setup = Setup(world, random_poses(world, args.poses, seed=args.seed + 1), args.repeats)
    print(f"machine: {machine()}")
    print(
        f"world:   {QUADS} quadrilaterals ({len(world.segments)} edges) in a "
        f"{FIELD_FT:g} x {FIELD_FT:g} ft field, seed {args.seed}; {args.poses} poses per pass, "
        f"median (best) of {args.repeats} passes"
    )
    for measure in MEASUREMENTS:
        rate = measure(setup)
        print(
            f"{rate.label:18s} {rate.median:9,.0f} {rate.unit} ({rate.best:,.0f})  [{rate.detail}]"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
