"""Exact clearance of the robot disc swept along a segment, against a world's obstacles.

The robot's centre moves on a straight segment between two samples (see :mod:`ifgm_ref.sim.robot`),
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
from numpy.typing import NDArray

from ifgm_ref.core.pose import Pose
from ifgm_ref.sim.world import World

#: How far, in robot radii, a path may stray from the point the obstacle order was computed
#: at before it is computed again (dimensionless): fewer rebuilds against more obstacles
#: measured per step (measured: ``docs/benchmark.md``, "The simulator's kernels").
_REUSE = 4.0
#: Relative slack of the pruning test (dimensionless, times the coordinates' magnitude): far
#: above the few-ulp rounding of the distances it compares, far below any real gap.
_SLACK = 1e-9


def _offset_distance(wx: float, wy: float, ex: float, ey: float, length2: float) -> float:
    """Distance from the point ``w`` to the segment ``0 -> e`` (``length2 = ex*ex + ey*ey``).

    The formula of :func:`point_segment_distance` with the segment moved to the origin; the
    clamped ends skip a product by 0 or 1, which changes no value (``hypot`` ignores the sign
    of a zero).
    """
    if length2 == 0.0:
        return math.hypot(wx, wy)
    t = (wx * ex + wy * ey) / length2
    if t <= 0.0:
        return math.hypot(wx, wy)
    if t >= 1.0:
        return math.hypot(wx - ex, wy - ey)
    return math.hypot(wx - t * ex, wy - t * ey)


def point_segment_distance(
    px: float, py: float, ax: float, ay: float, bx: float, by: float
) -> float:
    """Distance from the point ``(px, py)`` to the segment ``(ax, ay) -> (bx, by)``.

    The foot of the perpendicular, ``t = (w . e) / |e|^2`` along ``e = B - A`` with ``w = P -
    A``, clamped to ``[0, 1]``; a zero-length segment is a point.

    >>> point_segment_distance(1.0, 3.0, 0.0, 0.0, 2.0, 0.0)
    3.0
    >>> point_segment_distance(-3.0, -4.0, 0.0, 0.0, 2.0, 0.0)
    5.0
    >>> point_segment_distance(1.0, 1.0, 0.0, 0.0, 0.0, 0.0) == math.sqrt(2.0)
    True
    """
    ex, ey = bx - ax, by - ay
    return _offset_distance(px - ax, py - ay, ex, ey, ex * ex + ey * ey)


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
    ex, ey, rx, ry = bx - ax, by - ay, qx - px, qy - py
    edge = (ax, ay, bx, by, ex, ey, ex * ex + ey * ey)
    return _edge_distance(px, py, qx, qy, rx, ry, rx * rx + ry * ry, edge)


def _edge_distance(
    px: float,
    py: float,
    qx: float,
    qy: float,
    rx: float,
    ry: float,
    length2: float,
    edge: tuple[float, ...] | list[float],
) -> float:
    """:func:`segment_distance` from ``p -> q`` (vector ``r``, ``length2 = |r|^2``) to ``edge``.

    ``edge`` is ``(ax, ay, bx, by, ex, ey, |e|^2)`` with ``e = b - a``; the differences the
    crossing test and the four endpoint distances share are computed once.
    """
    ax, ay, bx, by, ex, ey, edge2 = edge
    wax, way, wbx, wby = ax - px, ay - py, bx - px, by - py  # a and b from p
    upx, upy, uqx, uqy = px - ax, py - ay, qx - ax, qy - ay  # p and q from a
    # Proper crossing: p and q strictly either side of the line ab, and a and b of the line pq.
    if (ex * upy - ey * upx) * (ex * uqy - ey * uqx) < 0.0 and (rx * way - ry * wax) * (
        rx * wby - ry * wbx
    ) < 0.0:
        return 0.0
    return min(
        _offset_distance(wax, way, rx, ry, length2),
        _offset_distance(wbx, wby, rx, ry, length2),
        _offset_distance(upx, upy, ex, ey, edge2),
        _offset_distance(uqx, uqy, ex, ey, edge2),
    )


class ClearanceChecker:
    """Clearance of a disc of radius ``radius`` swept along segments, in one world.

    Positive clearance is free space between the disc and the nearest obstacle; negative means
    the swept disc overlaps an obstacle by that much; ``inf`` means the world has no obstacle.

    The clearance is, bit for bit, the least :func:`segment_distance` to an edge or
    :func:`point_segment_distance` to a circle's centre less its radius, minus ``radius``;
    :meth:`segment_clearance` measures only the obstacles that can hold that minimum.

    Examples
    --------
    >>> from ifgm_ref.core.pose import Point
    >>> from ifgm_ref.sim.world import Circle, Polygon
    >>> square = Polygon(((0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)))
    >>> obstacles = (square, Circle((9.0, 2.0), 1.0))
    >>> world = World(start=Pose(-5, 2, 0), goal=Point(9, 9), obstacles=obstacles)
    >>> checker = ClearanceChecker(world, 0.5)
    >>> checker.segment_clearance(Pose(-5, 2, 0), Pose(-3, 2, 0))  # 3 ft from the left face
    2.5
    >>> checker.pose_clearance(Pose(6, 2, 0))  # 2 ft from the square and from the circle
    1.5
    >>> checker.segment_clearance(Pose(-3, 2, 0), Pose(1, 2, 0))  # crosses the left face
    -0.5
    """

    def __init__(self, world: World, radius: float) -> None:
        segs = world.segments
        ends = segs[:, 1] - segs[:, 0]
        # Contiguous columns for the vectorised rebuild; numpy's elementwise - * + round
        # exactly as Python's, so the edge rows below equal what segment_distance computes.
        self._ax, self._ay = (np.ascontiguousarray(c) for c in segs[:, 0, :].T)
        self._ex, self._ey = (np.ascontiguousarray(c) for c in ends.T)
        self._length2 = self._ex * self._ex + self._ey * self._ey
        self._edges: list[list[float]] = np.column_stack(
            [segs[:, 0], segs[:, 1], ends, self._length2]
        ).tolist()
        self._cx, self._cy = (np.ascontiguousarray(c) for c in world.circle_centers.T)
        self._radii = world.circle_radii
        self._circles: list[list[float]] = np.column_stack(
            [world.circle_centers, self._radii]
        ).tolist()
        self.radius = radius
        self._reuse = _REUSE * radius
        # The scale of every coordinate (ft), hence of every rounding error in the pruning.
        self._extent = self._reuse + float(
            max(np.abs(segs).max(initial=0.0), np.abs(world.circle_centers).max(initial=0.0))
            + self._radii.max(initial=0.0)
        )
        # The cache: the point it was built at, the pruning slack there, and the edges and
        # circles sorted by their distance from that point.
        self._origin = (math.inf, math.inf)
        self._slack = 0.0
        self._edge_order: list[tuple[float, list[float]]] = []
        self._circle_order: list[tuple[float, list[float]]] = []

    def segment_clearance(self, start: Pose, end: Pose) -> float:
        """Clearance of the disc swept from ``start`` to ``end`` (positions only).

        Only obstacles that can hold the minimum are measured exactly. The obstacles are kept
        sorted by their distance ``k`` from a point ``O`` (recomputed when the path strays more
        than ``_REUSE`` radii from ``O``); every point of the path is within ``rho`` of ``O``,
        so an obstacle is at least ``k - rho`` from it. Once ``k - rho`` exceeds the least
        distance measured so far (by more than ``_SLACK`` times the coordinates' magnitude,
        which bounds the rounding of ``k``, ``rho`` and the measured distances), that obstacle
        and every later one are farther than the minimum: skipping them leaves the same float.
        An edge before that point is also skipped, alone, when its distance from the path's
        midpoint exceeds the minimum by more than the path's half-length (and the slack): the
        same bound from a nearer point, at a quarter of the cost of the exact distance.
        """
        px, py, qx, qy = start.x, start.y, end.x, end.y
        x0, y0 = self._origin
        rho = max(math.hypot(px - x0, py - y0), math.hypot(qx - x0, qy - y0))
        if rho > self._reuse:
            x0, y0 = 0.5 * (px + qx), 0.5 * (py + qy)
            self._sort_obstacles(x0, y0)
            rho = max(math.hypot(px - x0, py - y0), math.hypot(qx - x0, qy - y0))
        limit = rho + self._slack
        rx, ry = qx - px, qy - py
        length2 = rx * rx + ry * ry
        best = math.inf
        for key, (cx, cy, r) in self._circle_order:
            if key > best + limit:
                break
            d = _offset_distance(cx - px, cy - py, rx, ry, length2) - r
            if d < best:
                best = d
        mx, my = 0.5 * (px + qx), 0.5 * (py + qy)
        near = 0.5 * math.sqrt(length2) + self._slack  # every point of the path within this of m
        for key, edge in self._edge_order:
            if key > best + limit:
                break
            ax, ay, _, _, ex, ey, edge2 = edge
            if _offset_distance(mx - ax, my - ay, ex, ey, edge2) > best + near:
                continue  # this edge only: farther than the minimum, as seen from m
            d = _edge_distance(px, py, qx, qy, rx, ry, length2, edge)
            if d < best:
                best = d
        return best - self.radius

    def pose_clearance(self, pose: Pose) -> float:
        """Clearance of the disc standing at ``pose``."""
        return self.segment_clearance(pose, pose)

    def _sort_obstacles(self, x0: float, y0: float) -> None:
        """Sort the edges and circles by their distance from ``(x0, y0)``, the new cache point.

        These distances only order and prune (with ``_slack``); no clearance is taken from
        them, so numpy's rounding here cannot change a result.
        """
        self._origin = (x0, y0)
        self._slack = _SLACK * (1.0 + self._extent + abs(x0) + abs(y0))
        wx, wy = x0 - self._ax, y0 - self._ay
        dot = wx * self._ex + wy * self._ey
        t = np.divide(dot, self._length2, out=np.zeros_like(dot), where=self._length2 > 0.0)
        np.clip(t, 0.0, 1.0, out=t)
        edge_keys = np.hypot(wx - t * self._ex, wy - t * self._ey)
        circle_keys = np.hypot(self._cx - x0, self._cy - y0) - self._radii
        self._edge_order = _sorted_rows(edge_keys, self._edges)
        self._circle_order = _sorted_rows(circle_keys, self._circles)


def _sorted_rows(
    keys: NDArray[np.float64], rows: list[list[float]]
) -> list[tuple[float, list[float]]]:
    """``(key, row)`` pairs in increasing order of key."""
    order = np.argsort(keys, kind="stable")
    return list(zip(keys[order].tolist(), [rows[i] for i in order.tolist()], strict=True))
