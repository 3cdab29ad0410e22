"""``sensor_msgs.msg`` under ifgm-ref: classes made from rosbags' ROS 2 Humble definitions."""

from ifgm_ref.io.ros.messages import package_namespace

globals().update(package_namespace("sensor_msgs", "msg", "ros2"))
