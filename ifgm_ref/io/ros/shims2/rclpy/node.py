"""``rclpy.node`` under ifgm-ref."""

from ifgm_ref.io.ros.rclpy_api import Client as Client
from ifgm_ref.io.ros.rclpy_api import Node as Node
from ifgm_ref.io.ros.rclpy_api import Parameter as Parameter
