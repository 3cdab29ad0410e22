"""IFGM's inputs to Figure 3: thresholds, state, one step's percepts, and :func:`read_atoms`, the
pure function from percepts and state to the flowchart's atoms (section 4; errata row 18).
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import StrEnum
from typing import NamedTuple

import numpy as np

from ifgm_ref.core.elements import traces
from ifgm_ref.core.formulas import Unit
from ifgm_ref.core.laserscan import Beam, LaserScan
from ifgm_ref.core.pose import Point, Pose, distance
from ifgm_ref.paper.equations import eq1_gap_midpoint
from ifgm_ref.paper.flowchart import Atoms
from ifgm_ref.paper.percepts.clusters import Cluster, Gap, Side
from ifgm_ref.paper.percepts.points import point_to_world, to_world
from ifgm_ref.planners.circuit import Circuit
from ifgm_ref.planners.edge_following import FollowSide
from ifgm_ref.planners.ifgm.readings import GapChoice, Readings
from ifgm_ref.planners.sight import Sight
from ifgm_ref.planners.tuning import Tuning, derived


@traces("d_th", "d_obs", "s3.robot_dimensions")
@dataclass(frozen=True)
class IFGMParams(Tuning):
    """IFGM's thresholds and weights (section 4), each derived from the robot. Why each
    default: ``docs/flowchart.md`` (IFGM's thresholds).

    Parameters
    ----------
    d_th : float, default ``3 r``
        Gap threshold, a length: Case-1 needs a gap wider than this (errata row 12).
    d_obs : float, default ``r + v/2``
        Nearest-obstacle threshold: at or below it IBA takes over (errata row 16).
    d_look : float, default ``8 r``
        Encounter distance: an obstacle in the robot-wide corridor towards the goal nearer
        than this ends *move to goal*; IBA's short one after leaving an edge with an obstacle
        still ahead (errata row 24).
    w_g : float, default ``9 r``
        Gap weight of eq. (4), a length, so that ``w_g / d_th`` keeps its balance with the
        goal at every scale (errata row 29).
    w_d : float, default 1
        Goal weight of eq. (4), a number.
    jump : float, default ``2 r``
        Consecutive returns further apart belong to different obstacles (errata row 15).
    preempt_margin : float, default ``r/2``
        Case-3: another obstacle pre-empts the followed edge when this much nearer.
    turn_done : float, default ``w dt / 2``
        A dead-end turn is done within this angle of its target: half a step's turn
        (errata row 32).
    """

    d_th: float = derived("3*r", Unit.LENGTH)
    d_obs: float = derived("r + v/2", Unit.LENGTH)
    d_look: float = derived("8*r", Unit.LENGTH)
    w_g: float = derived("9*r", Unit.LENGTH)
    w_d: float = derived("1", Unit.NUMBER)
    jump: float = derived("2*r", Unit.LENGTH)
    preempt_margin: float = derived("r/2", Unit.LENGTH)
    turn_done: float = derived("w*dt/2", Unit.ANGLE)


class Mode(StrEnum):
    """What IFGM is doing between two steps."""

    MOVE_TO_GOAL = "move_to_goal"  # on the reference path (eq. (3))
    THROUGH_GAP = "through_gap"  # Case-1: steering through the gap (eqs. (1)-(4))
    FOLLOWING = "following"  # Case-2, too close, Case-3: IBA follows an edge
    DEAD_END_TURN = "dead_end_turn"  # turning in place in 45-degree steps
    ESCAPING = "escaping"  # driving out of the dead end the way found free


@dataclass(frozen=True)
class DeadEndTurn:
    """A dead-end turn under way: from heading ``start`` in ``steps`` 45-degree steps of
    ``sign`` (+1 left); ``escape_from`` is where the robot started driving out, once it has;
    ``walled``: whether the left and the right beam of the view have seen a wall (a return
    within ``d_look``) since."""

    start: float
    sign: int
    steps: int
    escape_from: Point | None = None
    walled: tuple[bool, bool] = (False, False)


@dataclass(frozen=True)
class IFGMState:
    """Everything IFGM carries from one step to the next, in one immutable record; beside it
    only the planner's handle to a growing log, the remembered points
    (:class:`~ifgm_ref.paper.percepts.memory.PerceptMemory`).

    Attributes
    ----------
    mode : Mode
        What the robot is doing.
    turn : DeadEndTurn or None
        The dead-end turn, in ``DEAD_END_TURN`` and ``ESCAPING``.
    followed : Point or None
        The followed obstacle's point, world frame, tracked along its edge.
    stack : tuple of (Point, FollowSide)
        Case-3: the pre-empted obstacles and their sides, the last pushed resumed first.
    gap_mid : Point or None
        The middle of the gap chosen at the last step, world frame, if wider than ``d_th``.
    short_look : bool
        Meeting obstacles at IBA's short encounter distance, Case-1 off (errata row 24).
    escaped : bool
        Following the wall round from outside after a dead end.
    turn_other_way : FollowSide or None
        After a round of Bug1's that found no way on (errata row 34): the side the next
        round follows on, the other one than that round's; ``None`` otherwise.
    side : FollowSide
        The side the followed edge is kept on (IBA's freer side, section 4.1).
    d_min : float
        IBA's yardstick: the least distance to the goal seen while following, over the whole
        episode (errata row 31).
    circuit : Circuit
        Bug1's round of the followed obstacle (errata row 34).
    """

    mode: Mode = Mode.MOVE_TO_GOAL
    turn: DeadEndTurn | None = None
    followed: Point | None = None
    stack: tuple[tuple[Point, FollowSide], ...] = ()
    gap_mid: Point | None = None
    short_look: bool = False
    escaped: bool = False
    turn_other_way: FollowSide | None = None
    side: FollowSide = FollowSide.RIGHT
    d_min: float = math.inf
    circuit: Circuit = field(default_factory=Circuit)

    @property
    def following(self) -> bool:
        """IBA is following an edge (*obstacle avoidance*)."""
        return self.mode is Mode.FOLLOWING

    @property
    def turning(self) -> bool:
        """A dead-end turn sequence (45, 90, 135, 180 degrees) is under way, or the drive
        out of the dead end that ends it."""
        return self.mode in (Mode.DEAD_END_TURN, Mode.ESCAPING)


@dataclass(frozen=True)
class StepInputs:
    """One step's percepts, each computed once, with what they are measured against.

    Attributes
    ----------
    sight : Sight
        The pose, the remembered points and the way to the goal.
    view : LaserScan
        The paper's 135-degree view of the scan, ``view_range`` deep.
    clusters : tuple of Cluster
        The obstacles in the view, right to left.
    gaps : tuple of Gap
        The gaps between consecutive obstacles.
    may_leave : bool
        IBA's leaving rules hold (computed only while following an edge).
    params : IFGMParams
        The thresholds.
    goal_tolerance : float
        The goal counts as reached within this distance.
    readings : Readings
        The readings of the paper's open choices this planner runs.
    step_length : float
        DistBug's ``Step`` in its progress rule, one of IBA's leaving rules.
    """

    sight: Sight
    view: LaserScan
    clusters: tuple[Cluster, ...]
    gaps: tuple[Gap, ...]
    may_leave: bool
    params: IFGMParams
    goal_tolerance: float
    readings: Readings
    step_length: float


class Threshold(NamedTuple):
    """One atom of Figure 3 declared as a quantity against its threshold: :func:`read_atoms`
    decides by :attr:`holds`, :func:`~ifgm_ref.planners.ifgm.margins.margins` measures
    :meth:`margin`.

    Parameters
    ----------
    quantity : float
        The percept, a length (``-inf``: a return nearer than ``range_min``; ``+inf``: none).
    threshold : float
        What it is compared with.
    compare : callable
        The comparison that makes the atom hold, ``operator.le`` (at or below), ``lt`` or ``gt``.
    """

    quantity: float
    threshold: float
    compare: Callable[[float, float], bool]

    @property
    def holds(self) -> bool:
        """The comparison holds."""
        return bool(self.compare(self.quantity, self.threshold))

    def margin(self, unit: float) -> float:
        """``|quantity - threshold| / unit``; an infinite quantity is never within rounding
        of a threshold (``inf``)."""
        return finite_gap(self.quantity, self.threshold) / unit


def finite_gap(value: float, threshold: float) -> float:
    """``|value - threshold|``, ``inf`` unless ``value`` is finite."""
    return abs(value - threshold) if math.isfinite(value) else math.inf


class Thresholds(NamedTuple):
    """The atoms of one step that compare a quantity with a threshold, ``None`` where there
    is nothing to compare (the atom does not hold; ``blocked``: looking short, errata row 34).
    Their quantities and thresholds: :data:`~ifgm_ref.planners.ifgm.margins.DECISIONS`.
    """

    at_goal: Threshold
    blocked: Threshold | None
    close: Threshold | None
    wide: Threshold | None
    front: Threshold
    enclosed: Threshold


def _held(threshold: Threshold | None) -> bool:
    return threshold is not None and threshold.holds


@dataclass(frozen=True)
class StepAtoms:
    """What :func:`read_atoms` makes of one step: the atoms, the thresholds they compare, and the
    percepts behind them that the planner acts on or carries to the next step."""

    atoms: Atoms
    thresholds: Thresholds
    gap: Gap | None  # the chosen gap (Case-1 steers through it)
    gap_mid: Point | None  # its middle, world frame, if wider than d_th
    preemptor: Point | None  # Case-3's obstacle of most impact
    short_look: bool  # the state's short_look, cleared once in the open


def chosen_gap(
    pose: Pose,
    gaps: tuple[Gap, ...],
    previous: Point | None,
    params: IFGMParams,
    choice: GapChoice = GapChoice.KEEP,
) -> tuple[Gap | None, Point | None]:
    """The maximum gap (section 4) -- but, with ``GapChoice.KEEP`` (ours), the gap steered
    through at the last step while it stays wider than ``d_th``, so that two near-equal gaps
    (symmetric obstacles, Figure 7) do not make the robot swerve from one to the other at
    every step (errata row 19): of the gaps wider than ``d_th`` whose middle lies within
    ``jump`` of the last one (``previous``), the one whose middle is nearest it. Returns the
    gap and its middle in the world frame (``None`` unless it is wider than ``d_th``)."""
    if not gaps:
        return None, None
    chosen = max(gaps, key=lambda g: g.width)
    if previous is not None and choice is GapChoice.KEEP:
        kept = params.jump
        for gap in gaps:
            mid = point_to_world(eq1_gap_midpoint(gap.right, gap.left), pose)
            if gap.width > params.d_th and (apart := math.dist(mid, previous)) <= kept:
                chosen, kept = gap, apart
    if chosen.width <= params.d_th:
        return chosen, None
    return chosen, point_to_world(eq1_gap_midpoint(chosen.right, chosen.left), pose)


@traces("fig3.case3", "t1.bug_other_obstacles")
def preemptor(
    pose: Pose, clusters: tuple[Cluster, ...], followed: Point | None, params: IFGMParams
) -> Point | None:
    """Case-3: an obstacle apart from the followed one and nearer than it by a margin; of
    several, the nearest (the one of most impact: "the obstacle near to the robot is given
    higher priority", section 4). Its nearest return, world frame, or ``None``."""
    if followed is None:
        return None
    reach = distance(pose, followed) - params.preempt_margin
    candidates = []
    for c in clusters:
        if c.nearest >= reach:
            continue
        world = to_world(c.xy, pose)
        apart = np.hypot(world[:, 0] - followed.x, world[:, 1] - followed.y)
        if apart.min() > params.jump:
            candidates.append((c.nearest, world[int(c.ranges.argmin())]))
    if not candidates:
        return None
    _, point = min(candidates, key=lambda candidate: candidate[0])
    return Point(float(point[0]), float(point[1]))


def thresholds(percepts: StepInputs, gap: Gap | None, short_look: bool) -> Thresholds:
    """The :class:`Thresholds` of ``percepts`` with the chosen ``gap``, looking short or not."""
    sight, params, view = percepts.sight, percepts.params, percepts.view
    free_ahead = sight.goal_free_length
    nearest = min((c.nearest for c in percepts.clusters), default=None)
    front = view.ranges[view.beam_mask(Beam.FRONT)]
    return Thresholds(
        at_goal=Threshold(sight.goal_distance, percepts.goal_tolerance, operator.le),
        blocked=None
        if short_look
        else Threshold(free_ahead, min(params.d_look, sight.goal_distance), operator.lt),
        close=None if nearest is None else Threshold(nearest, params.d_obs, operator.le),
        wide=None if gap is None else Threshold(gap.width, params.d_th, operator.gt),
        front=Threshold(float(np.fmin.reduce(front, initial=math.inf)), params.d_look, operator.le),
        # -inf (a return nearer than range_min) returns too; nan (an error) does not
        enclosed=Threshold(
            float(view.ranges.max(initial=-math.inf)),
            sight.episode.tuning.view_range,
            operator.le,
        ),
    )


@traces("fig3.both_conditions", "fig3.case1", "fig3.case2", "fig3.dead_end")
def read_atoms(percepts: StepInputs, state: IFGMState) -> StepAtoms:
    """The flowchart's atoms for ``percepts`` in ``state``, and the percepts behind them."""
    sight, params = percepts.sight, percepts.params
    pose, clusters = sight.pose, percepts.clusters
    gap, gap_mid = chosen_gap(
        pose, percepts.gaps, state.gap_mid, params, percepts.readings.gap_choice
    )
    sides = {c.side for c in clusters}
    one_sided = bool(clusters) and (sides == {Side.LEFT} or sides == {Side.RIGHT})
    short_look = state.short_look and not sight.goal_free_length >= params.d_look  # open again
    found = thresholds(percepts, gap, short_look)
    gap_wide = _held(found.wide)
    following = state.following
    other = preemptor(pose, clusters, state.followed, params) if following else None
    atoms = Atoms(
        at_goal=found.at_goal.holds,
        turning=state.turning,
        avoiding=following,
        # Looking short, an obstacle is met as IBA meets one (errata row 34): in the corridor
        # within the encounter distance, and the nearest ahead -- not the one just left.
        blocked=sight.meets_obstacle() if found.blocked is None else found.blocked.holds,
        free=following and percepts.may_leave,
        close=_held(found.close),
        # Case-1 needs a gap measured from afar (d_look): near, gaps look wider than they
        # are (errata row 23), so not while looking short.
        wide=gap_wide and not short_look,
        one_sided=one_sided,
        dead_end=found.front.holds and found.enclosed.holds and not gap_wide,
        preempt=other is not None,
    )
    return StepAtoms(atoms, found, gap, gap_mid, other, short_look)
