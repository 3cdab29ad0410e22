"""``rclpy.duration`` under ifgm-ref."""

from ifgm_ref.ros.rclpy_api import Duration as Duration
