"""Swept-disc clearance (ifgm_ref.sim.collision) against shapely's exact geometry."""

from __future__ import annotations

import math

import shapely
from hypothesis import assume, example, given
from hypothesis import strategies as st

from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.sim.collision import ClearanceChecker, point_segment_distance, segment_distance
from ifgm_ref.sim.world import Circle, Polygon, World

coords = st.floats(-20.0, 20.0, allow_nan=False)
#: shapely.buffer approximates the disc's round caps with chords; with quad_segs=64 the chord
#: sagitta is r * (1 - cos(pi / 256)) < 1e-4 r, so verdicts closer than that are not compared.
BUFFER_BAND = 1e-4

SQUARE = Polygon(((0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)))
DISC = Circle((10.0, 0.0), 2.0)


def _world(*obstacles: Polygon | Circle) -> World:
    return World(start=Pose(-30.0, -30.0, 0.0), goal=Point(30.0, 30.0), obstacles=obstacles)


@given(px=coords, py=coords, qx=coords, qy=coords, radius=st.floats(0.1, 3.0))
@example(px=3.0, py=5.5, qx=5.5, qy=3.0, radius=1.0)  # grazes the corner (4, 4) mid-step
def test_clearance_equals_shapely_distance(
    px: float, py: float, qx: float, qy: float, radius: float
) -> None:
    checker = ClearanceChecker(_world(SQUARE, DISC), radius)
    got = checker.segment_clearance(Pose(px, py, 0.0), Pose(qx, qy, 0.0))
    path = (
        shapely.LineString([(px, py), (qx, qy)]) if (px, py) != (qx, qy) else shapely.Point(px, py)
    )
    square_distance = shapely.distance(path, shapely.Polygon(SQUARE.vertices).exterior)
    disc_distance = shapely.distance(path, shapely.Point(DISC.center)) - DISC.radius
    expected = min(square_distance, disc_distance) - radius
    assert math.isclose(got, expected, abs_tol=1e-9), (
        f"clearance={got}, but should be {expected} (shapely) "
        f"for segment ({px}, {py})->({qx}, {qy})"
    )


@given(px=coords, py=coords, qx=coords, qy=coords, radius=st.floats(0.1, 3.0))
def test_collision_verdict_agrees_with_shapely_buffered_segment(
    px: float, py: float, qx: float, qy: float, radius: float
) -> None:
    # The checker's precondition: the segment starts outside every obstacle.
    start = shapely.Point(px, py)
    assume(not shapely.Polygon(SQUARE.vertices).covers(start))
    assume(start.distance(shapely.Point(DISC.center)) > DISC.radius)
    checker = ClearanceChecker(_world(SQUARE, DISC), radius)
    clearance = checker.segment_clearance(Pose(px, py, 0.0), Pose(qx, qy, 0.0))
    swept = shapely.LineString([(px, py), (qx, qy)]).buffer(radius, quad_segs=64)
    obstacles = [
        shapely.Polygon(SQUARE.vertices),
        shapely.Point(DISC.center).buffer(DISC.radius, quad_segs=256),
    ]
    hit = any(swept.intersects(ob) for ob in obstacles)
    if abs(clearance) > BUFFER_BAND * (radius + DISC.radius) * 4:
        assert hit == (clearance < 0.0), f"clearance={clearance}, but shapely says hit={hit}"


def test_grazing_a_corner_between_samples_is_caught() -> None:
    # Both end points are 1.5 ft from the square, but the segment (on x + y = 8.5) passes
    # 0.5 / sqrt(2) ft from the corner (4, 4).
    checker = ClearanceChecker(_world(SQUARE), 1.0)
    start, end = Pose(3.0, 5.5, 0.0), Pose(5.5, 3.0, 0.0)
    assert checker.pose_clearance(start) > 0.0
    assert checker.pose_clearance(end) > 0.0
    swept = checker.segment_clearance(start, end)
    assert math.isclose(swept, 0.5 / math.sqrt(2) - 1.0, abs_tol=1e-12)
    assert swept < 0.0


def test_crossing_segments_have_zero_distance() -> None:
    assert segment_distance((-1.0, 0.0), (1.0, 0.0), (0.0, -1.0), (0.0, 1.0)) == 0.0


def test_world_without_obstacles_has_infinite_clearance() -> None:
    checker = ClearanceChecker(_world(), 1.0)
    assert checker.pose_clearance(Pose(0.0, 0.0, 0.0)) == math.inf


def _every_obstacle_minimum(world: World, radius: float, start: Pose, end: Pose) -> float:
    """The clearance by its definition: every edge and every circle measured, no pruning."""
    p, q = (start.x, start.y), (end.x, end.y)
    edges = [segment_distance(p, q, a, b) for a, b in world.segments.tolist()]
    circles = [
        point_segment_distance(cx, cy, *p, *q) - r
        for (cx, cy), r in zip(
            world.circle_centers.tolist(), world.circle_radii.tolist(), strict=True
        )
    ]
    return min(edges + circles, default=math.inf) - radius


@given(
    x=coords,
    y=coords,
    steps=st.lists(st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0)), max_size=30),
    radius=st.floats(0.1, 3.0),
)
def test_clearance_is_the_unpruned_minimum_bit_for_bit(
    x: float, y: float, steps: list[tuple[float, float]], radius: float
) -> None:
    # A walk of short and long steps, so the checker's cache is both reused and rebuilt.
    world = _world(SQUARE, DISC, Polygon(((5.0, 5.0), (7.0, 5.0), (6.0, 8.0))), Circle((-5, 3), 1))
    checker = ClearanceChecker(world, radius)
    here = Pose(x, y, 0.0)
    for dx, dy in [(0.0, 0.0), *steps]:
        there = Pose(here.x + dx, here.y + dy, 0.0)
        got = checker.segment_clearance(here, there)
        expected = _every_obstacle_minimum(world, radius, here, there)
        assert got == expected, (
            f"clearance={got!r}, but should be {expected!r} [segment_clearance({here}, {there})]"
        )
        here = there
