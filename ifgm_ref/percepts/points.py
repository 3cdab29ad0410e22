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

from ifgm_ref.laserscan import LaserScan
from ifgm_ref.pose import Pose


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


def to_robot(xy: NDArray[np.float64], pose: Pose) -> NDArray[np.float64]:
    """World-frame points ``(k, 2)`` -> robot-frame points (inverse of :func:`to_world`).

    >>> to_robot(np.array([[2.0, 4.0]]), Pose(2.0, 3.0, math.pi / 2)).round(12).tolist()
    [[1.0, 0.0]]
    """
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    dx, dy = xy[:, 0] - pose.x, xy[:, 1] - pose.y
    return np.column_stack([c * dx + s * dy, -s * dx + c * dy])
