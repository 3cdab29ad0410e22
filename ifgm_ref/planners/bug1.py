"""Bug1: go all the way round the obstacle, then leave from its point nearest the goal.

Reference: V. J. Lumelsky and A. A. Stepanov, "Path-planning strategies for a point mobile
automaton moving amidst unknown obstacles of arbitrary shape", *Algorithmica* 2 (1987)
403-430. Paper, section 2.1.1: "after detecting an obstacle, the robot moves around the
obstacle completely in order to find the point (leaving point) having minimum distance to
destination. The robot restarts following the edge until it reaches to the computed leaving
point and generates a new referenced path to destination."

The three phases of one obstacle, as this planner runs them on the
:class:`~ifgm_ref.planners.boundary.BoundaryPlanner` skeleton, as its leaving rule
(:class:`Bug1Rule`):

1. *circumnavigate*: from the hit point H follow the edge right round the obstacle, keeping
   the point Q of least distance to the goal seen on the way, and the distance followed from
   H to Q;
2. *return to Q*: back at H (the skeleton's loop closure), follow the edge on to Q the
   shorter way round, as Lumelsky and Stepanov's robot does (it knows the loop length and
   the distance from H to Q): on in the same direction if Q lies in the first half of the
   loop, back the way it came (the edge on the other side) if not. Q is reached when the
   distance to Q, within ``return_radius`` of it, stops shrinking (the closest approach of
   this second pass) once the distance followed is about the arc to Q, or at the latest
   when that arc is exceeded by a slack (the second pass is nearly, never exactly, the first
   path);
3. at Q, leave towards the goal if its direction is free (``not goal_blocked``); if it is
   blocked, or if the robot meets the obstacle again right at Q, the goal cannot be reached
   (Lumelsky and Stepanov's test) and the episode stops with ``goal_unreachable``.

Symbols: H (hit point, :attr:`EdgeFollower.hit_point`), Q (:attr:`Bug1Rule.q_point`),
d(x, T) (distance to the goal). The bound on the path length, ``D + 1.5 * sum(p_i)`` (D the
start-goal distance, ``p_i`` the perimeters of the obstacles met), is checked by the tests
with ``p_i`` the perimeter of the curve the robot can follow: the obstacle grown by the
stand-off. The 1.5 holds only because the return to Q takes the shorter way (at most half a
loop); always following on in the same direction would allow ``D + 2 * sum(p_i)``.
"""

from __future__ import annotations

import math
from enum import StrEnum
from typing import ClassVar

from ifgm_ref.paper import traces
from ifgm_ref.planners.boundary import BoundaryPlanner, EdgeFollower, LeaveRule
from ifgm_ref.planners.edge_following import FollowSide
from ifgm_ref.planners.sight import BoundaryParams, Sight
from ifgm_ref.planners.tuning import Tuning
from ifgm_ref.pose import Point, Pose, distance
from ifgm_ref.protocol import EpisodeParams

#: Slack on the distance followed to Q on the second pass, as a fraction of the loop length:
#: the second pass starts up to ``return_radius`` before H and cuts corners a little
#: differently, so its arc length drifts from the first pass's by a few per cent at most.
ARC_SLACK_FRACTION = 0.05


class Bug1Phase(StrEnum):
    """Where Bug1 is in its handling of one obstacle."""

    MOVE_TO_GOAL = "move_to_goal"
    CIRCUMNAVIGATE = "circumnavigate"
    RETURN_TO_Q = "return_to_q"
    LEFT_AT_Q = "left_at_q"


class Bug1Rule(LeaveRule):
    """Bug1's leaving rule: round the whole obstacle, back to Q, leave there.

    Attributes
    ----------
    phase : Bug1Phase
        The current phase (see the module docstring).
    q_point : Point
        Q, the point nearest the goal found so far on the current obstacle.
    q_distance : float
        d(Q, T).
    q_travelled : float
        Distance followed from the hit point to Q on the first pass.
    loop_length : float
        Length of the whole loop round the obstacle (``nan`` until it is closed).
    arc_to_q : float
        Length of the shorter way from the loop's closure to Q (``nan`` until then).
    """

    leave_branch: ClassVar[str] = "leave_at_q"

    def __init__(self) -> None:
        super().__init__()
        self.phase = Bug1Phase.MOVE_TO_GOAL
        self.q_point = Point(0.0, 0.0)
        self.q_distance = math.inf
        self.q_travelled = 0.0
        self.loop_length = math.nan
        self.arc_to_q = math.nan
        self._closed_at = math.nan
        self._q_gap = math.inf

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Start in *move to goal*; forget any obstacle of a previous episode."""
        super().reset(start, goal, params)
        self.phase = Bug1Phase.MOVE_TO_GOAL
        self.q_point = Point(start[0], start[1])
        self.q_distance = math.inf
        self.q_travelled = 0.0
        self.loop_length = math.nan
        self.arc_to_q = math.nan
        self._closed_at = math.nan

    def on_hit(self, sight: Sight, follower: EdgeFollower) -> None:
        """Start circumnavigating from H; H is the first candidate for Q.

        Meeting an obstacle again within ``return_radius`` of the Q just left means the
        robot could not move towards the goal from Q: the goal is unreachable.
        """
        here = sight.pose.position
        tuning = sight.body.tuning
        if (
            self.phase is Bug1Phase.LEFT_AT_Q
            and distance(here, self.q_point) <= tuning.return_radius
        ):
            self.stop = "q_blocked"
        self.phase = Bug1Phase.CIRCUMNAVIGATE
        self.q_point = here
        self.q_distance = sight.goal_distance
        self.q_travelled = 0.0
        self.loop_length = math.nan
        self.arc_to_q = math.nan
        self._closed_at = math.nan

    def update(self, sight: Sight, follower: EdgeFollower) -> bool:
        """On the first pass, track Q; on the second, leave at Q if the goal way is free."""
        if self.phase is Bug1Phase.CIRCUMNAVIGATE:
            d = sight.goal_distance
            if d < self.q_distance:
                self.q_point = sight.pose.position
                self.q_distance, self.q_travelled = d, follower.travelled
            return False
        if self.phase is not Bug1Phase.RETURN_TO_Q or not self.at_q(sight, follower.travelled):
            return False
        if sight.goal_blocked():
            self.stop = "q_blocked"
            return False
        self.phase = Bug1Phase.LEFT_AT_Q
        return True

    def on_loop_closed(self, sight: Sight, follower: EdgeFollower) -> str | None:
        """Back at H after the whole loop: note its length, then follow on to Q the shorter
        way round (turning back when Q is in the second half of the loop)."""
        if self.phase is not Bug1Phase.CIRCUMNAVIGATE:
            return self.follow_branch()
        travelled = follower.travelled
        self.loop_length = travelled + distance(sight.pose.position, follower.hit_point)
        onwards = self.loop_length - travelled + self.q_travelled
        back = travelled - self.q_travelled
        if back < onwards:
            follower.side = (
                FollowSide.LEFT if follower.side is FollowSide.RIGHT else FollowSide.RIGHT
            )
        self.arc_to_q = min(onwards, back)
        self._closed_at = travelled
        self._q_gap = math.inf
        self.phase = Bug1Phase.RETURN_TO_Q
        return "loop_closed"

    def follow_branch(self) -> str:
        """The second pass is labelled ``follow_to_q`` in the trace."""
        return "follow_to_q" if self.phase is Bug1Phase.RETURN_TO_Q else "follow_edge"

    def at_q(self, sight: Sight, travelled: float) -> bool:
        """Whether the robot, on its second pass, has reached Q.

        The distance followed since the loop closed is compared with :attr:`arc_to_q`. From
        ``ARC_SLACK_FRACTION`` of a loop (at least ``return_radius``) before it, Q is reached
        at the closest approach: within ``return_radius`` of Q, the first sample whose
        distance to Q is no smaller than the previous one's. That far after it, Q counts as
        reached anyway.
        """
        return_radius = sight.body.tuning.return_radius
        gap = distance(sight.pose.position, self.q_point)
        receding = gap >= self._q_gap
        self._q_gap = gap
        expected = self._closed_at + self.arc_to_q
        slack = max(return_radius, ARC_SLACK_FRACTION * self.loop_length)
        if travelled < expected - slack:
            return False
        if travelled >= expected + slack:
            return True
        return gap <= return_radius and receding


@traces("bug1", "t1.bug_long_paths")
class Bug1Planner(BoundaryPlanner):
    """Lumelsky and Stepanov's Bug1: the boundary-following skeleton with :class:`Bug1Rule`.

    Tunables (``params`` mapping of :func:`ifgm_ref.simulator.simulate`) are those of
    :class:`~ifgm_ref.planners.sight.BoundaryParams`; ``return_radius`` doubles as the
    radius within which Q counts as reached.

    Examples
    --------
    >>> from ifgm_ref.scenarios import resolve_world
    >>> from ifgm_ref.simulator import simulate
    >>> run = simulate(resolve_world("box"), Bug1Planner())
    >>> run.result.stop_reason, run.result.collided
    ('goal_reached', False)
    >>> [b for b in dict.fromkeys(s.branch for s in run.trace) if b]
    ['move_to_goal', 'follow_edge', 'loop_closed', 'follow_to_q', 'leave_at_q']
    """

    name: ClassVar[str] = "bug1"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (BoundaryParams,)
    parameters: ClassVar[tuple[str, ...]] = BoundaryParams.names()

    def __init__(self) -> None:
        super().__init__(Bug1Rule())
