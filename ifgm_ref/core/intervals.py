"""Which sorted values fall in which intervals: the pairs, without testing every pair.

Two kernels ask, for many intervals at once, which of a few hundred sorted values each one
holds: the ray caster (which rays can meet a circle, :mod:`ifgm_ref.sim.raycast`) and FGM (which
rays an inflated return blocks, :mod:`ifgm_ref.planners.fgm`). Testing every (interval, value)
pair costs ``intervals x values``; a binary search for each interval's ends costs
``intervals x log(values)`` plus the pairs found. Both kernels then evaluate their exact test
on the pairs found, so that a pair the search keeps for safety changes nothing. Imports only
numpy: planners may use it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["members"]


def members(
    values: NDArray[np.float64],
    low: NDArray[np.float64],
    high: NDArray[np.float64],
    *,
    most: int | None = None,
) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """Every pair ``(i, j)`` with ``low[i] <= values[j] <= high[i]``, as two index arrays,
    interval by interval and in the values' order within each; at most ``most`` values per
    interval (the first ones). ``values`` must be sorted ascending.

    >>> values = np.array([0.0, 1.0, 2.0, 3.0])
    >>> owner, index = members(values, np.array([0.5, -1.0, 9.0]), np.array([2.0, 0.0, 9.5]))
    >>> owner.tolist(), index.tolist()
    ([0, 0, 1], [1, 2, 0])
    >>> members(values, np.array([0.0]), np.array([3.0]), most=2)[1].tolist()
    [0, 1]
    """
    start = np.searchsorted(values, low, side="left")
    stop = np.searchsorted(values, high, side="right")
    if most is not None:
        stop = np.minimum(stop, start + most)
    counts = np.maximum(stop - start, 0)
    owner = np.repeat(np.arange(len(low)), counts)
    first = np.cumsum(counts) - counts
    index = np.arange(owner.shape[0]) - np.repeat(first - start, counts)
    return owner, index
