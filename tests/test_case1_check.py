"""passes_wide_gaps's Case-1 clause (ifgm_ref.oracle.checks._check_case1): a planner that
reports its branches and avoids the wall before a gap wider than d_th must take Case-1
there (section 4); one whose way through the gap is clear never avoids and passes."""

from __future__ import annotations

import pytest

from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner
from ifgm_ref.oracle.check_types import CheckFailed
from ifgm_ref.oracle.checks import CHECKS, _check_case1
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.runner import Status, run_check
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.sim.simulator import TraceStep
from ifgm_ref.sim.world import Polygon

GAP = Polygon(((9.5, -3.0), (10.5, -3.0), (10.5, 3.0), (9.5, 3.0)))


class Unlabelled:
    """A planner's commands without their branch and behaviour labels."""

    name = "unlabelled"

    def __init__(self, planner: Planner) -> None:
        self.planner = planner

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Reset the planner inside."""
        self.planner.reset(start, goal, params)

    def step(self, observation: Observation) -> Command:
        """The inner planner's heading, speed and stop only."""
        command = self.planner.step(observation)
        return Command(command.heading, command.speed, stop=command.stop)


def _trace(*branches: str | None) -> list[TraceStep]:
    """One step a foot, along y = 1, through the gap at x = 10."""
    return [TraceStep(0.1 * k, float(k), 1.0, 0.0, 0.0, 1.0, None, b, 1.0)
            for k, b in enumerate([*branches, *([None] * (13 - len(branches)))])]  # fmt: skip


def test_avoiding_by_case1_passes() -> None:
    assert _check_case1(_trace("move_to_goal", "case1_gap", "case1_gap"), GAP, "here")


def test_a_clear_way_through_never_avoids_and_passes_without_meeting_the_rule() -> None:
    assert not _check_case1(_trace(*["move_to_goal"] * 12), GAP, "here")


def test_a_run_that_reports_no_branches_never_meets_the_rule() -> None:
    assert not _check_case1(_trace(), GAP, "here")


@pytest.mark.parametrize(("labelled", "says"), [
    (True, "the Case-1 rule met in "),
    (False, "its Case-1 part not exercised: no avoidance branch reported before the gap"),
])  # fmt: skip
def test_the_verdict_says_whether_the_case1_part_was_exercised(labelled: bool, says: str) -> None:
    """The reference reports its branches and meets the rule; the same planner with its
    labels stripped passes the check on its path alone, and the summary says so."""
    impl = Implementation(
        IFGMPlanner if labelled else lambda: Unlabelled(IFGMPlanner()), "ifgm", promises_of("ifgm")
    )
    result = run_check(CHECKS["passes_wide_gaps"], impl, "brief", artifacts=None)
    assert result.status is Status.PASSED and says in result.message, result.line()


def test_avoiding_by_another_branch_only_fails() -> None:
    with pytest.raises(CheckFailed, match="avoided the wall by follow_edge, too_close"):
        _check_case1(_trace("too_close", "follow_edge"), GAP, "here")


def test_what_happens_after_the_gap_does_not_count() -> None:
    branches = ["move_to_goal"] * 11 + ["too_close"]
    _check_case1(_trace(*branches), GAP, "here")
