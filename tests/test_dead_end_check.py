"""The oracle's dead_end_turns check (ifgm_ref.oracle.dead_end): section 4's "recursively turns
in steps of 45°", read from the branches an implementation reports. Found missing by the
mutation benchmark (issue 26): two mutants that turned 90 degrees a step, or 73, passed every
other property of the paper level."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.oracle.dead_end import STEP, dead_end_turns, turn_errors
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.profiles import PROFILES
from ifgm_ref.oracle.runner import check_planner
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.planners.ifgm.readings import Readings
from ifgm_ref.sim.simulator import TraceStep, simulate

BAND = math.radians(4.5)  # w dt / 2 for the paper's robot


def _turns(start: float, *steps: float) -> list[float]:
    """The commands of a turn: each target held for three steps."""
    return [start + s for s in steps for _ in range(3)]


@pytest.mark.parametrize("way", [1, -1])
def test_45_degree_steps_either_way_pass(way: int) -> None:
    steps = [way * k * STEP for k in range(1, 5)]
    assert turn_errors(0.3, _turns(0.3, *steps), BAND) == ""


def test_steps_counted_from_where_the_last_turn_ended_pass_within_the_dead_band() -> None:
    drift = 0.9 * BAND
    steps = [k * (STEP + drift) for k in range(1, 4)]
    assert turn_errors(0.0, _turns(0.0, *steps), BAND) == ""


@pytest.mark.parametrize(
    ("steps", "says"),
    [
        ((2 * STEP,), "+90.0 degrees from the last target"),
        ((STEP, 3 * STEP), "+90.0 degrees from the last target"),
        ((1.0 / STEP,), "degrees from the last target"),  # the Mult -> Div mutant: 73 degrees
        ((STEP, 0.0), "45 degrees counter-clockwise"),
        ((STEP, 2 * STEP, 3 * STEP, 4 * STEP, 5 * STEP), "stop at 180"),
    ],
)
def test_other_turns_fail(steps: tuple[float, ...], says: str) -> None:
    assert says in turn_errors(0.0, _turns(0.0, *steps), BAND)


def test_dead_ends_are_read_from_the_reported_branches() -> None:
    def row(t: float, theta: float, heading: float, branch: str) -> TraceStep:
        return TraceStep(t, 0.0, 0.0, theta, heading, 0.0, None, branch, 1.0)

    trace = [
        row(0.0, 0.0, 0.0, "move_to_goal"),
        row(0.1, 0.1, STEP, "dead_end_turn"),
        row(0.2, 0.5, STEP, "dead_end_turn"),
        row(0.3, STEP, STEP, "dead_end_escape"),
        row(0.4, STEP, 2 * STEP, "dead_end_turn"),
    ]
    assert list(dead_end_turns(trace)) == [(0.1, [STEP, STEP]), (STEP, [2 * STEP])]


def test_the_reference_passes_and_turns_in_u_trap() -> None:
    run = simulate(resolve_world("u_trap"), IFGMPlanner())
    ((start, commanded),) = dead_end_turns(run.trace)
    assert commanded and turn_errors(start, commanded, BAND) == ""
    report = check_planner("ifgm", profile="brief", checks=["dead_end_turns"], artifacts=None)
    (result,) = report.results
    assert result.status == "passed" and "dead end(s) met" in result.message, result


def test_either_way_round_is_a_valid_reading() -> None:
    readings = Readings.declared({"dead_end_side": "right"})
    impl = Implementation(lambda: IFGMPlanner(readings), "right", promises_of("ifgm"))
    (result,) = check_planner(
        impl, profile="brief", checks=["dead_end_turns"], artifacts=None
    ).results
    assert result.status == "passed" and "dead end(s) met" in result.message, result


#: A robot that cannot stop at once: the stops_in_time check's slowest braking, its response.
BRAKING = (("braking", 0.874), ("acceleration", 0.874), ("response", 0.05))


def test_on_a_robot_with_mass_the_turns_may_be_commanded_in_parts() -> None:
    """Braking before it turns, the governed reference commands its dead-end turns in parts
    (the governor caps the turn while it moves): the strict reading fails it, the reading
    of a robot with mass passes it, and the reference passes the check on such a robot
    (it failed: "+3.8 degrees from the last target" in u_trap, before this reading)."""
    world = resolve_world("u_trap").with_robot(dict(BRAKING))
    ((start, commanded),) = dead_end_turns(simulate(world, IFGMPlanner()).trace)
    assert turn_errors(start, commanded, BAND) != ""
    assert turn_errors(start, commanded, BAND, in_parts=True) == ""
    profile = replace(PROFILES["brief"], robot=BRAKING)
    (result,) = check_planner("ifgm", profile=profile, checks=["dead_end_turns"]).results
    assert result.status == "passed" and "dead end(s) met" in result.message, result


@pytest.mark.parametrize(
    ("commanded", "says"),
    [
        (_turns(0.0, 0.3, 0.6), "holds heading 0.3000 rad, 17.2 degrees"),
        ([0.2, 0.5, 0.4], "turns back"),
        ([0.5 * k for k in range(1, 9)], "degrees in all, but the turns stop at 180"),
    ],
)
def test_turns_in_parts_still_rest_45_degrees_apart_one_way(
    commanded: list[float], says: str
) -> None:
    assert says in turn_errors(0.0, commanded, BAND, in_parts=True)
