#!/usr/bin/env python3
"""A test node: drives straight at the goal's heading, publishing in its scan callback."""

import math

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from tf.transformations import euler_from_quaternion

pose = None


def on_odom(msg):
    global pose
    q = msg.pose.pose.orientation
    yaw = euler_from_quaternion([q.x, q.y, q.z, q.w])[2]
    pose = (msg.pose.pose.position.x, msg.pose.pose.position.y, yaw)


def on_scan(scan):
    if pose is None:
        return
    gx, gy = rospy.get_param("~goal_x"), rospy.get_param("~goal_y")
    error = math.atan2(gy - pose[1], gx - pose[0]) - pose[2]
    error = math.atan2(math.sin(error), math.cos(error))
    cmd = Twist()
    cmd.linear.x = 0.3
    cmd.angular.z = max(-1.0, min(1.0, error / rospy.get_param("/ifgm_ref/dt")))
    pub.publish(cmd)


rospy.init_node("straight")
pub = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
rospy.Subscriber("/odom", Odometry, on_odom)
rospy.Subscriber("/scan", LaserScan, on_scan)
rospy.spin()
