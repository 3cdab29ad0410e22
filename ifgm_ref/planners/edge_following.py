"""Following an obstacle's edge at a stand-off distance, driven by the robot's own percepts.

The Bug family's *obstacle avoidance* behaviour (section 2.1: "the robot moves around the
obstacle") and IBA's "edge detection" (section 4.1) both follow the boundary of the obstacle
in the way. The follower here keeps the nearest remembered obstacle point (see
:class:`ifgm_ref.paper.percepts.memory.PerceptMemory`) at ``standoff`` ft on a chosen side: it
heads along the tangent to the circle of that radius round the point, turned towards the
point when too far and away from it when too near. Round a convex corner the nearest point
is the corner itself, so the robot circles it; at a concave corner the nearer wall takes
over and the robot turns along it.
"""

from __future__ import annotations

import math
from enum import StrEnum

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.pose import wrap_angle

#: Largest correction of the tangent heading towards or away from the edge, radians: at 60
#: degrees the robot still makes headway along the edge while it regains the stand-off.
MAX_CORRECTION = math.pi / 3


class FollowSide(StrEnum):
    """Which side of the robot the followed edge is on (REP-103: left is +y)."""

    LEFT = "left"
    RIGHT = "right"

    @property
    def sign(self) -> int:
        """+1 for an edge on the left, -1 on the right."""
        return 1 if self is FollowSide.LEFT else -1


def follow_heading(
    position: tuple[float, float],
    points: NDArray[np.float64],
    side: FollowSide,
    *,
    standoff: float,
    gain: float,
) -> float | None:
    """The heading that follows the edge nearest to ``position`` on ``side``.

    Returns ``None`` when there is no point to follow. ``gain`` is the correction in radians
    per unit of length off the stand-off; the planners pass ``1 / r``, one radian per robot
    radius, so that the follower behaves alike at every scale (the examples: a 1 ft robot).

    Examples
    --------
    A wall along y = -2 on the right, the robot at the stand-off: head along it, +x.

    >>> wall = np.array([[x, -2.0] for x in np.linspace(-5, 5, 101)])
    >>> follow_heading((0.0, 0.0), wall, FollowSide.RIGHT, standoff=2.0, gain=1.0)
    0.0

    Too far from it: turn towards it (negative angle); too near: turn away.

    >>> follow_heading((0.0, 1.0), wall, FollowSide.RIGHT, standoff=2.0, gain=1.0) < 0.0
    True
    >>> follow_heading((0.0, -1.0), wall, FollowSide.RIGHT, standoff=2.0, gain=1.0) > 0.0
    True
    """
    if len(points) == 0:
        return None
    dx = points[:, 0] - position[0]
    dy = points[:, 1] - position[1]
    d2 = dx * dx + dy * dy
    i = int(d2.argmin())
    to_edge = math.atan2(dy[i], dx[i])
    correction = max(-MAX_CORRECTION, min(MAX_CORRECTION, gain * (math.sqrt(d2[i]) - standoff)))
    # Edge on the right: the tangent is the direction to the edge turned left by 90 degrees.
    return wrap_angle(to_edge - side.sign * (math.pi / 2.0 - correction))


def turn_speed(heading_error: float, speed: float) -> float:
    """Forward speed for a turn of ``heading_error`` radians still to go: full speed when
    aligned, slowing with the cosine, turning in place from 90 degrees on.

    >>> turn_speed(0.0, 2.0), turn_speed(math.pi / 3, 2.0), turn_speed(2.0, 2.0)
    (2.0, 1.0000000000000002, 0.0)
    """
    return speed * max(0.0, math.cos(heading_error))
