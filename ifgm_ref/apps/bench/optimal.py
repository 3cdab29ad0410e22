"""The physical limit: the shortest collision-free path of the disc robot from start to goal.

The robot's centre may go anywhere outside the obstacles inflated by the robot radius ``r``
(the configuration-space obstacles of a disc), so the shortest path is the shortest path
between two points among those inflated sets: a taut string, straight between tangent
points, which the visibility graph of the inflated obstacles' vertices finds exactly for
polygons. extremitypathfinder (Michelfeit) builds the graph and searches it.

Curved boundaries (discs, and the rounded corners of an inflated polygon) are approximated by
inscribed chords, ``quad_segs`` per quarter circle. An inscribed polygon lies inside the true
inflated set, so the path found is never longer than the true shortest path: the length is a
*lower bound*, short by under ``(R + r) * (1 - cos(pi / (4 * quad_segs)))`` per curve it
wraps (0.014 ft for a 2 ft disc and a 1 ft robot at the default 8 chords per quarter), and a
planner's ``path / optimal`` ratio can only be overstated by that much.

A disc of radius 2 halfway along 20 ft, robot radius 1: two tangents of length
``sqrt(10**2 - 3**2)`` and an arc of radius 3 over ``pi - 2 * acos(3 / 10)``:

>>> import math
>>> from ifgm_ref.sim.shapes import circle
>>> from ifgm_ref.sim.world import World
>>> world = World(start=(0, 0, 0), goal=(20, 0), obstacles=[circle((10, 0), 2)])
>>> exact = 2 * math.sqrt(91) + 3 * (math.pi - 2 * math.acos(0.3))
>>> path = optimal_path(world)
>>> round(exact, 4), 0 <= exact - path.length < 0.015
(20.9069, True)
>>> optimal_path(World(start=(0, 0, 0), goal=(20, 0))).length
20.0
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np
import shapely
from numpy.typing import NDArray
from shapely.geometry.base import BaseGeometry
from shapely.geometry.polygon import orient

from ifgm_ref.core.elements import traces
from ifgm_ref.core.errors import ParameterError, WorldError
from ifgm_ref.core.pose import Point, distance
from ifgm_ref.sim.world import Circle, Obstacle, World

#: Chords per quarter circle of an inflated curve (see the module docstring for the error).
QUAD_SEGS = 8
#: Vertex jitters (ft) tried in turn when the search meets a degenerate configuration.
#: extremitypathfinder 2.7 solves a singular 2x2 system when an obstacle edge is parallel to
#: a line of sight through a vertex of another (exactly symmetric worlds; its issue #64, open
#: since 2022), and it can return a path straight through an obstacle along collinear edges
#: (an H with axis-aligned walls: ``tests/test_bench.py``). Every path is checked against the
#: free space, and searched again with jittered vertices if it fails. A jitter of 1e-7 ft
#: changes the length by as little.
JITTER = (1e-7, 1e-6, 1e-5)
#: How far outside the free space (ft) a returned path may stray: rounding along an edge.
SLACK = 1e-6
#: Margin of the free-space boundary round the obstacles, start and goal of an unbounded
#: world, ft. A shortest path stays in the convex hull of those, so any margin > 0 is exact.
MARGIN = 10.0


@dataclass(frozen=True)
class OptimalPath:
    """The shortest collision-free path of the robot's centre: its length in ft and its
    corners, from the start to the goal."""

    length: float
    waypoints: tuple[Point, ...]


class PathEnvironment(Protocol):
    """The part of extremitypathfinder's ``PolygonEnvironment`` used here (it has no types).

    Coordinates are ``(n, 2)`` arrays in ft, the boundary counter-clockwise and the holes
    clockwise; a path is its corners from start to goal and its length, ``None`` (with no
    corners) when none exists.
    """

    def store(
        self,
        boundary_coordinates: NDArray[np.float64],
        list_of_hole_coordinates: Sequence[NDArray[np.float64]],
        validate: bool = False,
    ) -> None: ...

    def find_shortest_path(
        self, start_coordinates: tuple[float, float], goal_coordinates: tuple[float, float]
    ) -> tuple[list[tuple[float, float]], float | None]: ...


def require_pathfinder() -> Callable[[], PathEnvironment]:
    """extremitypathfinder's ``PolygonEnvironment``, or a :class:`ParameterError` saying how
    to install it (it is the optional extra ``ifgm-ref[bench]``)."""
    try:
        from extremitypathfinder import PolygonEnvironment
    except ImportError:
        raise ParameterError(
            "the benchmark needs extremitypathfinder: pip install 'ifgm-ref[bench]'"
        ) from None
    environment: Callable[[], PathEnvironment] = PolygonEnvironment
    return environment


def inflated(obstacle: Obstacle, radius: float, quad_segs: int = QUAD_SEGS) -> shapely.Polygon:
    """``obstacle`` grown by ``radius`` (ft), curves as inscribed chords."""
    if isinstance(obstacle, Circle):
        return shapely.Point(obstacle.center).buffer(obstacle.radius + radius, quad_segs=quad_segs)
    return obstacle.geometry.buffer(radius, quad_segs=quad_segs)


def configuration_space(
    world: World, quad_segs: int = QUAD_SEGS
) -> tuple[shapely.Polygon, BaseGeometry]:
    """The box the robot's centre must stay in, and the obstacles inflated by the robot radius
    (their union) it must stay out of.

    The box is the world's bounds shrunk by the robot radius or, for an unbounded world,
    :data:`MARGIN` ft round everything.
    """
    r = world.robot.radius
    blocked = shapely.union_all([inflated(ob, r, quad_segs) for ob in world.obstacles])
    if world.bounds is not None:
        b = world.bounds
        box = shapely.box(b.xmin + r, b.ymin + r, b.xmax - r, b.ymax - r)
    else:
        ends = shapely.MultiPoint([world.start.position, world.goal])
        box = shapely.box(*ends.union(blocked).buffer(MARGIN).bounds)
    return box, blocked


def _parts(geometry: BaseGeometry) -> list[shapely.Polygon]:
    return list(getattr(geometry, "geoms", [geometry])) if not geometry.is_empty else []


@traces("s3.shorter", "t1.bug_long_paths")
def optimal_path(world: World, quad_segs: int = QUAD_SEGS) -> OptimalPath:
    """The shortest path of the robot's centre from ``world.start`` to ``world.goal``.

    Raises :class:`~ifgm_ref.core.errors.WorldError` when no path joins them (one of them
    enclosed). A valid :class:`World` keeps both the robot radius clear of every obstacle, so
    both are outside the inflated obstacles, whose chords lie inside the true ones.
    """
    PolygonEnvironment = require_pathfinder()
    start, goal = Point(*world.start.position), Point(*world.goal)
    box, blocked = configuration_space(world, quad_segs)
    # Pockets enclosed by merged obstacles go with them: a path to them does not exist.
    filled = [shapely.Polygon(part.exterior) for part in _parts(blocked)]
    free = box.difference(shapely.union_all(filled)) if filled else box
    parts = [part for part in _parts(free) if part.contains(shapely.Point(start))]
    if not parts or not parts[0].contains(shapely.Point(goal)):
        raise WorldError(f"{world.name or 'world'}: no collision-free path to the goal")
    if parts[0].covers(shapely.LineString([start, goal])):
        return OptimalPath(distance(start, goal), (start, goal))
    region = orient(parts[0], sign=1.0)
    slack = region.buffer(SLACK)  # a path may run along an edge, not through an obstacle
    boundary = np.asarray(region.exterior.coords)[:-1]
    holes = [np.asarray(ring.coords)[:-1] for ring in region.interiors]
    for attempt, jitter in enumerate((0.0, *JITTER)):
        rng = np.random.default_rng(attempt)
        moved = [hole + rng.uniform(-jitter, jitter, hole.shape) for hole in holes]
        env = PolygonEnvironment()
        try:
            env.store(boundary, moved, validate=False)
            waypoints, length = env.find_shortest_path(start, goal)
        except np.linalg.LinAlgError:
            continue
        if length is None or slack.covers(shapely.LineString(waypoints)):
            break
    else:
        raise WorldError(f"{world.name or 'world'}: the shortest-path search failed")
    if length is None:
        raise WorldError(f"{world.name or 'world'}: no collision-free path to the goal")
    return OptimalPath(float(length), tuple(Point(float(x), float(y)) for x, y in waypoints))
