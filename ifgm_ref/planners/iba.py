"""IBA, the Intelligent Bug Algorithm (section 4.1 of the paper).

"The *move to goal* behaviour of IBA is similar to Bug family. However in *obstacle avoidance*
behaviour, the robot continuously monitors the obstacles in the path toward destination during
edge detection. The leaving point is selected based on free path instead of shorter distance
toward destination. ... At leaving point, when an obstacles-free path is sensed, the robot
changes its behaviour to *move to goal* in order to generate new reference path." And: "In
contrast with Bug family algorithms, bidirectional mechanism is introduced in IBA using the
sensor's configuration on the robot."

So IBA is DistBug (:class:`~ifgm_ref.planners.distbug.DistBugPlanner`) with these changes
(:class:`IBARule` and :func:`freer_side`):

* **bidirectional**: on meeting an obstacle the robot turns towards the freer of its left and
  right beams (ties: towards the goal's side), instead of always the same way;
* **free-path leaving**: it leaves the edge at the first point where the goal is in view and
  the robot-wide corridor towards it is clear as far as the paper's sensor sees, or to the
  goal, and following it that far would bring the robot as near the goal as it has been;
* **one yardstick**: progress is measured against the best distance to the goal of the whole
  episode, not of the current obstacle (errata row 31);
* **DistBug's rule kept** beside the free path, which alone never fires while a second
  obstacle stands behind the followed one (errata row 24).

After a whole loop without leaving it falls back on Bug1's round, as DistBug does
(:mod:`~ifgm_ref.planners.circuit`, errata row 34).
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from ifgm_ref.core.elements import traces
from ifgm_ref.core.laserscan import Beam, LaserScan
from ifgm_ref.core.pose import Point, Pose, distance, wrap_angle
from ifgm_ref.planners.boundary import BoundaryPlanner, EdgeFollower
from ifgm_ref.planners.distbug import DistBugParams, DistBugRule, makes_progress
from ifgm_ref.planners.edge_following import FollowSide
from ifgm_ref.planners.sight import BoundaryParams, Sight
from ifgm_ref.planners.tuning import Tuning, parameter_names


def beam_openness(scan: LaserScan, beam: Beam) -> float:
    """Mean range seen in ``beam``, a no-return ray (``+inf``) counting as ``range_max`` and a
    return nearer than ``range_min`` (``-inf``, REP 117) as 0, ft.

    >>> scan = LaserScan(-1.0, 1.0, 0.5, 0.0, 10.0, [2.0, 2.0, 9.0, math.inf, math.inf])
    >>> beam_openness(scan, Beam.RIGHT), beam_openness(scan, Beam.LEFT)
    (2.0, 10.0)
    """
    mask = scan.beam_mask(beam)
    ranges = np.where(np.isposinf(scan.ranges), scan.range_max, scan.ranges)
    ranges = np.where(ranges < 0.0, 0.0, ranges)
    return float(ranges[mask].mean()) if mask.any() else 0.0


#: The goal counts as dead ahead within this angle, rad: moving to the goal points the robot
#: at it, so the sign of so small a bearing is rounding, not a side.
GOAL_AHEAD = 1e-6


@traces("iba.bidirectional", "s3.bidirectional")
def freer_side(scan: LaserScan, pose: Pose, goal_bearing: float) -> FollowSide:
    """The side to keep the obstacle on: turn towards the freer beam.

    Ties (equal side beams, e.g. both empty) go towards the goal's side; with the goal dead
    ahead (within :data:`GOAL_AHEAD`), away from the nearest return. Turning left keeps the
    obstacle on the robot's right, and vice versa.

    >>> scan = LaserScan(-1.0, 1.0, 0.5, 0.0, 10.0, [5.0, 3.0, 3.5, 5.0, 5.0])
    >>> freer_side(scan, Pose(0.0, 0.0, 0.0), 0.0)  # nearest return right of ahead: go left
    <FollowSide.RIGHT: 'right'>
    """
    left = beam_openness(scan, Beam.LEFT)
    right = beam_openness(scan, Beam.RIGHT)
    if not math.isclose(left, right, rel_tol=1e-9):
        goes_left = left > right
    elif abs(relative := wrap_angle(goal_bearing - pose.theta)) > GOAL_AHEAD:
        goes_left = relative > 0.0
    else:
        goes_left = bool(scan.angles[int(np.argmin(scan.ranges))] < 0.0)
    return FollowSide.RIGHT if goes_left else FollowSide.LEFT


class IBARule(DistBugRule):
    """IBA's leaving rule: the first free path towards the goal, or DistBug's progress, with
    one ``d_min`` for the whole episode (see the module docstring)."""

    leave_branch: ClassVar[str] = "leave"

    def on_hit(self, sight: Sight, follower: EdgeFollower) -> None:
        """A new obstacle, the same yardstick: ``d_min`` stays the least distance to the goal
        of the whole episode (DistBug restarts it at every hit point). IBA leaves by its free
        path with less promise than DistBug's ``Step``, so it may meet the next obstacle
        farther from the goal than it has been; measured from there, the next leave would
        count a return as progress, and the robot could circle an enclosure or swap between
        two walls for ever (BARN worlds; errata row 31)."""
        self.d_min = yardstick_at_hit(self.d_min, follower.hit_point, sight.episode.goal)

    @traces("iba.leave_free_path", "s3.clear_path")
    def update(self, sight: Sight, follower: EdgeFollower) -> bool:
        """Leave at the first free path towards the goal (section 4.1), or where the free
        range promises progress (DistBug's rule, errata row 24)."""
        self.note(sight)
        return leaves(sight, self.d_min, self.step_length)


def yardstick_at_hit(d_min: float, hit_point: Point, goal: Point) -> float:
    """IBA's ``d_min`` once an obstacle is met at ``hit_point``: still the least distance to
    the goal of the whole episode (:meth:`IBARule.on_hit`, errata row 31)."""
    return min(d_min, distance(hit_point, goal))


def leaves(sight: Sight, d_min: float, step_length: float, *, by_progress: bool = True) -> bool:
    """IBA's leaving rules on this step's sight, ``d_min`` noted: DistBug's progress rule
    (:func:`~ifgm_ref.planners.distbug.makes_progress`, unless ``by_progress`` is off) or a
    free path that leads on (:func:`free_path_leads_on`)."""
    return (by_progress and makes_progress(sight, d_min, step_length)) or free_path_leads_on(
        sight, d_min
    )


def free_path_leads_on(sight: Sight, d_min: float) -> bool:
    """IBA's free path, where following it as far as it is seen free would bring the robot
    at least as near the goal as it has been in this episode (``d_min``)."""
    if not sight.path_free():
        return False
    view_range = sight.episode.tuning.view_range
    return sight.goal_distance - min(sight.goal_free_length, view_range) <= d_min


class IBAPlanner(BoundaryPlanner):
    """Bidirectional edge following (:func:`freer_side`), leaving at the first free path
    towards the goal or, failing that, where DistBug would (:class:`IBARule`)."""

    name: ClassVar[str] = "iba"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (BoundaryParams, DistBugParams)
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self) -> None:
        super().__init__(IBARule(), choose_side=freer_side)
