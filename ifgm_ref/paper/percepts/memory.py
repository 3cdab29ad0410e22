"""The obstacle points of the last few seconds, kept in the world frame by odometry.

The paper's robot knows its position from "Odometry or GPS" (section 6) and sees 135 degrees
ahead. While it follows an obstacle's edge (sections 2.1 and 4.1) the edge soon lies beside
or behind it, outside the field of view; remembering the returns of the last few seconds is
what lets it keep following round a corner. This is a short-lived record of the robot's own
percepts, not a map: nothing is known before it is seen, and every point is forgotten after
``horizon`` seconds.
"""

from __future__ import annotations

from collections import deque

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Pose
from ifgm_ref.paper.percepts.points import scan_points, to_world


class PerceptMemory:
    """World-frame obstacle points seen in the last ``horizon`` seconds.

    Scans come every ``period`` seconds (the time step). The scan taken exactly ``horizon``
    before the newest is kept, and the one before it forgotten: the edge is decided half a
    period out, so that the rounding of the times never decides it (``t - horizon`` equals
    an earlier scan's time up to the last bit at every step when ``horizon`` is a whole
    number of periods; a float32 port and a double one would forget different scans).

    Examples
    --------
    >>> import math
    >>> memory = PerceptMemory(horizon=1.0, period=0.1)
    >>> scan = LaserScan(-0.5, 0.5, 0.5, 0.0, 10.0, [math.inf, 2.0, math.inf])
    >>> memory.add(0.0, Pose(0.0, 0.0, 0.0), scan)
    >>> memory.add(0.5, Pose(1.0, 0.0, 0.0), scan)
    >>> memory.points.tolist()
    [[2.0, 0.0], [3.0, 0.0]]
    >>> memory.add(1.2, Pose(1.0, 0.0, math.pi / 2), scan)  # the first scan is forgotten
    >>> memory.points.round(12).tolist()
    [[3.0, 0.0], [1.0, 2.0]]
    """

    def __init__(self, horizon: float, period: float) -> None:
        self.horizon = horizon
        self.period = period
        #: Each remembered scan's time and number of points, oldest first.
        self._scans: deque[tuple[float, int]] = deque()
        #: The points, oldest first, are ``_buffer[_start:_end]``; new ones go after them.
        self._buffer = np.zeros((0, 2))
        self._start = 0
        self._end = 0

    def add(self, t: float, pose: Pose, scan: LaserScan) -> None:
        """Remember the returns of ``scan`` taken at time ``t`` from ``pose``."""
        self.add_points(t, to_world(scan_points(scan).xy, pose))

    def add_points(self, t: float, points: NDArray[np.float64]) -> None:
        """Remember world-frame obstacle ``points`` seen at time ``t``; forget those seen
        more than ``horizon`` seconds before it (half a period out: see the class)."""
        n = len(points)
        if self._end + n > len(self._buffer):
            self._make_room(points)
        self._buffer[self._end : self._end + n] = points
        self._end += n
        self._scans.append((t, n))
        while self._scans and self._scans[0][0] < t - self.horizon - self.period / 2:
            self._start += self._scans.popleft()[1]

    def _make_room(self, points: NDArray[np.float64]) -> None:
        """A new buffer (an array like ``points``) with the remembered points at its start
        and room for twice as many again as they and ``points`` take (earlier :attr:`points`
        stay valid: the old buffer is left as it was)."""
        live = self._buffer[self._start : self._end]
        buffer = np.empty_like(points, shape=(max(64, 2 * (len(live) + len(points))), 2))
        buffer[: len(live)] = live
        self._buffer, self._start, self._end = buffer, 0, len(live)

    @property
    def points(self) -> NDArray[np.float64]:
        """Every remembered point, oldest first, an ``(n, 2)`` read-only array (a view that
        later additions leave unchanged)."""
        points = self._buffer[self._start : self._end]
        points.flags.writeable = False
        return points
