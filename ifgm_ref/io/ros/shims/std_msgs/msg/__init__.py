"""``std_msgs.msg`` under ifgm-ref: classes made from rosbags' ROS 1 Noetic definitions."""

from ifgm_ref.io.ros.messages import package_namespace

globals().update(package_namespace("std_msgs", "msg"))
