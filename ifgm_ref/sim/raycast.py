"""Exact 2-D ray casting against line segments and discs: the range sensor's numeric kernel.

The paper's robot sees its surroundings through one long-range IR ranger swept over 135 degrees
by a stepper motor (section 4, Figure 2): "An Improved Algorithm for Collision Avoidance in
Environments Having U and H Shaped Obstacles". This module answers the geometric question behind
every reading -- how far along a ray is the first obstacle? -- for many rays at once. It imports
only numpy; :mod:`ifgm_ref.sim.sensor` turns its answers into a
:class:`~ifgm_ref.core.laserscan.LaserScan`.

Geometry
--------
A ray is ``O + t d`` with origin ``O``, unit direction ``d = (cos a, sin a)`` and ``t >= 0``.
Points are taken relative to ``O``; ``cross(u, v) = u_x v_y - u_y v_x``.

*Segments.* For a segment ``AB`` let ``a = A - O``, ``b = B - O``, ``s_A = cross(d, a)``,
``s_B = cross(d, b)`` (the side of the ray's line each endpoint is on) and ``c = cross(a, b)``.
The ray's line meets the closed segment iff ``s_A s_B <= 0``, at

    ``t = c / (s_B - s_A)``,

which is a hit in front of the sensor iff ``t >= 0``. The kernel keeps ``q = 1 / t =
(s_B - s_A) / c`` and takes the largest ``q`` per ray: no division by zero (a ray parallel to
the segment has ``s_B = s_A``, so ``q = 0``, "no hit"), and rays behind (``q < 0``) drop out.

The side value ``s`` of each distinct vertex is computed *once* per ray (one product over the
vertices) and shared by every edge that ends there, so a ray through a polygon vertex cannot
slip between its two edges whatever the rounding: the test is watertight, and hits at segment
endpoints count.

An edge whose line passes through ``O`` (``c == 0``) is handled apart: if ``O`` lies on the
closed segment every ray reads 0; otherwise only a ray exactly along the edge meets it, at the
nearer endpoint (which the neighbouring edge of a polygon also reports).

*Circles.* For a circle of centre ``C`` and radius ``r`` let ``c = C - O``, ``p = d . c`` and
``h = cross(d, c)``. A sensor outside the disc (``g = |c|^2 - r^2 > 0``) sees it iff
``h^2 <= r^2`` and ``p > 0``, at the nearer root ``t = p - sqrt(r^2 - h^2)``, evaluated as
``g / (p + sqrt(r^2 - h^2))`` to avoid cancellation. A ray touching the circle (tangent) hits.

Choices at the boundary
-----------------------
* Circles are solid: a sensor inside or on a circle reads 0 on every ray.
* Polygons are given by their edges only, so the kernel sees their boundaries: a sensor on an
  edge reads 0 on every ray, but a sensor strictly inside a polygon reads the distance to its
  boundary. Worlds keep the robot outside every obstacle, so this does not arise in a valid run.
* A hit at exactly ``max_range`` counts; beyond it the ray reads ``inf``.

Cost
----
Elements that cannot come within ``max_range`` are culled first (the edges' cull is cached
round the last origin, ``_REUSE``), and circles are tested only against the rays within
their angular half-width when there are many (circle, ray) pairs. Neither changes a reading:
a cast's result is the same to the bit and does not depend on the casts before it. How each
works and what it saves: ``docs/benchmark.md``, "The simulator's kernels".
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ifgm_ref.core.intervals import members

__all__ = ["RayCaster", "RayFan", "cast_rays"]

#: Relative slack of the culling test (dimensionless): far above the few-ulp rounding of the
#: distances it compares, far below anything that would keep many more elements.
_MARGIN = 1.0 + 1e-9


#: Circles are tested only against the rays facing them (:func:`_facing_pairs`) from this
#: many (circle, ray) pairs: below it, testing them all costs less than choosing.
_PAIRS_FROM = 4096
#: Slack of the facing test, rad: far above the rounding of the bearings and of ``h``
#: (1e-16 relative), far below a ray spacing (a 720-ray LiDAR's is 0.0065 rad).
_FACING_MARGIN = 1e-9
#: A circle this close to O in radii (``r / |c|`` above it) is tested against every ray.
_NEAR_CIRCLE = 0.99

#: How far the origin may move before the edges are culled again, in ``max_range``\ s
#: (dimensionless): a local cull keeps every edge within reach of that disc; fewer culls
#: against more edges per cast (measured: ``docs/benchmark.md``, "The simulator's kernels").
_REUSE = 0.1


class _NearEdges(NamedTuple):
    """The edges a cull kept: their vertices, the vertex numbers of their ends, their number,
    and the radius round the cull's origin it serves."""

    #: Vertices used by the kept edges, row 0 the x, row 1 the y, shape (2, v).
    points: NDArray[np.float64]
    #: Indices into ``points``: the start of every kept edge, then the end of every one, (2n,).
    ends: NDArray[np.intp]
    #: Number of kept edges ``n``.
    edges: int
    #: How far from the cull's origin a cast may be and still use it, ft.
    radius: float


class RayFan(NamedTuple):
    """Rays at fixed angles relative to a heading, e.g. the steps of a swept sensor.

    Build with :meth:`of`; cast with :meth:`RayCaster.cast_fan`.
    """

    #: Relative angles, radians, shape (k,).
    angles: NDArray[np.float64]
    #: Their unit directions: row 0 the cosines, row 1 the sines, shape (2, k).
    unit: NDArray[np.float64]

    @classmethod
    def of(cls, angles: ArrayLike) -> RayFan:
        """The fan of rays at ``angles`` (radians, relative to the heading).

        >>> RayFan.of([0.0, math.pi / 2]).unit.round(12).tolist()
        [[1.0, 0.0], [0.0, 1.0]]
        """
        relative = np.array(angles, dtype=np.float64).reshape(-1)
        unit = np.stack([np.cos(relative), np.sin(relative)])
        relative.setflags(write=False)
        unit.setflags(write=False)
        return cls(relative, unit)


class RayCaster:
    """Cast rays against a fixed set of segments and circles, up to a fixed range.

    Build once per world (it indexes the vertices and precomputes the culling data), then call
    :meth:`cast` once per scan.

    Parameters
    ----------
    segments : array_like, shape (n, 2, 2)
        Line segments as ``(start, end)`` points, e.g. every polygon edge of a world.
    circle_centers : array_like, shape (m, 2)
        Centres of the circles.
    circle_radii : array_like, shape (m,)
        Radii of the circles, each > 0.
    max_range : float
        Largest distance reported; farther hits read ``inf``. Must be finite and > 0.

    Attributes
    ----------
    max_range : float
        The range given, as a float.

    Raises
    ------
    ValueError
        If an array has the wrong shape or a non-finite value, a radius is not > 0, or
        ``max_range`` is not a finite number > 0.

    Examples
    --------
    A 2 x 2 ft square whose near face is 5 ft ahead, and a circle of radius 1 ft centred 3 ft to
    the left:

    >>> square = [((5, -1), (5, 1)), ((5, 1), (7, 1)), ((7, 1), (7, -1)), ((7, -1), (5, -1))]
    >>> caster = RayCaster(square, [(0, 3)], [1.0], max_range=10.0)
    >>> caster.cast((0.0, 0.0), [0.0, math.pi / 2, math.pi]).tolist()
    [5.0, 2.0, inf]

    A ray through a vertex hits it; a ray along an edge hits the edge's nearer end:

    >>> caster.cast((0.0, 1.0), [0.0]).tolist()
    [5.0]
    >>> caster.cast((3.0, -1.0), [0.0]).tolist()
    [2.0]

    A sensor inside a circle or on an edge reads 0 on every ray; out of range reads ``inf``:

    >>> caster.cast((0.0, 3.5), [0.0, 1.0]).tolist()
    [0.0, 0.0]
    >>> caster.cast((5.0, 0.0), [math.pi, 0.0]).tolist()
    [0.0, 0.0]
    >>> caster.cast((-20.0, 0.0), [0.0]).tolist()
    [inf]
    """

    __slots__ = (
        "_centers",
        "_circle_reach2",
        "_edge_mids",
        "_edge_reach",
        "_edges",
        "_near",
        "_origin",
        "_points",
        "_q_floor",
        "_radii2",
        "_reuse",
        "_turned",
        "max_range",
    )

    def __init__(
        self,
        segments: ArrayLike,
        circle_centers: ArrayLike,
        circle_radii: ArrayLike,
        max_range: float,
    ) -> None:
        segs = _as_array("segments", segments, (-1, 2, 2))
        centers = _as_array("circle_centers", circle_centers, (-1, 2))
        radii = _as_array("circle_radii", circle_radii, (-1,))
        if len(radii) != len(centers):
            raise ValueError(
                f"len(circle_radii)={len(radii)}, but should be len(circle_centers)={len(centers)}"
            )
        if (radii <= 0).any():
            raise ValueError(f"`circle_radii` must be > 0, got {radii.tolist()!r}")
        if (
            isinstance(max_range, bool)
            or not isinstance(max_range, int | float)
            or not (0 < max_range < math.inf)
        ):
            raise ValueError(f"`max_range` must be a finite number > 0, got {max_range!r}")
        self.max_range = float(max_range)
        # Each distinct vertex once, so each side value is computed once (watertightness);
        # _edges[0] and _edges[1] index the start and end point of every segment.
        points, inverse = np.unique(segs.reshape(-1, 2), axis=0, return_inverse=True)
        self._points = np.ascontiguousarray(points.T)
        self._edges = np.ascontiguousarray(inverse.reshape(-1, 2).T)
        # Culling: a segment lies in the disc centred on its midpoint with radius half its
        # length, so no ray from O hits it within max_range if |mid - O| > max_range + half.
        ends = segs[:, 1] - segs[:, 0]
        mids = segs[:, 0] + 0.5 * ends
        # The margin keeps rounding in the test from dropping an edge hit at exactly max_range.
        self._edge_mids = mids[:, 0] + 1j * mids[:, 1]
        self._edge_reach = (self.max_range + 0.5 * np.hypot(ends[:, 0], ends[:, 1])) * _MARGIN
        self._centers = centers
        self._radii2 = radii * radii
        self._circle_reach2 = ((self.max_range + radii) * _MARGIN) ** 2
        # Every 1 / t is raised to at least this before inverting, so a ray with no hit gets a
        # finite t = 2 max_range (no division by zero), which the cut at max_range makes inf.
        self._q_floor = 0.5 / self.max_range
        # The cache of _near_edges: the point it was culled at and what it kept.
        self._reuse = _REUSE * self.max_range
        self._origin = (math.inf, math.inf)
        self._near = _NearEdges(self._points, self._edges.reshape(-1), 0, -1.0)
        # The cache of cast_fan: the last heading, its sign, the fan and the rays it turned.
        self._turned: tuple[float, float, RayFan | None, NDArray[np.float64]] = (
            math.nan,
            1.0,
            None,
            np.empty((3, 0)),
        )

    def cast(self, origin: tuple[float, float], angles: ArrayLike) -> NDArray[np.float64]:
        """Return the distance along each ray from ``origin`` to the first hit.

        Parameters
        ----------
        origin : tuple of float
            The rays' common start point ``(x, y)``, in the obstacles' frame.
        angles : array_like, shape (k,)
            Absolute ray directions, radians counter-clockwise from +x.

        Returns
        -------
        ndarray, shape (k,)
            Distance to the first segment or circle on each ray, ``inf`` if none lies within
            ``max_range``; 0 on every ray if ``origin`` is on a segment or in a circle.
        """
        angles = np.asarray(angles, dtype=np.float64)
        # Rows: (-sin, cos) is the normal n of each ray (s = n . p = cross(d, p)),
        # (cos, sin) its direction d (p . d = distance ahead).
        rows = np.empty((3, angles.shape[0]))
        np.sin(angles, out=rows[2])
        np.cos(angles, out=rows[1])
        np.negative(rows[2], out=rows[0])
        return self._cast_rows(float(origin[0]), float(origin[1]), rows)

    def cast_fan(
        self, origin: tuple[float, float], heading: float, fan: RayFan
    ) -> NDArray[np.float64]:
        """Like :meth:`cast` for the rays at ``heading + fan.angles``, a little faster.

        The directions are the fan's, turned by ``heading`` (one small matrix product instead
        of a sine and a cosine per ray); they agree with ``cos``/``sin`` of the summed angles to
        a few ulps. They are kept for the next call: the same heading (the same float, sign
        included) and the same fan reuse them as computed, so the result is the same.

        Examples
        --------
        >>> caster = RayCaster([((5, -5), (5, 5))], [], [], max_range=10.0)
        >>> fan = RayFan.of([-math.pi / 4, 0.0, math.pi / 4])
        >>> caster.cast_fan((0.0, 0.0), math.pi / 4, fan).round(12).tolist()
        [5.0, 7.071067811865, inf]
        """
        last, sign, last_fan, rows = self._turned
        if not (heading == last and math.copysign(1.0, heading) == sign and fan is last_fan):
            c, s = math.cos(heading), math.sin(heading)  # -0.0: the sine keeps the sign
            rows = dot2(np.array(((-s, -c), (c, -s), (s, c))), fan.unit)
            rows.setflags(write=False)  # shared by the casts at this heading
            self._turned = (heading, math.copysign(1.0, heading), fan, rows)
        return self._cast_rows(float(origin[0]), float(origin[1]), rows)

    def _cast_rows(self, x: float, y: float, rows: NDArray[np.float64]) -> NDArray[np.float64]:
        """Distances along the rays whose normals and directions are ``rows`` (see cast)."""
        q = self._segment_inverse_distances(x, y, rows)
        if q is not None and len(self._centers):
            q = self._circle_inverse_distances(x, y, rows, q)
        if q is None:
            return np.zeros(rows.shape[1])
        t = np.reciprocal(q, out=q)
        t[t > self.max_range] = np.inf
        return t

    def _segment_inverse_distances(
        self, x: float, y: float, rows: NDArray[np.float64]
    ) -> NDArray[np.float64] | None:
        """``1 / t`` of the nearest segment hit on each ray, at least ``_q_floor`` (no hit).

        ``None`` if O is on a segment. Arrays are laid out ``(edges, rays)``, so that the
        reduction over edges runs along contiguous rays.
        """
        x0, y0 = self._origin
        moved = math.hypot(x - x0, y - y0)
        if moved > self._near.radius:
            self._cull(x, y, local=moved <= 2.0 * self._reuse)
        points, ends, n, _ = self._near
        if not n:
            return np.full(rows.shape[1], self._q_floor)
        rel = points - np.array([[x], [y]])  # (2, vertices)
        side = dot2(rel.T, rows[:2])  # side[v, i] = cross(d_i, P_v - O): once per vertex
        ab = rel.take(ends, axis=1)
        cross_ab = ab[0, :n] * ab[1, n:] - ab[1, :n] * ab[0, n:]
        along: NDArray[np.float64] | None = None
        if np.count_nonzero(cross_ab) != n:
            on_line = cross_ab == 0.0
            a, b = ab[:, :n][:, on_line], ab[:, n:][:, on_line]
            # O on the closed segment iff a and b point apart (or one is zero).
            if (a[0] * b[0] + a[1] * b[1] <= 0.0).any():
                return None
            both = np.concatenate([ends[:n][on_line], ends[n:][on_line]])
            along = _along_edge_inverse_distances(rel[:, both], side[both], rows)
            keep = np.flatnonzero(~on_line)
            ends = np.concatenate([ends[:n][keep], ends[n:][keep]])
            cross_ab = cross_ab[keep]
            n = keep.shape[0]
            if not n:
                return np.maximum(along, self._q_floor, out=along)
        s_ab = side.take(ends, axis=0)
        s_a, s_b = s_ab[:n], s_ab[n:]
        crossing = s_a * s_b <= 0.0
        q = np.subtract(s_b, s_a, out=s_b)
        q /= cross_ab[:, None]
        q *= crossing
        out: NDArray[np.float64] = q.max(axis=0, initial=self._q_floor)
        if along is not None:
            np.maximum(out, along, out=out)
        return out

    def _cull(self, x: float, y: float, *, local: bool) -> None:
        """Keep, in the cache, the edges that may come within reach of the origin ``(x, y)``.

        A ``local`` cull (the origin moved little since the last one: a robot on its way)
        keeps every edge within reach of the disc of radius ``_reuse`` round the origin, and
        only their vertices (renumbered), to serve the casts from inside that disc. Any other
        cull (a first cast, or a jump: scans from unrelated poses) keeps the edges within reach
        of the origin alone, and every vertex, since compacting would not pay.

        An edge kept although out of reach changes no distance: a ray meets it, if at all,
        beyond ``max_range`` (with the margin), so it can only turn a reading that is ``inf``
        anyway into a hit beyond the range, i.e. ``inf``; nor can the origin lie on it. The
        side values are computed per vertex, each from the same two coordinates whatever the
        numbering, so they are unchanged too.
        """
        self._origin = (x, y)
        gap = np.abs(self._edge_mids - complex(x, y))
        if not local:
            kept = self._edges.compress(gap <= self._edge_reach, axis=1)
            self._near = _NearEdges(self._points, kept.reshape(-1), kept.shape[1], 0.0)
            return
        kept = self._edges.compress(gap <= (self._edge_reach + self._reuse) * _MARGIN, axis=1)
        used = np.zeros(self._points.shape[1], dtype=np.bool_)
        used[kept.reshape(-1)] = True
        renumber = np.cumsum(used) - 1
        points = np.ascontiguousarray(self._points[:, used])
        ends = renumber[kept.reshape(-1)]
        self._near = _NearEdges(points, ends, kept.shape[1], self._reuse)

    def _circle_inverse_distances(
        self, x: float, y: float, rows: NDArray[np.float64], q: NDArray[np.float64]
    ) -> NDArray[np.float64] | None:
        """Raise ``q`` to ``1 / t`` of the nearest circle hit per ray; ``None`` if O is in one.

        With few (circle, ray) pairs every pair is computed; with many (a LiDAR among BARN's
        cylinders) only those whose ray can meet the circle (:func:`_facing_pairs`), each by
        the same operations, so that the result is the same to the bit.
        """
        rel = self._centers - (x, y)
        c2 = rel[:, 0] * rel[:, 0] + rel[:, 1] * rel[:, 1]
        g = c2 - self._radii2
        if g.min() <= 0.0:
            return None
        near = c2 <= self._circle_reach2
        count = np.count_nonzero(near)
        if not count:
            return q
        rel, g, r2 = rel[near], g[near], self._radii2[near]
        if count * rows.shape[1] < _PAIRS_FROM:
            ahead = dot2(rel, rows[1:])
            disc = dot2(rel, rows[:2])
            circle = None
        else:
            circle, ray = _facing_pairs(rel, r2 / c2[near], rows)
            rel, pair_rows = rel[circle], rows[:, ray]
            ahead = rel[:, 0] * pair_rows[1] + rel[:, 1] * pair_rows[2]  # dot2's operations
            disc = rel[:, 0] * pair_rows[0] + rel[:, 1] * pair_rows[1]
        disc *= disc
        np.subtract(r2[:, None] if circle is None else r2[circle], disc, out=disc)  # r^2 - h^2
        touching = disc >= 0.0
        np.sqrt(disc, out=disc, where=touching)
        disc += ahead  # p + sqrt(r^2 - h^2): < 0 for circles behind the sensor
        disc *= (1.0 / g)[:, None] if circle is None else (1.0 / g)[circle]
        disc *= touching
        if circle is None:
            return np.maximum(q, disc.max(axis=0), out=q)
        np.maximum.at(q, ray, disc)
        return q


def _facing_pairs(
    rel: NDArray[np.float64], ratio2: NDArray[np.float64], rows: NDArray[np.float64]
) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """The (circle, ray) pairs of rays that may meet a circle: the rays within the circle's
    angular half-width ``asin(r / |c|)`` of its centre's bearing, plus
    :data:`_FACING_MARGIN`. ``rel`` are the centres relative to O, ``ratio2`` the
    ``(r / |c|)^2`` (below 1: O outside every circle), ``rows`` the rays as in ``cast``.

    Every pair left out reads no hit in the full computation: its ray misses the circle by
    far more than the rounding of ``h``, or points away from it (``p <= 0``, where the hit
    value is negative and loses to ``q``'s floor). A circle within :data:`_NEAR_CIRCLE` of
    O keeps every ray, since its half-width then moves fast with the rounding.
    """
    k = rows.shape[1]
    bearing = np.arctan2(rows[2], rows[1])
    order = np.argsort(bearing, kind="stable")
    sorted_bearing = bearing[order]
    wrapped = np.concatenate([sorted_bearing, sorted_bearing + 2.0 * math.pi])
    centre = np.arctan2(rel[:, 1], rel[:, 0])
    half = np.arcsin(np.sqrt(np.minimum(ratio2, 1.0))) + _FACING_MARGIN
    half[ratio2 > _NEAR_CIRCLE**2] = math.pi
    low = centre - half
    low += np.where(low < -math.pi, 2.0 * math.pi, 0.0)
    circle, position = members(wrapped, low, low + 2.0 * half, most=k)
    return circle, order[position % k]


def dot2(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    """``a @ b`` for ``a`` of shape ``(m, 2)`` and ``b`` of shape ``(2, n)``, elementwise: two
    products and a sum per entry, rounded the same way on every machine and memory layout.

    A matrix product goes to BLAS, whose kernels (fused multiply-adds, blocking, threads)
    depend on the arrays' alignment: the same scan then differed in the last bit from one
    process to another, and a planner's trajectory with it.

    >>> a = np.array([[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]])
    >>> b = np.array([[1.0, 0.0, 2.0], [0.0, 1.0, 3.0]])
    >>> dot2(a, b).tolist() == (a @ b).tolist()
    True
    """
    out: NDArray[np.float64] = a[:, :1] * b[0] + a[:, 1:] * b[1]
    return out


def _as_array(name: str, value: ArrayLike, shape: tuple[int, ...]) -> NDArray[np.float64]:
    """``value`` as a finite float64 array of ``shape`` (``-1``: any length, empty allowed)."""
    arr = np.array(value, dtype=np.float64)
    if arr.size == 0:
        return np.zeros((0, *shape[1:]))
    if arr.ndim != len(shape) or arr.shape[1:] != shape[1:]:
        want = "(n, " + ", ".join(map(str, shape[1:])) + ")" if len(shape) > 1 else "(n,)"
        raise ValueError(f"`{name}` must have shape {want}, got {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError(f"`{name}` must be finite, got {arr.tolist()!r}")
    return arr


def _along_edge_inverse_distances(
    ends: NDArray[np.float64], side: NDArray[np.float64], rows: NDArray[np.float64]
) -> NDArray[np.float64]:
    """``1 / t`` of endpoint hits on edges whose line passes through O but not their points.

    ``ends`` are the edges' endpoints relative to O (``(2, e)``), ``side`` their side values
    (``(e, k)``). A ray meets such an edge only if it runs exactly along it, and then first
    meets the nearer endpoint in front of it.
    """
    ahead = dot2(ends.T, rows[1:])
    on_ray = (side == 0.0) & (ahead > 0.0)
    inv = np.divide(1.0, ahead, out=np.zeros_like(ahead), where=on_ray)
    nearest: NDArray[np.float64] = inv.max(axis=0)
    return nearest


def cast_rays(
    origin: tuple[float, float],
    angles: ArrayLike,
    segments: ArrayLike,
    circle_centers: ArrayLike,
    circle_radii: ArrayLike,
    max_range: float,
) -> NDArray[np.float64]:
    """Return the distance along each ray to the first segment or circle it hits.

    A one-shot :meth:`RayCaster.cast`; build a :class:`RayCaster` to cast repeatedly against the
    same obstacles.

    Parameters
    ----------
    origin : tuple of float
        The rays' start point ``(x, y)``.
    angles : array_like, shape (k,)
        Absolute ray directions, radians counter-clockwise from +x.
    segments : array_like, shape (n, 2, 2)
        Line segments as ``(start, end)`` points.
    circle_centers : array_like, shape (m, 2)
        Circle centres.
    circle_radii : array_like, shape (m,)
        Circle radii, each > 0.
    max_range : float
        Largest distance reported; farther hits read ``inf``.

    Returns
    -------
    ndarray, shape (k,)
        Distance to the first hit on each ray, ``inf`` for none within ``max_range``.

    Examples
    --------
    >>> cast_rays((0, 0), [0.0, math.pi], [((2, -1), (2, 1))], [], [], max_range=5.0).tolist()
    [2.0, inf]
    >>> cast_rays((0, 0), [math.pi / 2], [], [(0, 4)], [1.0], max_range=5.0).tolist()
    [3.0]
    >>> cast_rays((0, 0), [math.pi / 2], [], [(0, 4)], [1.0], max_range=2.5).tolist()
    [inf]
    """
    return RayCaster(segments, circle_centers, circle_radii, max_range).cast(origin, angles)
