"""Tests of :mod:`ifgm_ref.sim.shapes`: valid simple polygons, documented areas and openings.

Expected areas are computed from the parameters (rectangles, strips, the regular polygon's
triangle fan), never from the returned vertices.
"""

from __future__ import annotations

import math
import re
from contextlib import AbstractContextManager
from typing import Any

import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.sim.shapes import circle, h_shape, rectangle, regular_polygon, u_shape
from ifgm_ref.sim.world import Circle, Polygon

centers = st.tuples(st.floats(-100.0, 100.0), st.floats(-100.0, 100.0))
lengths = st.floats(0.5, 50.0)
angles = st.floats(-2.0 * math.pi, 2.0 * math.pi)
#: Fraction of its upper limit a wall thickness takes; kept off the limits so that the cavity
#: stays wider than rounding noise.
fractions = st.floats(0.05, 0.95)


def assert_simple_ccw(polygon: Polygon, vertices: int) -> None:
    """The polygon has ``vertices`` vertices, a simple ring, and counter-clockwise order."""
    __tracebackhide__ = True
    ring = shapely.LinearRing(polygon.vertices)
    assert len(polygon.vertices) == vertices, f"len(vertices)={len(polygon.vertices)}"
    assert ring.is_simple, f"ring is not simple: {polygon.vertices}"
    assert polygon.geometry.is_valid, shapely.is_valid_reason(polygon.geometry)
    assert ring.is_ccw, f"vertices are clockwise: {polygon.vertices}"


def direction(angle: float) -> tuple[float, float]:
    return math.cos(angle), math.sin(angle)


def along(
    point: tuple[float, float], unit: tuple[float, float], length: float
) -> tuple[float, float]:
    return point[0] + length * unit[0], point[1] + length * unit[1]


def ray(point: tuple[float, float], unit: tuple[float, float], length: float) -> shapely.LineString:
    return shapely.LineString([point, along(point, unit, length)])


def raises(message: str) -> AbstractContextManager[Any]:
    return pytest.raises(ParameterError, match=f"^{re.escape(message)}$")


# --- rectangle, circle, regular polygon -------------------------------------------------------


@given(center=centers, width=lengths, height=lengths, angle=angles)
def test_rectangle(center: tuple[float, float], width: float, height: float, angle: float) -> None:
    rect = rectangle(center, width, height, angle)
    assert_simple_ccw(rect, 4)
    assert rect.geometry.area == pytest.approx(width * height, rel=1e-9)
    assert rect.geometry.centroid.distance(shapely.Point(center)) < 1e-9 * (1 + width + height)
    side = math.dist(rect.vertices[0], rect.vertices[1])
    assert side == pytest.approx(width, rel=1e-9)
    edge_direction = math.atan2(
        rect.vertices[1][1] - rect.vertices[0][1], rect.vertices[1][0] - rect.vertices[0][0]
    )
    assert math.cos(edge_direction - angle) == pytest.approx(1.0)


def test_rectangle_unrotated_is_exact() -> None:
    assert rectangle((10.0, 20.0), 4.0, 2.0).geometry.bounds == (8.0, 19.0, 12.0, 21.0)


def test_circle() -> None:
    assert circle([1, 2], 3) == Circle((1.0, 2.0), 3.0)


@given(
    center=centers,
    radius=lengths,
    sides=st.integers(3, 64),
    angle=angles,
)
def test_regular_polygon(
    center: tuple[float, float], radius: float, sides: int, angle: float
) -> None:
    poly = regular_polygon(center, radius, sides, angle)
    assert_simple_ccw(poly, sides)
    triangle = 0.5 * radius * radius * math.sin(2.0 * math.pi / sides)
    assert poly.geometry.area == pytest.approx(sides * triangle, rel=1e-9)
    for vertex in poly.vertices:
        assert math.dist(vertex, center) == pytest.approx(radius, rel=1e-9)
    first = (poly.vertices[0][0] - center[0], poly.vertices[0][1] - center[1])
    assert math.cos(math.atan2(first[1], first[0]) - angle) == pytest.approx(1.0)


# --- U ----------------------------------------------------------------------------------------


@st.composite
def u_parameters(draw: st.DrawFn) -> dict[str, object]:
    """Valid ``u_shape`` keyword arguments (thickness below both of its limits)."""
    width = draw(lengths, label="width")
    depth = draw(lengths, label="depth")
    thickness = draw(fractions, label="thickness fraction") * min(width / 2.0, depth)
    return {
        "center": draw(centers, label="center"),
        "width": width,
        "depth": depth,
        "thickness": thickness,
        "opening": draw(angles, label="opening"),
    }


@given(u_parameters())
def test_u_shape_is_simple_with_three_walls_area(kw: dict) -> None:
    u = u_shape(**kw)
    assert_simple_ccw(u, 8)
    w, d, t = kw["width"], kw["depth"], kw["thickness"]
    base = w * t  # the base wall, across the whole width
    sides = 2 * t * (d - t)  # two side walls, from the base to the mouth
    assert u.geometry.area == pytest.approx(base + sides, rel=1e-9)


@given(u_parameters())
def test_u_shape_opens_towards_opening(kw: dict) -> None:
    """From the documented cavity centre the way out is along ``opening``, and only there."""
    u = u_shape(**kw)
    w, d, t, opening = kw["width"], kw["depth"], kw["thickness"], kw["opening"]
    out = direction(opening)
    cavity = along(kw["center"], out, t / 2.0)
    far = 4.0 * (w + d)
    assert not u.geometry.covers(shapely.Point(cavity))
    # Nearest wall: a side wall, (w - 2t)/2 away, or the base, (d - t)/2 away.
    assert u.distance(cavity) == pytest.approx(min((w - 2 * t) / 2, (d - t) / 2), rel=1e-6)
    assert not ray(cavity, out, far).intersects(u.geometry), "the mouth is blocked"
    assert ray(cavity, (-out[0], -out[1]), far).intersects(u.geometry), "no base wall behind"
    assert ray(cavity, (-out[1], out[0]), far).intersects(u.geometry), "no side wall to the left"
    assert ray(cavity, (out[1], -out[0]), far).intersects(u.geometry), "no side wall to the right"


@pytest.mark.parametrize(
    ("opening", "mouth"),
    [(0.0, (1.0, 0.0)), (math.pi / 2, (0.0, 1.0)), (math.pi, (-1.0, 0.0))],
)
def test_u_shape_opening_examples(opening: float, mouth: tuple[float, float]) -> None:
    u = u_shape((0.0, 0.0), width=6.0, depth=4.0, thickness=1.0, opening=opening)
    cavity = (0.5 * mouth[0], 0.5 * mouth[1])
    assert not ray(cavity, mouth, 50.0).intersects(u.geometry)
    assert ray(cavity, (-mouth[0], -mouth[1]), 50.0).intersects(u.geometry)


def test_u_shape_center_is_the_bounding_box_centre() -> None:
    u = u_shape((10.0, -5.0), width=6.0, depth=4.0, thickness=1.0)
    assert u.geometry.bounds == (8.0, -8.0, 12.0, -2.0)


# --- H ----------------------------------------------------------------------------------------


@st.composite
def h_parameters(draw: st.DrawFn) -> dict[str, object]:
    """Valid ``h_shape`` keyword arguments, with or without an explicit crossbar thickness."""
    width = draw(lengths, label="width")
    height = draw(lengths, label="height")
    thickness = draw(fractions, label="thickness fraction") * width / 2.0
    bar = draw(st.none() | fractions.map(lambda f: f * height), label="bar_thickness")
    if bar is None and thickness >= height:
        bar = 0.5 * height
    return {
        "center": draw(centers, label="center"),
        "width": width,
        "height": height,
        "thickness": thickness,
        "bar_thickness": bar,
        "orientation": draw(angles, label="orientation"),
    }


@given(h_parameters())
def test_h_shape_is_simple_with_documented_area(kw: dict) -> None:
    h = h_shape(**kw)
    assert_simple_ccw(h, 12)
    w, height, t = kw["width"], kw["height"], kw["thickness"]
    bar = t if kw["bar_thickness"] is None else kw["bar_thickness"]
    walls = 2 * t * height
    crossbar = (w - 2 * t) * bar  # between the walls only
    assert h.geometry.area == pytest.approx(walls + crossbar, rel=1e-9)
    assert h.geometry.covers(shapely.Point(kw["center"])), "the crossbar is not in the middle"


@given(h_parameters())
def test_h_shape_cavities_open_along_the_walls(kw: dict) -> None:
    """Each cavity's way out runs along the walls, away from the crossbar."""
    h = h_shape(**kw)
    height = kw["height"]
    bar = kw["thickness"] if kw["bar_thickness"] is None else kw["bar_thickness"]
    walls_dir = direction(kw["orientation"] + math.pi / 2)  # local +y
    bar_dir = direction(kw["orientation"])  # local +x
    far = 4.0 * (kw["width"] + height)
    for sign in (1.0, -1.0):
        out = (sign * walls_dir[0], sign * walls_dir[1])
        cavity = along(kw["center"], out, (height + bar) / 4.0)  # midway, crossbar to wall end
        assert not h.geometry.covers(shapely.Point(cavity))
        assert not ray(cavity, out, far).intersects(h.geometry), "the cavity is closed"
        assert ray(cavity, (-out[0], -out[1]), far).intersects(h.geometry), "no crossbar"
        assert ray(cavity, bar_dir, far).intersects(h.geometry), "no wall on one side"
        assert ray(cavity, (-bar_dir[0], -bar_dir[1]), far).intersects(h.geometry), "no wall"


def test_h_shape_unrotated_stands_like_the_letter() -> None:
    h = h_shape((0.0, 0.0), width=6.0, height=8.0, thickness=1.0, bar_thickness=2.0)
    assert h.geometry.bounds == (-3.0, -4.0, 3.0, 4.0)
    assert h.geometry.covers(shapely.Point(-2.5, 3.9))  # left wall, near its head
    assert h.geometry.covers(shapely.Point(2.0, 0.9))  # crossbar
    assert not h.geometry.covers(shapely.Point(0.0, 1.1))  # upper cavity


# --- parameter validation ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("build", "message"),
    [
        (lambda: rectangle((0, 0), -1.0, 2.0), "`width` must be a finite number > 0, got -1.0"),
        (lambda: rectangle((0, 0), 1.0, math.nan), "`height` must be a finite number > 0, got nan"),
        (
            lambda: rectangle((0, 0), 1.0, 1.0, angle=math.inf),
            "`angle` must be a finite number, got inf",
        ),
        (
            lambda: rectangle((0, math.nan), 1.0, 1.0),
            "`center[1]` must be a finite number, got nan",
        ),
        (
            lambda: rectangle((0, 0, 0), 1.0, 1.0),
            "`center` must be a pair of numbers (x, y), got (0, 0, 0)",
        ),
        (lambda: rectangle("ab", 1.0, 1.0), "`center` must be a pair of numbers (x, y), got 'ab'"),
        (lambda: circle((0, 0), 0), "`radius` must be a finite number > 0, got 0"),
        (lambda: regular_polygon((0, 0), 1.0, 2), "`sides` must be an integer >= 3, got 2"),
        (lambda: regular_polygon((0, 0), 1.0, 4.0), "`sides` must be an integer >= 3, got 4.0"),
        (
            lambda: regular_polygon((0, 0), -1.0, 4),
            "`radius` must be a finite number > 0, got -1.0",
        ),
        (
            lambda: u_shape((0, 0), 6.0, 4.0, 0.0),
            "`thickness` must be a finite number > 0, got 0.0",
        ),
        (
            lambda: u_shape((0, 0), 6.0, 4.0, 3.0),
            "`thickness` must be < `width` / 2 = 3.0, got 3.0",
        ),
        (lambda: u_shape((0, 0), 10.0, 2.0, 2.0), "`thickness` must be < `depth` = 2.0, got 2.0"),
        (
            lambda: u_shape((0, 0), 6.0, 4.0, 1.0, opening=math.nan),
            "`opening` must be a finite number, got nan",
        ),
        (
            lambda: h_shape((0, 0), 6.0, 8.0, 3.5),
            "`thickness` must be < `width` / 2 = 3.0, got 3.5",
        ),
        (
            lambda: h_shape((0, 0), 6.0, 8.0, 1.0, bar_thickness=9.0),
            "`bar_thickness` must be < `height` = 8.0, got 9.0",
        ),
        (
            lambda: h_shape((0, 0), 6.0, 8.0, 1.0, bar_thickness=-1.0),
            "`bar_thickness` must be a finite number > 0, got -1.0",
        ),
        (lambda: h_shape((0, 0), 20.0, 2.0, 3.0), "`thickness` must be < `height` = 2.0, got 3.0"),
        (
            lambda: h_shape((0, 0), 6.0, 8.0, 1.0, orientation=math.inf),
            "`orientation` must be a finite number, got inf",
        ),
    ],
)
def test_shape_parameters_are_validated(build: object, message: str) -> None:
    with raises(message):
        build()  # type: ignore[operator]
