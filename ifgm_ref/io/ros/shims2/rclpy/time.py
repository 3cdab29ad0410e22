"""``rclpy.time`` under ifgm-ref."""

from ifgm_ref.io.ros.rclpy_api import Time as Time
