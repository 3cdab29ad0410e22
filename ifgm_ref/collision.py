"""Exact clearance of the robot disc swept along a segment, against a world's obstacles.

The robot's centre moves on a straight segment between two samples (see :mod:`ifgm_ref.robot`),
so the region its disc sweeps is that segment inflated by the robot radius. The disc collides
when the distance from the segment to an obstacle is less than the radius. Distances are exact
(segment-to-segment and segment-to-centre), not taken from ``shapely.buffer``, whose chords
make the inflated region slightly smaller than the true one.

A segment that starts outside every obstacle cannot enter one without crossing its boundary,
so distances to polygon *edges* suffice once the start is known to be outside (the world's
validation ensures it for the start pose; the simulator stops at the first collision).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.pose import Pose
from ifgm_ref.world import World


def _cross(ax: NDArray, ay: NDArray, bx: NDArray, by: NDArray) -> NDArray:
    return ax * by - ay * bx


def point_segment_distance(
    px: NDArray, py: NDArray, a: NDArray[np.float64], b: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Distance from points ``(px, py)`` to segments ``a -> b`` (arrays broadcast together).

    ``a`` and ``b`` have shape ``(..., 2)``; a zero-length segment is a point.

    >>> a, b = np.array([0.0, 0.0]), np.array([2.0, 0.0])
    >>> point_segment_distance(np.array([1.0, -3.0]), np.array([3.0, -4.0]), a, b).tolist()
    [3.0, 5.0]
    """
    ex, ey = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    wx, wy = px - a[..., 0], py - a[..., 1]
    length2 = ex * ex + ey * ey
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(length2 > 0.0, (wx * ex + wy * ey) / length2, 0.0)
    t = np.clip(t, 0.0, 1.0)
    return np.hypot(wx - t * ex, wy - t * ey)


def segment_segments_distance(
    p: NDArray[np.float64], q: NDArray[np.float64], edges: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Distance from the segment ``p -> q`` to each edge of an ``(n, 2, 2)`` array.

    Zero where they intersect or touch; otherwise the least of the four endpoint-to-segment
    distances, which is exact for two non-intersecting segments.

    >>> edges = np.array([[[1.0, -1.0], [1.0, 1.0]], [[3.0, 1.0], [4.0, 1.0]]])
    >>> segment_segments_distance(np.array([0.0, 0.0]), np.array([2.0, 0.0]), edges).tolist()
    [0.0, 1.4142135623730951]
    """
    a, b = edges[:, 0, :], edges[:, 1, :]
    d = np.minimum.reduce(
        [
            point_segment_distance(a[:, 0], a[:, 1], p, q),
            point_segment_distance(b[:, 0], b[:, 1], p, q),
            point_segment_distance(np.full(len(a), p[0]), np.full(len(a), p[1]), a, b),
            point_segment_distance(np.full(len(a), q[0]), np.full(len(a), q[1]), a, b),
        ]
    )
    # Proper crossings: p and q on strictly opposite sides of the edge line and vice versa.
    ex, ey = b[:, 0] - a[:, 0], b[:, 1] - a[:, 1]
    sp = _cross(ex, ey, p[0] - a[:, 0], p[1] - a[:, 1])
    sq = _cross(ex, ey, q[0] - a[:, 0], q[1] - a[:, 1])
    rx, ry = q[0] - p[0], q[1] - p[1]
    sa = _cross(rx, ry, a[:, 0] - p[0], a[:, 1] - p[1])
    sb = _cross(rx, ry, b[:, 0] - p[0], b[:, 1] - p[1])
    crossing = (sp * sq < 0.0) & (sa * sb < 0.0)
    return np.where(crossing, 0.0, d)


class ClearanceChecker:
    """Clearance of a disc of radius ``radius`` swept along segments, in one world.

    Positive clearance is free space between the disc and the nearest obstacle; negative means
    the swept disc overlaps an obstacle by that much; ``inf`` means the world has no obstacle.
    """

    def __init__(self, world: World, radius: float) -> None:
        self._edges = world.segments
        self._centers = world.circle_centers
        self._radii = world.circle_radii
        self.radius = radius

    def segment_clearance(self, start: Pose, end: Pose) -> float:
        """Clearance of the disc swept from ``start`` to ``end`` (positions only)."""
        p = np.array([start.x, start.y])
        q = np.array([end.x, end.y])
        best = np.inf
        if len(self._edges):
            best = float(segment_segments_distance(p, q, self._edges).min())
        if len(self._radii):
            to_centres = point_segment_distance(self._centers[:, 0], self._centers[:, 1], p, q)
            best = min(best, float((to_centres - self._radii).min()))
        return best - self.radius

    def pose_clearance(self, pose: Pose) -> float:
        """Clearance of the disc standing at ``pose``."""
        return self.segment_clearance(pose, pose)
