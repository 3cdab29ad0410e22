"""The Bug family's skeleton, composed: an edge follower and a leaving rule.

Section 2.1 of the paper: Bug algorithms have "two behaviours, *move to goal* and *obstacle
avoidance*. In *move to goal*, initially the robot generates a reference path and follows it
until obstacle is encountered or destination is reached." In *obstacle avoidance* it follows
the obstacle's edge until a leaving condition -- the one thing the variants disagree on --
holds, then regenerates the reference path from where it is (section 4).

So a Bug planner here is a :class:`BoundaryPlanner` made of parts:

* an :class:`EdgeFollower`, the *obstacle avoidance* behaviour (which side, since where, how
  far followed);
* a :class:`LeaveRule`: none (Bug1, :mod:`~ifgm_ref.planners.bug1`), Bug2's m-line
  (:mod:`~ifgm_ref.planners.bug2`), DistBug's progress (:mod:`~ifgm_ref.planners.distbug`)
  or IBA's free path (:mod:`~ifgm_ref.planners.iba`);
* a side choice: the Bug family's fixed one (:func:`bug_side`) or IBA's freer side;
* a :class:`~ifgm_ref.planners.circuit.Circuit`, Bug1's round of the obstacle, which every
  follower falls back on after a whole loop without leaving by its rule (errata row 34);
* :func:`keep_clear`, which never drives into a remembered obstacle.

An obstacle is met where one stands in the corridor towards the goal and it is the nearest
ahead (:meth:`~ifgm_ref.planners.sight.Sight.meets_obstacle`), not where the one just left
is still the nearest. IFGM (:mod:`~ifgm_ref.planners.ifgm`) holds the same follower, IBA's
rule and the round.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import ClassVar

from ifgm_ref.core.elements import traces
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import Behaviour, Command, EpisodeParams, Observation, PlannerStop
from ifgm_ref.paper.percepts.corridor import disc_travel
from ifgm_ref.paper.percepts.memory import PerceptMemory
from ifgm_ref.planners.circuit import Circuit
from ifgm_ref.planners.edge_following import FollowSide, follow_heading, turn_speed
from ifgm_ref.planners.governor import BrakingGovernor
from ifgm_ref.planners.sight import BoundaryParams, Episode, Sight, goal_bearing
from ifgm_ref.planners.tuning import Tuning, check_names, parameter_names

__all__ = [
    "GOAL_UNREACHABLE",
    "BoundaryParams",
    "BoundaryPlanner",
    "EdgeFollower",
    "LeaveRule",
    "bug_side",
    "edge_heading",
    "keep_clear",
]

#: The clearance filter's search step round a blocked heading, rad, and the number of steps
#: each way (a right angle): coarse enough to be cheap, fine enough to find a gap the robot
#: fits.
CLEAR_STEP = math.pi / 12
CLEAR_STEPS = 6

#: Stop reason of a planner that has proved the goal cannot be reached.
GOAL_UNREACHABLE = PlannerStop.GOAL_UNREACHABLE

#: How a planner picks the side to follow an obstacle on: from the scan, the pose and the
#: goal's bearing.
SideChoice = Callable[[LaserScan, Pose, float], FollowSide]


@traces("t1.bug_unidirectional")
def bug_side(scan: LaserScan, pose: Pose, goal_bearing: float) -> FollowSide:
    """The Bug family turns one fixed way: left, keeping the obstacle on the right.

    >>> bug_side(LaserScan(-1.0, 1.0, 1.0, 0.0, 5.0, [1.0, 1.0, 1.0]), Pose(0, 0, 0), 0.0)
    <FollowSide.RIGHT: 'right'>
    """
    return FollowSide.RIGHT


class EdgeFollower:
    """*Obstacle avoidance* (section 2.1): keep the nearest remembered edge on :attr:`side`
    at the stand-off.

    Attributes
    ----------
    following : bool
        An edge is being followed.
    side : FollowSide
        The side the edge is kept on.
    hit_point : Point
        H, where the robot met the obstacle.
    """

    def __init__(self) -> None:
        self.following = False
        self.side = FollowSide.RIGHT
        self.hit_point = Point(0.0, 0.0)

    def reset(self) -> None:
        """Not following."""
        self.following = False

    def start(self, here: Point, side: FollowSide) -> None:
        """Start following on ``side`` from the hit point ``here``."""
        self.following = True
        self.hit_point = here
        self.side = side

    def heading(self, sight: Sight) -> float | None:
        """The heading that follows the nearest remembered edge on :attr:`side`
        (:func:`edge_heading`)."""
        return edge_heading(sight, self.side)


def edge_heading(sight: Sight, side: FollowSide) -> float | None:
    """The heading that follows the nearest remembered edge, kept on ``side``; ``None`` if
    no edge is left."""
    pose, episode = sight.pose, sight.episode
    return follow_heading(
        (pose.x, pose.y), sight.points, side, standoff=episode.standoff, gain=1.0 / episode.radius
    )


class LeaveRule:
    """When to leave the followed edge: the part of a Bug planner its variants disagree on.

    The base rule never leaves (Bug1: the planner's round of the obstacle,
    :mod:`~ifgm_ref.planners.circuit`, does). A rule is reset with the episode and told of
    every hit point (:meth:`on_hit`); :meth:`update` is called once at every later step of
    following.
    """

    #: The rule's own parameter classes.
    tunings: ClassVar[tuple[type[Tuning], ...]] = ()
    #: The trace's branch label of a departure by this rule.
    leave_branch: ClassVar[str] = "leave"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """A new episode from ``start`` to ``goal``."""

    def on_hit(self, sight: Sight, follower: EdgeFollower) -> None:
        """An obstacle was met at ``follower.hit_point``."""

    def update(self, sight: Sight, follower: EdgeFollower) -> bool:
        """Advance the rule by one step of following; whether to leave here."""
        return False


def keep_clear(command: Command, sight: Sight) -> Command:
    """``command``, or the nearest heading to it that does not bring the robot's disc nearer a
    remembered obstacle point (``sight.points``) than the corridor margin during this step.

    The robot turns by at most ``max_turn_rate * dt`` and then drives
    (:mod:`ifgm_ref.sim.robot`), so the disc of the corridor's half-width is swept along the
    heading it will have. Headings are tried in :data:`CLEAR_STEP` steps either side of the
    commanded one, up to a right angle; if none is free the robot turns in place towards the
    command. The paper's robot, keeping ``standoff_margin`` from edges at 0.13 ft a step,
    never needs it in the paper's scenarios; a fast robot in clutter (BARN: 1 m/s, 0.22 m)
    can be carried into an obstacle by its own limited turn rate, or follow an edge into a
    gap narrower than itself (errata row 29).
    """
    if command.speed <= 0.0 or command.stop is not None:
        return command
    pose, episode, origin = sight.pose, sight.episode, (sight.pose.x, sight.pose.y)
    for k in range(CLEAR_STEPS + 1):
        for sign in (1, -1) if k else (1,):
            heading = wrap_angle(command.heading + sign * k * CLEAR_STEP)
            error = wrap_angle(heading - pose.theta)
            speed = min(command.speed, turn_speed(error, episode.speed) if k else episode.speed)
            turn = max(-episode.turn_limit, min(episode.turn_limit, error))
            direction = pose.theta + turn
            free = disc_travel(
                sight.points, origin, direction, episode.half_width, relative=sight.offsets
            )
            if free >= speed * episode.dt:
                return command if k == 0 else replace(command, heading=heading, speed=speed)
    return replace(command, speed=0.0)


def unreachable(sight: Sight, branch: str) -> Command:
    """Stop where the robot stands: the goal cannot be reached (``branch`` says how it knows)."""
    return Command(
        sight.pose.theta,
        0.0,
        behaviour=Behaviour.OBSTACLE_AVOIDANCE,
        branch=branch,
        stop=GOAL_UNREACHABLE,
    )


def steer(
    heading: float, pose: Pose, episode: Episode, behaviour: Behaviour, branch: str
) -> Command:
    """Turn towards ``heading``, slowing with the turn still to go."""
    return Command(
        heading,
        turn_speed(wrap_angle(heading - pose.theta), episode.speed),
        behaviour=behaviour,
        branch=branch,
    )


class BoundaryPlanner:
    """Move to goal; on meeting an obstacle, follow its edge until ``rule`` says leave.

    Parameters
    ----------
    rule : LeaveRule, default the base rule (never leaves)
        The leaving rule.
    choose_side : SideChoice, default :func:`bug_side`
        How the side to follow on is picked at each hit point.

    Attributes
    ----------
    follower : EdgeFollower
        The *obstacle avoidance* behaviour and its state.
    circuit : Circuit
        Bug1's round of the followed obstacle, a value replaced as the round goes on.
    memory : PerceptMemory
        The obstacle points of the last ``memory_horizon`` seconds.
    episode : Episode
        The robot and the episode.
    """

    name: ClassVar[str] = "boundary"
    #: The parameter classes the planner reads (``ifgm-ref planners`` lists their fields).
    tunings: ClassVar[tuple[type[Tuning], ...]] = (BoundaryParams,)
    #: The planner's parameter names.
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self, rule: LeaveRule | None = None, choose_side: SideChoice = bug_side) -> None:
        self.rule = rule if rule is not None else LeaveRule()
        self.choose_side = choose_side
        self.follower = EdgeFollower()
        self.governor = BrakingGovernor()
        self.reset(Pose(0.0, 0.0, 0.0), Point(0.0, 0.0), EpisodeParams())  # until reset

    # -- protocol ---------------------------------------------------------------------------
    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Start in *move to goal* towards ``goal``; read tuning from ``params.params``
        (unknown names are an error)."""
        check_names(params.params, self.parameters, self.name)
        tuning = BoundaryParams.for_episode(params)
        self.episode = Episode.of(goal, params, tuning)
        self.memory = PerceptMemory(tuning.memory_horizon, params.dt)
        self.follower.reset()
        self.rule.reset(start, goal, params)
        self.circuit = Circuit()
        self.governor.reset(params)

    def step(self, observation: Observation) -> Command:
        """Decide (:meth:`decide`), then never drive into a remembered obstacle
        (:func:`keep_clear`), and stop in time (the braking governor,
        :mod:`~ifgm_ref.planners.governor`)."""
        sight = self.observe(observation)
        return self.governor(keep_clear(self.decide(observation, sight), sight), observation)

    def decide(self, observation: Observation, sight: Sight) -> Command:
        """Move to goal or follow the edge (see the module docstring), given this step's
        ``sight`` (:meth:`observe`): the rule's leaving point, or else Bug1's after a whole
        loop (:mod:`~ifgm_ref.planners.circuit`)."""
        follower, rule = self.follower, self.rule
        here = observation.pose.position
        if not follower.following:
            if not sight.meets_obstacle():
                return self.move_to_goal(sight, "move_to_goal")
            side = self.choose_side(observation.scan, sight.pose, sight.bearing)
            follower.start(here, side)
            rule.on_hit(sight, follower)
            self.circuit = self.circuit.hit()
            return self.follow(sight, "follow_edge")
        self.circuit = circuit = self.circuit.noted(sight)
        if rule.update(sight, follower):
            follower.following = False
            return self.move_to_goal(sight, rule.leave_branch)
        if circuit.returning:
            self.circuit = circuit = circuit.advanced(sight)
            if not circuit.at_q(sight):
                return steer(
                    circuit.heading_to_q(sight), sight.pose, self.episode,
                    Behaviour.OBSTACLE_AVOIDANCE, "follow_to_q",
                )  # fmt: skip
            self.circuit = circuit.left_at_q()
            follower.following = False
            return self.move_to_goal(sight, "leave_at_q")
        back_at = circuit.closing(sight)
        if back_at is not None:
            self.circuit, way_on = circuit.closed(sight, back_at, follower.side)
            if not way_on:
                return unreachable(sight, "goal_enclosed")
            return self.follow(sight, "loop_closed")
        return self.follow(sight, "follow_edge")

    # -- parts ------------------------------------------------------------------------------
    def observe(self, observation: Observation) -> Sight:
        """Remember the scan, as far as the paper's sensor sees (``view_range``); return this
        step's sight of the goal."""
        scan = observation.scan.limited(self.episode.tuning.view_range)
        self.memory.add(observation.t, observation.pose, scan)
        return Sight(
            observation.pose, self.episode, self.memory.points, self.goal_bearing(observation.pose)
        )

    def goal_bearing(self, pose: Pose) -> float:
        """World-frame direction from the robot to the goal, radians (:func:`goal_bearing`)."""
        return goal_bearing(pose, self.episode.goal)

    def move_to_goal(self, sight: Sight, branch: str) -> Command:
        """Head for the goal on the regenerated reference path."""
        return steer(sight.bearing, sight.pose, self.episode, Behaviour.MOVE_TO_GOAL, branch)

    def follow(self, sight: Sight, branch: str) -> Command:
        """Follow the nearest remembered edge; move to goal if the edge is forgotten."""
        heading = self.follower.heading(sight)
        if heading is None:  # the edge is forgotten: the obstacle is behind us
            self.follower.following = False
            return self.move_to_goal(sight, "edge_lost")
        return steer(heading, sight.pose, self.episode, Behaviour.OBSTACLE_AVOIDANCE, branch)
