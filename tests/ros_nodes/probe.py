#!/usr/bin/env python3
"""A test node for tests/test_ros_nodes.py: one small behaviour per ~mode.

echo     publishes /cmd_vel with linear.x = the time, at 20 Hz (twice per 0.1 s step)
silent   publishes nothing
stale    publishes one /cmd_vel (linear.x 0.2) at the first scan, then nothing
stop     publishes ~reason on /ifgm_ref/stop at the first scan
shutdown calls rospy.signal_shutdown at the first scan
exit     returns from the script at the first scan
crash    raises at the first scan (in the main thread)
goal     drives at linear.x = 0.1 if ~goal_x, des_pos_x and the goal topic's pose agree
remap    on each scan of "base_scan", publishes linear.x 0.1 on "robot/cmd_vel"
"""

import sys

import rospy
from geometry_msgs.msg import PoseStamped, Twist
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String


def twist(linear):
    message = Twist()
    message.linear.x = linear
    return message


def main():
    rospy.init_node("probe")
    mode = rospy.get_param("~mode")
    print("probe: a print on stdout must not disturb the broker")
    pub = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
    if mode == "echo":
        rate = rospy.Rate(20)
        while not rospy.is_shutdown():
            pub.publish(twist(rospy.get_time()))
            rate.sleep()
    elif mode == "silent":
        rospy.spin()
    elif mode == "remap":
        out = rospy.Publisher("robot/cmd_vel", Twist, queue_size=1)
        rospy.Subscriber("base_scan", LaserScan, lambda scan: out.publish(twist(0.1)))
        rospy.spin()
    elif mode == "goal":
        topic = rospy.get_param("~topic", "/move_base_simple/goal")
        goal = rospy.wait_for_message(topic, PoseStamped)
        agree = rospy.get_param("~goal_x") == rospy.get_param("des_pos_x") == goal.pose.position.x
        rospy.loginfo("goal %s on %s, agree: %s", goal.pose.position.x, topic, agree)
        rospy.wait_for_message("/scan", LaserScan)
        pub.publish(twist(0.1 if agree else 0.0))
        rospy.spin()
    else:
        rospy.wait_for_message("/scan", LaserScan)
        if mode == "stale":
            pub.publish(twist(0.2))
            rospy.spin()
        elif mode == "stop":
            stop = rospy.Publisher("/ifgm_ref/stop", String, queue_size=1)
            stop.publish(String(data=rospy.get_param("~reason")))
            rospy.spin()
        elif mode == "shutdown":
            rospy.signal_shutdown("nothing more to do")
            rospy.spin()
        elif mode == "crash":
            raise RuntimeError("the probe crashes on purpose")
        elif mode != "exit":
            sys.exit(f"unknown mode {mode}")


if __name__ == "__main__":
    main()
