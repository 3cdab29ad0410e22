"""``ifgm-ref oracle --ros-node``: unchanged ROS 1 nodes as the implementation under test."""

from __future__ import annotations

import argparse

from ifgm_ref.bags.messages import metres_per_unit
from ifgm_ref.cli.ros import ros_options
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.ros.bridge import RosFactory


def ros_implementation(args: argparse.Namespace, equations: object | None) -> Implementation:
    """The implementation of ``--ros-node``, in the oracle's worlds (feet), promising what
    ``--promises`` says (default IFGM's); its nodes started and reset once here, so that
    nodes that cannot start are bad input, said once, not a failure of every check.

    Raises
    ------
    ImplementationError
        When a node cannot start or answer the first reset.
    """
    factory = RosFactory(args.ros_node, **ros_options(args, metres_per_unit("ft")))
    label = "ros: " + " + ".join(args.ros_node)
    impl = Implementation(factory, label, promises_of(args.promises or "ifgm"), equations)
    impl.answers_reset()
    return impl
