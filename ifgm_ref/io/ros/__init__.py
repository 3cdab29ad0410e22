"""Unchanged ROS nodes as a planner, with no ROS install (``docs/ros-nodes.md``): rospy
(ROS 1) nodes, and rclpy (ROS 2) nodes over the same broker.

=====================  ====================================================================
module                 what it is
=====================  ====================================================================
:mod:`.messages`       message classes made from rosbags' Noetic (and Humble) definitions
:mod:`.rostime`        rospy's ``Time`` and ``Duration`` on simulated nanoseconds
:mod:`.names`          graph names: resolution, remapping, ``rosrun``'s arguments
:mod:`.client`         the node's end: its link to the broker, its clock, its event loop
:mod:`.rospy_api`      rospy's API over the client (publishers, subscribers, time, ...)
:mod:`.params_log`     rospy's parameter server calls and logging
:mod:`.services`       rospy's services between the nodes
:mod:`.rclpy_api`      a small rclpy over the same client (ROS 2 nodes)
:mod:`.tf`             ``tf.transformations``' quaternion functions
:mod:`.process`        a node's process seen from the broker
:mod:`.broker`         the clock and the routing, one node at a time
:mod:`.bridge`         the nodes as a :class:`~ifgm_ref.core.protocol.Planner`
:mod:`.rules`          the constants that decide outcomes (the ``/cmd_vel`` timeout, topics)
``shims/``             the packages a node imports (``rospy``, ``tf``, ``sensor_msgs`` ...)
``shims2/``            the same for ROS 2 nodes (``rclpy``, Humble's message packages)
=====================  ====================================================================

Like the transport, this package sees what a planner sees and nothing more: it imports
neither the map nor the oracle (``tests/test_layers.py``).
"""
