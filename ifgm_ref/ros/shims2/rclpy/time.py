"""``rclpy.time`` under ifgm-ref."""

from ifgm_ref.ros.rclpy_api import Time as Time
