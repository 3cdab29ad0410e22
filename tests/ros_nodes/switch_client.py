#!/usr/bin/env python3
"""A test node calling switch_server's services; it drives (linear.x 0.1) if every answer is
the one expected, and says so with a Trigger-shaped log line."""

import rospy
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty, SetBool, Trigger

rospy.init_node("switch_client")
pub = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
rospy.wait_for_service("switch")
rospy.wait_for_service("/ping", timeout=1.0)
switch = rospy.ServiceProxy("switch", SetBool)
answers = [switch(True).message, switch(data=False).message]
rospy.ServiceProxy("reset", Empty)()
answers.append(rospy.ServiceProxy("ping", Trigger)().message)
try:
    rospy.ServiceProxy("nobody", Trigger)()
except rospy.ServiceException:
    answers.append("no such service")
rospy.loginfo("answers: %s", answers)
command = Twist()
command.linear.x = 0.1 if answers == ["on", "off", "pong 1", "no such service"] else 0.0
rate = rospy.Rate(10)
while not rospy.is_shutdown():
    pub.publish(command)
    rate.sleep()
