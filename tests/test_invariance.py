"""The invariance checks replay the original run's exchange, moved or scaled, open loop
(:mod:`ifgm_ref.oracle.invariance`, issue 24).

What is tested: the transformed exchange is what the simulator hands a planner in the moved
or scaled problem (up to its rounding); faithful planners pass however long the run; a frame
error fails at the first step it touches; a planner that crashes or answers nonsense on the
replay gets a verdict.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import strategies as st

from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.recording import Recording, RecordingPlanner
from ifgm_ref.io.worldfile import load_world
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.invariance import HEADING_TOL, SPEED_TOL, answer_errors, generic
from ifgm_ref.oracle.metamorphic import moved_recording, scale_world, scaled_recording
from ifgm_ref.oracle.mutants import GapAngleInWorldFrame, QuadrantBlindGoalAngle
from ifgm_ref.oracle.profiles import Profile
from ifgm_ref.oracle.runner import Status, run_check
from ifgm_ref.oracle.variants import VARIANTS
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.convergence import time_bound
from ifgm_ref.sim.shapes import rectangle
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import World
from ifgm_ref.sim.worldgen.classes import gap_wall, placed, random_world
from ifgm_ref.sim.worldgen.draws import RandomDraw

WORLDS = Path(__file__).parent / "worlds"
ONE = Profile("one", 1, shrink=False)
#: Rigid motions and scales tried: a quarter turn and more, far shifts, both rounded scales.
MOTIONS = [(0.7, (13.0, -21.0)), (-2.1, (-40.0, 5.5))]
#: The closed-loop twin's observations match the transformed ones this closely (ft, rad, or
#: relative for a scale) over the first seconds: the simulator's rounding of the moved or
#: scaled geometry, nothing more.
ROUNDING = 1e-9


def _enclosure() -> World:
    """The goal 20 ft ahead inside a closed box (inner half-size 5 ft, walls 1 ft): IFGM,
    which has no ``goal_unreachable`` exit, follows the box round until the time limit."""
    length, half, wall = 20.0, 5.0, 1.0
    outer, mid = 2.0 * (half + wall), half + wall / 2.0
    box = [
        rectangle((length - mid, 0.0), wall, outer),
        rectangle((length + mid, 0.0), wall, outer),
        rectangle((length, -mid), outer, wall),
        rectangle((length, mid), outer, wall),
    ]
    return generic(World(start=(0, 0, 0), goal=(length, 0), obstacles=box, name="enclosed"))


def long_mixed_example() -> tuple[World, tuple[float, tuple[float, float]]]:
    """The counterexample the closed-loop ``rigid_motion_invariant`` found against the C IFGM
    at the standard profile (example 191 of 200): a generated mixed world, and the rigid
    motion that moved it, recovered from its moved twin (both in ``tests/worlds``; the world
    is the check's, the goal already off the line). IFGM, the C port and the reference alike,
    then circled there for 9,502 steps to the bound, and the moved run was 0.278 ft and
    0.312 rad off at 160.8 s: rounding tipped a tie. Since Bug1's round and the dead-end
    escape that ends at the end of the wall (errata row 34) IFGM reaches the goal there in
    900 steps (90 s), through a dead-end escape."""
    world = load_world(WORLDS / "rigid_motion_long_mixed.json")
    moved = load_world(WORLDS / "rigid_motion_long_mixed_moved.json")
    angle = wrap_angle(moved.start.theta - world.start.theta)
    c, s = math.cos(angle), math.sin(angle)
    x, y = world.start.position
    shift = (moved.start.x - (c * x - s * y), moved.start.y - (s * x + c * y))
    assert math.dist(placed(world, angle, shift).goal, moved.goal) <= ROUNDING
    return world, (angle, shift)


def _recorded(planner: object, world: World, sim: SimParams) -> Recording:
    recorder = RecordingPlanner(planner)  # type: ignore[arg-type]
    simulate(world, recorder, sim)
    return recorder.recording()


def _worst(impl: Implementation, expected: Recording) -> tuple[float, float, int]:
    """The largest heading (rad) and speed (of the top speed) differences over the whole
    replay, and the steps replayed."""
    errors = list(answer_errors(impl, expected, "test"))
    assert all(e.expected.stop == e.answered.stop for e in errors)
    return max(e.heading for e in errors), max(e.speed for e in errors), len(errors)


# -- the transformed exchange ----------------------------------------------------------------


def _same_observations(ours: Observation, simulated: Observation, scale: float) -> None:
    __tracebackhide__ = True
    assert ours.t == simulated.t
    for mine, theirs in ((ours.pose, simulated.pose), (ours.goal, simulated.goal)):
        assert math.dist(mine[:2], theirs[:2]) <= ROUNDING * scale
    assert abs(math.remainder(ours.pose.theta - simulated.pose.theta, math.tau)) <= ROUNDING
    a, b = ours.scan.ranges, simulated.scan.ranges
    assert np.array_equal(np.isfinite(a), np.isfinite(b))
    assert np.allclose(a[np.isfinite(a)], b[np.isfinite(b)], rtol=ROUNDING, atol=0.0)
    assert (ours.scan.range_min, ours.scan.range_max) == pytest.approx(
        (simulated.scan.range_min, simulated.scan.range_max), rel=ROUNDING
    )


@pytest.mark.parametrize("motion", MOTIONS)
def test_the_moved_exchange_is_what_the_moved_problem_hands_over(motion) -> None:
    """FGM for 10 s in an open world: the moved recording's observations and answers are the
    moved problem's, closed loop, up to the simulator's rounding."""
    world, sim = generic(random_world("open", 1)), SimParams(max_time=10.0)
    angle, shift = motion
    expected = moved_recording(_recorded(make_planner("fgm"), world, sim), angle, shift)
    twin = _recorded(make_planner("fgm"), placed(world, angle, shift), sim)
    assert (expected.start, expected.goal, expected.params) == (twin.start, twin.goal, twin.params)
    assert len(expected.steps) == len(twin.steps) == 100
    for (ours, command), (simulated, answered) in zip(expected.steps, twin.steps, strict=True):
        _same_observations(ours, simulated, 1.0)
        assert abs(math.remainder(command.heading - answered.heading, math.tau)) <= ROUNDING
        assert command.speed == pytest.approx(answered.speed, abs=ROUNDING)


@pytest.mark.parametrize("k", [0.3048, 3.7])
def test_the_scaled_exchange_is_what_the_scaled_problem_hands_over(k: float) -> None:
    world, sim = generic(random_world("open", 1)), SimParams(max_time=10.0)
    expected = scaled_recording(_recorded(make_planner("fgm"), world, sim), k)
    scaled_sim = replace(sim, goal_tolerance=k * sim.goal_tolerance)
    twin = _recorded(make_planner("fgm"), scale_world(world, k), scaled_sim)
    assert expected.params == twin.params
    assert math.dist(expected.start[:2], twin.start[:2]) <= ROUNDING
    for (ours, command), (simulated, answered) in zip(expected.steps, twin.steps, strict=True):
        _same_observations(ours, simulated, k)
        assert command.heading == pytest.approx(answered.heading, abs=ROUNDING)
        assert command.speed == pytest.approx(answered.speed, rel=ROUNDING)


# -- faithful runs pass, however long --------------------------------------------------------


def test_the_reference_answers_the_moved_and_scaled_problem_in_a_long_run() -> None:
    """IFGM following a box round for 150 s (1,500 steps): every replayed answer within
    1e-12 of the transformed recorded one, far inside the tolerances."""
    world = _enclosure()
    recording = _recorded(make_planner("ifgm"), world, SimParams(max_time=150.0))
    assert len(recording.steps) == 1500  # the premise: a long run, to the time limit
    impl = Implementation.from_spec("ifgm")
    for expected in (
        *(moved_recording(recording, *motion) for motion in MOTIONS),
        scaled_recording(recording, 0.3048),
    ):
        heading, speed, steps = _worst(impl, expected)
        assert steps == 1500
        assert heading <= 1e-12 and speed <= 1e-12


@pytest.mark.slow
@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_faithful_variants_pass_in_long_runs(variant: str) -> None:
    """Each faithful variant (ifgm_ref/oracle/variants.py), following a box round for 400 s
    (4,000 steps), answers the moved and the scaled problems within the tolerances (about a
    minute each)."""
    impl = Implementation.from_spec(f"ifgm_ref.oracle.variants:{VARIANTS[variant].__name__}")
    recording = _recorded(impl.factory(), _enclosure(), SimParams(max_time=400.0))
    assert len(recording.steps) == 4000
    for expected in (
        *(moved_recording(recording, *motion) for motion in MOTIONS),
        *(scaled_recording(recording, k) for k in (0.3048, 0.22, 3.7)),
    ):
        heading, speed, _ = _worst(impl, expected)
        assert heading <= HEADING_TOL and speed <= SPEED_TOL


def test_the_reference_passes_where_the_c_port_was_rejected() -> None:
    """The reference IFGM in :func:`long_mixed_example`, given the time bound (950 s),
    reaches the goal in 900 steps; its run, moved by the example's rigid motion and replayed
    open loop, answers within 1e-12 of the moved recorded answers at every step (measured:
    1e-14 rad and of the top speed; under a second; the C port's replay:
    ``tests/test_c_port.py``)."""
    world, motion = long_mixed_example()
    recorder = RecordingPlanner(make_planner("ifgm"))
    run = simulate(world, recorder, SimParams(max_time=time_bound(world)))
    assert (run.result.stop_reason, run.result.steps) == ("goal_reached", 900)  # the premise
    expected = moved_recording(recorder.recording(), *motion)
    heading, speed, steps = _worst(Implementation.from_spec("ifgm"), expected)
    assert steps == 900
    assert heading <= 1e-12 and speed <= 1e-12


# -- frame errors fail at once ---------------------------------------------------------------


def _one(check: str, impl: Implementation, example: tuple[object, ...]):
    """``check`` on exactly ``example``, through the real runner."""
    only = replace(CHECKS[check], strategy=lambda i: st.just(example))
    return run_check(only, impl, ONE, artifacts=None)


def test_a_gap_angle_in_the_world_frame_fails_at_its_first_gap_step() -> None:
    """Eq. (2)'s robot-frame angle used as a world heading: the replay parts at the first
    Case-1 step, whatever came before it."""
    drawn, _ = gap_wall(RandomDraw(np.random.default_rng(3)))
    world = generic(drawn)  # as the check moves the goal
    impl = Implementation(GapAngleInWorldFrame, "gap-world-frame", promises_of("ifgm"))
    recording = _recorded(impl.factory(), world, SimParams(max_time=time_bound(world)))
    first_gap = next(
        n for n, (_, command) in enumerate(recording.steps) if command.branch == "case1_gap"
    )
    angle, shift = MOTIONS[0]
    failed = next(
        e
        for e in answer_errors(impl, moved_recording(recording, angle, shift), "test")
        if e.heading > HEADING_TOL
    )
    assert failed.step == first_gap
    result = _one("rigid_motion_invariant", impl, (drawn, (angle, shift)))
    assert result.status is Status.FAILED, result.line()
    assert result.message.startswith(f"moved, the original run's step {first_gap} (t=")
    assert "replayed open loop) was answered with heading" in result.message


def test_a_quadrant_blind_goal_angle_fails_where_the_goal_is_behind() -> None:
    """Eq. (3) as printed, ``arctan(dy / dx)``: moved by half a turn, every goal ahead is
    behind, and the first step's answer is off by pi."""
    world = random_world("open", 1)
    impl = Implementation(QuadrantBlindGoalAngle, "quadrant-blind", promises_of("ifgm"))
    result = _one("rigid_motion_invariant", impl, (world, (math.pi, (0.0, 0.0))))
    assert result.status is Status.FAILED, result.line()
    assert result.message.startswith("moved, the original run's step 0 (t=0.0 s")
    assert "(off by 3.14 rad" in result.message


# -- verdicts for misbehaving planners --------------------------------------------------------


class _FarAway:
    """Straight at the goal, but raises (or answers NaN) once more than 100 ft from the origin:
    the moved replay meets it, the original run never does."""

    name = "far-away"

    def __init__(self, nan: bool = False) -> None:
        self.nan = nan

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.goal = goal

    def step(self, observation: Observation) -> Command:
        pose = observation.pose
        if abs(pose.x) > 100.0:
            if not self.nan:
                raise RuntimeError("lost")
            return Command(math.nan, 1.0)
        return Command(math.atan2(self.goal.y - pose.y, self.goal.x - pose.x), 1.0)


@pytest.mark.parametrize(
    ("nan", "message"),
    [
        (False, "the planner raised RuntimeError: lost (replaying)"),
        (True, "invalid command at step 0: heading=nan, but should be finite"),
    ],
)
def test_a_planner_that_fails_on_the_replay_gets_a_verdict(nan: bool, message: str) -> None:
    impl = Implementation(lambda: _FarAway(nan), "far-away", promises_of("straight"))
    world = World(start=(0, 0, 0), goal=(10, 0))
    result = _one("rigid_motion_invariant", impl, (world, (0.0, (500.0, 0.0))))
    assert result.status is Status.FAILED, result.line()
    assert message in result.message
