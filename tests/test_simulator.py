"""The simulator (ifgm_ref.simulator): stop reasons, result figures, trace, determinism."""

from __future__ import annotations

import csv
import io
import json
import math

import pytest

from ifgm_ref.params import PAPER_FREE_DISTANCE_FT, PAPER_FREE_TIME_S, SimParams
from ifgm_ref.planners.straight import StraightPlanner
from ifgm_ref.pose import Point, Pose
from ifgm_ref.protocol import Command, EpisodeParams, Observation
from ifgm_ref.simulator import TRACE_FIELDS, StopReason, simulate
from ifgm_ref.world import Bounds, Polygon, World

FREE = World(start=Pose(0.0, 0.0, 0.0), goal=Point(PAPER_FREE_DISTANCE_FT, 0.0), name="free")
WALL = Polygon(((20.0, -5.0), (22.0, -5.0), (22.0, 5.0), (20.0, 5.0)))
BLOCKED = World(start=Pose(0.0, 0.0, 0.0), goal=Point(40.0, 0.0), obstacles=(WALL,), name="wall")


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
    sim = SimParams(max_time=2.0)
    result = simulate(FREE, ScriptedPlanner(Command(heading=0.0, speed=0.0)), sim).result
    assert result.stop_reason == StopReason.TIME_LIMIT
    assert result.steps == 20
    assert result.time_s == pytest.approx(2.0)
    assert result.path_length == 0.0


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


def test_planner_can_stop_with_its_own_reason() -> None:
    planner = ScriptedPlanner(Command(heading=0.0, speed=1.0, stop="goal_unreachable"))
    result = simulate(FREE, planner).result
    assert result.stop_reason == "goal_unreachable"
    assert not result.reached and result.steps == 0


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
