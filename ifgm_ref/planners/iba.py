"""IBA, the Intelligent Bug Algorithm (section 4.1 of the paper).

"The *move to goal* behaviour of IBA is similar to Bug family. However in *obstacle avoidance*
behaviour, the robot continuously monitors the obstacles in the path toward destination during
edge detection. The leaving point is selected based on free path instead of shorter distance
toward destination. ... At leaving point, when an obstacles-free path is sensed, the robot
changes its behaviour to *move to goal* in order to generate new reference path." And: "In
contrast with Bug family algorithms, bidirectional mechanism is introduced in IBA using the
sensor's configuration on the robot."

So IBA is DistBug's structure (:class:`~ifgm_ref.planners.boundary.BoundaryPlanner`) with two
changes:

* **bidirectional**: on meeting an obstacle the robot turns towards the freer of its left and
  right beams (ties: towards the goal's side), instead of always the same way;
* **free-path leaving**: it leaves the edge at the first point where the goal is in view and
  the robot-wide corridor towards it is clear as far as the sensor sees, or to the goal.

Back at its hit point after a whole loop it reports the goal unreachable, as DistBug does.
"""

from __future__ import annotations

import math

import numpy as np

from ifgm_ref.laserscan import Beam, LaserScan
from ifgm_ref.planners.boundary import BoundaryPlanner
from ifgm_ref.planners.edge_following import FollowSide
from ifgm_ref.pose import Pose, wrap_angle
from ifgm_ref.protocol import Observation


def beam_openness(scan: LaserScan, beam: Beam) -> float:
    """Mean range seen in ``beam``, a no-return ray counting as ``range_max``, ft.

    >>> scan = LaserScan(-1.0, 1.0, 0.5, 0.0, 10.0, [2.0, 2.0, 9.0, math.inf, math.inf])
    >>> beam_openness(scan, Beam.RIGHT), beam_openness(scan, Beam.LEFT)
    (2.0, 10.0)
    """
    mask = scan.beam_mask(beam)
    ranges = np.where(np.isfinite(scan.ranges), scan.ranges, scan.range_max)
    ranges = np.where(ranges < 0.0, 0.0, ranges)
    return float(ranges[mask].mean()) if mask.any() else 0.0


def freer_side(scan: LaserScan, pose: Pose, goal_bearing: float) -> FollowSide:
    """The side to keep the obstacle on: turn towards the freer beam (ties: the goal's side).

    Turning left keeps the obstacle on the robot's right, and vice versa.
    """
    left = beam_openness(scan, Beam.LEFT)
    right = beam_openness(scan, Beam.RIGHT)
    if math.isclose(left, right, rel_tol=1e-9):
        goes_left = wrap_angle(goal_bearing - pose.theta) >= 0.0
    else:
        goes_left = left > right
    return FollowSide.RIGHT if goes_left else FollowSide.LEFT


class IBAPlanner(BoundaryPlanner):
    """Bidirectional edge following, leaving at the first free path towards the goal."""

    name = "iba"

    def choose_side(self, observation: Observation) -> FollowSide:
        """Bidirectional: turn towards the freer beam (section 4.1)."""
        pose = observation.pose
        return freer_side(observation.scan, pose, self.goal_bearing(pose))

    def should_leave(self, observation: Observation) -> bool:
        """Leave at the first free path towards the goal (section 4.1)."""
        return self.path_free(observation.pose)
