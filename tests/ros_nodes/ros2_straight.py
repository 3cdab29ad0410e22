#!/usr/bin/env python3
"""A ROS 2 (rclpy) test node: steers at the goal in a 10 Hz timer, from /odom, as straight.py
does in rospy; the goal from its parameters goal_x and goal_y."""

import math

import rclpy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import LaserScan


class Straight(Node):
    def __init__(self):
        super().__init__("straight")
        self.goal = (
            self.declare_parameter("goal_x", 0.0).value,
            self.declare_parameter("goal_y", 0.0).value,
        )
        self.dt = self.get_parameter("ifgm_ref.dt").value
        self.pose = None
        self.scans = 0
        self.cmd = self.create_publisher(Twist, "/cmd_vel", 10)
        self.create_subscription(Odometry, "/odom", self.on_odom, 10)
        self.create_subscription(LaserScan, "/scan", self.on_scan, qos_profile_sensor_data)
        self.create_timer(0.1, self.tick)

    def on_odom(self, msg):
        q = msg.pose.pose.orientation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        self.pose = (msg.pose.pose.position.x, msg.pose.pose.position.y, yaw)

    def on_scan(self, msg):
        self.scans += 1

    def tick(self):
        if self.pose is None:
            return
        x, y, yaw = self.pose
        error = math.atan2(self.goal[1] - y, self.goal[0] - x) - yaw
        error = math.atan2(math.sin(error), math.cos(error))
        twist = Twist()
        twist.linear.x = 0.3
        twist.angular.z = max(-1.0, min(1.0, error / self.dt))
        self.cmd.publish(twist)
        if self.scans == 1:
            now = self.get_clock().now().nanoseconds
            self.get_logger().info(f"first tick after a scan at {now} ns")


def main():
    rclpy.init()
    node = Straight()
    rclpy.spin(node)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
