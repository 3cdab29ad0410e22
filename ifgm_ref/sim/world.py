"""The world: bounds, polygon and circle obstacles, a start pose and a goal.

The paper's worlds (section 5) hold "obstacles of simple but different shapes" and "critical
shaped" U and H obstacles. Obstacles here are simple polygons (any shape, U and H included)
and circles. Units are feet; the start heading is in radians.

This module knows the map; planners never import it (section 3: "No priori information or map
of the environment is required").

Validation
----------
Every type validates where input enters, in ``__post_init__``, and raises
:class:`~ifgm_ref.core.errors.WorldError`. A message starts with the location of the offending
item, written as a path, then a colon and the problem:

* :class:`Circle`: ``circle.center[1]: ...``, ``circle.radius: ...``;
* :class:`Polygon`: ``polygon: ...``, ``polygon[3][0]: ...`` (vertex 3, coordinate x);
* :class:`World`: ``start...``, ``goal...``, ``bounds...``, ``obstacles[2]...``, ``robot``,
  ``sensor``, ``name``.

These paths are also the paths of the world-file format (``docs/world-format.md``), so the
file reader only prefixes them (``world.json: obstacles[1].circle.radius: ...``).

Inputs are coerced on the way in: any sequence of numbers (lists, numpy arrays) becomes a
tuple of floats, ``start`` a :class:`~ifgm_ref.core.pose.Pose`, ``goal`` a
:class:`~ifgm_ref.core.pose.Point`, so equal worlds compare equal and hash alike.

Clearance verdicts use exact distances (analytic for circles, shapely's point-polygon
distance for polygons), never ``buffer()``, whose chords make an inflated obstacle slightly
*smaller* than the true one.
"""

from __future__ import annotations

import math
import reprlib
from collections.abc import Iterable, Mapping, Set
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import NamedTuple

import numpy as np
import shapely
from numpy.typing import NDArray

from ifgm_ref.core.errors import WorldError
from ifgm_ref.core.params import RobotParams, SensorParams, changed_robot
from ifgm_ref.core.pose import Point, PointLike, Pose
from ifgm_ref.core.validate import POSITIVE, REAL, Domain, violation

_SHORT = reprlib.Repr()
_SHORT.maxlist = _SHORT.maxtuple = 8
_SHORT.maxstring = _SHORT.maxother = 40


def _show(value: object) -> str:
    """``repr(value)``, shortened so that a message stays one readable line."""
    return _SHORT.repr(value)


def _items(value: object, where: str, what: str) -> tuple[object, ...]:
    """The items of a sequence (list, tuple, numpy array...), or a WorldError naming ``where``.

    Strings, mappings and sets are iterable but never a sequence of coordinates or obstacles.
    """
    if isinstance(value, str | bytes | Mapping | Set) or not isinstance(value, Iterable):
        raise WorldError(f"{where}: must be {what}, got {_show(value)}")
    try:
        return tuple(value)
    except TypeError:  # e.g. a 0-d numpy array
        raise WorldError(f"{where}: must be {what}, got {_show(value)}") from None


def _number(value: object, where: str, domain: Domain = REAL) -> float:
    """``value`` as a finite float in ``domain``; booleans are not numbers here."""
    if why := violation(value, domain, shown=_show(value)):
        raise WorldError(f"{where}: {why}")
    return float(value)  # type: ignore[arg-type]


def _numbers(value: object, where: str, names: tuple[str, ...]) -> tuple[float, ...]:
    """``value`` as a tuple of ``len(names)`` finite floats (``names`` only label the message)."""
    what = f"a sequence of {len(names)} numbers ({', '.join(names)})"
    items = _items(value, where, what)
    if len(items) != len(names):
        raise WorldError(f"{where}: must be {what}, got {len(items)} item(s): {_show(value)}")
    return tuple(_number(item, f"{where}[{i}]") for i, item in enumerate(items))


def _xy(point: tuple[float, float]) -> str:
    """A point for a message, with its coordinates as given (``repr``)."""
    return f"({point[0]!r}, {point[1]!r})"


class Bounds(NamedTuple):
    """The rectangular arena ``[xmin, xmax] x [ymin, ymax]``, in ft.

    A plain tuple: :class:`World` validates it (finite, ``xmin < xmax``, ``ymin < ymax``).
    """

    xmin: float
    ymin: float
    xmax: float
    ymax: float

    def contains(self, point: PointLike) -> bool:
        """Whether ``point`` (a position, or a pose: its heading not read) lies in the closed
        rectangle.

        >>> Bounds(0.0, 0.0, 10.0, 5.0).contains((10.0, 5.0))
        True
        >>> Bounds(0.0, 0.0, 10.0, 5.0).contains((10.5, 1.0))
        False
        """
        return self.xmin <= point[0] <= self.xmax and self.ymin <= point[1] <= self.ymax


def _bounds(value: object) -> Bounds:
    """Validate and coerce the ``bounds`` of a world."""
    bounds = Bounds(*_numbers(value, "bounds", Bounds._fields))
    if bounds.xmin >= bounds.xmax:
        raise WorldError(f"bounds: xmin must be < xmax, got {bounds.xmin!r} >= {bounds.xmax!r}")
    if bounds.ymin >= bounds.ymax:
        raise WorldError(f"bounds: ymin must be < ymax, got {bounds.ymin!r} >= {bounds.ymax!r}")
    return bounds


@dataclass(frozen=True)
class Circle:
    """A circular obstacle: centre ``(x, y)`` and radius, in ft.

    Parameters
    ----------
    center : tuple of 2 float
        Centre in ft; any sequence of two finite numbers, stored as a tuple of floats.
    radius : float
        Radius in ft, finite and > 0.

    Examples
    --------
    >>> Circle([1, 2], 3)
    Circle(center=(1.0, 2.0), radius=3.0)
    >>> Circle((0.0, 0.0), 2.0).distance((5.0, 0.0))
    3.0
    >>> Circle((0.0, 0.0), -2)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.WorldError: circle.radius: must be a finite number > 0, got -2
    """

    center: tuple[float, float]
    radius: float

    def __post_init__(self) -> None:
        center = _numbers(self.center, "circle.center", ("x", "y"))
        radius = _number(self.radius, "circle.radius", POSITIVE)
        object.__setattr__(self, "center", center)
        object.__setattr__(self, "radius", radius)

    @property
    def geometry(self) -> shapely.Polygon:
        """The exact disc as far as shapely allows (a fine polygon; use for plots only)."""
        return shapely.Point(self.center).buffer(self.radius, quad_segs=64)

    def distance(self, point: tuple[float, float]) -> float:
        """Exact distance in ft from ``point`` to the disc; 0 on or inside it."""
        gap = math.hypot(point[0] - self.center[0], point[1] - self.center[1]) - self.radius
        return max(0.0, gap)


def _ring(value: object) -> tuple[tuple[float, float], ...]:
    """Validate and coerce the vertices of a :class:`Polygon` (see its docstring)."""
    items = _items(value, "polygon", "a sequence of (x, y) vertices")
    points = [_numbers(item, f"polygon[{i}]", ("x", "y")) for i, item in enumerate(items)]
    ring: list[tuple[float, float]] = []
    for x, y in points:
        if not ring or (x, y) != ring[-1]:
            ring.append((x, y))
    while len(ring) > 1 and ring[-1] == ring[0]:
        ring.pop()
    if len(ring) < 3:
        raise WorldError(f"polygon: needs at least 3 distinct vertices, got {len(set(ring))}")
    if shapely.MultiPoint(ring).convex_hull.geom_type != "Polygon":
        raise WorldError("polygon: vertices are collinear (zero area)")
    if not shapely.LinearRing(ring).is_simple:
        reason = shapely.is_valid_reason(shapely.Polygon(ring))
        raise WorldError(f"polygon: is self-intersecting ({reason})")
    return tuple(ring)


@dataclass(frozen=True)
class Polygon:
    """A simple-polygon obstacle given by its vertices ``((x, y), ...)`` in order, in ft.

    Either orientation is accepted and kept. The ring closes itself: a last vertex equal to
    the first, and any vertex equal to the one before it, are dropped (they would be edges of
    zero length). What remains must be at least 3 distinct, not all collinear, points whose
    ring does not cross or touch itself.

    Examples
    --------
    >>> square = Polygon([[0, 0], [2, 0], [2, 2], [0, 2], [0, 0]])
    >>> square.vertices
    ((0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0))
    >>> square.distance((5.0, 6.0)), square.distance((1.0, 1.0))
    (5.0, 0.0)
    >>> Polygon([(0, 0), (2, 2), (2, 0), (0, 2)])
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.WorldError: polygon: is self-intersecting (Self-intersection[1 1])
    """

    vertices: tuple[tuple[float, float], ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "vertices", _ring(self.vertices))

    @cached_property
    def geometry(self) -> shapely.Polygon:
        """The obstacle as a shapely polygon (exact)."""
        return shapely.Polygon(self.vertices)

    @property
    def edges(self) -> NDArray[np.float64]:
        """The boundary edges as an ``(n, 2, 2)`` array of ``(start, end)`` points."""
        pts = np.asarray(self.vertices, dtype=np.float64)
        return np.stack([pts, np.roll(pts, -1, axis=0)], axis=1)

    def distance(self, point: tuple[float, float]) -> float:
        """Exact distance in ft from ``point`` to the polygon; 0 on or inside it."""
        return float(shapely.distance(self.geometry, shapely.Point(point[0], point[1])))


Obstacle = Circle | Polygon


def _obstacles(value: object) -> tuple[Obstacle, ...]:
    """Validate and coerce the ``obstacles`` of a world."""
    items = _items(value, "obstacles", "a sequence of Circle and Polygon obstacles")
    for i, item in enumerate(items):
        if not isinstance(item, Circle | Polygon):
            raise WorldError(f"obstacles[{i}]: must be a Circle or a Polygon, got {_show(item)}")
    return items  # type: ignore[return-value]  # checked element by element above


def _check_clear(
    label: str, point: Point, obstacles: tuple[Obstacle, ...], robot_radius: float
) -> None:
    """Raise unless the robot disc centred at ``point`` is clear of every obstacle.

    Touching counts as a collision: the distance must be strictly greater than the radius.
    """
    for i, obstacle in enumerate(obstacles):
        gap = obstacle.distance(point)
        if gap == 0.0:
            raise WorldError(f"{label}: {_xy(point)} is inside obstacles[{i}]")
        if gap <= robot_radius:
            raise WorldError(
                f"{label}: {_xy(point)} is within the robot radius {robot_radius!r} ft of "
                f"obstacles[{i}] (distance {gap:.6g} ft)"
            )


@dataclass(frozen=True)
class World:
    """A navigation problem: obstacles, start pose, goal, and the robot and sensor in it.

    Parameters
    ----------
    start : Pose
        Start pose ``(x, y, theta)``: ft, ft, radians; any sequence of 3 finite numbers.
    goal : Point
        Goal position ``(x, y)`` in ft; any sequence of 2 finite numbers.
    obstacles : tuple of Circle or Polygon, default ()
        Any sequence of obstacles; they may overlap each other.
    bounds : Bounds or None, default None
        The arena ``(xmin, ymin, xmax, ymax)`` in ft, or ``None`` for an unbounded plane.
    robot : RobotParams, default RobotParams()
        The disc robot; its ``radius`` sets the clearance ``start`` and ``goal`` need.
    sensor : SensorParams, default SensorParams()
        The range sensor.
    name : str or None, default None
        A label for plots and results.

    Raises
    ------
    WorldError
        On a non-finite or malformed number, a start or goal outside ``bounds``, or a start or
        goal whose robot disc (radius ``robot.radius``) touches or overlaps an obstacle.

    Examples
    --------
    >>> world = World(start=[0, 0, 0], goal=[10, 0], obstacles=[Circle((5, 3), 1.0)])
    >>> world.start, world.goal
    (Pose(x=0.0, y=0.0, theta=0.0), Point(x=10.0, y=0.0))
    >>> world == World(start=(0.0, 0.0, 0.0), goal=(10.0, 0.0), obstacles=(Circle((5, 3), 1),))
    True
    >>> pillar = Circle((5.0, 3.0), 1.0)
    >>> pillar.distance((5.0, 1.5))
    0.5
    >>> World(start=(5.0, 1.5, 0.0), goal=(10.0, 0.0), obstacles=[pillar])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.WorldError: start: (5.0, 1.5) is within the robot radius 1.0 ft of ...
    """

    start: Pose
    goal: Point
    obstacles: tuple[Obstacle, ...] = ()
    bounds: Bounds | None = None
    robot: RobotParams = field(default_factory=RobotParams)
    sensor: SensorParams = field(default_factory=SensorParams)
    name: str | None = None

    def __post_init__(self) -> None:
        start = Pose(*_numbers(self.start, "start", Pose._fields))
        goal = Point(*_numbers(self.goal, "goal", Point._fields))
        obstacles = _obstacles(self.obstacles)
        bounds = None if self.bounds is None else _bounds(self.bounds)
        if not isinstance(self.robot, RobotParams):
            raise WorldError(f"robot: must be a RobotParams, got {_show(self.robot)}")
        if not isinstance(self.sensor, SensorParams):
            raise WorldError(f"sensor: must be a SensorParams, got {_show(self.sensor)}")
        if self.name is not None and not isinstance(self.name, str):
            raise WorldError(f"name: must be a string, got {_show(self.name)}")
        for label, point in (("start", start.position), ("goal", goal)):
            if bounds is not None and not bounds.contains(point):
                raise WorldError(f"{label}: {_xy(point)} is outside the bounds {tuple(bounds)}")
            _check_clear(label, point, obstacles, self.robot.radius)
        object.__setattr__(self, "start", start)
        object.__setattr__(self, "goal", goal)
        object.__setattr__(self, "obstacles", obstacles)
        object.__setattr__(self, "bounds", bounds)

    def with_robot(self, changes: Mapping[str, float]) -> World:
        """This world with ``changes`` to its robot's fields (``--robot``:
        :func:`~ifgm_ref.core.params.changed_robot`).

        >>> World(start=(0, 0, 0), goal=(9, 0)).with_robot({"speed": 2.0}).robot.speed
        2.0
        """
        return replace(self, robot=changed_robot(self.robot, changes)) if changes else self

    @cached_property
    def segments(self) -> NDArray[np.float64]:
        """Every polygon edge of the world, an ``(n, 2, 2)`` array (empty if none)."""
        edges = [ob.edges for ob in self.obstacles if isinstance(ob, Polygon)]
        return np.concatenate(edges) if edges else np.zeros((0, 2, 2))

    @cached_property
    def circle_centers(self) -> NDArray[np.float64]:
        """Centres of the circular obstacles, an ``(m, 2)`` array."""
        centers = [ob.center for ob in self.obstacles if isinstance(ob, Circle)]
        return np.asarray(centers, dtype=np.float64).reshape(-1, 2)

    @cached_property
    def circle_radii(self) -> NDArray[np.float64]:
        """Radii of the circular obstacles, an ``(m,)`` array."""
        return np.asarray(
            [ob.radius for ob in self.obstacles if isinstance(ob, Circle)], dtype=np.float64
        )
