"""The lap rule: a robot that keeps coming back to one place, no nearer the goal.

The simulator's second stall rule (:mod:`ifgm_ref.sim.simulator`). It fires at step ``n``
when the robot's centre ``p_n`` is within ``rho`` of ``K`` earlier positions
``p_i1, ..., p_iK`` (oldest first), each passed the same way (a positive dot product of the
steps that reached them), that close ``K`` laps in a row -- each at least ``L`` of path after
the one before, and ``p_n`` at least ``L`` after ``p_iK`` -- and its best distance to the goal
is no better than at ``p_i1`` by more than ``eps``:

    ``best(n) >= best(i1) - eps``,  ``best(k) = min(|p_j - goal| for j <= k)``.

``rho`` is :data:`LAP_RADIUS`, ``L`` :data:`LAP_LENGTH`, ``eps`` :data:`LAP_PROGRESS` and ``K``
:attr:`SimParams.stall_laps <ifgm_ref.core.params.SimParams.stall_laps>` (2 by default). Why
these thresholds: ``docs/oracle.md``, "Why the stall rules' numbers".

Positions are kept in a grid hash of cells of side ``rho`` (:class:`LapLog`), so one step
costs the positions in the 3 x 3 cells around it. Every comparison is of squared distances,
path lengths and signs of dot products: scaled by a power of two, the rule fires at the
same step.
"""

from __future__ import annotations

import bisect
import math
from collections import defaultdict
from dataclasses import dataclass, field

from ifgm_ref.core.formulas import Scale, declare, evaluate
from ifgm_ref.core.pose import PointLike, distance

#: ``rho``, length: the radius of a place, the robot's radius ``r``.
LAP_RADIUS = declare("r")
#: ``L``, length: the shortest lap, the circumference of the robot's disc.
LAP_LENGTH = declare("2*pi*r")
#: ``eps``, length: the least improvement of the best distance to the goal that counts as
#: progress over the laps.
LAP_PROGRESS = declare("v*dt")


@dataclass(frozen=True)
class LapRule:
    """The thresholds of the lap rule (the module docstring's symbols).

    ``radius`` is ``rho``, ``length`` ``L`` and ``progress`` ``eps``, all in the world's
    length unit; ``laps`` is ``K``.
    """

    radius: float
    length: float
    progress: float
    laps: int

    @classmethod
    def of(cls, scale: Scale, laps: int) -> LapRule:
        """The rule for a robot, time step and sensor (:data:`LAP_RADIUS`,
        :data:`LAP_LENGTH` and :data:`LAP_PROGRESS` evaluated for ``scale``).

        >>> rule = LapRule.of(Scale.paper(), 2)
        >>> rule.radius, round(rule.length, 4), round(rule.progress, 4), rule.laps
        (1.0, 6.2832, 0.1322, 2)
        """
        return cls(
            evaluate(LAP_RADIUS, scale),
            evaluate(LAP_LENGTH, scale),
            evaluate(LAP_PROGRESS, scale),
            laps,
        )


@dataclass(slots=True)
class _Visit:
    """One logged position: where, the step that reached it (``dx``, ``dy``: 0 for the
    first), the path length there and the best distance to the goal by then."""

    x: float
    y: float
    dx: float
    dy: float
    path: float
    best: float


@dataclass
class LapLog:
    """The positions of an episode, for the lap rule: a grid hash of cells of side ``radius``.

    Log each new position with :meth:`log`, then ask :meth:`laps` what laps the robot has
    closed there. A position that repeats the last one logged (the robot turned on the spot)
    is not logged again: it would add nothing to any answer.
    """

    radius: float
    length: float
    goal: PointLike
    _cells: defaultdict[tuple[int, int], list[_Visit]] = field(
        default_factory=lambda: defaultdict(list)
    )
    _last: _Visit | None = None

    def _cell(self, x: float, y: float) -> tuple[int, int]:
        return math.floor(x / self.radius), math.floor(y / self.radius)

    def log(self, position: PointLike, path: float) -> _Visit:
        """Log ``position``, reached after ``path`` of path; return its visit (the best
        distance to the goal by then is the least of the last one's and this one's)."""
        x, y = position[0], position[1]
        last = self._last
        if last is not None and last.x == x and last.y == y:
            return last
        here = distance(position, self.goal)
        if last is None:
            visit = _Visit(x, y, 0.0, 0.0, path, here)
        else:
            visit = _Visit(x, y, x - last.x, y - last.y, path, min(last.best, here))
        self._cells[self._cell(x, y)].append(visit)
        self._last = visit
        return visit

    def laps(self, visit: _Visit, most: int) -> list[float]:
        """The laps closed at ``visit``, latest first, at most ``most`` of them: the best
        distance to the goal at the start of each (``best(i_k)``, ``k = most, ..., 1`` in the
        module docstring's terms), each lap as late as it can start.

        Going back from ``visit``, each lap starts at the latest logged position within
        ``radius`` of ``visit``, passed the same way (a positive dot product of the steps),
        that lies at least ``length`` of path before the previous one: the latest start of
        any chain of that many laps, so the best distance there is the least any such chain
        gives.
        """
        r2, latest = self.radius * self.radius, visit.path - self.length
        i, j = self._cell(visit.x, visit.y)
        near: list[tuple[float, float]] = []
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                for v in self._cells.get((i + di, j + dj), ()):
                    if v.path > latest:  # a cell's visits are in path order
                        break
                    dx, dy = v.x - visit.x, v.y - visit.y
                    if dx * dx + dy * dy <= r2 and v.dx * visit.dx + v.dy * visit.dy > 0.0:
                        near.append((v.path, v.best))
        near.sort()
        paths = [p for p, _ in near]
        starts: list[float] = []
        until = visit.path
        while len(starts) < most:
            k = bisect.bisect_right(paths, until - self.length)
            if k == 0:
                break
            until = paths[k - 1]
            starts.append(near[k - 1][1])
        return starts


@dataclass
class LapWatch:
    """The lap rule at work in one episode: its thresholds and the positions logged."""

    rule: LapRule
    log: LapLog

    @classmethod
    def start(cls, rule: LapRule, goal: PointLike) -> LapWatch:
        """A watch with nothing logged yet."""
        return cls(rule, LapLog(rule.radius, rule.length, goal))

    def stalled(self, position: PointLike, path: float) -> bool:
        """Log ``position`` (after ``path`` of path) and say whether the rule fires there:
        ``K`` laps closed, the best distance to the goal no better than at the first one's
        start by more than ``eps``."""
        visit = self.log.log(position, path)
        starts = self.log.laps(visit, self.rule.laps)
        return len(starts) == self.rule.laps and starts[-1] - visit.best <= self.rule.progress

    @property
    def detail(self) -> str:
        """What a stop by this rule reports (:attr:`ifgm_ref.sim.simulator.Result.detail`)."""
        return f"lap rule: {self.rule.laps} laps back to within r of here, no nearer the goal"
