"""Broken variants of the reference IFGM: the oracle must reject every one of them.

A conformance suite is only as good as the bugs it catches. Each mutant here changes one
thing a port could plausibly get wrong; ``tests/test_oracle.py`` asserts that the oracle
rejects each, in process and through ``ifgm-ref serve`` (serve any of them with
``ifgm-ref serve --planner ifgm_ref.oracle.mutants:GapAngleSignFlipped``).
"""

from __future__ import annotations

import math
from dataclasses import replace

from ifgm_ref.core.elements import traces
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Behaviour, Command, EpisodeParams
from ifgm_ref.paper.equations import eq3_goal_angle_literal
from ifgm_ref.paper.percepts.clusters import Gap
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.planners.ifgm.atoms import IFGMState, StepInputs
from ifgm_ref.planners.sight import Sight


class GapAngleSignFlipped(IFGMPlanner):
    """Case-1 steers at the mirror image of the gap: eq. (2)'s sign flipped."""

    name = "ifgm-gap-sign-flipped"

    def gap_heading(self, pose: Pose, gap: Gap) -> float:
        straight = super().gap_heading(pose, gap)
        return pose.theta - (straight - pose.theta)


class QuadrantBlindGoalAngle(IFGMPlanner):
    """Eq. (3) as printed: ``arctan(dy / dx)``, blind to goals behind (errata row 5)."""

    name = "ifgm-quadrant-blind"

    def goal_bearing(self, pose: Pose) -> float:
        dx = self.goal.x - pose.x
        return eq3_goal_angle_literal(pose.position, self.goal) if dx != 0.0 else math.pi / 2


class NeverLeavesEdge(IFGMPlanner):
    """Once following an edge, never leaves it (no free path is ever seen)."""

    name = "ifgm-never-leaves"

    def advance_round(self, state: IFGMState, sight: Sight) -> tuple[IFGMState, bool]:
        return state, False


class IgnoresDObs(IFGMPlanner):
    """``d_obs`` ignored: never "too close", so Case-1 steers through gaps to the end."""

    name = "ifgm-ignores-d-obs"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        super().reset(start, goal, params)
        # The least d_obs the parameters admit (they must be > 0): no obstacle is that near.
        self.ifgm = replace(self.ifgm, d_obs=math.ulp(0.0))


@traces("t1.bug_point_robot")
class PointRobot(IFGMPlanner):
    """Plans for a robot of (almost) zero radius: clearances, ``d_th`` and the stand-off all
    lose the robot's size."""

    name = "ifgm-point-robot"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        point = replace(params.robot, radius=1e-6)
        super().reset(start, goal, replace(params, robot=point))


class GapAngleInWorldFrame(IFGMPlanner):
    """Eq. (2)'s robot-frame gap angle used as a world heading (the pose's heading forgotten)."""

    name = "ifgm-gap-world-frame"

    def gap_heading(self, pose: Pose, gap: Gap) -> float:
        return super().gap_heading(Pose(pose.x, pose.y, 0.0), gap)


class AbsoluteStandoff(IFGMPlanner):
    """Follows walls at a fixed 1.0 (ft) stand-off margin whatever the robot's size: a margin
    written as a number instead of derived from the radius (``standoff_margin = 2 r / 3``,
    :mod:`ifgm_ref.planners.tuning`); the ``scale_invariant`` check rejects it."""

    name = "ifgm-absolute-standoff"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        fixed = {**params.params, "standoff_margin": 1.0}
        super().reset(start, goal, replace(params, params=fixed))


class NoDeadEndRule(IFGMPlanner):
    """Figure 3's dead-end rule left out: inside a U or an H, where no gap is wider than
    ``d_th`` and every ray returns, the port does what FGM does and stands still ("at the
    centre of obstacle, the robot becomes unable to take any decision", section 5.2) instead
    of turning in 45-degree steps. Only the paper's trap (a U or H met head-on) shows it."""

    name = "ifgm-no-dead-end-rule"

    def dead_end(self, state: IFGMState, percepts: StepInputs) -> tuple[IFGMState, Command]:
        pose = percepts.sight.pose
        return state, Command(pose.theta, 0.0, behaviour=Behaviour.OBSTACLE_AVOIDANCE)


class BrakesLate(IFGMPlanner):
    """The braking governor believes the robot brakes four times harder than it does: it
    keeps its speed until a quarter of the room it needs to stop (errata row 36)."""

    name = "ifgm-brakes-late"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        super().reset(start, goal, params)
        robot = replace(params.robot, braking=4 * params.robot.braking)
        self.governor.reset(replace(params, robot=robot))


#: Every mutant by a short name.
MUTANTS: dict[str, type[IFGMPlanner]] = {
    "gap_sign_flipped": GapAngleSignFlipped,
    "quadrant_blind": QuadrantBlindGoalAngle,
    "never_leaves": NeverLeavesEdge,
    "ignores_d_obs": IgnoresDObs,
    "point_robot": PointRobot,
    "gap_world_frame": GapAngleInWorldFrame,
    "absolute_standoff": AbsoluteStandoff,
    "no_dead_end_rule": NoDeadEndRule,
    "brakes_late": BrakesLate,
}
