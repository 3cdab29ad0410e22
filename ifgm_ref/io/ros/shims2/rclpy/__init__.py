"""The ``rclpy`` a node imports under ifgm-ref (:mod:`ifgm_ref.io.ros.rclpy_api`)."""

from ifgm_ref.io.ros.rclpy_api import *  # noqa: F403
from ifgm_ref.io.ros.rclpy_api import try_shutdown as try_shutdown
