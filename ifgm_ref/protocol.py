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

from ifgm_ref.laserscan import LaserScan
from ifgm_ref.paper import traces
from ifgm_ref.params import RobotParams, SensorParams
from ifgm_ref.pose import Point, Pose


class Behaviour(StrEnum):
    """The two top-level behaviours of the Bug family and of IFGM (sections 2.1 and 4)."""

    MOVE_TO_GOAL = "move_to_goal"
    OBSTACLE_AVOIDANCE = "obstacle_avoidance"


@dataclass(frozen=True)
class EpisodeParams:
    """Everything a planner may know before the first step, besides start and goal.

    ``params`` holds planner-specific settings (e.g. ``d_th``) by name; ``goal_tolerance`` is
    the distance, in ft, at which the episode counts the goal as reached.
    """

    robot: RobotParams = field(default_factory=RobotParams)
    sensor: SensorParams = field(default_factory=SensorParams)
    dt: float = 0.1
    params: dict[str, Any] = field(default_factory=dict)
    goal_tolerance: float = 0.5


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
        Set to end the episode with this stop reason, e.g. ``"goal_unreachable"``.
    """

    heading: float
    speed: float
    behaviour: str | None = None
    branch: str | None = None
    stop: str | None = None

    def problem(self) -> str | None:
        """Say what is wrong with this command, or ``None`` when it can be executed."""
        if not math.isfinite(self.heading):
            return f"heading={self.heading!r}, but should be finite"
        if not math.isfinite(self.speed) or self.speed < 0:
            return f"speed={self.speed!r}, but should be finite and >= 0"
        return None


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
