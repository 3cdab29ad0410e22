"""``ifgm-ref oracle --ros-node``: unchanged ROS 1 nodes as the implementation under test."""

from __future__ import annotations

import argparse

from ifgm_ref.apps.cli.ros import ros_options
from ifgm_ref.io.bags.messages import metres_per_unit
from ifgm_ref.io.ros.bridge import RosFactory
from ifgm_ref.io.ros.rules import GOAL_TOPIC
from ifgm_ref.oracle.implementation import Implementation, promises_of


def ros_implementation(args: argparse.Namespace, equations: object | None) -> Implementation:
    """The implementation of ``--ros-node``, in the oracle's worlds (feet), promising what
    ``--promises`` says (default IFGM's); its nodes started and reset once here, so that
    nodes that cannot start are bad input, said once, not a failure of every check.

    Raises
    ------
    ImplementationError
        When a node cannot start or answer the first reset.
    """
    options = ros_options(args, metres_per_unit("ft"))
    factory = RosFactory(args.ros_node, **options)
    label = "ros: " + " + ".join(args.ros_node)
    node_option = "--ros2-node" if options["distro"] == "ros2" else "--ros-node"
    runs_as = [arg for command in args.ros_node for arg in (node_option, command)]
    runs_as += [arg for remap in args.remap for arg in ("--remap", remap)]
    if args.ros_goal_topic != GOAL_TOPIC:
        runs_as += ["--ros-goal-topic", args.ros_goal_topic]
    promises = promises_of(args.promises or "ifgm")
    impl = Implementation(factory, label, promises, equations, runs_as=tuple(runs_as))
    impl.answers_reset()
    return impl
