#!/usr/bin/env python3
"""Go to point: turn towards the goal, then drive to it, while the Bug2 coordinator says so.

Switched on and off through the std_srvs/SetBool service go_to_point_switch. The goal comes
from the parameters des_pos_x and des_pos_y (metres, odom frame).

The private parameter ~wrap_heading (default true) chooses how the heading error is formed:
wrapped into (-pi, pi] (the robot turns the short way), or left as the plain difference of two
angles, which can be up to 2 pi off (the robot may turn the long way round) -- a classic slip
that the oracle's rigid_motion_invariant check catches.
"""

import math

import rospy
from geometry_msgs.msg import Point, Twist
from nav_msgs.msg import Odometry
from std_srvs.srv import SetBool, SetBoolResponse
from tf import transformations

active_ = False
position_ = Point()
yaw_ = 0.0
state_ = 0  # 0: face the goal, 1: drive to it, 2: arrived
goal_ = Point()
wrap_heading_ = True
cmd_pub_ = None

YAW_PRECISION = math.pi / 90  # 2 degrees
DIST_PRECISION = 0.05  # m
TURN_SPEED = 0.7  # rad/s
DRIVE_SPEED = 0.3  # m/s
STEER_GAIN = 1.0  # rad/s per rad while driving


def handle_switch(req):
    global active_
    active_ = req.data
    state = "on" if active_ else "off"
    return SetBoolResponse(success=True, message=f"go_to_point is now {state}")


def on_odom(msg):
    global position_, yaw_
    position_ = msg.pose.pose.position
    q = msg.pose.pose.orientation
    yaw_ = transformations.euler_from_quaternion([q.x, q.y, q.z, q.w])[2]


def wrapped(angle):
    """angle brought into (-pi, pi]."""
    angle = math.fmod(angle, 2 * math.pi)
    if angle > math.pi:
        angle -= 2 * math.pi
    elif angle <= -math.pi:
        angle += 2 * math.pi
    return angle


def heading_error():
    desired = math.atan2(goal_.y - position_.y, goal_.x - position_.x)
    error = desired - yaw_
    return wrapped(error) if wrap_heading_ else error


def set_state(state):
    global state_
    if state != state_:
        rospy.loginfo("go_to_point: state %d -> %d", state_, state)
    state_ = state


def face_goal():
    error = heading_error()
    twist = Twist()
    if abs(error) > YAW_PRECISION:
        twist.angular.z = TURN_SPEED if error > 0 else -TURN_SPEED
    cmd_pub_.publish(twist)
    if abs(error) <= YAW_PRECISION:
        set_state(1)


def drive_to_goal():
    error = heading_error()
    distance = math.hypot(goal_.y - position_.y, goal_.x - position_.x)
    if distance <= DIST_PRECISION:
        set_state(2)
        return
    twist = Twist()
    twist.linear.x = DRIVE_SPEED
    twist.angular.z = STEER_GAIN * error
    cmd_pub_.publish(twist)
    if abs(error) > 10 * YAW_PRECISION:
        set_state(0)


def arrived():
    cmd_pub_.publish(Twist())


def main():
    global goal_, wrap_heading_, cmd_pub_
    rospy.init_node("go_to_point")
    goal_ = Point(rospy.get_param("des_pos_x"), rospy.get_param("des_pos_y"), 0.0)
    wrap_heading_ = rospy.get_param("~wrap_heading", True)
    cmd_pub_ = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
    rospy.Subscriber("/odom", Odometry, on_odom)
    rospy.Service("go_to_point_switch", SetBool, handle_switch)
    rate = rospy.Rate(20)
    while not rospy.is_shutdown():
        if active_:
            if state_ == 0:
                face_goal()
            elif state_ == 1:
                drive_to_goal()
            else:
                arrived()
        rate.sleep()


if __name__ == "__main__":
    try:  # noqa: SIM105  (the rospy idiom)
        main()
    except rospy.ROSInterruptException:
        pass
