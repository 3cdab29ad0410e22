"""The braking governor (ifgm_ref.planners.governor), the robot's dynamics (RobotParams,
the kinematic engine's ramp) and ``--robot``: a robot that cannot stop at once stops in time.

The mathematics is proved in ``proofs/braking.py``; these tests hold the code to it on drawn
inputs: the fan's room is the exact room, the safe speed is the root, the speed bound bounds
the robot the kinematic engine moves, and a governed robot driven at a wall stops before it.
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import RobotParams, SimParams, robot_changes
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.recording import RecordingPlanner
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import PLANNERS, make_planner
from ifgm_ref.planners.governor import (
    GovernorState,
    Limits,
    fan_room,
    govern,
    next_state,
    safe_speed,
    stopping_distance,
)
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import Polygon, World
from tests.test_cli import run_cli

LIMITS = Limits(radius=0.5, top_speed=2.0, braking=3.0, acceleration=2.0, period=0.1)
#: A robot that cannot stop at once: the paper's, stopping from top speed in one radius.
HEAVY = RobotParams(braking=RobotParams().speed ** 2 / 2, acceleration=2.0, response=0.05)

limits = st.builds(
    Limits,
    radius=st.floats(0.1, 2.0),
    top_speed=st.floats(0.2, 3.0),
    braking=st.floats(0.5, 10.0),
    acceleration=st.floats(0.5, 10.0),
    period=st.sampled_from([0.05, 0.1, 0.2]),
    response=st.sampled_from([0.0, 0.02, 0.05]),
)


def states(top: float) -> st.SearchStrategy[GovernorState]:
    """A speed bound and a last command up to ``top``."""
    speeds = st.floats(0.0, top)
    return st.builds(GovernorState, speed_bound=speeds, heading=st.none(), speed=speeds)


# -- the stopping distance and the safe speed --------------------------------------------------


@given(limits, st.data())
def test_the_stopping_distance_grows_with_the_command(lim: Limits, data: st.DataObject) -> None:
    state = data.draw(states(lim.top_speed))
    commands = sorted(data.draw(st.lists(st.floats(0.0, lim.top_speed), min_size=2)))
    distances = [stopping_distance(state, c, lim) for c in commands]
    assert all(a <= b + 1e-12 for a, b in itertools.pairwise(distances))


@given(limits, st.data())
def test_the_safe_speed_is_the_fastest_command_whose_stop_fits(
    lim: Limits, data: st.DataObject
) -> None:
    state = data.draw(states(lim.top_speed))
    braking_only = stopping_distance(state, 0.0, lim)
    room = data.draw(st.floats(0.0, 2 * stopping_distance(state, lim.top_speed, lim)))
    speed = safe_speed(room, state, lim)
    if room < braking_only * (1 - 1e-9):
        assert speed is None
        return
    if speed is None:  # the room is braking-only to rounding
        assert room == pytest.approx(braking_only, rel=1e-9)
        return
    assert stopping_distance(state, speed, lim) <= room + 1e-9 * (1 + room)
    if speed < lim.top_speed:  # the root: a hair faster does not fit
        assert stopping_distance(state, speed + 1e-6, lim) > room - 1e-9


def test_with_no_response_time_speeding_up_is_mitsch_et_als_bound() -> None:
    u, b, a, eps = 1.0, LIMITS.braking, LIMITS.acceleration, LIMITS.period
    mitsch = u**2 / (2 * b) + (a / b + 1) * (a * eps**2 / 2 + eps * u)
    assert stopping_distance(GovernorState(u, None, u), 2.0, LIMITS) == pytest.approx(mitsch)


# -- the fan ---------------------------------------------------------------------------------


@given(
    st.lists(st.tuples(st.floats(-3, 3), st.floats(-3, 3)), min_size=1, max_size=6),
    st.floats(-1.5, 0.0),
    st.floats(0.0, 1.5),
    st.floats(0.1, 0.8),
)
def test_the_fan_room_is_exactly_the_room_of_the_swept_fan(
    points: list[tuple[float, float]], low: float, high: float, radius: float
) -> None:
    """The fan of headings ``[low, high]`` and radius ``room``, widened by the robot's radius,
    clears every point; a hair longer it does not (unless the room is unbounded)."""
    xy = np.array(points)
    room = fan_room(xy, low, high, radius)
    cloud = shapely.MultiPoint(points)

    def fan(length: float) -> shapely.Geometry:
        angles = np.linspace(low, high, 64)
        rim = [(length * math.cos(a), length * math.sin(a)) for a in angles]
        sector = shapely.Polygon([(0.0, 0.0), *rim]) if high > low else shapely.LineString(
            [(0.0, 0.0), rim[0]])  # fmt: skip
        return sector if length > 0 else shapely.Point(0.0, 0.0)

    if room == 0.0:
        assert cloud.distance(shapely.Point(0.0, 0.0)) <= radius + 1e-9 or math.isclose(
            fan(1e-3).distance(cloud), radius, abs_tol=1e-3
        ) or fan(1e-3).distance(cloud) < radius  # fmt: skip
        return
    reach = min(room, 10.0)
    assert fan(reach).distance(cloud) >= radius - 1e-6 * (1 + reach)  # a polygon's chords
    if math.isfinite(room):
        assert fan(room + 1e-3).distance(cloud) < radius + 1e-3


def test_the_margin_is_kept_ahead_but_not_beside_nor_from_what_is_already_near() -> None:
    ahead, beside = np.array([[2.0, 0.0]]), np.array([[2.0, 0.6]])
    assert fan_room(ahead, 0.0, 0.0, 0.5, 0.25) == 1.25
    assert fan_room(beside, 0.0, 0.0, 0.5, 0.25) == math.inf
    edge = np.array([[0.7, 0.0]])  # inside the margin, but not by half of it: held there
    assert fan_room(edge, 0.0, 0.0, 0.5, 0.25) == 0.0
    near = np.array([[0.6, 0.0]])  # by more than half of it: the robot's own disc only
    assert fan_room(near, 0.0, 0.0, 0.5, 0.25) == pytest.approx(0.1)


# -- the kinematic robot with dynamics and the governor in a loop --------------------------------


def _wall_world(robot: RobotParams, distance: float) -> World:
    wall = Polygon(((distance, -20.0), (distance + 1.0, -20.0), (distance + 1.0, 20.0),
                    (distance, 20.0)))  # fmt: skip
    return World(start=Pose(0.0, 0.0, 0.0), goal=Point(distance + 5.0, 0.0), obstacles=(wall,),
                 robot=robot)  # fmt: skip


class Headlong:
    """Drives straight at full speed, governed: nothing else stops it."""

    name = "headlong"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.limits, self.state = Limits.of(params), GovernorState()
        self.bounds: list[float] = [0.0]  # before each step, then after the last

    def step(self, observation: Observation) -> Command:
        command, self.state = govern(Command(0.0, 100.0), observation, self.state, self.limits)
        self.bounds.append(self.state.speed_bound)
        return command


@pytest.mark.parametrize(
    ("speed", "braking", "acceleration", "response", "distance"),
    [
        (2.0, 1.0, 2.0, 0.0, 3.0),
        (2.0, 1.0, 2.0, 0.0, 2.2),
        (3.0, 0.5, 1.0, 0.05, 1.0),
        (1.3, 0.9, 0.9, 0.05, 6.0),
    ],
)
def test_a_governed_robot_driven_at_a_wall_stops_before_it(
    speed: float, braking: float, acceleration: float, response: float, distance: float
) -> None:
    """The three walls of the first cases went through before a rounding fix of the safe
    speed's root (proofs/braking.py found them); the robot's speed never passes the bound."""
    robot = RobotParams(radius=0.5, speed=speed, braking=braking, acceleration=acceleration,
                        response=response)  # fmt: skip
    planner = Headlong()
    run = simulate(_wall_world(robot, distance), planner, SimParams(max_time=20.0))
    assert not run.result.collided and run.result.min_clearance >= 0.0
    assert run.result.stop_reason == "stalled"  # it stands before the wall
    mean_speeds = np.diff([step.x for step in run.trace]) / 0.1
    bounds = np.array(planner.bounds)
    assert np.all(mean_speeds <= np.maximum(bounds[:-1], bounds[1:]) + 1e-9)


@pytest.mark.parametrize("name", sorted(set(PLANNERS) - {"dwa", "straight"}))
def test_every_planner_with_dynamics_stops_in_time_in_the_u_trap(name: str) -> None:
    world = dataclasses.replace(resolve_world("u_trap"), robot=HEAVY)
    run = simulate(world, make_planner(name), SimParams(max_time=120.0))
    assert not run.result.collided and run.result.min_clearance >= 0.0, run.result


@pytest.mark.parametrize("name", sorted(set(PLANNERS) - {"dwa", "straight"}))
def test_the_paper_robot_is_governed_by_nothing(name: str) -> None:
    """With infinite braking the governor hands back every command as it came."""
    recorder = RecordingPlanner(make_planner(name))
    simulate(resolve_world("fig7b"), recorder, SimParams(max_time=20.0))
    recording = recorder.recording()
    planner = make_planner(name)
    planner.reset(recording.start, recording.goal, recording.params)
    governor = planner.governor  # type: ignore[attr-defined]
    for observation, command in recording.steps[:50]:
        assert governor(command, observation) is command


def test_the_speed_bound_bounds_the_kinematic_robot() -> None:
    rng = np.random.default_rng(7)
    robot = RobotParams(braking=1.5, acceleration=0.8, response=0.0)
    world = World(start=Pose(0.0, 0.0, 0.0), goal=Point(500.0, 0.0), robot=robot)
    lim = Limits.of(EpisodeParams(robot=robot))
    from ifgm_ref.sim.engine import KinematicEngine

    engine, state, pose = KinematicEngine(world, 0.1), GovernorState(), world.start
    for speed in rng.uniform(0.0, robot.speed, 200):
        pose = engine.move(pose, Command(0.0, float(speed)), 1.0, 1.0)[0]
        state = next_state(state, 0.0, float(speed), lim)
        assert engine.speed <= state.speed_bound + 1e-12


# -- the robot's dynamics as parameters and options ------------------------------------------


def test_the_papers_robot_writes_no_dynamics() -> None:
    assert "braking" not in RobotParams().to_mapping()
    told = RobotParams(braking=2.0, acceleration=1.0, response=0.1).to_mapping()
    assert (told["braking"], told["acceleration"], told["response"]) == (2.0, 1.0, 0.1)


def test_braking_without_acceleration_is_refused() -> None:
    with pytest.raises(ParameterError, match="`acceleration` is needed with `braking`"):
        RobotParams(braking=2.0)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("mass=3", "--robot mass=3: expected NAME=VALUE"),
        ("speed=x", "the value must be a number"),
        ("braking=-1", "--robot braking=-1: `braking` must be a finite number > 0"),
    ],
)
def test_a_bad_robot_option_names_itself(text: str, message: str) -> None:
    with pytest.raises(ParameterError, match=message):
        robot_changes(text)
    done = run_cli("simulate", "post", "--planner", "ifgm", "--robot", text)
    assert done.returncode == 2 and len(done.stderr.splitlines()) == 1
    assert message.split(":")[0] in done.stderr


def test_speed_and_robot_change_the_simulated_robot() -> None:
    import json

    fast = json.loads(run_cli("simulate", "free", "--planner", "straight", "--json",
                              "--speed", "2.644").stdout)  # fmt: skip
    slow = json.loads(run_cli("simulate", "free", "--planner", "straight", "--json").stdout)
    assert fast["time_s"] == pytest.approx(slow["time_s"] / 2, abs=0.2)
    heavy = run_cli("simulate", "u_trap", "--planner", "ifgm", "--json", "--robot",
                    "braking=0.9,acceleration=0.9,response=0.05")  # fmt: skip
    result = json.loads(heavy.stdout)
    assert result["reached"] and not result["collided"]


@pytest.mark.parametrize("latency", [1, 2, 3, 5])
def test_a_robot_that_carries_out_commands_steps_late_still_stops_where_it_means_to(
    latency: int,
) -> None:
    """The simulator's latency (steps between a decision and its execution) is a response
    time of whole periods: the governor allows for every command still in effect, the fastest
    of them, and the robot stands before the wall with the margin it keeps from what lies
    ahead (counting only the last command, it stood 1 cm from the wall at 5 steps)."""
    robot = RobotParams(radius=0.5, speed=2.0, braking=1.0, acceleration=4.0, latency=latency)
    run = simulate(_wall_world(robot, 3.0), Headlong(), SimParams(max_time=20.0))
    assert run.result.stop_reason == "stalled"  # it stands before the wall
    assert run.result.min_clearance >= robot.radius * Limits.MARGIN - 2e-3, run.result


def test_the_fan_holds_the_turn_the_robot_is_making() -> None:
    """A robot turning left at 0.2 rad a period, told to go straight on at its heading, may
    carry its turn on while it brakes: a post up there, beside the straight corridor, slows it
    (the Jackal at 1.8 m/s carried its turn 6 degrees past the command, BARN world 95)."""
    lim = Limits(radius=0.2, top_speed=2.0, braking=4.0, acceleration=2.0, period=0.1)
    angle = 0.5  # the post's bearing, left: outside the straight corridor at its range
    scan = LaserScan(angle - 0.1, angle + 0.1, 0.1, 0.0, 10.0, [math.inf, 0.6, math.inf])
    seen = Observation(0.0, Pose(0.0, 0.0, 0.0), Point(5.0, 0.0), scan)
    straight = GovernorState(1.5, 0.0, 1.5, (), 0.0)  # not turning
    turning = GovernorState(1.5, 0.0, 1.5, (), -0.6)  # 0.6 rad left in the last period
    free = govern(Command(0.0, 2.0), seen, straight, lim)[0].speed
    carried = govern(Command(0.0, 2.0), seen, turning, lim)[0].speed
    assert free > 1.5 and carried < free
