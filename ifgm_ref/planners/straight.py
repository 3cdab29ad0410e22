"""The trivial planner: steer straight at the goal, at full speed, whatever is in the way.

It is the *move to goal* behaviour of every planner in the paper ("the robot generates a path
from source to destination and starts following it", section 5.1, Figure 4a) with no obstacle
avoidance at all, and exercises the simulator, sensor and trace end to end.
"""

from __future__ import annotations

import math

from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Behaviour, Command, EpisodeParams, Observation
from ifgm_ref.planners.tuning import check_names


class StraightPlanner:
    """Head for the goal along the straight line; never avoids anything."""

    name = "straight"

    def __init__(self) -> None:
        self._speed = 0.0

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Remember the robot's speed; nothing else to prepare (it has no parameters)."""
        check_names(params.params, (), self.name)
        self._speed = params.robot.speed

    def step(self, observation: Observation) -> Command:
        """Command the bearing of the goal from the current position, at full speed."""
        pose, goal = observation.pose, observation.goal
        heading = math.atan2(goal.y - pose.y, goal.x - pose.x)
        return Command(heading=heading, speed=self._speed, behaviour=Behaviour.MOVE_TO_GOAL)
