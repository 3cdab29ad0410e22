#!/usr/bin/env python3
"""The reference IFGM behind a small rospy node: /scan and /odom in, /cmd_vel out.

Run it under ifgm-ref's rospy stand-in (no ROS install needed):

    ifgm-ref simulate u_trap --ros-node "python3 examples/ros/ifgm_node.py" --plot u.png
    ifgm-ref oracle --ros-node "python3 examples/ros/ifgm_node.py" --profile quick

The planner is ifgm_ref.planners.ifgm.planner.IFGMPlanner, unchanged; the node only translates. It
reads the goal from its private parameters ~goal_x and ~goal_y (metres, odom frame), and the
robot and the sensor from /ifgm_ref/robot and /ifgm_ref/sensor (docs/ros-nodes.md). It
decides once per scan, in the scan's callback, from the latest odometry, and publishes the decision
as a Twist, with its behaviour on /ifgm_ref/behaviour (and its Figure 3 branch on /ifgm_ref/branch,
given _report_branch:=true); a stop the planner asks for goes to /ifgm_ref/stop. Everything is in
metres: the planner derives its lengths from the robot and the sensor, so it runs in any unit.
"""

import math

import numpy as np
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String
from tf.transformations import euler_from_quaternion

from ifgm_ref.core.laserscan import LaserScan as Scan
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import EpisodeParams, Observation
from ifgm_ref.planners.ifgm import IFGMPlanner


def episode_params():
    """The robot, the sensor and the time step, from the parameter server (SI units)."""
    robot = rospy.get_param("/ifgm_ref/robot")
    sensor = rospy.get_param("/ifgm_ref/sensor")
    return EpisodeParams(
        robot=RobotParams(
            radius=robot["radius"],
            speed=robot["speed"],
            max_turn_rate=robot["max_turn_rate"],
            latency=robot.get("latency", 0),
            braking=robot.get("braking", math.inf),
            acceleration=robot.get("acceleration", math.inf),
            response=robot.get("response", 0.0),
        ),
        sensor=SensorParams(
            fov=sensor["fov"],
            rays=sensor["rays"],
            range_min=sensor["range_min"],
            range_max=sensor["range_max"],
        ),
        dt=rospy.get_param("/ifgm_ref/dt"),
        goal_tolerance=rospy.get_param("/ifgm_ref/goal_tolerance"),
    )


class IfgmNode:
    """Subscribes /odom and /scan, publishes /cmd_vel (and /ifgm_ref/stop)."""

    def __init__(self):
        self.goal = Point(rospy.get_param("~goal_x"), rospy.get_param("~goal_y"))
        self.params = episode_params()
        self.planner = IFGMPlanner()
        self.pose = None
        self.started = False
        self.cmd_vel = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
        self.stop = rospy.Publisher("/ifgm_ref/stop", String, queue_size=1)
        # Optional labels for the trace (a Twist cannot carry them): the behaviour always; the
        # Figure 3 branch only if ~report_branch is true, since the oracle's dead_end_turns
        # then reads the 45-degree turns from the commanded headings, and a velocity command
        # only says one step's turn (the reference answering Twists fails it the same way:
        # ifgm-ref oracle --planner ifgm_ref.oracle.variants:Twist --check dead_end_turns).
        self.report_branch = rospy.get_param("~report_branch", False)
        self.branch = rospy.Publisher("/ifgm_ref/branch", String, queue_size=1)
        self.behaviour = rospy.Publisher("/ifgm_ref/behaviour", String, queue_size=1)
        rospy.Subscriber("/odom", Odometry, self.on_odom, queue_size=1)
        rospy.Subscriber("/scan", LaserScan, self.on_scan, queue_size=1)

    def on_odom(self, msg):
        position, q = msg.pose.pose.position, msg.pose.pose.orientation
        yaw = euler_from_quaternion([q.x, q.y, q.z, q.w])[2]
        self.pose = Pose(position.x, position.y, yaw)

    def on_scan(self, msg):
        if self.pose is None:
            return
        if not self.started:
            self.planner.reset(self.pose, self.goal, self.params)
            self.started = True
        # The angles as the sensor's description gives them in float64 (the message's are
        # float32); the ranges as measured.
        sensor = self.params.sensor
        scan = Scan(
            angle_min=-sensor.fov / 2,
            angle_max=sensor.fov / 2,
            angle_increment=sensor.fov / (sensor.rays - 1),
            range_min=sensor.range_min,
            range_max=sensor.range_max,
            ranges=np.asarray(msg.ranges, dtype=np.float64),
        )
        observation = Observation(rospy.get_time(), self.pose, self.goal, scan)
        command = self.planner.step(observation)
        linear, angular = command.twist(self.pose, self.params)
        twist = Twist()
        twist.linear.x = linear
        twist.angular.z = angular
        self.cmd_vel.publish(twist)
        if self.report_branch:
            self.branch.publish(String(data=command.branch or ""))
        self.behaviour.publish(String(data=command.behaviour or ""))
        if command.stop is not None:
            self.stop.publish(String(data=command.stop))


def main():
    rospy.init_node("ifgm")
    IfgmNode()
    rospy.spin()


if __name__ == "__main__":
    main()
