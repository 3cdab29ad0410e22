"""The rules that decide a ROS node's outcome, as named constants (``docs/ros-nodes.md``).

Kept apart from the bridge so that the command line can name them without importing
the stand-in.
"""

from __future__ import annotations

__all__ = [
    "CMD_VEL",
    "CMD_VEL_TIMEOUT",
    "GOAL_TOPIC",
    "LABEL_TOPICS",
    "MAX_ACTIVATIONS",
    "STOP_TOPIC",
]

#: A ``/cmd_vel`` older than this (s of simulated time) is no longer executed: the robot
#: stops. 0.5 s is ``diff_drive_controller``'s default ``cmd_vel_timeout``, the common ROS
#: base controller's: a node that falls silent does not drive on blind for long.
CMD_VEL_TIMEOUT = 0.5
#: Where the goal is published at the start (``--ros-goal-topic`` names another): rviz's
#: "2D Nav Goal" topic, which nodes written for move_base read.
GOAL_TOPIC = "/move_base_simple/goal"
#: The velocity topic the robot's base listens to, and its type.
CMD_VEL = ("/cmd_vel", "geometry_msgs/Twist")
#: The topic on which a node ends its episode, and its type: ``goal_unreachable`` or
#: ``done`` (:class:`~ifgm_ref.core.protocol.PlannerStop`); any other text is an invalid command.
STOP_TOPIC = ("/ifgm_ref/stop", "std_msgs/String")
#: Optional topics (``std_msgs/String``) on which a node labels its decisions for the trace,
#: as the recorded bags carry them (:mod:`ifgm_ref.io.bags.messages`): the Figure 3 branch and
#: the behaviour. A label published since the step before is the step's.
LABEL_TOPICS = {"/ifgm_ref/branch": "branch", "/ifgm_ref/behaviour": "behaviour"}
#: The most node activations at one simulated time: beyond, nodes that keep waking each
#: other without letting the clock move are reported, not waited for.
MAX_ACTIVATIONS = 10_000
