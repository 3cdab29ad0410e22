"""ROS 1 package nav_msgs under ifgm-ref: its msg classes (:mod:`ifgm_ref.io.ros.messages`)."""
