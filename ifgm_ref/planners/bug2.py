"""Bug2: follow the obstacle until the robot is back on the start-goal line, nearer the goal.

Reference: V. J. Lumelsky and A. A. Stepanov, "Path-planning strategies for a point mobile
automaton moving amidst unknown obstacles of arbitrary shape", *Algorithmica* 2 (1987)
403-430. Paper, section 2.1.2: "the robot stores the initial slope of reference path to
destination. When an obstacle is encountered, the robot starts following edges of obstacle
and continuously calculates slope of the line from its current position to the destination.
The point where this slope becomes equal to the slope of reference path is considered as the
leaving point."

The "initial slope of reference path" defines the *m-line*, the segment from the start S to
the goal T. The slope from x to T equals the initial slope exactly when x is on that line;
the planner tests the equivalent, better-conditioned, signed distance ``s(x)`` of x to the
line (positive on its left). While following an obstacle hit at H it leaves at x when

* x is on the m-line: ``|s(x)| <= m_line_tolerance``, or ``s`` changed sign since the last
  sample (the line was crossed between two samples), with x's projection between S and T;
* x is strictly nearer the goal than H: ``d(x, T) < d(H, T) - m_line_tolerance`` (the margin
  keeps the robot from "leaving" where it has just met the obstacle);
* the robot would not meet an obstacle at once (``not meets_obstacle``), as Lumelsky and
  Stepanov's robot leaves only if it can move towards T. An obstacle in the way that is not
  the nearest one, while the one followed lies behind, does not keep it: leaving, the robot
  meets that one and follows it (errata row 34).

After a whole loop without having left, the robot falls back on Bug1's round
(:mod:`~ifgm_ref.planners.circuit`): it goes on to the point nearest the goal and leaves
there, or reports the goal unreachable (stop reason ``goal_unreachable``) if the loop shows
that the obstacle stands between the robot and the goal. The bound ``D + sum(n_i * p_i) / 2``
(``n_i`` the number of times the m-line crosses obstacle i, ``p_i`` its perimeter) is
checked by the tests.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from ifgm_ref.core.elements import traces
from ifgm_ref.core.formulas import Unit
from ifgm_ref.core.pose import Point, Pose, distance
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.planners.boundary import BoundaryPlanner, EdgeFollower, LeaveRule
from ifgm_ref.planners.sight import BoundaryParams, Sight
from ifgm_ref.planners.tuning import Tuning, derived, parameter_names


def signed_distance(point: tuple[float, float], start: Point, goal: Point) -> float:
    """Signed distance from ``point`` to the line from ``start`` to ``goal``, ft.

    Positive on the left of the line (looking from ``start`` to ``goal``), negative on its
    right. ``start`` and ``goal`` must differ.

    Examples
    --------
    >>> signed_distance((3.0, 2.0), Point(0.0, 0.0), Point(10.0, 0.0))
    2.0
    >>> signed_distance((3.0, -2.0), Point(0.0, 0.0), Point(10.0, 0.0))
    -2.0
    >>> signed_distance((1.0, 1.0), Point(0.0, 0.0), Point(2.0, 2.0))
    0.0
    """
    ux, uy = goal.x - start.x, goal.y - start.y
    return (ux * (point[1] - start.y) - uy * (point[0] - start.x)) / math.hypot(ux, uy)


@dataclass(frozen=True)
class Bug2Params(Tuning):
    """Bug2's own parameter.

    Parameters
    ----------
    m_line_tolerance : float, default one step, ``v dt``
        How near the m-line counts as on it, a length; a crossing between two samples counts
        too.
    """

    m_line_tolerance: float = derived("v*dt", Unit.LENGTH)


class Bug2Rule(LeaveRule):
    """Bug2's leaving rule: back on the m-line, nearer the goal than H, no obstacle met there.

    Attributes
    ----------
    start : Point
        S, the m-line's start.
    goal : Point
        T, the m-line's end.
    m_line_tolerance : float
        How near the m-line counts as on it (:class:`Bug2Params`).
    hit_distance : float
        d(H, T) of the current obstacle.
    """

    tunings: ClassVar[tuple[type[Tuning], ...]] = (Bug2Params,)
    leave_branch: ClassVar[str] = "leave_on_m_line"

    def __init__(self) -> None:
        super().__init__()
        self.start = Point(0.0, 0.0)
        self.goal = Point(0.0, 0.0)
        self.m_line_tolerance = 0.1
        self.hit_distance = math.inf
        self._side = 0.0

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Store the m-line from ``start`` to ``goal`` and read ``m_line_tolerance``."""
        super().reset(start, goal, params)
        self.start = Point(start[0], start[1])
        self.goal = Point(*goal)
        self.m_line_tolerance = Bug2Params.for_episode(params).m_line_tolerance
        self.hit_distance = math.inf
        self._side = 0.0

    def on_hit(self, sight: Sight, follower: EdgeFollower) -> None:
        """Remember d(H, T) and which side of the m-line the robot starts following on."""
        self.hit_distance = distance(follower.hit_point, self.goal)
        self._side = self.m_line_offset(follower.hit_point)

    def update(self, sight: Sight, follower: EdgeFollower) -> bool:
        """Leave on the m-line, strictly nearer the goal than H, meeting no obstacle there."""
        here = sight.pose.position
        offset = self.m_line_offset(here)
        crossed = offset * self._side < 0.0
        self._side = offset
        on_line = (abs(offset) <= self.m_line_tolerance or crossed) and self.on_segment(here)
        if not on_line:
            return False
        if sight.goal_distance >= self.hit_distance - self.m_line_tolerance:
            return False
        return not sight.meets_obstacle()

    def m_line_offset(self, point: tuple[float, float]) -> float:
        """Signed distance of ``point`` to the m-line (0 when start and goal coincide)."""
        if distance(self.start, self.goal) == 0.0:
            return 0.0
        return signed_distance(point, self.start, self.goal)

    def on_segment(self, point: tuple[float, float]) -> bool:
        """Whether ``point`` projects onto the m-line between the start and the goal."""
        ux, uy = self.goal.x - self.start.x, self.goal.y - self.start.y
        along = ux * (point[0] - self.start.x) + uy * (point[1] - self.start.y)
        return 0.0 <= along <= ux * ux + uy * uy


@traces("bug2")
class Bug2Planner(BoundaryPlanner):
    """Lumelsky and Stepanov's Bug2: the boundary-following skeleton with :class:`Bug2Rule`.

    Parameters (``params`` mapping of :func:`ifgm_ref.sim.simulator.simulate`): those of
    :class:`~ifgm_ref.planners.sight.BoundaryParams` and :class:`Bug2Params`.

    Examples
    --------
    >>> from ifgm_ref.io.scenarios import resolve_world
    >>> from ifgm_ref.sim.simulator import simulate
    >>> run = simulate(resolve_world("box"), Bug2Planner())
    >>> run.result.stop_reason, run.result.collided
    ('goal_reached', False)
    >>> [b for b in dict.fromkeys(s.branch for s in run.trace) if b]
    ['move_to_goal', 'follow_edge', 'leave_on_m_line']
    >>> simulate(resolve_world("box"), Bug2Planner(), params={"m_line_tolerance": 0})
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `m_line_tolerance` must be a finite number > 0, got 0
    """

    name: ClassVar[str] = "bug2"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (BoundaryParams, Bug2Params)
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self) -> None:
        super().__init__(Bug2Rule())
