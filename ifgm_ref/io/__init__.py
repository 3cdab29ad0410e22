"""Worlds, runs and planners from and to the outside: world files (:mod:`.worldfile`),
Gazebo's and BARN's worlds, the built-in scenarios by name, ROS bags (:mod:`.bags`), programs
over JSON lines (:mod:`.transport`) and unchanged ROS nodes (:mod:`.ros`).

Imports the layers below (core, paper, planners, sim); never the oracle or the applications.
"""
