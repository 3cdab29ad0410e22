"""What a boundary follower knows at one step: its robot and episode, and its sight of the goal.

Section 4.1 of the paper: "the robot continuously monitors the obstacles in the path toward
destination during edge detection". Every rule of the Bug family, IBA's and IFGM's asks the
same few questions of one step's percepts: how far the goal is, whether it is in view, how far
the robot-wide corridor towards it is free of remembered obstacle points. :class:`Sight`
answers each of them once per step (the corridor test is the costly one), and every rule reads
the answer from it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.formulas import Unit
from ifgm_ref.core.laserscan import PAPER_HALF_FOV
from ifgm_ref.core.pose import Point, Pose, distance, wrap_angle
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.paper.equations import eq3_goal_angle
from ifgm_ref.paper.percepts.corridor import Offsets, disc_travel, free_length, offsets
from ifgm_ref.planners.tuning import Tuning, derived

#: The goal counts as in view this far inside the view's edge, rad (:meth:`Sight.goal_in_view`).
IN_VIEW_MARGIN = math.radians(10.0)


@dataclass(frozen=True)
class BoundaryParams(Tuning):
    """Tuning shared by the boundary followers; every default is a formula in the robot's
    radius ``r`` (and the other symbols of :mod:`ifgm_ref.core.formulas`).

    Parameters
    ----------
    standoff_margin : float, default ``Max(2 r / 3, pi r / (2 fov))``
        Free space kept between the robot's disc and the followed edge, a length: the
        follower keeps the edge at ``radius + standoff_margin`` from the robot's centre.
        ``2 r / 3`` with the paper's 135-degree sensor or a wider one, since BARN's passages
        are little wider than the robot; a narrower sensor sees less of the edge it rounds,
        so the margin grows as the field of view shrinks: ``r`` at 90 degrees (errata row
        29, with what each margin gave on BARN and in a U).
    corridor_margin : float, default ``r/4``
        The path towards the goal is tested in a corridor of half-width
        ``radius + corridor_margin``: as wide as the robot, plus a little.
    hit_margin : float, default ``r/2``
        An obstacle is *encountered* when the corridor towards the goal is blocked nearer
        than ``radius + standoff_margin + hit_margin``.
    memory_horizon : float, default 8 s
        How long obstacle points are remembered (:class:`PerceptMemory`), a time: long enough
        to round the corner of an obstacle the size of the paper's, short enough to forget it
        once passed.
    return_radius : float, default ``r``
        The robot is back at its hit point when this close to it ...
    min_loop : float, default ``12 r``
        ... after following the edge at least this far.
    view_range : float, default ``Min(R, 15 r)``
        How far the paper's rules look: IBA's free path must be free this far (or to the
        goal), and IFGM's view is closed when every ray of the paper's 135-degree view
        returns within it and a dead-end turn ends where the way ahead is free this far. The
        paper's IR sensor sees 15 robot radii (15 ft); a longer sensor (a 30 m LiDAR in a
        walled field) would find no path free and every view closed, so the rules look no
        farther than the paper's sensor does (errata row 30).
    """

    standoff_margin: float = derived("Max(2*r/3, pi*r/(2*fov))", Unit.LENGTH)
    corridor_margin: float = derived("r/4", Unit.LENGTH)
    hit_margin: float = derived("r/2", Unit.LENGTH)
    memory_horizon: float = derived("8", Unit.TIME)
    return_radius: float = derived("r", Unit.LENGTH)
    min_loop: float = derived("12*r", Unit.LENGTH)
    view_range: float = derived("Min(R, 15*r)", Unit.LENGTH)


@dataclass(frozen=True)
class Episode:
    """The robot and its episode as a boundary follower plans with them, fixed at reset.

    Attributes
    ----------
    goal : Point
        The destination T.
    radius, speed : float
        The robot's radius (a length) and top speed (length/s).
    fov, range_max : float
        The sensor's field of view (rad) and range (a length).
    turn_limit : float
        The largest turn in one step, ``max_turn_rate * dt``, rad.
    dt : float
        The time step, s.
    tuning : BoundaryParams
        The boundary followers' parameters for this episode.
    """

    goal: Point
    radius: float
    speed: float
    fov: float
    range_max: float
    turn_limit: float
    dt: float
    tuning: BoundaryParams

    @classmethod
    def of(cls, goal: Point, params: EpisodeParams, tuning: BoundaryParams) -> Episode:
        """The robot and episode of a run towards ``goal``."""
        return cls(
            goal=Point(*goal),
            radius=params.robot.radius,
            speed=params.robot.speed,
            fov=params.sensor.fov,
            range_max=params.sensor.range_max,
            turn_limit=params.robot.max_turn_rate * params.dt,
            dt=params.dt,
            tuning=tuning,
        )

    @property
    def standoff(self) -> float:
        """Distance kept from the followed edge to the robot's centre."""
        return self.radius + self.tuning.standoff_margin

    @property
    def half_width(self) -> float:
        """Half-width of the corridor the robot needs."""
        return self.radius + self.tuning.corridor_margin

    @property
    def encounter(self) -> float:
        """The hit distance: an obstacle this near in the corridor is met."""
        return self.standoff + self.tuning.hit_margin


def goal_bearing(pose: Pose, goal: Point) -> float:
    """The destination angle theta_d of eq. (3), world frame (the reading we run,
    :func:`~ifgm_ref.paper.equations.eq3_goal_angle`); at the goal itself, where eq. (3) has no
    direction, the robot's heading.

    >>> goal_bearing(Pose(0.0, 0.0, 0.5), Point(0.0, 2.0)) == math.pi / 2
    True
    >>> goal_bearing(Pose(1.0, 1.0, 0.5), Point(1.0, 1.0))
    0.5
    """
    if pose.position == goal:
        return pose.theta
    return eq3_goal_angle(pose.position, goal)


class Sight:
    """One step's sight of the goal from ``pose``: each question asked once, then remembered
    (plain attributes, not ``functools.cached_property``, which takes a lock at every first
    access on Python 3.11).

    Parameters
    ----------
    pose : Pose
        Where the robot is.
    episode : Episode
        The robot and its episode.
    points : (n, 2) array
        The remembered obstacle points (:class:`~ifgm_ref.paper.percepts.memory.PerceptMemory`).
    bearing : float
        The world-frame direction to the goal (the planner's reading of it), rad.

    Examples
    --------
    >>> episode = Episode.of(Point(10.0, 0.0), EpisodeParams(), BoundaryParams.paper())
    >>> sight = Sight(Pose(0.0, 0.0, 0.0), episode, np.array([[4.0, 0.5]]), 0.0)
    >>> sight.goal_distance, sight.goal_free_length, sight.goal_blocked()
    (10.0, 4.0, False)
    >>> sight.goal_in_view(), sight.path_free()
    (True, False)
    >>> sight.nearest_ahead(), sight.meets_obstacle()  # 4 ft ahead: beyond the encounter
    (True, False)
    """

    def __init__(
        self, pose: Pose, episode: Episode, points: NDArray[np.float64], bearing: float
    ) -> None:
        self.pose = pose
        self.episode = episode
        self.points = points
        self.bearing = bearing
        #: The distance to the goal.
        self.goal_distance = distance(pose, episode.goal)
        self._free_length: float | None = None
        self._offsets: Offsets | None = None
        self._distances: NDArray[np.float64] | None = None

    @property
    def offsets(self) -> Offsets:
        """Each remembered point's offset from the robot (shared by every corridor test and
        distance of the step)."""
        if self._offsets is None:
            self._offsets = offsets(self.points, (self.pose.x, self.pose.y))
        return self._offsets

    @property
    def goal_free_length(self) -> float:
        """How far the robot-wide corridor towards the goal is free of remembered points
        (worked out at the first question)."""
        if self._free_length is None:
            pose, half_width = self.pose, self.episode.half_width
            self._free_length = free_length(
                self.points, (pose.x, pose.y), self.bearing, half_width, relative=self.offsets
            )
        return self._free_length

    @property
    def point_distances(self) -> NDArray[np.float64]:
        """The distance from the robot to each remembered point (worked out at the first
        question)."""
        if self._distances is None:
            self._distances = np.hypot(*self.offsets)
        return self._distances

    def goal_blocked(self) -> bool:
        """Whether an obstacle stands in the corridor towards the goal, nearer than both the
        goal and the encounter distance ``standoff + hit_margin``."""
        return self.goal_free_length < min(self.episode.encounter, self.goal_distance)

    def nearest_ahead(self) -> bool:
        """Whether the nearest remembered point lies ahead on the way to the goal: on the
        goal's side of the line through the robot square to the goal's bearing (a point
        exactly abeam is not ahead; with nothing remembered, nothing is)."""
        d = self.point_distances
        if len(d) == 0:
            return False
        i = int(d.argmin())
        dx, dy = self.offsets
        return bool(math.cos(self.bearing) * dx[i] + math.sin(self.bearing) * dy[i] > 0.0)

    def goal_approachable(self) -> bool:
        """Whether the robot's corridor-wide disc can move one step of travel
        (``speed * dt``) straight towards the goal."""
        pose, episode = self.pose, self.episode
        travel = disc_travel(
            self.points, (pose.x, pose.y), self.bearing, episode.half_width, relative=self.offsets
        )
        return travel >= episode.speed * episode.dt

    def meets_obstacle(self) -> bool:
        """Whether the robot meets an obstacle here: one blocks the corridor towards the goal
        (:meth:`goal_blocked`) and it is the one the follower would follow -- the nearest
        remembered point lies ahead (:meth:`nearest_ahead`) -- or the robot cannot move
        towards the goal at all (:meth:`goal_approachable`).

        While the nearest obstacle lies behind or abeam (the one just left, with another
        in the way), the robot moves on towards the one in the way until that one is the
        nearest: a follower that met one obstacle and followed another could go round the
        wrong one for ever (errata row 34)."""
        return self.goal_blocked() and (self.nearest_ahead() or not self.goal_approachable())

    def goal_in_view(self) -> bool:
        """Whether the goal's bearing lies inside the view, :data:`IN_VIEW_MARGIN` from its
        edge.

        The view is the field of view, but no wider than the paper's 135 degrees: a robot
        that "sees" its goal behind it would leave the edge for a goal it must first turn
        to, meet the same edge again and circle for ever (errata row 30)."""
        half = min(self.episode.fov / 2, PAPER_HALF_FOV)
        return abs(wrap_angle(self.bearing - self.pose.theta)) <= half - IN_VIEW_MARGIN

    def path_free(self) -> bool:
        """IBA's free path: the goal in view and its corridor clear as far as the paper's
        sensor sees (``view_range``) or to the goal (section 4.1: "the leaving point is
        selected based on free path")."""
        if not self.goal_in_view():
            return False
        needed = min(self.episode.tuning.view_range, self.goal_distance)
        return self.goal_free_length >= needed
