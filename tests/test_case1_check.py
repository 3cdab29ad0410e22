"""passes_wide_gaps's Case-1 clause (ifgm_ref.oracle.checks._check_case1): a planner that
reports its branches and avoids the wall before a gap wider than d_th must take Case-1
there (section 4); one whose way through the gap is clear never avoids and passes."""

from __future__ import annotations

import pytest

from ifgm_ref.oracle.check_types import CheckFailed
from ifgm_ref.oracle.checks import _check_case1
from ifgm_ref.simulator import TraceStep
from ifgm_ref.world import Polygon

GAP = Polygon(((9.5, -3.0), (10.5, -3.0), (10.5, 3.0), (9.5, 3.0)))


def _trace(*branches: str | None) -> list[TraceStep]:
    """One step a foot, along y = 1, through the gap at x = 10."""
    return [TraceStep(0.1 * k, float(k), 1.0, 0.0, 0.0, 1.0, None, b, 1.0)
            for k, b in enumerate([*branches, *([None] * (13 - len(branches)))])]  # fmt: skip


def test_avoiding_by_case1_passes() -> None:
    _check_case1(_trace("move_to_goal", "case1_gap", "case1_gap"), GAP, "here")


def test_a_clear_way_through_never_avoids_and_passes() -> None:
    _check_case1(_trace(*["move_to_goal"] * 12), GAP, "here")


def test_avoiding_by_another_branch_only_fails() -> None:
    with pytest.raises(CheckFailed, match="avoided the wall by follow_edge, too_close"):
        _check_case1(_trace("too_close", "follow_edge"), GAP, "here")


def test_what_happens_after_the_gap_does_not_count() -> None:
    branches = ["move_to_goal"] * 11 + ["too_close"]
    _check_case1(_trace(*branches), GAP, "here")
