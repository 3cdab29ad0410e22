"""The shared skeleton of the boundary-following planners: Bug1, Bug2, DistBug and IBA.

Section 2.1 of the paper: Bug algorithms have "two behaviours, *move to goal* and *obstacle
avoidance*. In *move to goal*, initially the robot generates a reference path and follows it
until obstacle is encountered or destination is reached." In *obstacle avoidance* it follows
the obstacle's edge until a leaving condition -- the one thing the variants disagree on --
holds, then regenerates the reference path from where it is (section 4).

A subclass chooses the side to follow (:meth:`BoundaryPlanner.choose_side`), the leaving rule
(:meth:`BoundaryPlanner.should_leave`) and what to do when the robot comes back to the point
where it met the obstacle (:meth:`BoundaryPlanner.on_loop_closed`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

from ifgm_ref.laserscan import PAPER_HALF_FOV
from ifgm_ref.paper import traces
from ifgm_ref.percepts.corridor import disc_travel, free_length
from ifgm_ref.percepts.memory import PerceptMemory
from ifgm_ref.planners.edge_following import FollowSide, follow_heading, turn_speed
from ifgm_ref.planners.tuning import Tuning, Unit, check_names, derived
from ifgm_ref.pose import Point, Pose, distance, wrap_angle
from ifgm_ref.protocol import Behaviour, Command, EpisodeParams, Observation

#: The guard's search step round a blocked heading, rad, and the number of steps each way (a
#: right angle): coarse enough to be cheap, fine enough to find a gap the robot fits.
GUARD_STEP = math.pi / 12
GUARD_STEPS = 6

#: Stop reason of a planner that has proved the goal cannot be reached.
GOAL_UNREACHABLE = "goal_unreachable"


@dataclass(frozen=True)
class BoundaryParams(Tuning):
    """Tuning shared by the boundary followers; every default is a formula in the robot's
    radius ``r`` (and the other symbols of :mod:`ifgm_ref.planners.tuning`).

    Parameters
    ----------
    standoff_margin : float, default ``Max(2 r / 3, pi r / (2 fov))``
        Free space kept between the robot's disc and the followed edge, a length: the
        follower keeps the edge at ``radius + standoff_margin`` from the robot's centre.
        ``2 r / 3`` with the paper's 135-degree sensor or a wider one. It was ``r`` (1 ft for
        the paper's robot); on BARN's 200 worlds IFGM then reached the goal in 90 % of them,
        and in 97 % with ``2 r / 3`` (the paper's IR sensor): BARN's passages are little
        wider than the robot. A narrower sensor sees less of the edge it rounds, so the
        margin grows as the field of view shrinks: ``r`` at 90 degrees, where ``2 r / 3``
        swept the robot into the unseen far corner of a U's arm (errata row 29).
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


class BoundaryPlanner:
    """Move to goal; on meeting an obstacle, follow its edge until the leaving rule holds."""

    name: ClassVar[str] = "boundary"
    #: The parameter classes the planner reads (``ifgm-ref planners`` lists their fields).
    tunings: ClassVar[tuple[type[Tuning], ...]] = (BoundaryParams,)
    #: The planner's parameter names.
    parameters: ClassVar[tuple[str, ...]] = BoundaryParams.names()

    def __init__(self) -> None:
        self.tuning = BoundaryParams.for_episode(EpisodeParams())
        self.memory = PerceptMemory(self.tuning.memory_horizon)
        self.goal = Point(0.0, 0.0)
        self.radius = 1.0
        self.speed = 1.0
        self.fov = math.pi
        self.range_max = math.inf
        self.turn_limit = math.pi
        self.dt = 0.1
        self.following = False
        self.side = FollowSide.RIGHT
        self.hit_point = Point(0.0, 0.0)
        self.travelled = 0.0
        self._last = Point(0.0, 0.0)

    # -- protocol ---------------------------------------------------------------------------
    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Start in *move to goal* towards ``goal``; read tuning from ``params.params``
        (unknown names are an error)."""
        check_names(params.params, self.parameters, self.name)
        self.tuning = BoundaryParams.for_episode(params)
        self.memory = PerceptMemory(self.tuning.memory_horizon)
        self.goal = Point(*goal)
        self.radius = params.robot.radius
        self.speed = params.robot.speed
        self.fov = params.sensor.fov
        self.range_max = params.sensor.range_max
        self.turn_limit = params.robot.max_turn_rate * params.dt
        self.dt = params.dt
        self.following = False
        self._last = Point(start[0], start[1])

    def step(self, observation: Observation) -> Command:
        """Decide (:meth:`act`), then never drive into a remembered obstacle (:meth:`guard`)."""
        return self.guard(self.act(observation), observation.pose)

    def act(self, observation: Observation) -> Command:
        """Remember the scan, then move to goal or follow the edge (see the class docstring)."""
        pose = observation.pose
        here = self.observe(observation)
        if not self.following:
            if not self.goal_blocked(pose):
                return self.move_to_goal(pose, "move_to_goal")
            self.start_following(observation)
        elif self.should_leave(observation):
            self.following = False
            return self.move_to_goal(pose, "leave")
        elif self.travelled >= self.tuning.min_loop and (
            distance(here, self.hit_point) <= self.tuning.return_radius
        ):
            closed = self.on_loop_closed(observation)
            if closed is not None:
                return closed
        return self.follow(pose, "follow_edge")

    def guard(self, command: Command, pose: Pose) -> Command:
        """``command``, or the nearest heading to it that does not bring the robot's disc
        nearer a remembered obstacle point than the corridor margin during this step.

        The robot turns by at most ``max_turn_rate * dt`` and then drives
        (:mod:`ifgm_ref.robot`), so the disc of the corridor's half-width is swept along the
        heading it will have. Headings are tried in :data:`GUARD_STEP` steps either side of
        the commanded one, up to a right angle; if none is free the robot turns in place
        towards the command. The paper's robot, keeping ``standoff_margin`` from edges at
        0.13 ft a step, never needs it in the paper's scenarios; a fast robot in clutter (BARN:
        1 m/s, 0.22 m) can be carried into an obstacle by its own limited turn rate, or
        follow an edge into a gap narrower than itself (errata row 29).
        """
        if command.speed <= 0.0 or command.stop is not None:
            return command
        for k in range(GUARD_STEPS + 1):
            for sign in (1, -1) if k else (1,):
                heading = wrap_angle(command.heading + sign * k * GUARD_STEP)
                error = wrap_angle(heading - pose.theta)
                speed = min(command.speed, turn_speed(error, self.speed) if k else self.speed)
                turn = max(-self.turn_limit, min(self.turn_limit, error))
                free = disc_travel(
                    self.memory.points, (pose.x, pose.y), pose.theta + turn, self.half_width
                )
                if free >= speed * self.dt:
                    return command if k == 0 else replace(command, heading=heading, speed=speed)
        return replace(command, speed=0.0)

    # -- pieces for subclasses --------------------------------------------------------------
    def observe(self, observation: Observation) -> Point:
        """Remember the scan, as far as the paper's sensor sees (``view_range``), and count
        the distance followed; return the robot's position."""
        scan = observation.scan.limited(self.tuning.view_range)
        self.memory.add(observation.t, observation.pose, scan)
        here = observation.pose.position
        if self.following:
            self.travelled += distance(self._last, here)
        self._last = here
        return here

    @property
    def standoff(self) -> float:
        """Distance kept from the followed edge to the robot's centre."""
        return self.radius + self.tuning.standoff_margin

    @property
    def half_width(self) -> float:
        """Half-width of the corridor the robot needs."""
        return self.radius + self.tuning.corridor_margin

    def goal_bearing(self, pose: Pose) -> float:
        """World-frame direction from the robot to the goal, radians."""
        return math.atan2(self.goal.y - pose.y, self.goal.x - pose.x)

    def goal_free_length(self, pose: Pose) -> float:
        """How far the corridor towards the goal is free of remembered obstacle points."""
        return free_length(
            self.memory.points, (pose.x, pose.y), self.goal_bearing(pose), self.half_width
        )

    def goal_blocked(self, pose: Pose) -> bool:
        """Whether an obstacle stands in the corridor towards the goal, nearer than both the
        goal and the encounter distance ``standoff + hit_margin``."""
        reach = min(self.standoff + self.tuning.hit_margin, distance(pose, self.goal))
        return self.goal_free_length(pose) < reach

    def goal_in_view(self, pose: Pose, margin: float = math.radians(10.0)) -> bool:
        """Whether the goal's bearing lies inside the view, ``margin`` from its edge.

        The view is the field of view, but no wider than the paper's 135 degrees: a robot
        that "sees" its goal behind it would leave the edge for a goal it must first turn
        to, meet the same edge again and circle for ever (errata row 30)."""
        half = min(self.fov / 2, PAPER_HALF_FOV)
        return abs(wrap_angle(self.goal_bearing(pose) - pose.theta)) <= half - margin

    def path_free(self, pose: Pose) -> bool:
        """IBA's free path: the goal in view and its corridor clear as far as the paper's
        sensor sees (``view_range``) or to the goal (section 4.1: "the leaving point is
        selected based on free path")."""
        if not self.goal_in_view(pose):
            return False
        needed = min(self.tuning.view_range, distance(pose, self.goal))
        return self.goal_free_length(pose) >= needed

    def start_following(self, observation: Observation) -> None:
        """Record the hit point and pick the side to follow on."""
        self.following = True
        self.hit_point = observation.pose.position
        self.travelled = 0.0
        self.side = self.choose_side(observation)
        self.on_hit(observation)

    def move_to_goal(self, pose: Pose, branch: str) -> Command:
        """Head for the goal on the regenerated reference path."""
        heading = self.goal_bearing(pose)
        return Command(
            heading,
            turn_speed(wrap_angle(heading - pose.theta), self.speed),
            behaviour=Behaviour.MOVE_TO_GOAL,
            branch=branch,
        )

    def follow(self, pose: Pose, branch: str) -> Command:
        """Follow the nearest remembered edge on :attr:`side` at the stand-off."""
        heading = follow_heading(
            (pose.x, pose.y),
            self.memory.points,
            self.side,
            standoff=self.standoff,
            gain=1.0 / self.radius,
        )
        if heading is None:  # the edge is forgotten: the obstacle is behind us
            self.following = False
            return self.move_to_goal(pose, "edge_lost")
        return Command(
            heading,
            turn_speed(wrap_angle(heading - pose.theta), self.speed),
            behaviour=Behaviour.OBSTACLE_AVOIDANCE,
            branch=branch,
        )

    # -- hooks ------------------------------------------------------------------------------
    @traces("t1.bug_unidirectional")
    def choose_side(self, observation: Observation) -> FollowSide:
        """The Bug family turns one fixed way: left, keeping the obstacle on the right."""
        return FollowSide.RIGHT

    def on_hit(self, observation: Observation) -> None:
        """Called once when an obstacle is met (after :attr:`hit_point` is set)."""

    def should_leave(self, observation: Observation) -> bool:
        """The leaving rule; the base class never leaves."""
        return False

    def on_loop_closed(self, observation: Observation) -> Command | None:
        """Back at the hit point after a whole loop: by default the goal is unreachable."""
        return Command(
            observation.pose.theta,
            0.0,
            behaviour=Behaviour.OBSTACLE_AVOIDANCE,
            branch="loop_closed",
            stop=GOAL_UNREACHABLE,
        )
