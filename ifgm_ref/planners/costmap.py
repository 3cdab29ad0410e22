"""A costmap built from the robot's own scans: ROS costmap_2d's obstacle and inflation layers.

Reference
---------
ROS 1 ``costmap_2d`` (navigation stack): ``ObstacleLayer`` marks the cell of every return
nearer than ``obstacle_range`` and clears every cell a ray crosses, up to ``raytrace_range``
(clearing first, then marking); ``InflationLayer`` gives every cell a cost from its distance
``d`` to the nearest marked cell::

    254 (LETHAL)                                   d = 0 (the marked cell itself)
    253 (INSCRIBED)                                0 < d <= inscribed radius
    floor(252 exp(-(d - inscribed radius) / L))    inscribed radius < d <= inflation_radius
    0                                              beyond

with ``L = 1 / cost_scaling_factor`` (costmap_2d's default factor 10 per metre: ``L`` 0.1 m)
and ``d`` the distance between cell centres. The robot is a disc here, so its inscribed
radius is ``r``. Cells never seen are free (cost 0), as navfn's ``allow_unknown`` (default
true) and TrajectoryPlannerROS treat a costmap that does not track unknown space.

Unlike the paper's planners this keeps a map, but only of what the planner itself has sensed:
nothing here knows the world. The grid lives in the frame of the observed poses (odometry),
covers the start, the goal and a margin, and grows when the robot nears its edge. Marking and
clearing are numpy-vectorised over the rays (720 for BARN's LiDAR); the inflation is
recomputed only round the cells a scan can change.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose

__all__ = ["FREE", "INSCRIBED", "LETHAL", "Costmap", "CostmapSettings", "inflation_costs"]

#: costmap_2d's cost of a marked cell (``LETHAL_OBSTACLE``).
LETHAL = 254
#: costmap_2d's cost of a cell within the robot's inscribed radius of a marked cell
#: (``INSCRIBED_INFLATED_OBSTACLE``): the robot's centre there means a collision.
INSCRIBED = 253
#: The cost of a free (or never seen) cell.
FREE = 0


@dataclass(frozen=True)
class CostmapSettings:
    """The costmap's lengths, each in the world's unit (:class:`~ifgm_ref.planners.dwa.
    CostmapParams` derives them from the robot).

    Parameters
    ----------
    resolution : float
        Cell side.
    inscribed_radius : float
        The robot's radius: cells this near a marked cell are :data:`INSCRIBED`.
    inflation_radius : float
        Cells up to this far from a marked cell get a decaying cost.
    decay_length : float
        ``1 / cost_scaling_factor``: the cost falls by ``e`` over this length.
    obstacle_range : float
        Returns up to this range mark their cell.
    raytrace_range : float
        Rays clear the cells they cross up to this range.
    margin : float
        Free border kept round the start, the goal and the robot when the grid is sized.
    """

    resolution: float
    inscribed_radius: float
    inflation_radius: float
    decay_length: float
    obstacle_range: float
    raytrace_range: float
    margin: float


def inflation_costs(distance: NDArray[np.float64], settings: CostmapSettings) -> NDArray[np.uint8]:
    """costmap_2d's ``InflationLayer::computeCost`` of cell-centre distances (world units).

    Examples
    --------
    >>> s = CostmapSettings(0.05, 0.22, 0.30, 0.1, 2.5, 3.0, 2.5)
    >>> inflation_costs(np.array([0.0, 0.05, 0.22, 0.25, 0.30, 0.31, np.inf]), s).tolist()
    [254, 253, 253, 186, 113, 0, 0]
    """
    beyond = np.maximum(distance - settings.inscribed_radius, 0.0)
    with np.errstate(invalid="ignore", over="ignore"):
        decayed = np.floor((INSCRIBED - 1) * np.exp(-beyond / settings.decay_length))
    cost = np.where(distance <= settings.inflation_radius + 1e-9, decayed, FREE)
    cost = np.where(distance <= settings.inscribed_radius + 1e-9, INSCRIBED, cost)
    cost = np.where(distance == 0.0, LETHAL, cost)
    return cost.astype(np.uint8)


class Costmap:
    """A growing occupancy grid with costmap_2d's costs, fed one scan at a time.

    Cell ``(i, j)`` is row ``i`` (y) and column ``j`` (x); its centre is
    ``origin + ((j + 0.5) res, (i + 0.5) res)``.

    Examples
    --------
    A wall 1 m ahead, seen by three rays, marks its cells and inflates them:

    >>> s = CostmapSettings(0.05, 0.22, 0.30, 0.1, 2.5, 3.0, 0.5)
    >>> grid = Costmap(s, Point(0.0, 0.0), Point(2.0, 0.0))
    >>> scan = LaserScan(-0.05, 0.05, 0.05, 0.0, 30.0, [1.0, 1.0, 1.0])
    >>> grid.update(Pose(0.0, 0.0, 0.0), scan)
    >>> grid.cost_at(1.0, 0.0), grid.cost_at(0.8, 0.0), grid.cost_at(0.5, 0.0)
    (254, 253, 0)
    """

    def __init__(self, settings: CostmapSettings, start: Point, goal: Point) -> None:
        self.settings = settings
        res = settings.resolution
        low = (min(start.x, goal.x) - settings.margin, min(start.y, goal.y) - settings.margin)
        high = (max(start.x, goal.x) + settings.margin, max(start.y, goal.y) + settings.margin)
        self.origin = (math.floor(low[0] / res) * res, math.floor(low[1] / res) * res)
        cols = math.ceil((high[0] - self.origin[0]) / res)
        rows = math.ceil((high[1] - self.origin[1]) / res)
        self.occupied = np.zeros((rows, cols), dtype=bool)
        self.cost = np.zeros((rows, cols), dtype=np.uint8)
        reach = math.ceil(settings.inflation_radius / res)
        offsets = [
            (di, dj, math.hypot(di, dj) * res)
            for di in range(-reach, reach + 1)
            for dj in range(-reach, reach + 1)
            if math.hypot(di, dj) * res <= settings.inflation_radius + 1e-9
        ]
        #: Cell offsets within the inflation radius, nearest first, with their distance.
        self._offsets = sorted(offsets, key=lambda o: o[2])
        #: How many times the grid has grown (each growth moves cells: plans must be redone).
        self.generation = 0

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)``."""
        rows, cols = self.cost.shape
        return rows, cols

    def cell_of(self, x: float, y: float) -> tuple[int, int]:
        """The ``(row, col)`` of the point ``(x, y)`` (possibly outside the grid)."""
        res = self.settings.resolution
        return math.floor((y - self.origin[1]) / res), math.floor((x - self.origin[0]) / res)

    def cells_of(self, xy: NDArray[np.float64]) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
        """Rows and columns of the points ``xy[..., 0], xy[..., 1]``."""
        res = self.settings.resolution
        rows = np.floor((xy[..., 1] - self.origin[1]) / res).astype(np.intp)
        cols = np.floor((xy[..., 0] - self.origin[0]) / res).astype(np.intp)
        return rows, cols

    def centre(self, row: int, col: int) -> Point:
        """The world point at the centre of a cell."""
        res = self.settings.resolution
        return Point(self.origin[0] + (col + 0.5) * res, self.origin[1] + (row + 0.5) * res)

    def cost_at(self, x: float, y: float) -> int:
        """The cost of the cell holding ``(x, y)``; :data:`FREE` outside the grid."""
        row, col = self.cell_of(x, y)
        rows, cols = self.shape
        return int(self.cost[row, col]) if 0 <= row < rows and 0 <= col < cols else FREE

    def update(self, pose: Pose, scan: LaserScan) -> None:
        """Clear along every ray, mark every near return, re-inflate round the robot."""
        reach = self.settings.raytrace_range + self.settings.inflation_radius
        self._cover(pose.x - reach, pose.y - reach, pose.x + reach, pose.y + reach)
        angles = scan.angles + pose.theta
        cos, sin = np.cos(angles), np.sin(angles)
        ranges = scan.ranges
        self._clear(pose, cos, sin, ranges)
        near = np.isfinite(ranges) & (ranges >= 0.0) & (ranges <= self.settings.obstacle_range)
        xy = np.stack((pose.x + ranges[near] * cos[near], pose.y + ranges[near] * sin[near]), -1)
        rows, cols = self.cells_of(xy)
        self.occupied[rows, cols] = True
        self._inflate(self.cell_of(pose.x, pose.y), math.ceil(reach / self.settings.resolution))

    def _clear(
        self,
        pose: Pose,
        cos: NDArray[np.float64],
        sin: NDArray[np.float64],
        ranges: NDArray[np.float64],
    ) -> None:
        """Free every cell each ray crosses before its return (or up to ``raytrace_range``
        when it has none): the rays sampled every half cell, the return's cell kept."""
        res = self.settings.resolution
        limit = self.settings.raytrace_range
        valid = ~np.isnan(ranges) & (ranges != -np.inf)
        length = np.minimum(np.where(np.isfinite(ranges), ranges, limit), limit)[valid]
        steps = np.arange(0.0, limit, res / 2.0)
        inside = steps[np.newaxis, :] < length[:, np.newaxis] - res / 2.0
        t = np.broadcast_to(steps, inside.shape)[inside]
        cx = np.broadcast_to(cos[valid][:, np.newaxis], inside.shape)[inside]
        cy = np.broadcast_to(sin[valid][:, np.newaxis], inside.shape)[inside]
        xy = np.stack((pose.x + t * cx, pose.y + t * cy), -1)
        rows, cols = self.cells_of(xy)
        hit = np.isfinite(ranges[valid]) & (ranges[valid] <= limit)
        ends = np.stack(
            (pose.x + length[hit] * cos[valid][hit], pose.y + length[hit] * sin[valid][hit]), -1
        )
        end_rows, end_cols = self.cells_of(ends)
        keep = self.occupied[end_rows, end_cols].copy()
        self.occupied[rows, cols] = False
        self.occupied[end_rows, end_cols] |= keep

    def _inflate(self, centre: tuple[int, int], half: int) -> None:
        """Recompute the costs of the cells within ``half`` cells of ``centre``."""
        rows, cols = self.shape
        pad = math.ceil(self.settings.inflation_radius / self.settings.resolution)
        r0, r1 = max(centre[0] - half, 0), min(centre[0] + half + 1, rows)
        c0, c1 = max(centre[1] - half, 0), min(centre[1] + half + 1, cols)
        s0, s1 = max(r0 - pad, 0), min(r1 + pad, rows)
        t0, t1 = max(c0 - pad, 0), min(c1 + pad, cols)
        source = np.zeros((r1 - r0 + 2 * pad, c1 - c0 + 2 * pad), dtype=bool)
        source[s0 - r0 + pad : s1 - r0 + pad, t0 - c0 + pad : t1 - c0 + pad] = self.occupied[
            s0:s1, t0:t1
        ]
        distance = np.full((r1 - r0, c1 - c0), np.inf)
        h, w = distance.shape
        for di, dj, d in reversed(self._offsets):  # nearest last: it wins
            window = source[pad + di : pad + di + h, pad + dj : pad + dj + w]
            distance[window] = d
        self.cost[r0:r1, c0:c1] = inflation_costs(distance, self.settings)

    def _cover(self, x0: float, y0: float, x1: float, y1: float) -> None:
        """Grow the grid, by ``margin`` beyond what is asked, until it holds the box."""
        res, margin = self.settings.resolution, self.settings.margin
        rows, cols = self.shape
        left = max(0, math.ceil((self.origin[0] - x0) / res))
        below = max(0, math.ceil((self.origin[1] - y0) / res))
        right = max(0, math.ceil((x1 - self.origin[0]) / res) - cols)
        above = max(0, math.ceil((y1 - self.origin[1]) / res) - rows)
        if not (left or below or right or above):
            return
        extra = math.ceil(margin / res)
        left, below = left + extra if left else 0, below + extra if below else 0
        right, above = right + extra if right else 0, above + extra if above else 0
        pads = ((below, above), (left, right))
        self.occupied = np.pad(self.occupied, pads)
        self.cost = np.pad(self.cost, pads)
        self.origin = (self.origin[0] - left * res, self.origin[1] - below * res)
        self.generation += 1
