"""Shim packages put first on a ROS 2 node's PYTHONPATH: rclpy and message packages."""
