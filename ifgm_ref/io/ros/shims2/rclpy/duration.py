"""``rclpy.duration`` under ifgm-ref."""

from ifgm_ref.io.ros.rclpy_api import Duration as Duration
