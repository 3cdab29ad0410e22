"""Scan -> obstacle points: each return "resolved into rectangular coordinates" (section 4).

Robot frame (REP-103): x forward, y left. A ray with no return (``+inf``) or an error
(``nan``) gives no point; a return nearer than ``range_min`` (``-inf``, REP 117) gives a point
at ``range_min`` along its ray, the nearest place the obstacle can be.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose


@dataclass(frozen=True, eq=False)
class ScanPoints:
    """The returns of one scan: ray index, robot-frame angle, range and ``(x, y)`` point."""

    indices: NDArray[np.intp]
    angles: NDArray[np.float64]
    ranges: NDArray[np.float64]
    xy: NDArray[np.float64]

    def __len__(self) -> int:
        return len(self.indices)


def scan_points(scan: LaserScan) -> ScanPoints:
    """Resolve every return of ``scan`` into a robot-frame point.

    >>> scan = LaserScan(-0.5, 0.5, 0.5, 0.0, 10.0, [math.inf, 2.0, -math.inf])
    >>> pts = scan_points(scan)
    >>> pts.indices.tolist(), pts.xy.round(3).tolist()
    ([1, 2], [[2.0, 0.0], [0.0, 0.0]])
    """
    ranges = np.where(scan.ranges == -np.inf, scan.range_min, scan.ranges)
    keep = np.isfinite(ranges)
    indices = keep.nonzero()[0]
    r = ranges[indices]
    cos, sin = scan.directions
    xy = np.empty_like(r, shape=(len(r), 2))  # like r: an ndarray subclass survives
    xy[:, 0] = r * cos[indices]
    xy[:, 1] = r * sin[indices]
    return ScanPoints(indices, scan.angles[indices], r, xy)


def to_world(xy: NDArray[np.float64], pose: Pose) -> NDArray[np.float64]:
    """Robot-frame points ``(k, 2)`` -> world-frame points, given the robot's pose.

    >>> to_world(np.array([[1.0, 0.0]]), Pose(2.0, 3.0, math.pi / 2)).round(12).tolist()
    [[2.0, 4.0]]
    """
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    x, y = xy[:, 0], xy[:, 1]
    world = np.empty_like(xy)
    world[:, 0] = pose.x + c * x - s * y
    world[:, 1] = pose.y + s * x + c * y
    return world


def point_to_world(xy: tuple[float, float], pose: Pose) -> Point:
    """One robot-frame point in the world frame: :func:`to_world`'s arithmetic on two floats,
    the same to the bit (``tests/test_percepts.py``), without the arrays' cost.

    >>> point_to_world((1.0, 0.0), Pose(2.0, 3.0, 0.0))
    Point(x=3.0, y=3.0)
    """
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    return Point(pose.x + c * xy[0] - s * xy[1], pose.y + s * xy[0] + c * xy[1])
