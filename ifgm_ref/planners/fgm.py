"""Follow the Gap Method (FGM): steer through the middle of the widest free gap, towards the goal.

Reference
---------
V. Sezer and M. Gokasan, "A novel obstacle avoidance algorithm: 'Follow the Gap Method'",
*Robotics and Autonomous Systems* 60(9):1123-1134, 2012 -- as the IFGM paper (Zohaib et al.,
*Studies in Informatics and Control* 23(1):97-106, 2014) summarises it in section 2.2: "FGM
involves three main computations; calculation of the gap array and finding the maximum gap,
calculation of theta_g and finally determination of theta_f ... it assumes the robot and
obstacles as circular objects. It also adds the robot's dimensions into the obstacle
dimensions." The FGM paper itself is not in our store; the formulas are FGM's as secondary
sources give them, implemented in :mod:`ifgm_ref.paper.equations` (``fgm_gap_centre_angle``,
``eq4_final_heading_fgm``).

FGM is a *local* method: it only knows the current scan. Table 1 of the IFGM paper: "The algo.
cannot avoid U shaped obstacles due to its local characteristics" and "H-shaped obstacles are
dead-end scenarios for this algo."; section 5.2: the robot "is steered towards centre of the
obstacle ... At the centre of obstacle, the robot becomes unable to take any decision." This
module reproduces that: when no gap is left the robot stops (speed 0) facing the goal.

==========================  ========================  ============================================
FGM symbol                  here                      meaning
==========================  ========================  ============================================
obstacle radius + robot     ``inflation``             ``r_inf = robot.radius + margin``, ft: each
radius                                                return is a disc of this radius
``phi_i`` (border half-     ``asin(min(1, r/d))``     angular half-width an inflated return at
angle)                                                ``d`` ft blocks, rad
gap array                   :func:`find_gaps`         runs of consecutive free (unblocked) rays
``d_1, phi_1``              ``RayGap.right_*``        right border: distance, clockwise angle
``d_2, phi_2``              ``RayGap.left_*``         left border: distance, counter-clockwise
``theta_gap_c``             ``RayGap.centre``         gap centre angle, robot frame, rad
``theta_goal``              ``goal_angle``            goal bearing, robot frame, rad
``alpha``, ``beta``         ``alpha``, ``beta``       gap and goal weights of the final heading
``d_min``                   ``d_min``                 range of the nearest return, ft
``theta_final``             ``FGMDecision.heading``   final heading, robot frame, rad
==========================  ========================  ============================================

Frames: REP-103 robot frame (x forward, y left, angles counter-clockwise positive) for every
angle here; :class:`FGMPlanner` turns the final heading into a world heading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.elements import traces
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.formulas import Unit
from ifgm_ref.core.intervals import members
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import Behaviour, Command, EpisodeParams, Observation
from ifgm_ref.core.validate import NON_NEGATIVE, require
from ifgm_ref.paper.equations import eq4_final_heading_fgm, fgm_gap_centre_angle
from ifgm_ref.paper.percepts.points import scan_points
from ifgm_ref.planners.edge_following import turn_speed
from ifgm_ref.planners.governor import BrakingGovernor
from ifgm_ref.planners.tuning import Tuning, check_names, derived, parameter_names

__all__ = [
    "FGMBranch",
    "FGMDecision",
    "FGMParams",
    "FGMPlanner",
    "RayGap",
    "blocked_rays",
    "choose_max_gap",
    "fgm_decide",
    "find_gaps",
]

#: Smallest ``d_min`` used in the final heading, ft: a return at range 0 means the robot
#: touches an obstacle; FGM's weight ``alpha / d_min`` is then taken as ``alpha / 1e-6``.
D_MIN_FLOOR = 1e-6


class FGMBranch(StrEnum):
    """The decision FGM took at one step (the trace's ``branch``)."""

    NO_OBSTACLE = "no_obstacle"  #: nothing in the scan: head straight for the goal
    MAX_GAP = "max_gap"  #: steer by the final-heading weighting through the maximum gap
    NO_GAP = "no_gap"  #: every ray blocked: stop, facing the goal (section 5.2)


@dataclass(frozen=True)
class FGMParams(Tuning):
    """FGM's settings, read from ``EpisodeParams.params`` by name.

    The IFGM paper gives no values and our store has no copy of the FGM paper; the defaults
    are ours, each a formula in the robot's radius ``r`` with its reason.

    Parameters
    ----------
    alpha : float, default ``8 r``
        Gap weight of the final heading (multiplied by ``1 / d_min``), >= 0, a length. At
        ``8 r`` the gap and the goal weigh the same when the nearest return is four robot
        diameters away, and the gap dominates nearer than that (measured in the ``box``
        world: ``docs/benchmark.md``, "Measured").
    beta : float, default 1
        Goal weight of the final heading, >= 0, a number; ``alpha`` and ``beta`` must not
        both be 0.
    inflation_margin : float, default ``r/2``
        Free space kept between the robot's disc and every return, >= 0, a length: each
        return is inflated by ``robot.radius + inflation_margin`` (FGM "adds the robot's
        dimensions into the obstacle dimensions", section 2.2). For the paper's robot half a
        foot covers the 0.13 ft it moves per step several times over.
    """

    alpha: float = derived("8*r", Unit.LENGTH, zero=True)
    beta: float = derived("1", Unit.NUMBER, zero=True)
    inflation_margin: float = derived("r/2", Unit.LENGTH, zero=True)

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.alpha == 0 and self.beta == 0:
            raise ParameterError("`alpha` and `beta` must not both be 0")


@dataclass(frozen=True)
class RayGap:
    """One run of consecutive free rays, ``first`` to ``last`` (right to left).

    A border's distance is that of the nearest return blocking the ray just outside the gap;
    where the gap reaches the edge of the field of view there is no such return, and the
    border distance is ``range_max`` (the farthest an unseen obstacle can be said to be).
    """

    first: int
    last: int
    right_angle: float
    right_distance: float
    left_angle: float
    left_distance: float

    @property
    def rays(self) -> int:
        """Number of free rays in the gap: its angular width in ray increments, plus one."""
        return self.last - self.first + 1

    @property
    def width(self) -> float:
        """Angle from the right border ray to the left one, rad (0 for a one-ray gap)."""
        return self.left_angle - self.right_angle

    @property
    def centre(self) -> float:
        """FGM's gap centre angle, robot frame, rad (cosine and Apollonius theorems).

        ``fgm_gap_centre_angle(d_1, phi_1, d_2, phi_2)`` with ``phi_1 = -right_angle``
        (clockwise) and ``phi_2 = left_angle``: the direction of the midpoint of the two
        border points. That formula needs ``phi_1 + phi_2 <= pi``; a gap wider than pi (only
        with a field of view wider than pi) is steered through its angular bisector.
        """
        if self.width > math.pi:
            return (self.right_angle + self.left_angle) / 2.0
        return fgm_gap_centre_angle(
            self.right_distance, -self.right_angle, self.left_distance, self.left_angle
        )


@dataclass(frozen=True)
class FGMDecision:
    """FGM's answer to one scan: the branch, the final heading and what led to it.

    ``heading`` is robot-frame (rad): the final heading for ``max_gap``, the goal angle
    otherwise. ``gap`` is the maximum gap (``None`` unless ``max_gap``); ``d_min`` is the
    nearest return's range (``inf`` with no return).
    """

    branch: FGMBranch
    heading: float
    gap: RayGap | None
    d_min: float


#: A return blocks the rays up to this much beyond its half-width, rad: rounding at an
#: exact border keeps the border ray blocked.
BORDER = 1e-12
#: From this many (return, ray) pairs on, only the rays near each return are tested: a
#: 720-ray LiDAR's scan has some 500,000, the paper's 76-ray sensor at most 5,776.
PAIRS_FROM = 16384


def blocked_rays(
    scan: LaserScan, inflation: float
) -> tuple[NDArray[np.bool_], NDArray[np.float64]]:
    """Which rays an inflated return blocks, and the range of the nearest blocking return.

    Every return (every finite range, and ``-inf`` read as ``range_min``) is an obstacle point
    inflated to a disc of radius ``inflation``; seen from the robot at range ``d`` that disc
    covers the rays within ``asin(min(1, inflation / d))`` of the return's own ray (pi/2 when
    the robot is inside the disc). Rays with no return (``+inf``) or an error (``nan``) block
    nothing by themselves.

    Parameters
    ----------
    scan : LaserScan
        The current scan.
    inflation : float
        Radius of every inflated return, ft (robot radius plus margin), >= 0.

    Returns
    -------
    blocked : (n,) bool array
        ``True`` for every blocked ray.
    distance : (n,) float array
        Range of the nearest return blocking each ray, ft; ``inf`` for free rays.

    Examples
    --------
    One return 2 ft ahead inflated by 1 ft blocks the rays within asin(1/2) = 30 degrees:

    >>> deg = math.radians
    >>> scan = LaserScan(deg(-40), deg(40), deg(20), 0.0, 10.0, [math.inf, math.inf, 2.0,
    ...                  math.inf, math.inf])
    >>> blocked, distance = blocked_rays(scan, 1.0)
    >>> blocked.tolist(), distance.tolist()
    ([False, True, True, True, False], [inf, 2.0, 2.0, 2.0, inf])

    No inflation blocks only the return's own ray; a return inside the disc blocks +-90 deg:

    >>> blocked_rays(scan, 0.0)[0].tolist()
    [False, False, True, False, False]
    >>> blocked_rays(scan, 2.5)[0].tolist()
    [True, True, True, True, True]
    """
    require("inflation", inflation, NON_NEGATIVE)
    angles = scan.angles
    n = len(angles)
    points = scan_points(scan)
    if len(points) == 0:
        return np.zeros(n, dtype=bool), np.full(n, np.inf)
    d = points.ranges
    with np.errstate(divide="ignore"):
        ratio = np.where(d > 0.0, inflation / np.where(d > 0.0, d, 1.0), 1.0)
    half = np.arcsin(np.minimum(1.0, ratio))
    distance = _nearest_blocking(angles, points.angles, half, d)
    return np.isfinite(distance), distance


def _nearest_blocking(
    angles: NDArray[np.float64],
    at: NDArray[np.float64],
    half: NDArray[np.float64],
    d: NDArray[np.float64],
) -> NDArray[np.float64]:
    """For each ray angle, the least range ``d[i]`` of a return at angle ``at[i]`` whose
    half-width ``half[i]`` covers it (``inf`` for none). A wide scan tests each return against
    the rays near it only (:func:`ifgm_ref.core.intervals.members`), by the same comparison."""
    if len(d) * len(angles) < PAIRS_FROM:
        # covers[i, j]: return i blocks ray j (a tolerance keeps exact borders blocked).
        covers = np.abs(angles[np.newaxis, :] - at[:, np.newaxis]) <= half[:, None] + BORDER
        nearest: NDArray[np.float64] = np.where(covers, d[:, np.newaxis], np.inf).min(axis=0)
        return nearest
    order = np.argsort(angles, kind="stable")
    reach = half + 2.0 * BORDER
    owner, position = members(angles[order], at - reach, at + reach)
    ray = order[position]
    covers = np.abs(angles[ray] - at[owner]) <= half[owner] + BORDER
    nearest = np.full(len(angles), np.inf)
    np.minimum.at(nearest, ray[covers], d[owner[covers]])
    return nearest


def find_gaps(scan: LaserScan, inflation: float) -> tuple[RayGap, ...]:
    """The gap array: every run of consecutive free rays, right to left.

    See :func:`blocked_rays` for which rays are free and :class:`RayGap` for the borders.

    Examples
    --------
    A post straight ahead leaves a gap on each side, bounded by the post and by the edge of
    the field of view (at ``range_max``):

    >>> deg = math.radians
    >>> scan = LaserScan(deg(-60), deg(60), deg(10), 0.0, 10.0,
    ...                  [math.inf] * 6 + [3.0] + [math.inf] * 6)
    >>> [(g.first, g.last, g.right_distance, g.left_distance) for g in find_gaps(scan, 1.0)]
    [(0, 4, 10.0, 3.0), (8, 12, 3.0, 10.0)]

    Nothing seen: one gap over the whole field of view; everything blocked: no gap.

    >>> [(g.first, g.last) for g in find_gaps(LaserScan(-1.0, 1.0, 1.0, 0.0, 5.0,
    ...                                                 [math.inf] * 3), 1.0)]
    [(0, 2)]
    >>> find_gaps(LaserScan(-1.0, 1.0, 1.0, 0.0, 5.0, [1.0] * 3), 1.0)
    ()
    """
    blocked, distance = blocked_rays(scan, inflation)
    angles = scan.angles
    n = len(blocked)
    free = ~blocked
    edges = np.diff(np.concatenate([[False], free, [False]]).astype(np.int8))
    starts = np.flatnonzero(edges == 1)
    ends = np.flatnonzero(edges == -1) - 1
    gaps = []
    for a, b in zip(starts.tolist(), ends.tolist(), strict=True):
        right_d = float(distance[a - 1]) if a > 0 else scan.range_max
        left_d = float(distance[b + 1]) if b < n - 1 else scan.range_max
        gaps.append(RayGap(a, b, float(angles[a]), right_d, float(angles[b]), left_d))
    return tuple(gaps)


def choose_max_gap(gaps: tuple[RayGap, ...], goal_angle: float) -> RayGap | None:
    """The maximum gap: the one with the most free rays (the widest angular run).

    FGM's maximum gap is the widest gap *in angle*, the one with the most free elements in
    the gap array; counting rays makes the comparison exact. Ties go to the gap whose centre
    is nearer the goal angle (rad, robot frame), then to the rightmost, so the choice is
    deterministic.

    Examples
    --------
    >>> narrow = RayGap(0, 2, -1.0, 5.0, -0.8, 5.0)
    >>> wide = RayGap(5, 12, -0.4, 5.0, 1.0, 5.0)
    >>> choose_max_gap((narrow, wide), goal_angle=-1.0) is wide
    True
    >>> choose_max_gap((), goal_angle=0.0) is None
    True
    """
    if not gaps:
        return None
    return max(
        gaps,
        key=lambda g: (g.rays, -round(abs(wrap_angle(g.centre - goal_angle)), 9), -g.first),
    )


def fgm_decide(
    scan: LaserScan, goal_angle: float, *, inflation: float, alpha: float, beta: float
) -> FGMDecision:
    """FGM on one scan: the branch taken and the robot-frame heading to steer.

    * No return in the scan: ``no_obstacle``, heading ``goal_angle``.
    * Some free ray: ``max_gap``; the heading is FGM's final heading
      ``((alpha / d_min) theta_gap_c + beta theta_goal) / (alpha / d_min + beta)``
      (:func:`~ifgm_ref.paper.equations.eq4_final_heading_fgm`) with the maximum gap's centre.
    * Every ray blocked: ``no_gap``, heading ``goal_angle`` -- FGM "cannot find theta_g and
      thus theta_f" (section 2.2).

    Examples
    --------
    A post straight ahead, the goal straight ahead: the robot turns off to one side.

    >>> deg = math.radians
    >>> scan = LaserScan(deg(-60), deg(60), deg(10), 0.0, 10.0,
    ...                  [math.inf] * 6 + [3.0] + [math.inf] * 6)
    >>> decision = fgm_decide(scan, 0.0, inflation=1.0, alpha=4.0, beta=1.0)
    >>> str(decision.branch), decision.gap.first, round(math.degrees(decision.heading), 1)
    ('max_gap', 0, -29.2)
    """
    points = scan_points(scan)
    if len(points) == 0:
        return FGMDecision(FGMBranch.NO_OBSTACLE, goal_angle, None, math.inf)
    d_min = float(points.ranges.min())
    gap = choose_max_gap(find_gaps(scan, inflation), goal_angle)
    if gap is None:
        return FGMDecision(FGMBranch.NO_GAP, goal_angle, None, d_min)
    heading = eq4_final_heading_fgm(
        gap.centre, goal_angle, alpha=alpha, beta=beta, d_min=max(d_min, D_MIN_FLOOR), heading=0.0
    )
    return FGMDecision(FGMBranch.MAX_GAP, heading, gap, d_min)


@traces("fgm", "t1.fgm_u", "t1.fgm_h", "s5.fgm_trapped")
class FGMPlanner:
    """Follow the Gap Method on the current scan only; stops when no gap is left.

    Speed is :func:`~ifgm_ref.planners.edge_following.turn_speed`: full speed when facing the
    final heading, slower while turning, turning in place beyond 90 degrees; 0 on ``no_gap``.

    Examples
    --------
    >>> planner = FGMPlanner()
    >>> planner.reset(Pose(0.0, 0.0, 0.0), Point(10.0, 0.0), EpisodeParams())
    >>> empty = LaserScan(-1.0, 1.0, 1.0, 0.0, 15.0, [math.inf] * 3)
    >>> command = planner.step(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(10.0, 0.0), empty))
    >>> command.heading, round(command.speed, 3), command.branch
    (0.0, 1.322, 'no_obstacle')
    """

    name: ClassVar[str] = "fgm"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (FGMParams,)
    #: Names of the settings read from ``EpisodeParams.params``.
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self) -> None:
        self.tuning = FGMParams.for_episode(EpisodeParams())
        self.radius = 1.0
        self.speed = 1.0
        self.last: FGMDecision | None = None
        self.governor = BrakingGovernor()

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Read the settings from ``params.params`` (see :class:`FGMParams`); unknown names
        are an error."""
        check_names(params.params, self.parameters, self.name)
        self.tuning = FGMParams.for_episode(params)
        self.radius = params.robot.radius
        self.speed = params.robot.speed
        self.last = None
        self.governor.reset(params)

    @property
    def inflation(self) -> float:
        """Radius every return is inflated by: robot radius plus margin."""
        return self.radius + self.tuning.inflation_margin

    def step(self, observation: Observation) -> Command:
        """Decide from the current scan (see :func:`fgm_decide`), then stop in time (the
        braking governor, :mod:`~ifgm_ref.planners.governor`)."""
        return self.governor(self.decide(observation), observation)

    def decide(self, observation: Observation) -> Command:
        """FGM's command for ``observation`` (see :func:`fgm_decide`)."""
        pose, goal = observation.pose, observation.goal
        goal_angle = wrap_angle(math.atan2(goal.y - pose.y, goal.x - pose.x) - pose.theta)
        decision = fgm_decide(
            observation.scan,
            goal_angle,
            inflation=self.inflation,
            alpha=self.tuning.alpha,
            beta=self.tuning.beta,
        )
        self.last = decision
        heading = wrap_angle(pose.theta + decision.heading)
        if decision.branch is FGMBranch.NO_GAP:
            speed = 0.0
        else:
            speed = turn_speed(decision.heading, self.speed)
        behaviour = (
            Behaviour.MOVE_TO_GOAL
            if decision.branch is FGMBranch.NO_OBSTACLE
            else Behaviour.OBSTACLE_AVOIDANCE
        )
        return Command(heading, speed, behaviour=behaviour, branch=str(decision.branch))
