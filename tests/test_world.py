"""Tests of :mod:`ifgm_ref.sim.world`: coercion, validation messages and exact distances."""

from __future__ import annotations

import math
import re
from contextlib import AbstractContextManager
from typing import Any

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import WorldError
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.sim.world import Bounds, Circle, Polygon, World

SQUARE = Polygon(((0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)))
PILLAR = Circle((10.0, 0.0), 2.0)
FAR_START = (-20.0, -20.0, 0.0)
FAR_GOAL = (30.0, 30.0)


def raises(message: str) -> AbstractContextManager[Any]:
    """Expect a WorldError whose message is exactly ``message``."""
    return pytest.raises(WorldError, match=f"^{re.escape(message)}$")


# --- Circle -----------------------------------------------------------------------------------


def test_circle_coerces_to_floats() -> None:
    circle = Circle([1, np.float32(2.5)], np.int64(3))  # type: ignore[arg-type]
    assert circle == Circle((1.0, 2.5), 3.0)
    assert type(circle.center) is tuple
    assert all(type(c) is float for c in (*circle.center, circle.radius))
    assert hash(circle) == hash(Circle((1.0, 2.5), 3.0))


@pytest.mark.parametrize(
    ("center", "radius", "message"),
    [
        ((0.0, 0.0), 0, "circle.radius: must be a finite number > 0, got 0"),
        ((0.0, 0.0), -2, "circle.radius: must be a finite number > 0, got -2"),
        ((0.0, 0.0), math.nan, "circle.radius: must be a finite number > 0, got nan"),
        ((0.0, 0.0), "1", "circle.radius: must be a finite number > 0, got '1'"),
        ((0.0, 0.0), True, "circle.radius: must be a finite number > 0, got True"),
        ((0.0, math.inf), 1.0, "circle.center[1]: must be a finite number, got inf"),
        (
            (0.0,),
            1.0,
            "circle.center: must be a sequence of 2 numbers (x, y), got 1 item(s): (0.0,)",
        ),
        ("ab", 1.0, "circle.center: must be a sequence of 2 numbers (x, y), got 'ab'"),
        (5.0, 1.0, "circle.center: must be a sequence of 2 numbers (x, y), got 5.0"),
    ],
)
def test_circle_rejects(center: object, radius: object, message: str) -> None:
    with raises(message):
        Circle(center, radius)  # type: ignore[arg-type]


def test_circle_distance_is_analytic() -> None:
    assert PILLAR.distance((13.0, 4.0)) == 3.0  # 5 from the centre, minus the radius 2
    assert PILLAR.distance((10.5, 0.5)) == 0.0


# --- Polygon ----------------------------------------------------------------------------------


def test_polygon_coerces_lists_and_arrays() -> None:
    from_lists = Polygon([[0, 0], [4, 0], [4, 4], [0, 4]])  # type: ignore[arg-type]
    from_array = Polygon(np.array([[0, 0], [4, 0], [4, 4], [0, 4]]))  # type: ignore[arg-type]
    assert from_lists == from_array == SQUARE
    assert hash(from_lists) == hash(SQUARE)
    assert all(type(c) is float for vertex in from_array.vertices for c in vertex)


def test_polygon_drops_repeated_and_closing_vertices() -> None:
    closed = Polygon([(0, 0), (4, 0), (4, 0), (4, 4), (0, 4), (0, 0)])  # type: ignore[list-item]
    assert closed == SQUARE
    assert len(closed.edges) == 4


def test_polygon_keeps_its_orientation() -> None:
    clockwise = Polygon(SQUARE.vertices[::-1])
    assert clockwise.vertices == SQUARE.vertices[::-1]


@pytest.mark.parametrize(
    ("vertices", "message"),
    [
        ([(0, 0), (1, 0)], "polygon: needs at least 3 distinct vertices, got 2"),
        ([(0, 0), (1, 0), (1, 0), (0, 0)], "polygon: needs at least 3 distinct vertices, got 2"),
        ([], "polygon: needs at least 3 distinct vertices, got 0"),
        ([(0, 0), (1, 1), (3, 3)], "polygon: vertices are collinear (zero area)"),
        (
            [(0, 0), (2, 2), (2, 0), (0, 2)],
            "polygon: is self-intersecting (Self-intersection[1 1])",
        ),
        (
            [(0, 0), (2, 0), (1, 1), (2, 2), (0, 2), (1, 1)],
            "polygon: is self-intersecting (Ring Self-intersection[1 1])",
        ),
        ([(0, 0), (2, 0), (math.nan, 2)], "polygon[2][0]: must be a finite number, got nan"),
        (
            [(0, 0), (2, 0), (2, 2, 2)],
            "polygon[2]: must be a sequence of 2 numbers (x, y), got 3 item(s): (2, 2, 2)",
        ),
        ("square", "polygon: must be a sequence of (x, y) vertices, got 'square'"),
        (
            {(0, 0), (1, 0), (0, 1)},
            "polygon: must be a sequence of (x, y) vertices, got {(0, 0), (0, 1), (1, 0)}",
        ),
    ],
)
def test_polygon_rejects(vertices: object, message: str) -> None:
    with raises(message):
        Polygon(vertices)  # type: ignore[arg-type]


XY = tuple[float, float]


def _segment_distance(p: XY, a: XY, b: XY) -> float:
    """Distance from ``p`` to segment ``ab``, written out independently of shapely."""
    ex, ey = b[0] - a[0], b[1] - a[1]
    t = ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / (ex * ex + ey * ey)
    t = min(1.0, max(0.0, t))
    return math.hypot(p[0] - a[0] - t * ex, p[1] - a[1] - t * ey)


@given(
    x=st.floats(-20.0, 20.0, allow_nan=False),
    y=st.floats(-20.0, 20.0, allow_nan=False),
)
def test_polygon_distance_is_exact(x: float, y: float) -> None:
    expected = min(_segment_distance((x, y), a, b) for a, b in SQUARE.edges.tolist())
    if 0.0 <= x <= 4.0 and 0.0 <= y <= 4.0:
        expected = 0.0
    assert SQUARE.distance((x, y)) == pytest.approx(expected, rel=1e-12, abs=1e-12)


def test_polygon_edges_close_the_ring() -> None:
    assert SQUARE.edges.shape == (4, 2, 2)
    assert SQUARE.edges[-1].tolist() == [[0.0, 4.0], [0.0, 0.0]]


# --- World: coercion --------------------------------------------------------------------------


def test_world_coerces_start_goal_obstacles_and_bounds() -> None:
    world = World(
        start=[0, 1, 2],  # type: ignore[arg-type]
        goal=np.array([5, 6]),  # type: ignore[arg-type]
        obstacles=[PILLAR],  # type: ignore[arg-type]
        bounds=[-50, -50, 50, 50],  # type: ignore[arg-type]
    )
    assert type(world.start) is Pose and world.start == Pose(0.0, 1.0, 2.0)
    assert type(world.goal) is Point and world.goal == Point(5.0, 6.0)
    assert type(world.obstacles) is tuple and world.obstacles == (PILLAR,)
    assert type(world.bounds) is Bounds and world.bounds == Bounds(-50.0, -50.0, 50.0, 50.0)
    assert all(type(v) is float for v in (*world.start, *world.goal, *world.bounds))


def test_equal_worlds_hash_alike() -> None:
    a = World(start=[-9, -9, 0], goal=[9, 9], obstacles=[SQUARE])  # type: ignore[arg-type]
    b = World(start=Pose(-9.0, -9.0, 0.0), goal=Point(9.0, 9.0), obstacles=(SQUARE,))
    assert a == b and hash(a) == hash(b)
    assert len({a, b}) == 1


def test_world_arrays_for_the_simulator() -> None:
    world = World(start=FAR_START, goal=FAR_GOAL, obstacles=(SQUARE, PILLAR))  # type: ignore[arg-type]
    assert world.segments.shape == (4, 2, 2)
    assert world.circle_centers.tolist() == [[10.0, 0.0]]
    assert world.circle_radii.tolist() == [2.0]
    empty = World(start=FAR_START, goal=FAR_GOAL)  # type: ignore[arg-type]
    assert empty.segments.shape == (0, 2, 2)
    assert empty.circle_centers.shape == (0, 2)
    assert empty.circle_radii.shape == (0,)


# --- World: validation messages ---------------------------------------------------------------


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"start": (0.0, math.nan, 0.0)}, "start[1]: must be a finite number, got nan"),
        ({"start": (0.0, 0.0, math.inf)}, "start[2]: must be a finite number, got inf"),
        (
            {"start": (0.0, 0.0)},
            "start: must be a sequence of 3 numbers (x, y, theta), got 2 item(s): (0.0, 0.0)",
        ),
        (
            {"goal": Pose(1.0, 1.0, 0.0)},
            "goal: must be a sequence of 2 numbers (x, y), "
            "got 3 item(s): Pose(x=1.0, y=1.0, theta=0.0)",
        ),
        ({"goal": (1.0, None)}, "goal[1]: must be a finite number, got None"),
        (
            {"bounds": (0.0, 0.0, 10.0)},
            "bounds: must be a sequence of 4 numbers "
            "(xmin, ymin, xmax, ymax), got 3 item(s): (0.0, 0.0, 10.0)",
        ),
        ({"bounds": (-50.0, -50.0, math.nan, 50.0)}, "bounds[2]: must be a finite number, got nan"),
        ({"bounds": (50.0, -50.0, -50.0, 50.0)}, "bounds: xmin must be < xmax, got 50.0 >= -50.0"),
        ({"bounds": (-50.0, 5.0, 50.0, 5.0)}, "bounds: ymin must be < ymax, got 5.0 >= 5.0"),
        (
            {"bounds": (-10.0, -10.0, 50.0, 50.0)},
            "start: (-20.0, -20.0) is outside the bounds (-10.0, -10.0, 50.0, 50.0)",
        ),
        (
            {"bounds": (-50.0, -50.0, 20.0, 50.0)},
            "goal: (30.0, 30.0) is outside the bounds (-50.0, -50.0, 20.0, 50.0)",
        ),
        (
            {"obstacles": (SQUARE, {"circle": 1})},
            "obstacles[1]: must be a Circle or a Polygon, got {'circle': 1}",
        ),
        (
            {"obstacles": PILLAR},
            "obstacles: must be a sequence of Circle and Polygon obstacles, "
            "got Circle(center=(10.0, 0.0), radius=2.0)",
        ),
        ({"robot": {"radius": 2.0}}, "robot: must be a RobotParams, got {'radius': 2.0}"),
        ({"sensor": None}, "sensor: must be a SensorParams, got None"),
        ({"name": 7}, "name: must be a string, got 7"),
        ({"start": (2.0, 2.0, 0.0)}, "start: (2.0, 2.0) is inside obstacles[0]"),
        ({"goal": (4.0, 1.0)}, "goal: (4.0, 1.0) is inside obstacles[0]"),
        ({"goal": (10.0, 1.0)}, "goal: (10.0, 1.0) is inside obstacles[1]"),
        (
            {"start": (5.0, 2.0, 0.0)},
            "start: (5.0, 2.0) is within the robot radius 1.0 ft of obstacles[0] (distance 1 ft)",
        ),
        (
            {"start": (4.3, 4.4, 0.0)},
            "start: (4.3, 4.4) is within the robot radius 1.0 ft of obstacles[0] (distance 0.5 ft)",
        ),
        (
            {"goal": (13.0, 0.0)},
            "goal: (13.0, 0.0) is within the robot radius 1.0 ft of obstacles[1] (distance 1 ft)",
        ),
        (
            {"goal": (10.0, 5.0), "robot": RobotParams(radius=3.5)},
            "goal: (10.0, 5.0) is within the robot radius 3.5 ft of obstacles[1] (distance 3 ft)",
        ),
    ],
)
def test_world_rejects(changes: dict[str, object], message: str) -> None:
    arguments: dict[str, object] = {
        "start": FAR_START,
        "goal": FAR_GOAL,
        "obstacles": (SQUARE, PILLAR),
        **changes,
    }
    with raises(message):
        World(**arguments)  # type: ignore[arg-type]


def test_world_rejects_integers_beyond_the_float_range() -> None:
    with pytest.raises(WorldError, match=r"^start\[2\]: must be a finite number, got 1000"):
        World(start=(0.0, 0.0, 10**400), goal=FAR_GOAL)  # type: ignore[arg-type]


def test_world_accepts_a_robot_just_clear_of_obstacles() -> None:
    """1e-9 ft beyond the robot radius from the square's side and from the pillar: accepted."""
    radius = RobotParams().radius
    start, goal = (4.0 + radius + 1e-9, 2.0, 0.0), (12.0 + radius + 1e-9, 0.0)
    world = World(start=start, goal=goal, obstacles=(SQUARE, PILLAR))  # type: ignore[arg-type]
    assert SQUARE.distance(world.start.position) > radius
    assert PILLAR.distance(world.goal) > radius


def test_clearance_is_exact_where_buffer_would_miss() -> None:
    """A start 0.9995 radius from a corner, between two chord vertices of ``buffer(radius)``.

    shapely's ``buffer`` (16 segments per quarter circle) puts its vertices every pi/32 around
    the corner; midway between two of them its chord lies at ``cos(pi/64) = 0.9988`` radius
    from the corner, inside the true circle, so a buffered obstacle misses this start.
    """
    radius = RobotParams().radius
    angle = math.pi / 4 + math.pi / 64
    start = (4.0 + 0.9995 * radius * math.cos(angle), 4.0 + 0.9995 * radius * math.sin(angle))
    assert not SQUARE.geometry.buffer(radius).contains(shapely.Point(start))
    with pytest.raises(WorldError, match=r"^start: .* is within the robot radius 1\.0 ft"):
        World(start=(*start, 0.0), goal=FAR_GOAL, obstacles=(SQUARE,))  # type: ignore[arg-type]


def test_world_uses_its_own_robot_radius() -> None:
    small = RobotParams(radius=0.25)
    world = World(start=(4.5, 2.0, 0.0), goal=FAR_GOAL, obstacles=(SQUARE,), robot=small)
    assert world.robot is small
    assert World(start=FAR_START, goal=FAR_GOAL, sensor=SensorParams(rays=3)).sensor.rays == 3  # type: ignore[arg-type]


def test_bounds_contains_is_closed() -> None:
    bounds = Bounds(0.0, 0.0, 10.0, 5.0)
    assert bounds.contains((0.0, 0.0)) and bounds.contains((10.0, 5.0))
    assert not bounds.contains((-1e-12, 2.0)) and not bounds.contains((5.0, 5.000001))
