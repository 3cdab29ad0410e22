"""The world: bounds, polygon and circle obstacles, a start pose and a goal.

The paper's worlds (section 5) hold "obstacles of simple but different shapes" and "critical
shaped" U and H obstacles. Obstacles here are simple polygons (any shape, U and H included)
and circles. Units are feet; the start heading is in radians.

This module knows the map; planners never import it (section 3: "No priori information or map
of the environment is required").
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import NamedTuple

import numpy as np
import shapely
from numpy.typing import NDArray

from ifgm_ref.params import RobotParams, SensorParams
from ifgm_ref.pose import Point, Pose


class Bounds(NamedTuple):
    """The rectangular arena ``[xmin, xmax] x [ymin, ymax]``, in ft."""

    xmin: float
    ymin: float
    xmax: float
    ymax: float


@dataclass(frozen=True)
class Circle:
    """A circular obstacle: centre ``(x, y)`` and radius, in ft."""

    center: tuple[float, float]
    radius: float

    @property
    def geometry(self) -> shapely.Geometry:
        """The exact disc as far as shapely allows (a fine polygon; use for plots only)."""
        return shapely.Point(self.center).buffer(self.radius, quad_segs=64)


@dataclass(frozen=True)
class Polygon:
    """A simple-polygon obstacle given by its vertices ``((x, y), ...)`` in order, in ft."""

    vertices: tuple[tuple[float, float], ...]

    @property
    def geometry(self) -> shapely.Polygon:
        """The obstacle as a shapely polygon (exact)."""
        return shapely.Polygon(self.vertices)

    @property
    def edges(self) -> NDArray[np.float64]:
        """The boundary edges as an ``(n, 2, 2)`` array of ``(start, end)`` points."""
        pts = np.asarray(self.vertices, dtype=np.float64)
        return np.stack([pts, np.roll(pts, -1, axis=0)], axis=1)


Obstacle = Circle | Polygon


@dataclass(frozen=True)
class World:
    """A navigation problem: obstacles, start pose, goal, and the robot and sensor in it."""

    start: Pose
    goal: Point
    obstacles: tuple[Obstacle, ...] = ()
    bounds: Bounds | None = None
    robot: RobotParams = field(default_factory=RobotParams)
    sensor: SensorParams = field(default_factory=SensorParams)
    name: str | None = None

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
