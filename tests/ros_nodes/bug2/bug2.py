#!/usr/bin/env python3
"""Bug2 coordinator: go to the goal along the m-line; on meeting an obstacle, follow its wall
until the m-line is met again nearer the goal, then go to the goal again.

It drives nothing itself: it switches go_to_point and follow_wall on and off through their
std_srvs/SetBool services (go_to_point_switch, wall_follower_switch), at 20 Hz. The m-line runs
from where the robot starts to the goal (parameters des_pos_x and des_pos_y, metres).
"""

import math

import rospy
from geometry_msgs.msg import Point
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_srvs.srv import SetBool

position_ = Point()
regions_ = None
start_ = Point()
goal_ = Point()
mode_ = 0  # 0: go to point, 1: follow the wall
MODES = ("go to point", "follow wall")
hit_distance_ = 0.0  # distance to the goal where the wall was met
ticks_in_mode_ = 0
go_to_point_switch_ = None
wall_follower_switch_ = None

OBSTACLE_AHEAD = 0.7  # m: a front return nearer than this is a wall met
LINE_TOLERANCE = 0.1  # m: this near the m-line counts as on it
MIN_FOLLOW_TICKS = 40  # 2 s at 20 Hz before leaving the wall
SECTOR_HALF_WIDTH = math.radians(18.0)


def on_odom(msg):
    global position_
    position_ = msg.pose.pose.position


def on_scan(msg):
    global regions_
    front = 10.0
    for i, r in enumerate(msg.ranges):
        angle = msg.angle_min + i * msg.angle_increment
        if abs(angle) <= SECTOR_HALF_WIDTH and not math.isnan(r):
            front = min(front, max(r, 0.0))
    regions_ = {"front": front}


def distance_to_m_line(p):
    dx, dy = goal_.x - start_.x, goal_.y - start_.y
    length = math.hypot(dx, dy)
    if length == 0.0:
        return math.hypot(p.x - start_.x, p.y - start_.y)
    return abs(dy * p.x - dx * p.y + goal_.x * start_.y - goal_.y * start_.x) / length


def distance_to_goal(p):
    return math.hypot(goal_.x - p.x, goal_.y - p.y)


def change_mode(mode):
    global mode_, ticks_in_mode_
    mode_ = mode
    ticks_in_mode_ = 0
    go_to_point_switch_(mode == 0)
    wall_follower_switch_(mode == 1)
    rospy.loginfo("bug2: mode %s", MODES[mode])


def main():
    global start_, goal_, hit_distance_, ticks_in_mode_, go_to_point_switch_, wall_follower_switch_
    rospy.init_node("bug2")
    rospy.Subscriber("/odom", Odometry, on_odom)
    rospy.Subscriber("/scan", LaserScan, on_scan)
    rospy.wait_for_service("go_to_point_switch")
    rospy.wait_for_service("wall_follower_switch")
    go_to_point_switch_ = rospy.ServiceProxy("go_to_point_switch", SetBool)
    wall_follower_switch_ = rospy.ServiceProxy("wall_follower_switch", SetBool)
    start_ = rospy.wait_for_message("/odom", Odometry).pose.pose.position
    goal_ = Point(rospy.get_param("des_pos_x"), rospy.get_param("des_pos_y"), 0.0)
    change_mode(0)
    rate = rospy.Rate(20)
    while not rospy.is_shutdown():
        if regions_ is not None:
            if mode_ == 0 and regions_["front"] < OBSTACLE_AHEAD:
                hit_distance_ = distance_to_goal(position_)
                change_mode(1)
            elif (
                mode_ == 1
                and ticks_in_mode_ > MIN_FOLLOW_TICKS
                and distance_to_m_line(position_) < LINE_TOLERANCE
                and distance_to_goal(position_) < hit_distance_ - LINE_TOLERANCE
            ):
                change_mode(0)
        ticks_in_mode_ += 1
        rate.sleep()


if __name__ == "__main__":
    try:  # noqa: SIM105  (the rospy idiom)
        main()
    except rospy.ROSInterruptException:
        pass
