"""Poses and points in the world frame (REP-103: x forward/east, y left/north, angles CCW).

Lengths are in feet, angles in radians, as everywhere in this package.
"""

from __future__ import annotations

import math
from typing import NamedTuple, TypeAlias


class Point(NamedTuple):
    """A position in the world frame, in feet."""

    x: float
    y: float


class Pose(NamedTuple):
    """A robot pose: position in feet, heading ``theta`` in radians counter-clockwise from +x."""

    x: float
    y: float
    theta: float

    @property
    def position(self) -> Point:
        """The position part of the pose."""
        return Point(self.x, self.y)


def wrap_angle(angle: float) -> float:
    """Wrap ``angle`` (radians) into ``[-pi, pi)``.

    Examples
    --------
    >>> wrap_angle(3 * math.pi / 2)
    -1.5707963267948966
    >>> wrap_angle(math.pi)
    -3.141592653589793
    >>> wrap_angle(0.0)
    0.0
    """
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


#: A position as a tuple whose first two fields are ``x`` and ``y``: a :class:`Point`, a
#: :class:`Pose` (its heading not read) or a plain ``(x, y)`` pair.
PointLike: TypeAlias = tuple[float, float, *tuple[float, ...]]


def distance(a: PointLike, b: PointLike) -> float:
    """Euclidean distance between two positions given as ``(x, y, ...)``.

    >>> distance((0.0, 0.0), (3.0, 4.0))
    5.0
    >>> distance(Pose(0.0, 0.0, 1.0), Point(3.0, 4.0))  # a pose's heading is not read
    5.0
    """
    return math.hypot(b[0] - a[0], b[1] - a[1])
