"""``rclpy.parameter`` under ifgm-ref."""

from ifgm_ref.ros.rclpy_api import Parameter as Parameter
