"""The simulator (ifgm_ref.sim.simulator): stop reasons, the stall rule, result figures, trace,
determinism."""

from __future__ import annotations

import csv
import io
import json
import math

import pytest

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import PAPER_FREE_DISTANCE_FT, PAPER_FREE_TIME_S, RobotParams, SimParams
from ifgm_ref.core.pose import Point, Pose, distance
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, PlannerStop
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.oracle.metamorphic import scale_sim, scale_world
from ifgm_ref.planners.bug1 import Bug1Planner
from ifgm_ref.planners.fgm import FGMPlanner
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.planners.straight import StraightPlanner
from ifgm_ref.sim.shapes import rectangle
from ifgm_ref.sim.simulator import TRACE_FIELDS, StopReason, TraceStep, simulate, stall_steps
from ifgm_ref.sim.world import Bounds, Polygon, World

FREE = World(start=Pose(0.0, 0.0, 0.0), goal=Point(PAPER_FREE_DISTANCE_FT, 0.0), name="free")
WALL = Polygon(((20.0, -5.0), (22.0, -5.0), (22.0, 5.0), (20.0, 5.0)))
BLOCKED = World(start=Pose(0.0, 0.0, 0.0), goal=Point(40.0, 0.0), obstacles=(WALL,), name="wall")
#: Both stall rules off: the disc rule and the lap rule.
NO_STALL = SimParams(stall_time=None, stall_laps=None)


class ScriptedPlanner:
    """Answers a fixed command, to drive the simulator into each stop reason."""

    name = "scripted"

    def __init__(self, command: Command) -> None:
        self.command = command
        self.observations: list[Observation] = []

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.observations.clear()

    def step(self, observation: Observation) -> Command:
        self.observations.append(observation)
        return self.command


@pytest.mark.paper("s5.free_run")
def test_free_run_takes_the_papers_149_seconds() -> None:
    result = simulate(FREE, StraightPlanner()).result
    assert result.reached and not result.collided
    assert result.stop_reason == StopReason.GOAL_REACHED
    tolerance = SimParams().goal_tolerance
    assert PAPER_FREE_DISTANCE_FT - tolerance <= result.path_length <= PAPER_FREE_DISTANCE_FT
    # The goal is entered within one step of tolerance / speed seconds before the full 149 s.
    assert abs(result.time_s - PAPER_FREE_TIME_S) <= tolerance / FREE.robot.speed + 0.1
    assert result.min_clearance == math.inf


def test_straight_into_a_wall_collides_at_the_wall() -> None:
    run = simulate(BLOCKED, StraightPlanner())
    result = run.result
    assert result.collided and not result.reached
    assert result.stop_reason == StopReason.COLLISION
    assert result.min_clearance < 0.0
    last = run.trace[-1]
    # The disc (radius 1) first overlaps the wall face x = 20 when its centre passes x = 19.
    assert 19.0 < last.x <= 19.0 + BLOCKED.robot.speed * SimParams().dt
    assert run.trace[-2].clearance < 0.0


def test_time_limit_stops_the_episode() -> None:
    sim = SimParams(max_time=2.0)  # less than the stall time: the limit comes first
    result = simulate(FREE, ScriptedPlanner(Command(heading=0.0, speed=0.0)), sim).result
    assert result.stop_reason == StopReason.TIME_LIMIT
    assert result.steps == 20
    assert result.time_s == pytest.approx(2.0)
    assert result.path_length == 0.0


class SpinningPlanner:
    """Turns in place for ever: always a quarter turn further left than it faces."""

    name = "spinning"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Nothing to prepare."""

    def step(self, observation: Observation) -> Command:
        return Command(heading=observation.pose.theta + math.pi / 2, speed=0.0)


class RockingPlanner:
    """Drives along the x axis to ``x = reach``, turns on the spot, drives back to ``x = 0``,
    turns, and so on for ever."""

    name = "rocking"

    def __init__(self, reach: float) -> None:
        self.reach = reach
        self.heading = 0.0

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.heading = 0.0

    def step(self, observation: Observation) -> Command:
        x = observation.pose.x
        if (x >= self.reach and self.heading == 0.0) or (x <= 0.0 and self.heading == math.pi):
            self.heading = math.pi - self.heading
        facing = math.cos(observation.pose.theta - self.heading) > 1.0 - 1e-9
        return Command(heading=self.heading, speed=1.0 if facing else 0.0)


def within(trace: list[TraceStep], radius: float) -> float:
    """How long, s, the end of ``trace`` has stayed within ``radius`` of where it began: the
    duration of the longest suffix whose samples all lie within ``radius`` of its first."""
    points = [(s.x, s.y) for s in trace]
    start = len(points) - 1
    while start > 0 and all(distance(points[start - 1], p) <= radius for p in points[start:]):
        start -= 1
    return trace[-1].t - trace[start].t


def test_stall_time_is_three_full_turns_for_the_papers_robot() -> None:
    # Max(6 pi/w, 10 r/v, 20 dt): 12 s (w = pi/2), 7.6 s and 2 s; BARN's robot (w = pi): 6 s.
    assert stall_steps(SimParams(), EpisodeParams()) == 120
    barn = EpisodeParams(robot=RobotParams(radius=0.22, speed=1.0, max_turn_rate=math.pi), dt=0.05)
    assert stall_steps(SimParams(dt=0.05), barn) == 120
    fast_turner = EpisodeParams(robot=RobotParams(max_turn_rate=20.0))  # 10 r/v = 7.6 s
    assert stall_steps(SimParams(), fast_turner) == 76
    assert stall_steps(SimParams(dt=1.0), EpisodeParams(dt=1.0)) == 20  # 20 decisions


def test_a_robot_that_stands_still_stalls_at_the_stall_time() -> None:
    result = simulate(FREE, ScriptedPlanner(Command(heading=0.0, speed=0.0))).result
    assert result.stop_reason == StopReason.STALLED and not result.reached
    assert result.steps == 120 and result.time_s == pytest.approx(12.0)
    sim = SimParams(stall_time=5.0)
    assert simulate(FREE, ScriptedPlanner(Command(heading=0.0, speed=0.0)), sim).result.steps == 50


def test_a_robot_that_spins_in_place_for_ever_stalls() -> None:
    run = simulate(FREE, SpinningPlanner())
    assert run.result.stop_reason == StopReason.STALLED and run.result.steps == 120
    assert len({round(s.theta, 6) for s in run.trace}) > 4  # it did turn


def test_a_robot_rocking_within_its_diameter_stalls_and_one_rocking_wider_does_not() -> None:
    # Rocking over 1.5 ft, the robot stays within r = 1 ft of the middle of its beat, where it
    # passes every few seconds: stalled. Over 2.5 ft it never stays within r of any point, so
    # the disc rule lets it rock on; the lap rule (out and back is a closed lap) ends it.
    run = simulate(FREE, RockingPlanner(reach=1.5))
    assert run.result.stop_reason == StopReason.STALLED and run.result.steps < 150
    assert run.result.detail is not None and run.result.detail.startswith("disc rule")
    assert max(s.x for s in run.trace) > 1.5 and run.result.path_length > 6.0  # it did move
    disc_only = SimParams(max_time=60.0, stall_laps=None)
    wider = simulate(FREE, RockingPlanner(reach=2.5), disc_only).result
    assert wider.stop_reason == StopReason.TIME_LIMIT
    lapped = simulate(FREE, RockingPlanner(reach=2.5), SimParams(max_time=60.0)).result
    assert lapped.stop_reason == StopReason.STALLED and lapped.detail is not None
    assert lapped.detail.startswith("lap rule") and lapped.path_length >= 2 * 2.0 * math.pi


def test_a_stall_ends_stall_time_after_the_robot_last_left_the_disc() -> None:
    run = simulate(resolve_world("u_trap"), FGMPlanner())
    result = run.result
    assert result.stop_reason == StopReason.STALLED and not result.collided
    assert run.trace[-2].branch == "no_gap" and run.trace[-2].speed_cmd == 0.0
    radius = resolve_world("u_trap").robot.radius
    assert within(run.trace, radius) == pytest.approx(12.0)  # the stall time, no more
    assert within(run.trace[:-1], radius) < 12.0  # one step earlier it had not stalled


def test_stall_time_none_or_zero_turns_the_rule_off() -> None:
    for off in (None, 0.0):
        sim = SimParams(max_time=30.0, stall_time=off)
        result = simulate(FREE, ScriptedPlanner(Command(heading=0.0, speed=0.0)), sim).result
        assert result.stop_reason == StopReason.TIME_LIMIT and result.steps == 300


@pytest.mark.parametrize("value", ["soon", -1.0, math.nan, True])
def test_a_bad_stall_time_is_rejected(value: object) -> None:
    with pytest.raises(ParameterError, match="`stall_time` must be"):
        SimParams(stall_time=value)  # type: ignore[arg-type]


def test_ifgms_dead_end_turns_in_the_u_do_not_stall() -> None:
    """Section 4: IFGM turns in place at the base of the U, 45 degrees at a time (it stays
    about 3 s within r of one point, a quarter of the stall time); the episode is the one
    without the stall rules, step for step."""
    world = resolve_world("u_trap")
    run = simulate(world, IFGMPlanner())
    assert run.result.reached
    assert sum(s.branch == "dead_end_turn" and s.speed_cmd == 0.0 for s in run.trace) >= 10
    unstalled = simulate(world, IFGMPlanner(), NO_STALL)
    assert run.trace == unstalled.trace and run.result == unstalled.result


def test_bug1_round_a_big_obstacle_does_not_stall() -> None:
    """Bug1 goes right round a 40 ft box and back (section 2.1.1): for most of a minute no
    nearer the goal than it has been, but always on the move, and never twice round (the
    lap rule waits for two laps without progress)."""
    world = World(
        start=Pose(0.0, 0.0, 0.0),
        goal=Point(70.0, 0.0),
        obstacles=(rectangle((35.0, 0.0), 20.0, 40.0),),
        name="big box",
    )
    run = simulate(world, Bug1Planner())
    assert run.result.reached
    best, since = math.inf, 0.0
    longest = 0.0  # the longest time without a new best distance to the goal
    for s in run.trace:
        d = distance((s.x, s.y), world.goal)
        if d < best:
            best, since = d, s.t
        longest = max(longest, s.t - since)
    assert longest > 5 * 12.0
    unstalled = simulate(world, Bug1Planner(), NO_STALL)
    assert run.trace == unstalled.trace and run.result == unstalled.result


@pytest.mark.parametrize("k", [0.25, 2.0, 4.0])
def test_the_stall_rule_scales_with_the_robot(k: float) -> None:
    """Every length (the world, the robot's radius and speed, the sensor) times ``k``: the
    trapped FGM stalls at the same step (the rule holds no absolute length)."""
    world = resolve_world("u_trap")
    first = simulate(world, FGMPlanner()).result
    scaled = simulate(scale_world(world, k), FGMPlanner(), scale_sim(SimParams(), k)).result
    assert first.stop_reason == scaled.stop_reason == StopReason.STALLED
    assert scaled.steps == first.steps


@pytest.mark.parametrize(
    ("command", "detail"),
    [
        (Command(heading=math.nan, speed=1.0), "heading=nan"),
        (Command(heading=0.0, speed=-1.0), "speed=-1.0"),
        (Command(heading=0.0, speed=math.inf), "speed=inf"),
    ],
)
def test_invalid_command_stops_with_detail(command: Command, detail: str) -> None:
    result = simulate(FREE, ScriptedPlanner(command)).result
    assert result.stop_reason == StopReason.INVALID_COMMAND
    assert result.detail is not None and detail in result.detail


@pytest.mark.parametrize("stop", list(PlannerStop))
def test_planner_can_stop_with_its_own_reason(stop: PlannerStop) -> None:
    planner = ScriptedPlanner(Command(heading=0.0, speed=1.0, stop=stop))
    result = simulate(FREE, planner).result
    assert result.stop_reason == stop
    assert not result.reached and result.steps == 0


@pytest.mark.parametrize("claim", [*StopReason, "arrived", ""])
def test_a_planner_cannot_claim_the_simulators_reasons(claim: str) -> None:
    """A planner that says ``goal_reached`` (or any reason not its own) standing far from the
    goal has sent an invalid command: only the robot's true position decides an arrival."""
    planner = ScriptedPlanner(Command(heading=0.0, speed=0.0, stop=claim))
    result = simulate(FREE, planner).result
    assert (result.stop_reason, result.reached) == (StopReason.INVALID_COMMAND, False)
    assert result.detail is not None and f"stop={claim!r}" in result.detail


def test_leaving_the_bounds_stops_the_episode() -> None:
    world = World(start=Pose(0.0, 0.0, 0.0), goal=Point(5.0, 0.0), bounds=Bounds(-10, -10, 10, 10))
    result = simulate(world, ScriptedPlanner(Command(heading=math.pi, speed=2.0))).result
    assert result.stop_reason == StopReason.OUT_OF_BOUNDS


def test_planner_is_handed_time_pose_goal_and_scan() -> None:
    planner = ScriptedPlanner(Command(heading=0.0, speed=1.0))
    simulate(BLOCKED, planner, SimParams(max_time=1.0))
    first, second = planner.observations[:2]
    assert first.t == 0.0 and second.t == pytest.approx(0.1)
    assert first.pose == BLOCKED.start and first.goal == BLOCKED.goal
    assert second.pose.x == pytest.approx(0.1)
    # The wall is 20 ft ahead, beyond the default 15 ft range: the front ray sees nothing yet.
    assert len(first.scan.ranges) == BLOCKED.sensor.rays
    assert all(math.isinf(r) for r in first.scan.ranges)


def test_same_world_same_trace_bit_for_bit() -> None:
    a = simulate(BLOCKED, StraightPlanner())
    b = simulate(BLOCKED, StraightPlanner())
    assert a.trace == b.trace and a.result == b.result


def test_trace_csv_and_json_carry_every_sample() -> None:
    run = simulate(BLOCKED, StraightPlanner())
    rows = list(csv.DictReader(io.StringIO(run.trace_csv())))
    assert tuple(rows[0]) == TRACE_FIELDS
    assert len(rows) == run.result.steps + 1
    assert float(rows[5]["x"]) == run.trace[5].x
    assert rows[-1]["heading_cmd"] == ""
    doc = json.loads(run.trace_json())
    assert doc["result"]["stop_reason"] == "collision"
    assert len(doc["trace"]) == run.result.steps + 1
    assert doc["trace"][3]["behaviour"] == "move_to_goal"
