"""``--ros-node`` and its options, shared by ``ifgm-ref simulate`` and ``ifgm-ref oracle``:
unchanged ROS 1 nodes as the planner (``docs/ros-nodes.md``)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from ifgm_ref.errors import ParameterError
from ifgm_ref.ros.rules import GOAL_TOPIC

if TYPE_CHECKING:
    from ifgm_ref.ros.bridge import RosPlanner

#: What ``--planner``, ``--cmd`` and ``--ros-node`` say when not exactly one is given.
EXACTLY_ONE = "give exactly one of --planner NAME, --cmd 'PROGRAM' and --ros-node 'COMMAND'"


def add_ros_options(parser: argparse.ArgumentParser) -> None:
    """Add ``--ros-node``, ``--remap`` and ``--ros-goal-topic``."""
    parser.add_argument(
        "--ros-node",
        action="append",
        metavar="COMMAND",
        help="run this ROS 1 rospy node unchanged as (part of) the planner, e.g. "
        "'python3 my_nodes/bug2.py _rate:=20' (repeatable: one per node; no ROS install "
        "needed; docs/ros-nodes.md)",
    )
    parser.add_argument(
        "--remap",
        action="append",
        default=[],
        metavar="FROM:=TO",
        help="with --ros-node: remap a topic or service name for every node, in ROS's syntax "
        "(e.g. /scan:=/base_scan; repeatable)",
    )
    parser.add_argument(
        "--ros-goal-topic",
        default=GOAL_TOPIC,
        metavar="TOPIC",
        help=f"with --ros-node: publish the goal (geometry_msgs/PoseStamped) here at the start "
        f"(default {GOAL_TOPIC}; the goal is also in the parameters ~goal_x, ~goal_y, "
        "des_pos_x, des_pos_y)",
    )


def exactly_one(args: argparse.Namespace) -> None:
    """Refuse anything but exactly one of ``--planner``, ``--cmd`` and ``--ros-node``."""
    if sum(option is not None for option in (args.planner, args.cmd, args.ros_node)) != 1:
        raise ParameterError(EXACTLY_ONE)


def ros_options(args: argparse.Namespace, scale: float) -> dict[str, object]:
    """The keyword arguments of :class:`~ifgm_ref.ros.bridge.RosPlanner` from ``args``, for
    worlds of ``scale`` metres per length unit."""
    return {
        "scale": scale,
        "timeout": args.timeout,
        "startup_timeout": args.startup_timeout,
        "remaps": tuple(args.remap),
        "goal_topic": args.ros_goal_topic,
    }


def ros_planner(args: argparse.Namespace, scale: float) -> RosPlanner:
    """The planner of ``--ros-node`` (``ifgm-ref simulate``)."""
    from ifgm_ref.ros.bridge import RosPlanner

    return RosPlanner(args.ros_node, **ros_options(args, scale))  # type: ignore[arg-type]
