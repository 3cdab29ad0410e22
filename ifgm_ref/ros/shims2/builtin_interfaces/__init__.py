"""ROS 2 package builtin_interfaces under ifgm-ref (:mod:`ifgm_ref.ros.messages`)."""
