"""ROS 2 package builtin_interfaces under ifgm-ref (:mod:`ifgm_ref.io.ros.messages`)."""
