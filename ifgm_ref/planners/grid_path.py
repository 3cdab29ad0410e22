"""Grid search on a costmap: navfn's global plan and base_local_planner's MapGrid distances.

Reference
---------
ROS 1 navigation: ``navfn`` (Brock & Khatib's navigation function, a Dijkstra wavefront over
cell costs) plans the global path; ``base_local_planner::MapGrid`` gives the local planner,
for every cell of its window, the number of 4-connected steps to the nearest cell of the plan
(``path_map``) and to the local goal (``goal_map``), a breadth-first wavefront that does not
enter lethal or inscribed cells.

:func:`plan_path` is A* over the same cell costs as navfn (``COST_NEUTRAL`` 50 plus
``COST_FACTOR`` 0.8 times the costmap cost per cell, lethal and inscribed cells blocked),
8-connected, from cell centre to cell centre; navfn interpolates its potential and descends
its gradient, which smooths the path but does not change where it goes round obstacles.
:func:`wavefront` is MapGrid's breadth-first distance, one ring at a time (numpy over the ring's
cells), stopped once the cells asked about are settled.
"""

from __future__ import annotations

import heapq
import math

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.planners.costmap import INSCRIBED

__all__ = ["COST_FACTOR", "COST_NEUTRAL", "blocked", "plan_path", "wavefront"]

#: navfn's cost of a free cell (``COST_NEUTRAL``).
COST_NEUTRAL = 50.0
#: navfn's weight of a costmap cost (``COST_FACTOR``): a cell costs 50 + 0.8 cost.
COST_FACTOR = 0.8
_SQRT2 = math.sqrt(2.0)


def blocked(cost: NDArray[np.uint8]) -> NDArray[np.bool_]:
    """Cells no plan or trajectory may enter: lethal or inscribed.

    >>> blocked(np.array([0, 252, 253, 254], dtype=np.uint8)).tolist()
    [False, False, True, True]
    """
    return cost >= INSCRIBED


def plan_path(
    cost: NDArray[np.uint8], start: tuple[int, int], goal: tuple[int, int]
) -> list[tuple[int, int]] | None:
    """The cheapest 8-connected chain of cells from ``start`` to ``goal`` (both included),
    or ``None`` when the goal cannot be reached.

    A step into a cell costs its length in cells times ``(50 + 0.8 cost) / 50``; blocked cells
    (:func:`blocked`) are never entered, except the start, where the robot already is (navfn
    clears the robot's cell). The heuristic is the octile distance in cells, which never
    overestimates, so the chain is a cheapest one.

    Examples
    --------
    A wall across a 5 x 5 grid with a gap at the right: the chain goes through the gap.

    >>> grid = np.zeros((5, 5), dtype=np.uint8)
    >>> grid[2, :4] = 254
    >>> plan_path(grid, (0, 0), (4, 0))
    [(0, 0), (1, 1), (1, 2), (1, 3), (2, 4), (3, 3), (3, 2), (3, 1), (4, 0)]
    >>> grid[2, 4] = 253
    >>> plan_path(grid, (0, 0), (4, 0)) is None
    True
    """
    rows, cols = cost.shape
    if not (0 <= goal[0] < rows and 0 <= goal[1] < cols) or blocked(cost[goal]):
        return None
    if not (0 <= start[0] < rows and 0 <= start[1] < cols):
        return None
    # A blocked border round the grid: neighbours need no bounds check.
    weight = np.full((rows + 2, cols + 2), math.inf)
    inner = (COST_NEUTRAL + COST_FACTOR * cost.astype(np.float64)) / COST_NEUTRAL
    weight[1:-1, 1:-1] = np.where(blocked(cost), math.inf, inner)
    weights: list[float] = weight.ravel().tolist()
    width = cols + 2
    source, target = (start[0] + 1) * width + start[1] + 1, (goal[0] + 1) * width + goal[1] + 1
    moves = [(di * width + dj, math.hypot(di, dj)) for di in (-1, 0, 1) for dj in (-1, 0, 1)]
    moves = [(d, step) for d, step in moves if d]
    best = [math.inf] * len(weights)
    best[source] = 0.0
    parent: dict[int, int] = {}
    closed = bytearray(len(weights))
    gi, gj = divmod(target, width)
    frontier = [(_octile(source, gi, gj, width), 0.0, source)]
    while frontier:
        _, g, here = heapq.heappop(frontier)
        if here == target:
            return [(i - 1, j - 1) for i, j in _chain(parent, source, target, width)]
        if closed[here]:
            continue
        closed[here] = 1
        for d, step in moves:
            there = here + d
            new = g + step * weights[there]
            if new < best[there]:
                best[there], parent[there] = new, here
                heapq.heappush(frontier, (new + _octile(there, gi, gj, width), new, there))
    return None


def _octile(cell: int, gi: int, gj: int, width: int) -> float:
    """The octile distance from a flat cell index to ``(gi, gj)``: the shortest 8-connected
    length in cells, so it never overestimates (every cell costs at least 1 per cell)."""
    i, j = divmod(cell, width)
    di, dj = abs(i - gi), abs(j - gj)
    return max(di, dj) + (_SQRT2 - 1.0) * min(di, dj)


def _chain(parent: dict[int, int], source: int, target: int, cols: int) -> list[tuple[int, int]]:
    """The cells from ``source`` to ``target`` by following ``parent`` back."""
    chain = [target]
    while chain[-1] != source:
        chain.append(parent[chain[-1]])
    return [divmod(k, cols) for k in reversed(chain)]


def wavefront(
    passable: NDArray[np.bool_],
    sources: NDArray[np.bool_],
    wanted: tuple[slice, slice] | None = None,
) -> NDArray[np.int32]:
    """4-connected breadth-first distance, in cells, from the ``sources`` cells that are
    ``passable`` to every passable cell; ``passable.size`` (MapGrid's ``obstacleCosts``)
    where no passable chain leads.

    ``wanted`` is the part of the grid the caller will read: the wave stops once every
    passable cell there is reached (cells beyond may then read unreached).

    Examples
    --------
    >>> free = np.ones((3, 4), dtype=bool)
    >>> free[1, 1:3] = False
    >>> goal = np.zeros((3, 4), dtype=bool)
    >>> goal[2, 1] = True
    >>> wavefront(free, goal).tolist()
    [[3, 4, 5, 4], [2, 12, 12, 3], [1, 0, 1, 2]]
    """
    height, width = passable.shape
    far = np.int32(passable.size)
    distance = np.full(passable.shape, far, dtype=np.int32)
    ring_rows, ring_cols = np.nonzero(sources & passable)
    if len(ring_rows) == 0:
        return distance
    # Flat indices into the grid with a blocked border round it: neighbours need no bounds
    # check. ``open_`` marks the passable cells the wave has not reached.
    stride = width + 2
    open_ = _bordered(passable)
    asked = np.zeros(passable.shape, dtype=bool)
    asked[wanted or (slice(None), slice(None))] = True
    in_box = _bordered(asked) & open_
    reached = np.full(open_.shape, far, dtype=np.int32)
    ring = (ring_rows + 1) * stride + ring_cols + 1
    open_[ring] = False
    reached[ring] = 0
    left = int(np.count_nonzero(in_box & open_))  # passable cells of the box not yet reached
    neighbours = np.array([-stride, stride, -1, 1])
    step = 0
    while left:
        step += 1
        ring = (ring[:, None] + neighbours).ravel()
        ring = np.unique(ring[open_[ring]])
        if len(ring) == 0:
            break
        open_[ring] = False
        reached[ring] = step
        left -= int(np.count_nonzero(in_box[ring]))
    distance[:] = reached.reshape(height + 2, stride)[1:-1, 1:-1]
    return distance


def _bordered(cells: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """``cells`` with a row and a column of ``False`` round them, flattened."""
    bordered = np.zeros((cells.shape[0] + 2, cells.shape[1] + 2), dtype=bool)
    bordered[1:-1, 1:-1] = cells
    return bordered.ravel()
