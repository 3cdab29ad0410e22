"""Shim packages put first on a node's PYTHONPATH: rospy, tf and message packages."""
