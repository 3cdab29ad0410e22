"""Bug1's round of one obstacle: what every boundary follower falls back on after a lap.

Paper, section 2.1.1: "In Bug-1, after detecting an obstacle, the robot moves around the
obstacle completely in order to find the point (leaving point) having minimum distance to
destination. The robot restarts following the edge until it reaches to the computed leaving
point and generates a new referenced path to destination." Reference: V. J. Lumelsky and
A. A. Stepanov, "Path-planning strategies for a point mobile automaton moving amidst unknown
obstacles of arbitrary shape", *Algorithmica* 2 (1987) 403-430.

Bug1 is complete: every leaving point Q is the nearest point of its obstacle to the goal T,
so the next obstacle, if any, is met nearer T than Q, and no obstacle is met twice. The other
followers (Bug2, DistBug, IBA, IFGM's IBA) leave earlier, by their own rules, and for a point
robot that sees all round those rules suffice. A disc robot with the paper's 135-degree sensor
can go round an obstacle without any of them firing: the goal is out of view wherever the way
to it is free, and in view only where a second obstacle stands in it (IFGM lapped a post for
ever with a box behind it; DistBug and Bug2 reported a solvable goal unreachable). So every
follower here runs Bug1's round beside its own rule (errata row 34):

1. *first pass*: from the hit point H, lay a trail of the way followed; the loop is closed
   where the robot passes a point of its trail again, heading the same way (within
   :data:`SAME_WAY`), at least ``min_loop`` further on. The trail, not H alone, because IFGM
   may start following away from the edge (after a dead-end escape it drives to the wall),
   so H need not lie on the loop; the same way, because a robot that follows a wall into a
   narrow bay and out again, or crosses its own way between two obstacles near each other,
   has not gone round;
2. *on to Q*: once the loop is closed, retrace the trail, the same way round, to the point Q
   of the loop nearest the goal. Lumelsky and Stepanov's robot follows the edge again, the
   shorter way; ours drives along its own trail, because a disc robot that follows the
   nearest edge may, where two obstacles are near each other, follow the other one the
   second time and never come to Q;
3. at Q, leave towards the goal. Lumelsky and Stepanov's robot first tests whether it can
   move towards the goal from Q; ours reads the test from the loop instead, when it closes
   (:meth:`Circuit.close`): the goal cannot be reached if it lies on the obstacle's side of
   the loop (:func:`encloses`), or if the robot met this obstacle on leaving the last Q and
   its loop has no point nearer the goal than that Q. A disc robot's test at Q could not
   tell the obstacle it went round from another one just ahead of Q.

A follower whose own rule leaves earlier never gets to step 2. The class here holds the
bookkeeping; :class:`~ifgm_ref.planners.boundary.BoundaryPlanner` and
:class:`~ifgm_ref.planners.ifgm.planner.IFGMPlanner` drive it.
"""

from __future__ import annotations

import math
from enum import StrEnum

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.pose import Point, distance
from ifgm_ref.planners.edge_following import FollowSide
from ifgm_ref.planners.sight import Sight

__all__ = ["SAME_WAY", "TRAIL_SPACING_FRACTION", "Circuit", "CircuitPhase", "encloses"]

#: The trail's spacing, as a fraction of ``return_radius``: a path that passes within half a
#: ``return_radius`` of the earlier one comes within ``return_radius`` of one of its points.
TRAIL_SPACING_FRACTION = 0.5

#: A place is passed again the same way when the headings differ by less than this, rad.
#: Along a loop followed twice the headings differ by the follower's corner cutting (a few
#: degrees); where the way crosses itself between two obstacles they differ by far more.
SAME_WAY = math.pi / 4


def encloses(loop: NDArray[np.float64], goal: Point, side: FollowSide) -> bool:
    """Whether ``goal`` lies on the followed obstacle's side of the closed ``loop`` (an
    ``(n, 2)`` array of its points in order, followed with the edge on ``side``).

    A loop followed with the edge on the right runs clockwise round an obstacle it
    encloses, and anticlockwise inside an enclosure; on the left, the other way round.
    The goal is inside the loop when the loop winds round it.

    >>> square = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]])  # anticlockwise
    >>> encloses(square, Point(2.0, 2.0), FollowSide.LEFT)  # round an obstacle, goal inside
    True
    >>> outside = Point(9.0, 2.0)
    >>> encloses(square, outside, FollowSide.LEFT), encloses(square, outside, FollowSide.RIGHT)
    (False, True)
    """
    x, y = loop[:, 0] - goal.x, loop[:, 1] - goal.y
    x2, y2 = np.roll(x, -1), np.roll(y, -1)
    cross = x * y2 - x2 * y
    upward = (y <= 0.0) & (y2 > 0.0) & (cross > 0.0)
    downward = (y > 0.0) & (y2 <= 0.0) & (cross < 0.0)
    goal_inside = int(upward.sum()) != int(downward.sum())
    obstacle_inside = bool(cross.sum() < 0.0) == (side is FollowSide.RIGHT)
    return goal_inside == obstacle_inside


class CircuitPhase(StrEnum):
    """Where a follower is in Bug1's round of the obstacle it follows."""

    #: Not following: moving to the goal, before any obstacle.
    IDLE = "idle"
    #: From H round the whole obstacle, laying the trail.
    FIRST_PASS = "first_pass"
    #: The loop closed: retracing the trail to Q.
    RETURN_TO_Q = "return_to_q"
    #: Left at Q towards the goal.
    LEFT_AT_Q = "left_at_q"


#: The trail's columns: x, y, heading, distance to the goal, distance driven, and 1 where the
#: robot was following an edge (0 elsewhere).
_X, _Y, _HEADING, _GOAL_DISTANCE, _TRAVELLED, _FOLLOWING = range(6)


class Circuit:
    """Bug1's round of the followed obstacle (see the module docstring).

    Attributes
    ----------
    phase : CircuitPhase
        The current phase.
    q_point : Point
        Q, the point of the loop nearest the goal (``nan`` until the loop is closed).
    q_distance : float
        d(Q, T) (``inf`` until the loop is closed).
    left_q : float
        d(Q) of the round before, when the robot left it at Q and met this obstacle without
        leaving another by its own rule in between; ``inf`` otherwise.
    """

    def __init__(self) -> None:
        self.reset()

    def _start(self) -> None:
        self.q_point = Point(math.nan, math.nan)
        self.q_distance = math.inf
        self._trail = np.empty((64, 6))
        self._laid = 0
        self._travelled = 0.0  # the way driven since the round began
        self._last: Point | None = None
        self._next = 0  # on to Q: the trail point steered for
        self._q_index = 0  # Q's trail point

    @property
    def returning(self) -> bool:
        """On the way to Q after a whole loop."""
        return self.phase is CircuitPhase.RETURN_TO_Q

    def reset(self) -> None:
        """A new episode: no obstacle met yet."""
        self.phase = CircuitPhase.IDLE
        self.left_q = math.inf
        self._start()

    def on_hit(self) -> None:
        """An obstacle met: start the first pass. Met on the way from Q, the round remembers
        d(Q) in :attr:`left_q`."""
        self.left_q = self.q_distance if self.phase is CircuitPhase.LEFT_AT_Q else math.inf
        self.phase = CircuitPhase.FIRST_PASS
        self._start()

    def note(self, sight: Sight, following: bool = True) -> None:
        """On the first pass, count the way driven since the last call and lay this step's
        pose on the trail if it lies the trail's spacing beyond the last point laid;
        ``following``: whether the robot follows an edge here (only such points close a
        loop: :meth:`closing`)."""
        if self.phase is not CircuitPhase.FIRST_PASS:
            return
        here = sight.pose.position
        if self._last is not None:
            self._travelled += distance(self._last, here)
        self._last = here
        travelled = self._travelled
        n = self._laid
        spacing = TRAIL_SPACING_FRACTION * sight.body.tuning.return_radius
        if n and travelled < self._trail[n - 1, _TRAVELLED] + spacing:
            return
        if n == len(self._trail):
            self._trail = np.concatenate([self._trail, np.empty_like(self._trail)])
        pose = sight.pose
        self._trail[n] = (pose.x, pose.y, pose.theta, sight.goal_distance, travelled, following)
        self._laid = n + 1

    def closing(self, sight: Sight) -> int | None:
        """On the first pass, the trail point the robot is back at, if any: one laid while
        following an edge, within ``return_radius``, heading the same way (within
        :data:`SAME_WAY`), at least ``min_loop`` driven since; of several, the earliest."""
        if self.phase is not CircuitPhase.FIRST_PASS:
            return None
        tuning = sight.body.tuning
        trail = self._trail[: self._laid]
        back = self._travelled - tuning.min_loop
        old = int(np.searchsorted(trail[:, _TRAVELLED], back, "right"))
        if old == 0:
            return None
        pose = sight.pose
        x, y, heading = trail[:old, _X], trail[:old, _Y], trail[:old, _HEADING]
        near = np.hypot(x - pose.x, y - pose.y) <= tuning.return_radius
        same_way = np.cos(heading - pose.theta) > math.cos(SAME_WAY)
        (back_at,) = (near & same_way & (trail[:old, _FOLLOWING] > 0.0)).nonzero()
        return int(back_at[0]) if len(back_at) else None

    def close(self, sight: Sight, at: int, side: FollowSide) -> bool:
        """Back at trail point ``at`` (:meth:`closing`) after the whole loop, followed with
        the edge on ``side``: take Q, the loop's point nearest the goal, and start on to it.

        Return whether the goal may yet be reached: not if it lies on the obstacle's side of
        the loop (:func:`encloses`: the obstacle gone round surrounds it, or the robot went
        round the inside of an enclosure with the goal outside), nor if this Q is no nearer
        the goal, by a step of travel, than the Q the robot left just before meeting this
        obstacle (:attr:`left_q`: it went round what stood between that Q and the goal and
        found no nearer way)."""
        loop = self._trail[at : self._laid]
        best = int(loop[:, _GOAL_DISTANCE].argmin())
        self.q_point = Point(float(loop[best, _X]), float(loop[best, _Y]))
        self.q_distance = float(loop[best, _GOAL_DISTANCE])
        self._next, self._q_index = at, at + best
        self.phase = CircuitPhase.RETURN_TO_Q
        if encloses(loop[:, :2], sight.body.goal, side):
            return False
        return self.q_distance < self.left_q - sight.body.speed * sight.body.dt

    def heading_to_q(self, sight: Sight) -> float:
        """On to Q: the heading towards the first trail point, not beyond Q, that lies more
        than ``return_radius`` ahead of the robot (the trail points passed are dropped)."""
        pose, reach = sight.pose, sight.body.tuning.return_radius
        trail = self._trail
        while self._next < self._q_index and (
            math.hypot(trail[self._next, _X] - pose.x, trail[self._next, _Y] - pose.y) <= reach
        ):
            self._next += 1
        target = trail[self._next]
        return math.atan2(target[_Y] - pose.y, target[_X] - pose.x)

    def at_q(self, sight: Sight) -> bool:
        """Whether the robot, on its way, has come to Q: every trail point before Q passed,
        and Q within half a ``return_radius`` (the trail's spacing)."""
        spacing = TRAIL_SPACING_FRACTION * sight.body.tuning.return_radius
        return (
            self._next >= self._q_index and distance(sight.pose.position, self.q_point) <= spacing
        )

    def leave(self) -> None:
        """Left at Q towards the goal."""
        self.phase = CircuitPhase.LEFT_AT_Q
