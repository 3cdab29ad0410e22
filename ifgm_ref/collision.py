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

import math

import numpy as np

from ifgm_ref.pose import Pose
from ifgm_ref.world import World


def point_segment_distance(
    px: float, py: float, ax: float, ay: float, bx: float, by: float
) -> float:
    """Distance from the point ``(px, py)`` to the segment ``(ax, ay) -> (bx, by)``.

    A zero-length segment is a point.

    >>> point_segment_distance(1.0, 3.0, 0.0, 0.0, 2.0, 0.0)
    3.0
    >>> point_segment_distance(-3.0, -4.0, 0.0, 0.0, 2.0, 0.0)
    5.0
    >>> point_segment_distance(1.0, 1.0, 0.0, 0.0, 0.0, 0.0) == math.sqrt(2.0)
    True
    """
    ex, ey = bx - ax, by - ay
    wx, wy = px - ax, py - ay
    length2 = ex * ex + ey * ey
    t = 0.0 if length2 == 0.0 else min(max((wx * ex + wy * ey) / length2, 0.0), 1.0)
    return math.hypot(wx - t * ex, wy - t * ey)


def segment_distance(
    p: tuple[float, float], q: tuple[float, float], a: tuple[float, float], b: tuple[float, float]
) -> float:
    """Distance between the segments ``p -> q`` and ``a -> b``.

    Zero where they cross or touch; otherwise the least of the four endpoint-to-segment
    distances, which is exact for two segments that do not cross.

    >>> segment_distance((0.0, 0.0), (2.0, 0.0), (1.0, -1.0), (1.0, 1.0))
    0.0
    >>> segment_distance((0.0, 0.0), (2.0, 0.0), (3.0, 1.0), (4.0, 1.0)) == math.sqrt(2.0)
    True
    """
    (px, py), (qx, qy), (ax, ay), (bx, by) = p, q, a, b
    # Proper crossing: p and q strictly either side of the line ab, and a and b of the line pq.
    ex, ey, rx, ry = bx - ax, by - ay, qx - px, qy - py
    sp = ex * (py - ay) - ey * (px - ax)
    sq = ex * (qy - ay) - ey * (qx - ax)
    sa = rx * (ay - py) - ry * (ax - px)
    sb = rx * (by - py) - ry * (bx - px)
    if sp * sq < 0.0 and sa * sb < 0.0:
        return 0.0
    return min(
        point_segment_distance(ax, ay, px, py, qx, qy),
        point_segment_distance(bx, by, px, py, qx, qy),
        point_segment_distance(px, py, ax, ay, bx, by),
        point_segment_distance(qx, qy, ax, ay, bx, by),
    )


class ClearanceChecker:
    """Clearance of a disc of radius ``radius`` swept along segments, in one world.

    Positive clearance is free space between the disc and the nearest obstacle; negative means
    the swept disc overlaps an obstacle by that much; ``inf`` means the world has no obstacle.
    """

    def __init__(self, world: World, radius: float) -> None:
        self._edges = world.segments
        # Contiguous 1-D columns: the per-step pass below is a dozen small array operations.
        self._sx, self._sy = (np.ascontiguousarray(c) for c in self._edges[:, 0, :].T)
        self._ex, self._ey = (
            np.ascontiguousarray(c) for c in (self._edges[:, 1] - self._edges[:, 0]).T
        )
        self._length2 = self._ex * self._ex + self._ey * self._ey
        self._cx, self._cy = (np.ascontiguousarray(c) for c in world.circle_centers.T)
        self._radii = world.circle_radii
        self.radius = radius

    def segment_clearance(self, start: Pose, end: Pose) -> float:
        """Clearance of the disc swept from ``start`` to ``end`` (positions only).

        Only obstacles that can hold the minimum are measured exactly. Every point of the
        path is within ``h`` (its half-length) of its midpoint ``m``, so its distance to an
        obstacle lies within ``d(m) -+ h``; an obstacle whose lower bound ``d(m) - h`` exceeds
        the least upper bound cannot be the nearest. ``d(m)`` is computed for all obstacles at
        once, the exact segment distance for the few that remain.
        """
        p, q = (start.x, start.y), (end.x, end.y)
        mx, my = 0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])
        h = 0.5 * math.hypot(q[0] - p[0], q[1] - p[1])
        best = bound = math.inf
        if len(self._sx):
            wx, wy = mx - self._sx, my - self._sy
            t = (wx * self._ex + wy * self._ey) / self._length2
            t = np.minimum(np.maximum(t, 0.0), 1.0)
            edge_mid = np.hypot(wx - t * self._ex, wy - t * self._ey)
            bound = float(edge_mid.min()) + h
        if len(self._cx):
            circle_mid = np.hypot(self._cx - mx, self._cy - my) - self._radii
            bound = min(bound, float(circle_mid.min()) + h)
            near = circle_mid - h <= bound
            for cx, cy, r in zip(
                self._cx[near].tolist(),
                self._cy[near].tolist(),
                self._radii[near].tolist(),
                strict=True,
            ):
                best = min(best, point_segment_distance(cx, cy, *p, *q) - r)
        if len(self._sx):
            for a, b in self._edges[edge_mid - h <= bound].tolist():
                best = min(best, segment_distance(p, q, a, b))
        return best - self.radius

    def pose_clearance(self, pose: Pose) -> float:
        """Clearance of the disc standing at ``pose``."""
        return self.segment_clearance(pose, pose)
