#!/usr/bin/env python3
"""A ROS 2 (rclpy) test node: with ``-p role:=server`` it offers std_srvs/SetBool ``switch``;
with ``-p role:=client`` it calls it and drives (linear.x 0.1) if the answer is right."""

import rclpy
from geometry_msgs.msg import Twist
from rclpy.node import Node
from std_srvs.srv import SetBool


def serve(node):
    def on_switch(request, response):
        response.success = True
        response.message = "on" if request.data else "off"
        return response

    node.create_service(SetBool, "switch", on_switch)
    rclpy.spin(node)


def call(node):
    publisher = node.create_publisher(Twist, "cmd_vel", 10)
    client = node.create_client(SetBool, "switch")
    while not client.wait_for_service(timeout_sec=1.0):
        node.get_logger().info("waiting for the switch")
    request = SetBool.Request()
    request.data = True
    future = client.call_async(request)
    rclpy.spin_until_future_complete(node, future)
    twist = Twist()
    twist.linear.x = 0.1 if future.result().message == "on" else 0.0
    node.create_timer(0.1, lambda: publisher.publish(twist))
    rclpy.spin(node)


def main():
    rclpy.init()
    node = Node("switch_" + "node")
    role = node.declare_parameter("role", "server").value
    serve(node) if role == "server" else call(node)


if __name__ == "__main__":
    main()
