#!/usr/bin/env python3
"""Follow wall: keep an obstacle on the robot's right, while the Bug2 coordinator says so.

Switched on and off through the std_srvs/SetBool service wall_follower_switch. The laser is
cut into five sectors by angle, right to left (right, fright, front, fleft, left), each read as
its nearest return; a small state machine looks for a wall, turns left away from it, or drives
along it.
"""

import math

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan
from std_srvs.srv import SetBool, SetBoolResponse

active_ = False
regions_ = None
state_ = 0  # 0: find the wall, 1: turn left, 2: follow the wall
cmd_pub_ = None

WALL_DISTANCE = 0.9  # m: what counts as "near" in a sector
FAR = 10.0  # m: a sector that sees nothing reads this
SECTORS = (  # name, from, to (degrees, robot frame, positive to the left)
    ("right", -90.0, -54.0),
    ("fright", -54.0, -18.0),
    ("front", -18.0, 18.0),
    ("fleft", 18.0, 54.0),
    ("left", 54.0, 90.0),
)


def handle_switch(req):
    global active_
    active_ = req.data
    state = "on" if active_ else "off"
    return SetBoolResponse(success=True, message=f"follow_wall is now {state}")


def sectors(scan):
    nearest = {name: FAR for name, _, _ in SECTORS}
    for i, r in enumerate(scan.ranges):
        if math.isnan(r) or r == math.inf:
            continue
        angle = math.degrees(scan.angle_min + i * scan.angle_increment)
        for name, low, high in SECTORS:
            if low <= angle < high or (high == 90.0 and angle == high):
                nearest[name] = min(nearest[name], max(r, 0.0))
    return nearest


def on_scan(msg):
    global regions_
    regions_ = sectors(msg)


def set_state(state):
    global state_
    if state != state_:
        rospy.loginfo("follow_wall: state %d -> %d", state_, state)
    state_ = state


def choose_state():
    d = WALL_DISTANCE
    front, fleft, fright = regions_["front"], regions_["fleft"], regions_["fright"]
    if front > d and fleft > d and fright > d:
        set_state(0)  # nothing near: look for a wall
    elif front < d:
        set_state(1)  # something ahead: turn left
    elif fright < d and fleft > d:
        set_state(2)  # wall on the right only: follow it
    elif fleft < d and fright > d:
        set_state(0)  # wall on the left only: look for one on the right
    else:
        set_state(1)  # walls on both sides: turn left


def command():
    twist = Twist()
    if state_ == 0:
        twist.linear.x = 0.3
        twist.angular.z = -0.3
    elif state_ == 1:
        twist.angular.z = 0.3
    else:
        twist.linear.x = 0.3
        if regions_["fright"] < 0.8 * WALL_DISTANCE:
            twist.angular.z = 0.3  # too near the wall: lean away from it
    return twist


def main():
    global cmd_pub_
    rospy.init_node("follow_wall")
    cmd_pub_ = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
    rospy.Subscriber("/scan", LaserScan, on_scan)
    rospy.Service("wall_follower_switch", SetBool, handle_switch)
    rate = rospy.Rate(20)
    while not rospy.is_shutdown():
        if active_ and regions_ is not None:
            choose_state()
            cmd_pub_.publish(command())
        rate.sleep()


if __name__ == "__main__":
    try:  # noqa: SIM105  (the rospy idiom)
        main()
    except rospy.ROSInterruptException:
        pass
