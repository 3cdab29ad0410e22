"""Bug1's round of one obstacle, what every boundary follower falls back on after a lap
(errata row 34: with the paper's 135-degree sensor a disc robot can go round an obstacle
without its own leaving rule ever firing).

Paper, section 2.1.1: "In Bug-1, after detecting an obstacle, the robot moves around the
obstacle completely in order to find the point (leaving point) having minimum distance to
destination. The robot restarts following the edge until it reaches to the computed leaving
point and generates a new referenced path to destination." Reference: V. J. Lumelsky and
A. A. Stepanov, "Path-planning strategies for a point mobile automaton moving amidst unknown
obstacles of arbitrary shape", *Algorithmica* 2 (1987) 403-430.

The round (:class:`Circuit`, in the phases of :class:`CircuitPhase`):

1. *first pass*: from the hit point H, lay a trail of the way driven (:meth:`Circuit.noted`);
   the loop is closed where the robot passes a point of its trail again, heading the same way
   (within :data:`SAME_WAY`), at least ``min_loop`` further on (:meth:`Circuit.closing`);
2. *on to Q*: retrace the trail, the same way round, to the loop's point Q nearest the goal
   (:meth:`Circuit.closed`, :meth:`Circuit.advanced`, :meth:`Circuit.at_q`);
3. at Q, leave towards the goal (:meth:`Circuit.left_at_q`), unless the loop showed that the
   goal cannot be reached (:func:`encloses`, :attr:`Circuit.left_q`).

A follower whose own rule leaves earlier never gets to step 2. Why the trail, the heading and
the loop's shape instead of Lumelsky and Stepanov's hit point, edge and test at Q: errata row
34 and ``docs/ifgm-state.md``, which also says who holds the round.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
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

#: Q before the loop is closed.
_NO_Q = Point(math.nan, math.nan)


@dataclass(frozen=True, eq=False)
class Circuit:
    """Bug1's round of the followed obstacle (see the module docstring), one immutable value:
    the methods that change the round return the changed round (:meth:`hit`, :meth:`noted`,
    :meth:`closed`, :meth:`advanced`, :meth:`left_at_q`); the others only read it.

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
    trail : ndarray, shape (n, 6)
        The trail laid on the first pass, one row a point: x, y, heading, distance to the
        goal, distance driven, 1 where following an edge (never written: :meth:`noted`
        returns a longer one).
    travelled : float
        The way driven on the first pass.
    last : Point or None
        Where the first pass was noted last (``None`` before).
    cursor : int
        On to Q: the trail point steered for.
    q_index : int
        Q's trail point.
    """

    phase: CircuitPhase = CircuitPhase.IDLE
    q_point: Point = _NO_Q
    q_distance: float = math.inf
    left_q: float = math.inf
    trail: NDArray[np.float64] = field(default_factory=lambda: np.empty((0, 6)))
    travelled: float = 0.0
    last: Point | None = None
    cursor: int = 0
    q_index: int = 0

    @property
    def returning(self) -> bool:
        """On the way to Q after a whole loop."""
        return self.phase is CircuitPhase.RETURN_TO_Q

    def hit(self) -> Circuit:
        """An obstacle met: a new first pass. Met on the way from Q, the round remembers d(Q)
        in :attr:`left_q`."""
        left_q = self.q_distance if self.phase is CircuitPhase.LEFT_AT_Q else math.inf
        return Circuit(CircuitPhase.FIRST_PASS, left_q=left_q)

    def noted(self, sight: Sight, following: bool = True) -> Circuit:
        """On the first pass, the way driven since the last call counted, and this step's
        pose laid on the trail if it lies the trail's spacing beyond the last point laid;
        ``following``: whether the robot follows an edge here (only such points close a
        loop: :meth:`closing`)."""
        if self.phase is not CircuitPhase.FIRST_PASS:
            return self
        here = sight.pose.position
        travelled = self.travelled
        if self.last is not None:
            travelled += distance(self.last, here)
        trail = self.trail
        spacing = TRAIL_SPACING_FRACTION * sight.episode.tuning.return_radius
        if len(trail) and travelled < trail[-1, _TRAVELLED] + spacing:
            return replace(self, travelled=travelled, last=here)
        pose = sight.pose
        point = (pose.x, pose.y, pose.theta, sight.goal_distance, travelled, following)
        trail = np.concatenate([trail, np.array([point], dtype=np.float64)])
        return replace(self, trail=trail, travelled=travelled, last=here)

    def closing(self, sight: Sight) -> int | None:
        """On the first pass, the trail point the robot is back at, if any: one laid while
        following an edge, within ``return_radius``, heading the same way (within
        :data:`SAME_WAY`), at least ``min_loop`` driven since; of several, the earliest."""
        if self.phase is not CircuitPhase.FIRST_PASS:
            return None
        tuning = sight.episode.tuning
        trail = self.trail
        back = self.travelled - tuning.min_loop
        old = int(np.searchsorted(trail[:, _TRAVELLED], back, "right"))
        if old == 0:
            return None
        pose = sight.pose
        x, y, heading = trail[:old, _X], trail[:old, _Y], trail[:old, _HEADING]
        near = np.hypot(x - pose.x, y - pose.y) <= tuning.return_radius
        same_way = np.cos(heading - pose.theta) > math.cos(SAME_WAY)
        (back_at,) = (near & same_way & (trail[:old, _FOLLOWING] > 0.0)).nonzero()
        return int(back_at[0]) if len(back_at) else None

    def closed(self, sight: Sight, at: int, side: FollowSide) -> tuple[Circuit, bool]:
        """Back at trail point ``at`` (:meth:`closing`) after the whole loop, followed with
        the edge on ``side``: the round with Q taken, the loop's point nearest the goal, and
        on its way to it; and whether the goal may yet be reached.

        It may not if it lies on the obstacle's side of the loop (:func:`encloses`: the
        obstacle gone round surrounds it, or the robot went round the inside of an enclosure
        with the goal outside), nor if this Q is no nearer the goal, by a step of travel,
        than the Q the robot left just before meeting this obstacle (:attr:`left_q`: it went
        round what stood between that Q and the goal and found no nearer way)."""
        loop = self.trail[at:]
        best = int(loop[:, _GOAL_DISTANCE].argmin())
        q_distance = float(loop[best, _GOAL_DISTANCE])
        closed = replace(
            self,
            phase=CircuitPhase.RETURN_TO_Q,
            q_point=Point(float(loop[best, _X]), float(loop[best, _Y])),
            q_distance=q_distance,
            cursor=at,
            q_index=at + best,
        )
        if encloses(loop[:, :2], sight.episode.goal, side):
            return closed, False
        return closed, q_distance < self.left_q - sight.episode.speed * sight.episode.dt

    def advanced(self, sight: Sight) -> Circuit:
        """On to Q: the :attr:`cursor` moved past the trail points, short of Q, that lie
        within ``return_radius`` of the robot."""
        pose, reach = sight.pose, sight.episode.tuning.return_radius
        trail, cursor = self.trail, self.cursor
        while cursor < self.q_index and (
            math.hypot(trail[cursor, _X] - pose.x, trail[cursor, _Y] - pose.y) <= reach
        ):
            cursor += 1
        return self if cursor == self.cursor else replace(self, cursor=cursor)

    def heading_to_q(self, sight: Sight) -> float:
        """On to Q: the heading towards the trail point at the :attr:`cursor`."""
        pose, target = sight.pose, self.trail[self.cursor]
        return math.atan2(target[_Y] - pose.y, target[_X] - pose.x)

    def at_q(self, sight: Sight) -> bool:
        """Whether the robot, on its way, has come to Q: every trail point before Q passed,
        and Q within half a ``return_radius`` (the trail's spacing)."""
        spacing = TRAIL_SPACING_FRACTION * sight.episode.tuning.return_radius
        return (
            self.cursor >= self.q_index and distance(sight.pose.position, self.q_point) <= spacing
        )

    def left_at_q(self) -> Circuit:
        """The round left at Q towards the goal."""
        return replace(self, phase=CircuitPhase.LEFT_AT_Q)
