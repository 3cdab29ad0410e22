"""ROS 1 package geometry_msgs under ifgm-ref: its msg classes (:mod:`ifgm_ref.io.ros.messages`)."""
