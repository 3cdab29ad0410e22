"""Percepts: what a planner makes of one scan (and of the scans it has just seen).

Section 4 of the paper: "A distance vector is calculated with the help of sensed position of
obstacle and the robot's current position ... an obstacle array is created, which indicates
the position of obstacles in terms of (x, y) coordinates obtained by resolving distance vector
into rectangular coordinates. Using this array, the gap (Euclidian distance) between every two
consecutive obstacles is calculated."

Modules: :mod:`~ifgm_ref.paper.percepts.points` (scan -> points),
:mod:`~ifgm_ref.paper.percepts.clusters` (points -> obstacles and the gaps between them),
:mod:`~ifgm_ref.paper.percepts.memory` (the obstacle points of the last few seconds, from odometry)
and :mod:`~ifgm_ref.paper.percepts.corridor` (is the straight path towards a point free?). Nothing
here knows the map.
"""
