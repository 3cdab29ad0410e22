"""Reports say exactly what happened (issue 42): the stall rule that fired, the speed the
robot executed beside the one asked, and a world shrunk to no obstacle named as such."""

from __future__ import annotations

import math

from ifgm_ref.core.params import RobotParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.episodes import ending, place_of
from ifgm_ref.oracle.implementation import Implementation, Promises
from ifgm_ref.oracle.profiles import Profile
from ifgm_ref.oracle.runner import Status, run_check
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import World

#: Two examples: the first stalls.
TWO = Profile("two", 2)


class Circler:
    """Drives round a small circle for ever."""

    name = "circler"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Nothing to prepare."""

    def step(self, observation: Observation) -> Command:
        """A little left of the heading, at full speed."""
        return Command(observation.pose.theta + 0.2, 10.0)


def test_a_stall_names_the_rule_that_fired() -> None:
    impl = Implementation(Circler, "circler", Promises())
    result = run_check(CHECKS["converges_open"], impl, TWO, artifacts=None)
    assert result.status is Status.FAILED, result.line()
    assert "stop_reason='stalled' (" in result.message, result.message
    assert " rule: " in result.message.split("'stalled' (")[1].split(")")[0], result.message


def test_the_trace_keeps_the_speed_asked_beside_the_speed_executed() -> None:
    run = simulate(World(Pose(0.0, 0.0, 0.0), Point(20.0, 0.0)), Circler())
    top = RobotParams().speed
    step = run.trace[0]
    assert (step.speed_cmd, step.speed_executed) == (10.0, top)
    assert math.isclose(math.dist((step.x, step.y), (run.trace[1].x, run.trace[1].y)), top * 0.1)
    assert run.trace[-1].speed_executed is None  # the last sample has no command


def test_messages_give_the_speed_as_executed() -> None:
    robot = RobotParams()
    assert Command(0.0, 10.0).executed_speed(robot) == f"{robot.speed:.4f} (asked 10.0000)"


def test_a_world_with_no_obstacle_says_so_and_gives_no_clearance() -> None:
    world = World(Pose(0.0, 0.0, 0.0), Point(20.0, 0.0), name="open")
    run = simulate(world, Circler())
    impl = Implementation(Circler, "circler", Promises())
    assert "open world with no obstacle from (0.000, 0.000, 0.000)" in place_of(impl, world)
    assert "clearance" not in ending(run) and "inf" not in ending(run), ending(run)
