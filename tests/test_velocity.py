"""Velocity commands (ROS's Twist): the second command form, in process and on the robot."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.velocity import VelocityPlanner
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.simulator import simulate


@pytest.mark.parametrize("world", ["u_trap", "fig7a"])
def test_a_planner_answering_velocities_drives_its_own_path(world: str) -> None:
    """The same decisions in the other form move the robot the same way, within rounding:
    ``theta + w dt`` against the heading it stands for."""
    sim = SimParams(max_time=60.0)
    heading = simulate(resolve_world(world), make_planner("ifgm"), sim)
    twist = simulate(resolve_world(world), VelocityPlanner(make_planner("ifgm")), sim)
    assert twist.result.stop_reason == heading.result.stop_reason
    assert len(twist.trace) == len(heading.trace)
    a = np.array([(s.x, s.y, s.theta) for s in heading.trace])
    b = np.array([(s.x, s.y, s.theta) for s in twist.trace])
    assert np.allclose(a, b, rtol=0.0, atol=1e-9)
    assert [s.branch for s in twist.trace] == [s.branch for s in heading.trace]


class _Answers:
    """A planner that answers one fixed velocity command."""

    name = "fixed"

    def __init__(self, linear: float, angular: float) -> None:
        self.linear, self.angular = linear, angular
        self.params = EpisodeParams()

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.params = params

    def step(self, observation: Observation) -> Command:
        return Command.from_twist(self.linear, self.angular, observation.pose, self.params)


#: ``invalid_command``'s detail for a velocity command the robot cannot execute.
REVERSE = "linear velocity=-0.5, but should be finite and >= 0 (the robot does not reverse)"


@pytest.mark.parametrize(
    ("linear", "angular", "detail"),
    [(-0.5, 0.0, REVERSE), (0.5, math.inf, "angular velocity=inf, but should be finite")],
)
def test_an_impossible_velocity_command_ends_the_episode(
    linear: float, angular: float, detail: str
) -> None:
    run = simulate(resolve_world("free"), _Answers(linear, angular), SimParams(max_time=1.0))
    assert (run.result.stop_reason, run.result.detail) == ("invalid_command", detail)


def test_the_robot_turns_at_the_commanded_rate_within_its_limit() -> None:
    """Faster than ``max_turn_rate`` is clipped to it; a slower turn is kept; the speed too."""
    world = resolve_world("free")
    robot = world.robot
    for rate, expected in ((0.25, 0.25), (10.0, robot.max_turn_rate)):
        run = simulate(world, _Answers(0.1, rate), SimParams(max_time=1.0))
        turns = np.diff([s.theta for s in run.trace]) / 0.1
        assert np.allclose(turns, expected, atol=1e-9)
        steps = np.hypot(np.diff([s.x for s in run.trace]), np.diff([s.y for s in run.trace]))
        assert np.allclose(steps, 0.1 * 0.1, atol=1e-12)
