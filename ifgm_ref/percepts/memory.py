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

from ifgm_ref.laserscan import LaserScan
from ifgm_ref.percepts.points import scan_points, to_world
from ifgm_ref.pose import Pose


class PerceptMemory:
    """World-frame obstacle points seen in the last ``horizon`` seconds.

    Examples
    --------
    >>> import math
    >>> memory = PerceptMemory(horizon=1.0)
    >>> scan = LaserScan(-0.5, 0.5, 0.5, 0.0, 10.0, [math.inf, 2.0, math.inf])
    >>> memory.add(0.0, Pose(0.0, 0.0, 0.0), scan)
    >>> memory.add(0.5, Pose(1.0, 0.0, 0.0), scan)
    >>> memory.points.tolist()
    [[2.0, 0.0], [3.0, 0.0]]
    >>> memory.add(1.2, Pose(1.0, 0.0, math.pi / 2), scan)  # the first scan is forgotten
    >>> memory.points.round(12).tolist()
    [[3.0, 0.0], [1.0, 2.0]]
    """

    def __init__(self, horizon: float) -> None:
        self.horizon = horizon
        self._scans: deque[tuple[float, NDArray[np.float64]]] = deque()
        self._points: NDArray[np.float64] | None = None

    def clear(self) -> None:
        """Forget everything."""
        self._scans.clear()
        self._points = None

    def add(self, t: float, pose: Pose, scan: LaserScan) -> None:
        """Remember the returns of ``scan`` taken at time ``t`` from ``pose``."""
        self.add_points(t, to_world(scan_points(scan).xy, pose))

    def add_points(self, t: float, points: NDArray[np.float64]) -> None:
        """Remember world-frame obstacle ``points`` seen at time ``t``."""
        self._scans.append((t, points))
        while self._scans and self._scans[0][0] < t - self.horizon:
            self._scans.popleft()
        self._points = None

    @property
    def points(self) -> NDArray[np.float64]:
        """Every remembered point, oldest first, an ``(n, 2)`` array."""
        if self._points is None:
            parts = [pts for _, pts in self._scans]
            self._points = np.concatenate(parts) if parts else np.zeros((0, 2))
        return self._points
