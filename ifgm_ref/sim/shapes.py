"""Obstacle builders: rectangles, circles, regular polygons, and the paper's U and H blocks.

Reference: "An Improved Algorithm for Collision Avoidance in Environments Having U and H
Shaped Obstacles" (IFGM / IBA), section 5. Scenario 1 (section 5.1, Figures 4-7) holds
"obstacles of simple but different shapes"; Scenario 2 (section 5.2, Figure 8) holds the
"critical shaped (U and H shaped) obstacles" that trap local planners such as FGM: a robot
that enters the U's cavity meets the base wall and must turn back "towards 180 degrees". The
figures are not in our copy of the paper, so every dimension here is a free parameter.

Conventions, shared by every builder:

* lengths in ft, angles in radians, counter-clockwise from +x (REP-103);
* ``center`` is the centre of the shape's *unrotated bounding box* (of the circumscribed
  circle for :func:`regular_polygon`), and the shape is rotated about it;
* polygons come out as a validated :class:`~ifgm_ref.sim.world.Polygon` with counter-clockwise
  vertices; with an angle of 0 the vertices are exact, other angles round them to floats.

Parameters out of their domain raise :class:`~ifgm_ref.core.errors.ParameterError`, e.g.
"`thickness` must be < `width` / 2 = 2.5, got 3".
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.validate import POSITIVE, require
from ifgm_ref.sim.world import Circle, Polygon

__all__ = ["circle", "h_shape", "rectangle", "regular_polygon", "u_shape"]


def _center(center: Sequence[float]) -> tuple[float, float]:
    """Validate a centre given as a pair of finite numbers."""
    try:
        if isinstance(center, str | bytes):
            raise TypeError
        x, y = center
    except (TypeError, ValueError):
        raise ParameterError(f"`center` must be a pair of numbers (x, y), got {center!r}") from None
    require("center[0]", x)
    require("center[1]", y)
    return float(x), float(y)


def _below(name: str, value: float, limit_name: str, limit: float) -> None:
    """Raise unless ``value < limit`` (both already checked finite)."""
    if not value < limit:
        raise ParameterError(f"`{name}` must be < {limit_name} = {limit!r}, got {value!r}")


def _place(
    center: tuple[float, float], local: Sequence[tuple[float, float]], angle: float
) -> Polygon:
    """Rotate ``local`` vertices by ``angle`` about the origin, then move it to ``center``."""
    cos, sin = math.cos(angle), math.sin(angle)
    cx, cy = center
    return Polygon(tuple((cx + cos * x - sin * y, cy + sin * x + cos * y) for x, y in local))


def rectangle(center: Sequence[float], width: float, height: float, angle: float = 0.0) -> Polygon:
    """Build a rectangle of ``width`` by ``height`` ft centred at ``center``.

    Parameters
    ----------
    center : pair of float
        Centre ``(x, y)`` in ft.
    width : float
        Side along the rectangle's own x axis, ft, > 0.
    height : float
        Side along its own y axis, ft, > 0.
    angle : float, default 0.0
        Rotation about ``center``, radians, counter-clockwise.

    Examples
    --------
    >>> rectangle((0.0, 0.0), 4.0, 2.0).vertices
    ((-2.0, -1.0), (2.0, -1.0), (2.0, 1.0), (-2.0, 1.0))
    >>> round(rectangle((5.0, 5.0), 4.0, 2.0, angle=0.3).geometry.area, 12)
    8.0
    >>> rectangle((0.0, 0.0), 0.0, 2.0)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `width` must be a finite number > 0, got 0.0
    """
    c = _center(center)
    require("width", width, POSITIVE)
    require("height", height, POSITIVE)
    require("angle", angle)
    w2, h2 = width / 2.0, height / 2.0
    return _place(c, ((-w2, -h2), (w2, -h2), (w2, h2), (-w2, h2)), angle)


def circle(center: Sequence[float], radius: float) -> Circle:
    """Build a circular obstacle (the same as :class:`~ifgm_ref.sim.world.Circle`, checked here).

    Examples
    --------
    >>> circle((1.0, 2.0), 0.5)
    Circle(center=(1.0, 2.0), radius=0.5)
    >>> circle((1.0, 2.0), math.inf)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `radius` must be a finite number > 0, got inf
    """
    c = _center(center)
    require("radius", radius, POSITIVE)
    return Circle(c, radius)


def regular_polygon(
    center: Sequence[float], radius: float, sides: int, angle: float = 0.0
) -> Polygon:
    """Build a regular polygon inscribed in the circle of ``radius`` about ``center``.

    Parameters
    ----------
    center : pair of float
        Centre ``(x, y)`` in ft.
    radius : float
        Circumradius (centre to vertex), ft, > 0.
    sides : int
        Number of sides, >= 3.
    angle : float, default 0.0
        Direction of the first vertex from the centre, radians; the others follow
        counter-clockwise.

    Examples
    --------
    >>> regular_polygon((0.0, 0.0), 1.0, 4).vertices[0]
    (1.0, 0.0)
    >>> round(regular_polygon((0.0, 0.0), 1.0, 6).geometry.area, 12)  # 3 sqrt(3) / 2
    2.598076211353
    >>> regular_polygon((0.0, 0.0), 1.0, 2)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `sides` must be an integer >= 3, got 2
    """
    c = _center(center)
    require("radius", radius, POSITIVE)
    if isinstance(sides, bool) or not isinstance(sides, int) or sides < 3:
        raise ParameterError(f"`sides` must be an integer >= 3, got {sides!r}")
    require("angle", angle)
    step = 2.0 * math.pi / sides
    local = [(radius * math.cos(k * step), radius * math.sin(k * step)) for k in range(sides)]
    return _place(c, local, angle)


def u_shape(
    center: Sequence[float],
    width: float,
    depth: float,
    thickness: float,
    opening: float = 0.0,
) -> Polygon:
    """Build a U block: a base wall and two side walls, as one simple 8-vertex polygon.

    Unrotated (``opening=0``) the U opens towards +x: the base wall is the strip
    ``x in [-depth/2, -depth/2 + thickness]``, the side walls run along y = -width/2 and
    y = +width/2 up to ``x = +depth/2``, where the mouth is. All three walls are ``thickness``
    thick. A robot driving *towards* +x is trapped by ``opening=pi`` (the paper's Figure 8).

    Parameters
    ----------
    center : pair of float
        Centre ``(x, y)`` of the U's bounding box (outer outline), ft. The cavity's centre is
        ``center + (thickness / 2) * (cos(opening), sin(opening))``.
    width : float
        Outer size across the mouth (side wall to side wall), ft, > 0.
    depth : float
        Outer size from the back of the base wall to the mouth, ft, > 0.
    thickness : float
        Wall thickness, ft: ``0 < thickness < width / 2`` (the cavity is not closed) and
        ``thickness < depth`` (the side walls stick out of the base).
    opening : float, default 0.0
        Direction the mouth faces, radians, counter-clockwise from +x: 0 opens towards +x,
        pi/2 towards +y, pi towards -x.

    Returns
    -------
    Polygon
        Area ``width * depth - (width - 2 thickness) * (depth - thickness)``.

    Examples
    --------
    >>> u = u_shape((0.0, 0.0), width=6.0, depth=4.0, thickness=1.0)
    >>> u.vertices[:4]  # the -y side wall, outside then inside
    ((-2.0, -3.0), (2.0, -3.0), (2.0, -2.0), (-1.0, -2.0))
    >>> u.vertices[4:]  # the +y side wall, inside then outside
    ((-1.0, 2.0), (2.0, 2.0), (2.0, 3.0), (-2.0, 3.0))
    >>> u.geometry.area  # 6 x 4 outline minus the 4 x 3 cavity
    12.0
    >>> u_shape((0.0, 0.0), width=6.0, depth=4.0, thickness=3.0)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `thickness` must be < `width` / 2 = 3.0, got 3.0
    """
    c = _center(center)
    require("width", width, POSITIVE)
    require("depth", depth, POSITIVE)
    require("thickness", thickness, POSITIVE)
    _below("thickness", thickness, "`width` / 2", width / 2.0)
    _below("thickness", thickness, "`depth`", depth)
    require("opening", opening)
    return _place(c, _u_outline(width, depth, thickness), opening)


def _u_outline(width: float, depth: float, thickness: float) -> tuple[tuple[float, float], ...]:
    """The vertices of an unrotated U centred on the origin (see :func:`u_shape`)."""
    w2, d2, t = width / 2.0, depth / 2.0, thickness
    return (
        (-d2, -w2),  # outer corners of the base and the right-hand (-y) side wall
        (d2, -w2),
        (d2, -w2 + t),  # inner face of the -y side wall, back to the base
        (-d2 + t, -w2 + t),
        (-d2 + t, w2 - t),  # inner face of the base, then of the +y side wall
        (d2, w2 - t),
        (d2, w2),
        (-d2, w2),
    )


def h_shape(
    center: Sequence[float],
    width: float,
    height: float,
    thickness: float,
    bar_thickness: float | None = None,
    orientation: float = 0.0,
) -> Polygon:
    """Build an H block: two parallel walls joined in the middle by a crossbar, 12 vertices.

    Unrotated (``orientation=0``) the H stands like the letter: its two walls run along y at
    ``x in [-width/2, -width/2 + thickness]`` and ``x in [width/2 - thickness, width/2]``, and
    the crossbar runs along x, centred on y = 0. Its two cavities (two U's back to back) open
    towards +y and -y.

    Parameters
    ----------
    center : pair of float
        Centre ``(x, y)`` of the H (of its bounding box and of the crossbar), ft.
    width : float
        Outer size across the walls, along the crossbar, ft, > 0.
    height : float
        Length of the walls, ft, > 0.
    thickness : float
        Thickness of each wall, ft: ``0 < thickness < width / 2``.
    bar_thickness : float or None, default None
        Thickness of the crossbar, ft: ``0 < bar_thickness < height``; ``None`` means
        ``thickness``, which must then be < ``height`` too.
    orientation : float, default 0.0
        Rotation about ``center``, radians, counter-clockwise: at pi/2 the walls run along x
        and the cavities open towards -x and +x.

    Returns
    -------
    Polygon
        Area ``2 * thickness * height + (width - 2 * thickness) * bar_thickness``.

    Examples
    --------
    >>> h = h_shape((0.0, 0.0), width=6.0, height=8.0, thickness=1.0)
    >>> len(h.vertices), h.geometry.area  # two 1 x 8 walls and a 4 x 1 bar
    (12, 20.0)
    >>> h_shape((0.0, 0.0), width=6.0, height=8.0, thickness=1.0, bar_thickness=8.0)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `bar_thickness` must be < `height` = 8.0, got 8.0
    """
    c = _center(center)
    require("width", width, POSITIVE)
    require("height", height, POSITIVE)
    require("thickness", thickness, POSITIVE)
    bar = thickness if bar_thickness is None else bar_thickness
    require("bar_thickness", bar, POSITIVE)
    _below("thickness", thickness, "`width` / 2", width / 2.0)
    _below("thickness" if bar_thickness is None else "bar_thickness", bar, "`height`", height)
    require("orientation", orientation)
    return _place(c, _h_outline(width, height, thickness, bar), orientation)


def _h_outline(
    width: float, height: float, thickness: float, bar: float
) -> tuple[tuple[float, float], ...]:
    """The vertices of an unrotated H centred on the origin, its crossbar ``bar`` thick (see
    :func:`h_shape`)."""
    w2, h2, t, b2 = width / 2.0, height / 2.0, thickness, bar / 2.0
    return (
        (-w2, -h2),  # foot of the left wall
        (-w2 + t, -h2),
        (-w2 + t, -b2),  # underside of the crossbar
        (w2 - t, -b2),
        (w2 - t, -h2),  # foot of the right wall
        (w2, -h2),
        (w2, h2),  # head of the right wall
        (w2 - t, h2),
        (w2 - t, b2),  # top of the crossbar
        (-w2 + t, b2),
        (-w2 + t, h2),  # head of the left wall
        (-w2, h2),
    )
