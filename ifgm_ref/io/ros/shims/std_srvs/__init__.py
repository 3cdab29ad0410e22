"""ROS 1 package std_srvs under ifgm-ref: its srv classes (:mod:`ifgm_ref.io.ros.messages`)."""
