"""Obstacles as clusters of scan points, and the gaps between consecutive obstacles.

Section 4: "In case of more than one obstacle, average clustered value is considered as the
obstacle position for distance vector. The obstacle near to the robot is given higher
priority. ... Using this array, the gap (Euclidian distance) between every two consecutive
obstacles is calculated. The coordinates of obstacles having maximum gap are stored to steer
the robot from middle of obstacles."

Clusters are runs of consecutive rays whose returns lie within ``jump`` of each other; a ray
with no return, or a jump wider than ``jump``, starts a new obstacle. Clusters are ordered by
angle, right to left (REP-103: increasing angle), so "consecutive obstacles" are neighbours
in the field of view. A gap is the Euclidean distance *between* two consecutive obstacles: from
the nearest point of one to the nearest point of the other, the narrowest place the robot must
pass. Not between their average positions, which for a long wall lie far from its end, nor
between the borders the robot happens to see, which for obstacles seen obliquely are far
corners (errata row 15; :func:`gaps_between` offers the printed reading too).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from itertools import pairwise

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.elements import traces
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, distance
from ifgm_ref.paper.percepts.points import ScanPoints, scan_points


class Side(StrEnum):
    """Where an obstacle lies relative to the heading (REP-103: left is positive angles)."""

    RIGHT = "right"
    LEFT = "left"
    BOTH = "both"


@dataclass(frozen=True, eq=False)
class Cluster:
    """One obstacle: the robot-frame returns of consecutive rays ``first`` to ``last``.

    Attributes
    ----------
    first, last : int
        The first and last ray.
    angles, ranges : (k,) arrays
        Each return's robot-frame angle (rad) and range.
    xy : (k, 2) array
        Each return as a robot-frame point.
    nearest : float
        Distance from the robot to the obstacle's nearest return, ft.
    side : Side
        Whether every return is right of the heading, left of it, or some of each.
    """

    first: int
    last: int
    angles: NDArray[np.float64]
    ranges: NDArray[np.float64]
    xy: NDArray[np.float64]
    nearest: float
    side: Side

    @property
    def mean(self) -> Point:
        """The "average clustered value": the obstacle position of section 4."""
        x, y = self.xy.mean(axis=0)
        return Point(float(x), float(y))

    @property
    def right_border(self) -> Point:
        """The return of the obstacle's rightmost ray (lowest angle)."""
        return Point(float(self.xy[0, 0]), float(self.xy[0, 1]))

    @property
    def left_border(self) -> Point:
        """The return of the obstacle's leftmost ray (highest angle)."""
        return Point(float(self.xy[-1, 0]), float(self.xy[-1, 1]))


@dataclass(frozen=True)
class Gap:
    """The free space between two consecutive obstacles, from ``right`` to ``left`` point."""

    right: Point
    left: Point

    @property
    def width(self) -> float:
        """The gap's Euclidean width, ft (section 4: "the gap (Euclidian distance)")."""
        return distance(self.right, self.left)


@traces("percepts.obstacle_array")
def cluster_scan(scan: LaserScan, *, jump: float) -> tuple[Cluster, ...]:
    """Group the returns of ``scan`` into obstacles, ordered right to left.

    Examples
    --------
    Two posts, one either side of the heading, and nothing in between:

    >>> import math
    >>> scan = LaserScan(-0.6, 0.6, 0.3, 0.0, 10.0, [5.0, 5.0, math.inf, 5.0, 5.0])
    >>> [(c.first, c.last, str(c.side)) for c in cluster_scan(scan, jump=2.0)]
    [(0, 1, 'right'), (3, 4, 'left')]

    A jump in range splits consecutive returns:

    >>> scan = LaserScan(-0.3, 0.3, 0.3, 0.0, 10.0, [2.0, 8.0, 8.0])
    >>> [(c.first, c.last) for c in cluster_scan(scan, jump=3.0)]
    [(0, 0), (1, 2)]
    """
    return cluster_points(scan_points(scan), jump)


def cluster_points(pts: ScanPoints, jump: float) -> tuple[Cluster, ...]:
    """Group a scan's returns (:func:`~ifgm_ref.paper.percepts.points.scan_points`) into obstacles,
    ordered right to left: :func:`cluster_scan` for returns already resolved."""
    if len(pts) == 0:
        return ()
    xy, indices = pts.xy, pts.indices
    steps = np.hypot(xy[1:, 0] - xy[:-1, 0], xy[1:, 1] - xy[:-1, 1])
    breaks = (indices[1:] - indices[:-1] > 1) | (steps > jump)
    starts = [0, *(breaks.nonzero()[0] + 1).tolist()]
    ends = [*starts[1:], len(pts)]
    indices = pts.indices.tolist()
    angles = pts.angles.tolist()
    nearest = np.minimum.reduceat(pts.ranges, starts).tolist()
    return tuple(
        Cluster(
            first=indices[a],
            last=indices[b - 1],
            angles=pts.angles[a:b],
            ranges=pts.ranges[a:b],
            xy=pts.xy[a:b],
            nearest=near,
            side=_side(angles[a], angles[b - 1]),
        )
        for a, b, near in zip(starts, ends, nearest, strict=True)
    )


def _side(first: float, last: float) -> Side:
    """The side of an obstacle whose returns run from angle ``first`` to ``last``."""
    if last < 0.0:
        return Side.RIGHT
    if first > 0.0:
        return Side.LEFT
    return Side.BOTH


class GapReading(StrEnum):
    """Which points of two consecutive obstacles a gap runs between."""

    NEAREST = "nearest"  # the closest pair of returns: the obstacles' distance (our reading)
    MEANS = "means"  # their average positions (the printed "average clustered value")


@traces("percepts.obstacle_array")
def gaps_between(
    clusters: tuple[Cluster, ...], *, reading: GapReading = GapReading.NEAREST
) -> tuple[Gap, ...]:
    """The gap between each two consecutive obstacles, right to left.

    With ``GapReading.NEAREST`` (our reading) a gap runs between the closest pair of returns
    of the two obstacles; with ``GapReading.MEANS`` (the printed reading) between their
    average positions.

    >>> import math
    >>> scan = LaserScan(-0.6, 0.6, 0.3, 0.0, 10.0, [5.0, 5.0, math.inf, 5.0, 5.0])
    >>> [round(g.width, 3) for g in gaps_between(cluster_scan(scan, jump=2.0))]
    [2.955]
    >>> [round(g.width, 3) for g in gaps_between(cluster_scan(scan, jump=2.0),
    ...                                          reading=GapReading.MEANS)]
    [4.301]
    """
    if reading is GapReading.MEANS:
        return tuple(Gap(a.mean, b.mean) for a, b in pairwise(clusters))
    gaps = []
    for a, b in pairwise(clusters):
        d = np.hypot(a.xy[:, None, 0] - b.xy[None, :, 0], a.xy[:, None, 1] - b.xy[None, :, 1])
        i, j = np.unravel_index(int(np.argmin(d)), d.shape)
        gaps.append(Gap(Point(*map(float, a.xy[i])), Point(*map(float, b.xy[j]))))
    return tuple(gaps)
