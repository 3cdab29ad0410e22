"""The foundations: what every layer may use, importing nothing of ours outside this folder.

Errors and the one validator, poses and angles, the laser scan, the planner's protocol
(observation in, command out), the robot's and sensor's parameters, the formulas every
threshold is derived from, the paper's element index and its ``traces`` marker, and the
small services of a command (files written whole, progress lines, the cache folder).
"""
