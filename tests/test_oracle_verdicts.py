"""Every check gives a verdict, whatever the implementation does (issue: "the oracle a
stranger can trust"): planners that collide, stop, spin, stand still or raise are failed or
passed with a message, never crash the oracle.

Each pair (check, failing planner) runs the check under a small profile with shrinking on (the
crashes this pins surfaced while shrinking: a far obstacle placed on the goal of a run that
stopped early, an index into an empty difference of two unequal runs).
"""

from __future__ import annotations

import math

import pytest

from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.oracle.check_types import Kind
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation, Promises, promises_of
from ifgm_ref.oracle.profiles import Profile
from ifgm_ref.oracle.runner import CheckResult, Report, Status, run_check
from ifgm_ref.planners import PLANNERS

#: The reference IFGM, with what it promises.
IFGM = Implementation(PLANNERS["ifgm"].factory, "ifgm", promises_of("ifgm"))
#: A few examples per check, shrinking on: enough to meet every failing path of a check.
SMALL = Profile("small", 4)


class Stopper:
    """Ends the episode at its first step with a stop reason of its own."""

    name = "stopper"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Nothing to prepare."""

    def step(self, observation: Observation) -> Command:
        """Stop at once."""
        return Command(observation.pose.theta, 0.0, stop="done")


class Spinner:
    """Turns in place for ever."""

    name = "spinner"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Nothing to prepare."""

    def step(self, observation: Observation) -> Command:
        """A quarter turn further than the heading, at speed 0."""
        return Command(observation.pose.theta + math.pi / 2, 0.0)


class Raiser:
    """Drives straight for ten steps, then raises."""

    name = "raiser"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Count steps from zero."""
        self.steps = 0

    def step(self, observation: Observation) -> Command:
        """Straight ahead, until the eleventh step."""
        self.steps += 1
        if self.steps > 10:
            raise RuntimeError("planner bug")
        return Command(observation.pose.theta, 1.0)


FAILING = {
    "straight": PLANNERS["straight"].factory,
    "apf": PLANNERS["apf"].factory,
    "stopper": Stopper,
    "spinner": Spinner,
    "raiser": Raiser,
}
SIMULATION_CHECKS = [name for name, check in CHECKS.items() if check.kind is Kind.SIMULATION]


@pytest.mark.parametrize("planner", FAILING)
@pytest.mark.parametrize("check", SIMULATION_CHECKS)
def test_every_check_gives_a_verdict(check: str, planner: str, tmp_path) -> None:
    """Promising everything, each failing planner gets a verdict with a message."""
    impl = Implementation(
        FAILING[planner],
        planner,
        Promises(
            reports_unreachable=True,
            turns_at_dead_ends=True,
            reference="ifgm",
            stops_in_time=True,
        ),
    )
    result = run_check(CHECKS[check], impl, SMALL, artifacts=tmp_path)
    assert result.status in (Status.PASSED, Status.NOT_EXERCISED, Status.FAILED), result.line()
    if result.status is Status.NOT_EXERCISED:
        assert result.message.startswith("nothing to check: "), result.line()
    if result.status is Status.FAILED:
        assert result.message and "\n" not in result.message
        assert result.artifacts is not None and (result.artifacts / "report.md").is_file()


#: The checks that hold vacuously when nothing happens, and what each must meet.
VACUOUS = {
    "collision_free": "moved within its sensor's range of an obstacle",
    "rigid_motion_invariant": "the robot moved",
    "scale_invariant": "the robot moved",
    "ignores_unseen_obstacles": "the robot moved",
    "stops_in_time": "the robot moved",
    "dead_end_turns": "a dead end reported as dead_end_turn",
}


@pytest.mark.parametrize("check", VACUOUS)
def test_a_check_that_met_nothing_is_not_exercised(check: str) -> None:
    """A robot that only turns in place passes none of the checks of what it would do: each
    says it met nothing to check, and the summary counts it apart from the passes."""
    everything = Promises(turns_at_dead_ends=True, stops_in_time=True)
    impl = Implementation(Spinner, "spinner", everything)
    result = run_check(CHECKS[check], impl, SMALL, artifacts=None)
    assert result.status is Status.NOT_EXERCISED, result.line()
    assert VACUOUS[check] in result.message and f"of {result.examples} examples" in result.message
    report = Report("spinner", "small", (result, CheckResult("x", Status.PASSED, 1, 1)))
    assert report.summary().endswith(": 1 not exercised, 1 passed"), report.summary()
    assert report.ok  # met nothing to check is not a failure


@pytest.mark.parametrize("check", VACUOUS)
def test_the_reference_meets_what_each_check_checks(check: str) -> None:
    """The reference IFGM moves, comes near obstacles and meets dead ends: each of these
    checks passes it, not exercised by none."""
    result = run_check(CHECKS[check], IFGM, SMALL, artifacts=None)
    assert result.status is Status.PASSED, result.line()
