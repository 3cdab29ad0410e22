"""The planner protocol: what a planner is handed and what it must answer.

The paper's planners decide from current percepts only: "No priori information or map of the
environment is required since the decisions are based on current percepts" (section 3). The
protocol makes that structural: an :class:`Observation` carries the time, the robot's pose
(from odometry or GPS, section 6), the goal and the range scan -- never the obstacle map.

A planner is reset once per episode with the start pose, the goal and an
:class:`EpisodeParams`, then stepped once per time step with an observation; it answers a
:class:`Command`. The same exchange runs over JSON lines for programs in other languages.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any, Protocol, runtime_checkable

from ifgm_ref.core.elements import traces
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import DT, GOAL_TOLERANCE, RobotParams, SensorParams
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.validate import POSITIVE, require


class PlannerStop(StrEnum):
    """The reasons a planner may give to end its episode (:attr:`Command.stop`).

    Only the world decides arrival: the simulator ends an episode with ``goal_reached`` when
    the robot's true centre is within the goal tolerance, and never because a planner says so.
    A planner may only give up (``goal_unreachable``: it has proved the goal enclosed) or
    declare itself done (``done``: it believes it has arrived, or has nothing more to do),
    which ends the episode as a stop, not an arrival. Any other value, the simulator's own
    reasons included, is an invalid command.
    """

    GOAL_UNREACHABLE = "goal_unreachable"
    DONE = "done"


class Behaviour(StrEnum):
    """The two top-level behaviours of the Bug family and of IFGM (sections 2.1 and 4)."""

    MOVE_TO_GOAL = "move_to_goal"
    OBSTACLE_AVOIDANCE = "obstacle_avoidance"


@dataclass(frozen=True)
class EpisodeParams:
    """Everything a planner may know before the first step, besides start and goal: the one
    configuration of an episode, each field typed and checked on construction
    (:mod:`ifgm_ref.core.validate`).

    ``params`` holds planner settings by name (e.g. ``d_th``), passed on as the protocol's
    ``reset.params`` carries them: the planner that reads them checks its names and values
    (:class:`~ifgm_ref.planners.tuning.Tuning`); ``goal_tolerance`` is the distance, in ft,
    at which the episode counts the goal as reached.

    >>> EpisodeParams(dt=0.0)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `dt` must be a finite number > 0, got 0.0
    """

    robot: RobotParams = field(default_factory=RobotParams)
    sensor: SensorParams = field(default_factory=SensorParams)
    dt: float = DT
    params: dict[str, Any] = field(default_factory=dict)
    goal_tolerance: float = GOAL_TOLERANCE

    def __post_init__(self) -> None:
        for name, kind in (("robot", RobotParams), ("sensor", SensorParams)):
            if not isinstance(getattr(self, name), kind):
                raise ParameterError(f"`{name}` must be a {kind.__name__}")
        require("dt", self.dt, POSITIVE)
        require("goal_tolerance", self.goal_tolerance, POSITIVE)
        for name in self.params:
            if not isinstance(name, str):
                raise ParameterError(f"a parameter's name must be a string, got {name!r}")


@traces("s3.no_map")
@dataclass(frozen=True)
class Observation:
    """What a planner sees at one step: time (s), pose, goal and scan."""

    t: float
    pose: Pose
    goal: Point
    scan: LaserScan


@dataclass(frozen=True)
class Command:
    """A planner's answer.

    Parameters
    ----------
    heading : float
        Desired heading in the world frame, radians; the robot turns towards it at most
        ``max_turn_rate`` per second.
    speed : float
        Desired forward speed, ft/s, in ``[0, robot.speed]`` (0 turns in place; more than the
        robot's speed is clipped to it).
    behaviour : str, optional
        The planner's current behaviour, e.g. ``"move_to_goal"``, for the trace.
    branch : str, optional
        The decision branch taken at this step (IFGM: the Figure 3 flowchart branch).
    stop : str, optional
        Set to end the episode with this stop reason: one of :class:`PlannerStop`
        (``"goal_unreachable"`` or ``"done"``); any other value is an invalid command.
    turn_rate : float, optional
        Set for a velocity command, ROS's ``geometry_msgs/Twist`` (``speed`` is then its
        ``linear.x`` and ``turn_rate`` its ``angular.z``, rad/s, positive to the left): the
        robot turns at this rate, within ``max_turn_rate``, whatever ``heading`` says. Build
        such a command with :meth:`from_twist`, which sets ``heading`` to where the turn
        leads within the step, so that traces, plots and the oracle's comparisons read both
        forms alike.
    """

    heading: float
    speed: float
    behaviour: str | None = None
    branch: str | None = None
    stop: str | None = None
    turn_rate: float | None = None

    @classmethod
    def from_twist(
        cls,
        linear: float,
        angular: float,
        pose: Pose,
        params: EpisodeParams,
        *,
        behaviour: str | None = None,
        branch: str | None = None,
        stop: str | None = None,
    ) -> Command:
        """The velocity command ``(linear, angular)`` (ft/s, rad/s) decided at ``pose``.

        Its ``heading`` is the heading the robot reaches after one step ``params.dt`` at
        ``angular`` limited to ``max_turn_rate``: the heading command that moves the robot
        exactly as the twist does (:func:`ifgm_ref.sim.robot.advance`).

        >>> params = EpisodeParams()  # max_turn_rate pi/2 rad/s, dt 0.1 s
        >>> command = Command.from_twist(1.0, 0.5, Pose(0.0, 0.0, 1.0), params)
        >>> round(command.heading, 12), command.speed, command.turn_rate
        (1.05, 1.0, 0.5)
        >>> Command.from_twist(1.0, 100.0, Pose(0.0, 0.0, 0.0), params).heading == math.pi / 20
        True
        """
        limit = params.robot.max_turn_rate
        turn = min(max(angular, -limit), limit) * params.dt if math.isfinite(angular) else 0.0
        return cls(
            heading=wrap_angle(pose.theta + turn),
            speed=linear,
            behaviour=behaviour,
            branch=branch,
            stop=stop,
            turn_rate=angular,
        )

    def twist(self, pose: Pose, params: EpisodeParams) -> tuple[float, float]:
        """This command as ROS's ``(linear.x, angular.z)`` when decided at ``pose``: the
        speed and turn rate the robot executes over one step ``params.dt`` (``speed``
        clipped to the robot's, the turn towards ``heading`` limited to ``max_turn_rate``).

        >>> params = EpisodeParams()  # 1.32 ft/s (0.4 m/s), pi/2 rad/s, dt 0.1 s
        >>> linear, angular = Command(0.1, 2.0).twist(Pose(0.0, 0.0, 0.0), params)
        >>> round(linear, 2), round(angular, 12)
        (1.32, 1.0)
        >>> Command(3.0, 0.5).twist(Pose(0.0, 0.0, 0.0), params) == (0.5, math.pi / 2)
        True
        """
        robot = params.robot
        speed = min(self.speed, robot.speed)
        rate = self.turn_rate
        if rate is None:
            rate = wrap_angle(self.heading - pose.theta) / params.dt
        return speed, min(max(rate, -robot.max_turn_rate), robot.max_turn_rate)

    def executed_speed(self, robot: RobotParams) -> str:
        """This command's speed as the robot executes it, clipped to its top speed, with the
        speed asked beside it when it was clipped: for messages.

        >>> robot = RobotParams()  # 0.403 m/s in ft/s
        >>> Command(0.0, 1.0).executed_speed(robot), Command(0.0, 50.0).executed_speed(robot)
        ('1.0000', '1.3221 (asked 50.0000)')
        """
        executed = min(self.speed, robot.speed)
        asked = f" (asked {self.speed:.4f})" if executed < self.speed else ""
        return f"{executed:.4f}{asked}"

    def problem(self) -> str | None:
        """Say what is wrong with this command, or ``None`` when it can be executed."""
        if not math.isfinite(self.heading):
            return f"heading={self.heading!r}, but should be finite"
        if not math.isfinite(self.speed) or self.speed < 0:
            what = "speed" if self.turn_rate is None else "linear velocity"
            return (
                f"{what}={self.speed!r}, but should be finite and >= 0 (the robot does not reverse)"
            )
        if self.turn_rate is not None and not math.isfinite(self.turn_rate):
            return f"angular velocity={self.turn_rate!r}, but should be finite"
        if self.stop is not None and self.stop not in PLANNER_STOPS:
            allowed = ", ".join(repr(str(stop)) for stop in PLANNER_STOPS)
            return (
                f"stop={self.stop!r}, but should be one of {allowed} (only the robot's true "
                "position decides an arrival)"
            )
        return None


#: The values :attr:`Command.stop` may take, in the order messages list them.
PLANNER_STOPS = tuple(PlannerStop)


@runtime_checkable
class Planner(Protocol):
    """What every planner implements (built-in ones and the oracle's implementations).

    ``name`` is read-only here, so that a class constant (``name: ClassVar[str] = "ifgm"``, as
    the built-in planners have), an instance attribute or a property all satisfy it.
    """

    @property
    def name(self) -> str:
        """The planner's name in results and reports."""
        ...

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Start a new episode from ``start`` towards ``goal``."""
        ...

    def step(self, observation: Observation) -> Command:
        """Decide one command from the current observation."""
        ...
