"""``builtin_interfaces.msg`` under ifgm-ref: made from rosbags' Humble definitions."""

from ifgm_ref.io.ros.messages import package_namespace

globals().update(package_namespace("builtin_interfaces", "msg", "ros2"))
