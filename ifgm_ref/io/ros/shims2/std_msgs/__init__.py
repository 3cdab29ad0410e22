"""ROS 2 package std_msgs under ifgm-ref: its msg classes (:mod:`ifgm_ref.io.ros.messages`)."""
