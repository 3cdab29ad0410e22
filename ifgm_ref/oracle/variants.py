"""Faithful variants of the reference IFGM: the oracle must accept every one of them.

The converse of :mod:`ifgm_ref.oracle.mutants`. A port of IFGM to another language or robot
differs from the reference in ways that do not make it wrong, and an oracle that rejects
them is not used twice. Each variant here differs in one such way, of a stated size;
``tests/test_oracle.py`` runs each through ``ifgm-ref serve`` and the quick profile and
asserts that no check fails (serve any of them with
``ifgm-ref serve --planner ifgm_ref.oracle.variants:HeadingWobble``):

* :class:`HeadingWobble`: the commanded heading off by up to :data:`WOBBLE` (1 degree), as
  rounding, a coarser angle type or a heading controller's dead band would leave it;
* :class:`Float32`: everything the planner reads and answers rounded to 32-bit floats, as a
  port in ``float`` on a microcontroller computes;
* :class:`OppositeTies`: the other choice wherever the reference breaks an exact tie
  (left or right round a symmetric obstacle, the first or the last of equal gaps);
* :func:`Twist`: every command answered as a velocity command, ``(v, w)`` as a ROS node
  publishes it (:class:`~ifgm_ref.core.velocity.VelocityPlanner`), the same motion within
  rounding.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner
from ifgm_ref.core.velocity import VelocityPlanner
from ifgm_ref.planners.ifgm import IFGMPlanner

#: :class:`HeadingWobble`'s largest heading error, rad (1 degree).
WOBBLE = math.radians(1.0)
#: The golden angle, rad: step k of the wobble is ``WOBBLE * sin(k * GOLDEN)``, spread over
#: the whole interval and never repeating.
GOLDEN = math.pi * (3.0 - math.sqrt(5.0))


class HeadingWobble(IFGMPlanner):
    """The reference, its commanded heading off by a deterministic ``WOBBLE sin(k GOLDEN)``
    at step ``k``: within one degree, never the same twice."""

    name = "ifgm-heading-wobble"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        super().reset(start, goal, params)
        self.steps = 0

    def step(self, observation: Observation) -> Command:
        command = super().step(observation)
        self.steps += 1
        return replace(command, heading=command.heading + WOBBLE * math.sin(self.steps * GOLDEN))


def _f32(value: float) -> float:
    return float(np.float32(value))


class Float32(IFGMPlanner):
    """The reference fed and answering in 32-bit floats: pose, goal, time and every range
    rounded to ``float32`` on the way in, heading and speed on the way out (about 7
    significant digits: 1e-6 ft at 10 ft, 4e-8 rad)."""

    name = "ifgm-float32"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        super().reset(Pose(*map(_f32, start)), Point(*map(_f32, goal)), params)

    def step(self, observation: Observation) -> Command:
        scan = observation.scan
        rounded = replace(
            observation,
            t=_f32(observation.t),
            pose=Pose(*map(_f32, observation.pose)),
            goal=Point(*map(_f32, observation.goal)),
            scan=replace(scan, ranges=scan.ranges.astype(np.float32).astype(np.float64)),
        )
        command = super().step(rounded)
        return replace(command, heading=_f32(command.heading), speed=_f32(command.speed))


def _mirrored_scan(scan: LaserScan) -> LaserScan:
    """The scan of the mirror image: the ray at angle ``a`` reads what the ray at ``-a`` did
    (the field of view is symmetric about the heading, so that is the reversed array)."""
    return replace(
        scan,
        angle_min=-scan.angle_max,
        angle_max=-scan.angle_min,
        ranges=np.ascontiguousarray(scan.ranges[::-1]),
    )


class OppositeTies(IFGMPlanner):
    """The reference run in the mirror image of the world (``y -> -y``), its answers mirrored
    back. Away from ties IFGM is mirror-symmetric, so it drives the reference's path; at an
    exact tie (a symmetric obstacle met head-on, equal side beams, equal gaps) the mirrored
    reference's fixed rule picks the mirror choice: the other side."""

    name = "ifgm-opposite-ties"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        super().reset(Pose(start.x, -start.y, -start.theta), Point(goal.x, -goal.y), params)

    def step(self, observation: Observation) -> Command:
        pose, goal = observation.pose, observation.goal
        mirrored = replace(
            observation,
            pose=Pose(pose.x, -pose.y, -pose.theta),
            goal=Point(goal.x, -goal.y),
            scan=_mirrored_scan(observation.scan),
        )
        command = super().step(mirrored)
        return replace(command, heading=-command.heading)


class Twist(VelocityPlanner):
    """The reference answering velocity commands (linear and angular velocity)."""

    promises = "ifgm"

    def __init__(self) -> None:
        super().__init__(IFGMPlanner())


#: Every accepted variant by a short name.
VARIANTS: dict[str, Callable[[], Planner]] = {
    "heading_wobble": HeadingWobble,
    "float32": Float32,
    "opposite_ties": OppositeTies,
    "twist": Twist,
}
