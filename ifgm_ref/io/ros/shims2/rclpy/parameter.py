"""``rclpy.parameter`` under ifgm-ref."""

from ifgm_ref.io.ros.rclpy_api import Parameter as Parameter
