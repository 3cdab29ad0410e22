"""How far each of one IFGM step's decisions was from going the other way.

A port that follows the reference's readings may still decide otherwise where a decision
sits on its threshold: a gap within rounding of ``d_th``, two gaps of equal width, two side
beams equally open. :func:`margins` measures, for one step, the distance of every such
quantity from the value that would flip it, so that the oracle's reference agreement
(``agrees_with_reference``, :mod:`ifgm_ref.oracle.agreement`) can tell a port's tie from
a port's fault. Lengths are in robot radii and angles in radians, so that one tie tolerance
serves every robot and unit (errata row 29's rule: no absolute lengths).
"""

from __future__ import annotations

import math

import numpy as np

from ifgm_ref.core.laserscan import PAPER_HALF_FOV, Beam
from ifgm_ref.core.pose import Point, distance, wrap_angle
from ifgm_ref.paper.equations import eq1_gap_midpoint
from ifgm_ref.paper.flowchart import Branch
from ifgm_ref.paper.percepts.clusters import Gap
from ifgm_ref.paper.percepts.points import point_to_world
from ifgm_ref.planners.distbug import DistBugRule
from ifgm_ref.planners.iba import beam_openness
from ifgm_ref.planners.ifgm.atoms import IFGMState, StepAtoms, StepInputs, finite_gap
from ifgm_ref.planners.ifgm.readings import DeadEndSide, GapChoice, GapReading, LeavingRule
from ifgm_ref.planners.sight import IN_VIEW_MARGIN, Sight

__all__ = ["DECISIONS", "margins"]

#: The decisions :func:`margins` measures, and what each compares.
DECISIONS: dict[str, str] = {
    "at_goal": "the distance to the goal against the goal tolerance",
    "blocked": "the corridor towards the goal against the encounter distance",
    "close": "the nearest obstacle against d_obs",
    "wide": "the chosen gap's width against d_th",
    "widest_gap": "the widest gap's width against the next widest",
    "gap_ends": "where Case-1 steers through the gap: its closest pair of returns against the "
    "next closest pair whose middle lies elsewhere",
    "kept_gap": "the gap kept from the last step: each candidate's middle against jump and "
    "its width against d_th, the nearest middle against the next",
    "front": "the front beam's nearest return against d_look",
    "enclosed": "the view's farthest return against view_range",
    "side": "an obstacle's end ray against the heading (its side)",
    "side_beams": "the left beam's openness against the right's (the freer side)",
    "preempt": "an obstacle's nearest return against the followed one less the margin",
    "nearest_point": "the followed point tracked along its edge: the nearest candidate "
    "against the next nearest seen elsewhere, and a nearer point elsewhere against jump",
    "leave": "IBA's leaving rules: the goal's bearing against the view's edge, the corridor "
    "against the length a free path needs, where it leads against d_min, and DistBug's reach "
    "against 0 and d_min - Step",
}


def margins(
    percepts: StepInputs,
    state: IFGMState,
    step_atoms: StepAtoms,
    branch: Branch,
    *,
    apart: float,
    followed_before: Point | None,
) -> dict[str, float]:
    """The margin of every decision of :data:`DECISIONS` that a step consults on its way to
    ``branch``, given its ``percepts``, the ``state`` they were read in and the ``step_atoms``
    (radii or radians, never negative; the smallest is the nearest tie).

    Figure 3 consults the goal and the corridor at every step; the gap, the nearest obstacle
    and the dead end only on meeting an obstacle; the freer side only where IBA takes over
    or Case-3 pre-empts (where the beams are equal, the goal's side decides: its bearing is
    the margin); the ends of the gap only where Case-1 steers through it; the followed edge's
    point and the pre-emption only while following. The followed point is tracked from
    ``followed_before``, the one followed the step before (``None`` if none), as
    :meth:`~ifgm_ref.planners.ifgm.planner.IFGMPlanner.perceive` tracks it. Of the remembered
    points, only those seen more than ``apart`` rad from the one tracked are another choice of point
    to follow: a wall is remembered as a cloud of points a hair apart, and following one of them
    rather than its neighbour turns the robot by less than their angle apart (the oracle's heading
    tolerance is the ``apart`` that matters).

    >>> from ifgm_ref.planners.ifgm import IFGMPlanner
    >>> from ifgm_ref.io.scenarios import resolve_world
    >>> from ifgm_ref.sim.simulator import simulate
    >>> from ifgm_ref.core.params import SimParams
    >>> planner = IFGMPlanner()
    >>> _ = simulate(resolve_world("post"), planner, SimParams(max_time=0.1))
    >>> found = margins(*planner.last_seen, planner.last_branch, apart=0.01, followed_before=None)
    >>> {name: round(value, 3) for name, value in found.items()}
    {'at_goal': 59.368, 'blocked': inf}
    """
    r, declared = percepts.sight.episode.radius, step_atoms.thresholds
    found = {"at_goal": declared.at_goal.margin(r)}
    if declared.blocked is not None:  # not while looking short
        found["blocked"] = declared.blocked.margin(r)
    atoms = step_atoms.atoms
    if atoms.blocked and not atoms.avoiding and not atoms.turning:  # meeting an obstacle
        found.update(_encounter(percepts, step_atoms))
    readings = percepts.readings
    if branch in _TAKING_A_SIDE or (
        branch is Branch.DEAD_END_TURN
        and state.turn is None
        and readings.dead_end_side is DeadEndSide.FREER
    ):
        found["side_beams"] = _side_margin(percepts)
    if readings.gap_choice is GapChoice.WIDEST:  # consulted at every step, not only on meeting
        found.update(_widest_margin(percepts))
    elif state.gap_mid is not None:
        found.update(_kept_gap_margin(percepts, state.gap_mid))
    if branch is Branch.CASE1_GAP and step_atoms.gap is not None:
        found.update(_gap_ends_margin(percepts, step_atoms.gap, apart))
    if state.following:
        found.update(_following(percepts, state, followed_before, apart))
    return found


def _gap_ends_margin(percepts: StepInputs, gap: Gap, apart: float) -> dict[str, float]:
    """``gap_ends``: how much wider than ``gap`` the next closest pair of returns of its two
    obstacles is, among the pairs whose middle lies more than ``apart`` rad (seen from the
    robot) from ``gap``'s, in radii. Two parallel faces have many closest pairs: rounding
    picks one, and the robot steers at its middle (eq. 1). The printed reading's gaps run
    between the obstacles' means, a choice of no pair (no margin)."""
    if percepts.readings.gap_points is not GapReading.NEAREST:
        return {}
    at = next((k for k, g in enumerate(percepts.gaps) if g == gap), None)
    if at is None:
        return {}
    right, left = percepts.clusters[at].xy, percepts.clusters[at + 1].xy
    middle = np.asarray(eq1_gap_midpoint(gap.right, gap.left))
    pairs = np.linalg.norm(right[:, None, :] - left[None, :, :], axis=2)
    middles = (right[:, None, :] + left[None, :, :]) / 2.0
    elsewhere = np.linalg.norm(middles - middle, axis=2) > apart * float(np.hypot(*middle))
    if not elsewhere.any():
        return {}
    return {"gap_ends": float(pairs[elsewhere].min() - gap.width) / percepts.sight.episode.radius}


def _following(
    percepts: StepInputs, state: IFGMState, before: Point | None, apart: float
) -> dict[str, float]:
    """The margins of the decisions taken while following an edge: Case-3's pre-emption, the
    followed point tracked from ``before`` (:func:`_tracking_margin`) and IBA's leaving
    rules."""
    sight, params, followed = percepts.sight, percepts.params, state.followed
    r = sight.episode.radius
    found = {"leave": _leave_margin(percepts, state)}
    if followed is not None:
        found["nearest_point"] = _tracking_margin(sight, followed, before, params.jump, apart) / r
        if percepts.clusters:
            reach = distance(sight.pose, followed) - params.preempt_margin
            found["preempt"] = min(abs(c.nearest - reach) for c in percepts.clusters) / r
    return found


def _leave_margin(percepts: StepInputs, state: IFGMState) -> float:
    """The nearest of IBA's leaving rules to going the other way
    (:func:`~ifgm_ref.planners.iba.leaves`): the goal's bearing against the edge of the view
    (rad); with the goal in view, in radii, the corridor towards it against the length a free
    path needs, the distance that path leads to against ``d_min``, and, where the progress
    rule is on, DistBug's reach against 0 and against ``d_min - Step``."""
    sight = percepts.sight
    edge = min(sight.episode.fov / 2, PAPER_HALF_FOV) - IN_VIEW_MARGIN
    off = abs(wrap_angle(sight.bearing - sight.pose.theta))
    if off > edge:  # out of view: no rule can leave
        return off - edge
    d, free = sight.goal_distance, sight.goal_free_length
    view_range = sight.episode.tuning.view_range
    lengths = [
        finite_gap(free, min(view_range, d)),
        finite_gap(d - min(free, view_range), state.d_min),
    ]
    progress = percepts.readings.leaving_rule is LeavingRule.FREE_PATH_OR_PROGRESS
    if progress and not state.escaped:
        reach = d - DistBugRule.free_range(sight)
        lengths += [abs(reach), finite_gap(reach, state.d_min - percepts.step_length)]
    return min(edge - off, min(lengths) / sight.episode.radius)


def _tracking_margin(
    sight: Sight, tracked: Point, before: Point | None, jump: float, apart: float
) -> float:
    """How near the choice of ``tracked``
    (:func:`~ifgm_ref.planners.ifgm.planner.nearest_remembered` from ``before``) came to another
    point seen more than ``apart`` rad from it: the candidates are the remembered points within
    ``jump`` of ``before`` (all of them when there is no ``before`` or none is within it); the
    nearest candidate elsewhere is that much farther than ``tracked``, and a point elsewhere nearer
    than ``tracked`` but not a
    candidate lies that much beyond ``jump`` from ``before`` (``inf`` if neither exists)."""
    points, d = sight.points, sight.point_distances
    pose = sight.pose
    bearings = np.arctan2(points[:, 1] - pose.y, points[:, 0] - pose.x)
    towards = math.atan2(tracked.y - pose.y, tracked.x - pose.x)
    elsewhere = np.abs(np.angle(np.exp(1j * (bearings - towards)))) > apart
    d_tracked = distance(pose, tracked)
    found = [math.inf]
    candidates = np.ones(len(d), dtype=bool)
    if before is not None:
        from_before = np.hypot(points[:, 0] - before.x, points[:, 1] - before.y)
        if (from_before <= jump).any():
            candidates = from_before <= jump
            outside = elsewhere & ~candidates & (d < d_tracked)
            if outside.any():
                found.append(float(from_before[outside].min()) - jump)
    inside = elsewhere & candidates
    if inside.any():
        found.append(float(d[inside].min()) - d_tracked)
    return min(found)


#: The branches that pick the side to keep an obstacle on (IBA's freer side).
_TAKING_A_SIDE = frozenset(
    {Branch.CASE2_NARROW_GAP, Branch.CASE2_ONE_SIDED, Branch.TOO_CLOSE, Branch.CASE3_PREEMPT}
)


def _encounter(percepts: StepInputs, step_atoms: StepAtoms) -> dict[str, float]:
    """The margins of the decisions taken on meeting an obstacle: too close, one-sided, the
    gap, the dead end."""
    r, declared = percepts.sight.episode.radius, step_atoms.thresholds
    found: dict[str, float] = {}
    if declared.close is not None:
        found["close"] = declared.close.margin(r)
        found["side"] = min(abs(float(c.angles[i])) for c in percepts.clusters for i in (0, -1))
    if declared.wide is not None:
        found["wide"] = declared.wide.margin(r)
    found.update(_widest_margin(percepts))
    found["front"] = declared.front.margin(r)
    found["enclosed"] = declared.enclosed.margin(r)
    return found


def _kept_gap_margin(percepts: StepInputs, previous: Point) -> dict[str, float]:
    """``kept_gap``: how near :func:`~ifgm_ref.planners.ifgm.atoms.chosen_gap`'s hold on the
    last step's gap (middle ``previous``) was to taking another, in radii: each gap's middle
    against ``jump`` from ``previous`` and, for those within it, its width against ``d_th``;
    and the nearest wide middle against the next (none without a gap)."""
    params, pose = percepts.params, percepts.sight.pose
    near, found = [], []
    for gap in percepts.gaps:
        apart = math.dist(point_to_world(eq1_gap_midpoint(gap.right, gap.left), pose), previous)
        found.append(abs(apart - params.jump))
        if apart <= params.jump:
            found.append(abs(gap.width - params.d_th))
            if gap.width > params.d_th:
                near.append(apart)
    if len(near) > 1:
        first, second = sorted(near)[:2]
        found.append(second - first)
    return {"kept_gap": min(found) / percepts.sight.episode.radius} if found else {}


def _widest_margin(percepts: StepInputs) -> dict[str, float]:
    """``widest_gap``: how much wider the widest gap is than the next widest, in radii (no
    margin with fewer than two gaps)."""
    widths = sorted((g.width for g in percepts.gaps), reverse=True)
    if len(widths) < 2:
        return {}
    return {"widest_gap": (widths[0] - widths[1]) / percepts.sight.episode.radius}


def _side_margin(percepts: StepInputs) -> float:
    """The freer side's margin: the beams' difference in openness, in radii; where they are
    equal, the goal's bearing off the heading, whose sign decides."""
    sight, view = percepts.sight, percepts.view
    left, right = beam_openness(view, Beam.LEFT), beam_openness(view, Beam.RIGHT)
    if not math.isclose(left, right, rel_tol=1e-9):
        return abs(left - right) / sight.episode.radius
    return abs(wrap_angle(sight.bearing - sight.pose.theta))
