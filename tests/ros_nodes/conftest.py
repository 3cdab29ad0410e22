"""The ROS nodes here run under ifgm-ref's rospy stand-in, not under pytest: never import them."""

collect_ignore_glob = ["*.py", "*/*.py"]
