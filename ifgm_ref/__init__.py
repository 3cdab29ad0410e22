"""ifgm-ref: the executable reference specification of IFGM and IBA.

The paper: "An Improved Algorithm for Collision Avoidance in Environments Having U and H
Shaped Obstacles" (Intelligent Follow the Gap Method, IFGM, and Intelligent Bug Algorithm,
IBA). Layers, bottom up: equations -> percepts -> flowchart -> planners -> simulator (world,
sensor, robot) -> oracle, figures and command line.
"""

__version__ = "0.1.0"
