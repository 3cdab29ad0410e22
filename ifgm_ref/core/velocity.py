"""Any planner as one that answers velocity commands, ROS's ``geometry_msgs/Twist``.

A ROS node commands a robot with a linear and an angular velocity ``(v, w)``, not with the
paper's heading and speed. :class:`VelocityPlanner` wraps a planner and answers each of its
commands in that form (:meth:`Command.twist`, then :meth:`Command.from_twist`): the speed
and the turn rate the robot executes over the step. ``ifgm-ref serve --twist`` serves a
planner so, which is how the test suite checks that the oracle takes both forms.
"""

from __future__ import annotations

from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner


class VelocityPlanner:
    """``planner``, answering ``(v, w)``: the same robot motion, the other command form.

    Examples
    --------
    >>> from ifgm_ref.planners import StraightPlanner
    >>> from ifgm_ref.core.laserscan import LaserScan
    >>> planner = VelocityPlanner(StraightPlanner())
    >>> planner.reset(Pose(0.0, 0.0, 0.0), Point(0.0, 5.0), EpisodeParams())
    >>> scan = LaserScan(-0.5, 0.5, 1.0, 0.0, 15.0, [float("inf")] * 2)
    >>> command = planner.step(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(0.0, 5.0), scan))
    >>> command.turn_rate == EpisodeParams().robot.max_turn_rate  # a left turn, at the limit
    True
    """

    def __init__(self, planner: Planner) -> None:
        self.planner = planner
        self.name = planner.name
        self._params = EpisodeParams()

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Reset the wrapped planner; keep ``params`` for the conversion."""
        self._params = params
        self.planner.reset(start, goal, params)

    def step(self, observation: Observation) -> Command:
        """The wrapped planner's command as a velocity command decided at the observed pose."""
        command = self.planner.step(observation)
        linear, angular = command.twist(observation.pose, self._params)
        return Command.from_twist(
            linear,
            angular,
            observation.pose,
            self._params,
            behaviour=command.behaviour,
            branch=command.branch,
            stop=command.stop,
        )
