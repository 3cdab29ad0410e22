"""``--ros-node`` and its options, shared by ``ifgm-ref simulate`` and ``ifgm-ref oracle``:
unchanged ROS 1 nodes as the planner (``docs/ros-nodes.md``)."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.io.ros.rules import GOAL_TOPIC

if TYPE_CHECKING:
    from ifgm_ref.io.ros.bridge import RosPlanner

#: What ``--planner``, ``--cmd`` and ``--ros-node`` say when not exactly one is given.
EXACTLY_ONE = (
    "give exactly one of --planner NAME, --cmd 'PROGRAM', --ros-node 'COMMAND' and "
    "--ros2-node 'COMMAND'"
)


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
        "--ros2-node",
        action="append",
        metavar="COMMAND",
        help="the same for a ROS 2 rclpy node (ROS 2 Humble's messages; not with --ros-node)",
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
    """Refuse anything but exactly one of ``--planner``, ``--cmd``, ``--ros-node`` and
    ``--ros2-node``; ROS 2 nodes are then run as ``args.ros_node``, with ``args.ros_distro``
    ``ros2`` (``ros1`` otherwise)."""
    given = (args.planner, args.cmd, args.ros_node, args.ros2_node)
    if sum(option is not None for option in given) != 1:
        raise ParameterError(EXACTLY_ONE)
    args.ros_distro = "ros1" if args.ros2_node is None else "ros2"
    if args.ros2_node is not None:
        args.ros_node = args.ros2_node


def ros_options(args: argparse.Namespace, scale: float) -> dict[str, object]:
    """The keyword arguments of :class:`~ifgm_ref.io.ros.bridge.RosPlanner` from ``args``, for
    worlds of ``scale`` metres per length unit."""
    return {
        "scale": scale,
        "timeout": args.timeout,
        "startup_timeout": args.startup_timeout,
        "remaps": tuple(args.remap),
        "goal_topic": args.ros_goal_topic,
        "distro": getattr(args, "ros_distro", "ros1"),
    }


def ros_planner(args: argparse.Namespace, scale: float) -> RosPlanner:
    """The planner of ``--ros-node`` (``ifgm-ref simulate``), the nodes' output copied to
    stderr."""
    from ifgm_ref.io.ros.bridge import RosPlanner

    options = {
        **ros_options(args, scale),
        "log": sys.stderr,
    }  # the nodes' output, as rosrun shows it
    return RosPlanner(args.ros_node, **options)  # type: ignore[arg-type]
