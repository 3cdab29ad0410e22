"""The reconstructed Figure 3 (ifgm_ref.paper.flowchart): one branch for every percept."""

from __future__ import annotations

import itertools
import math
import re

import numpy as np
import pytest

from ifgm_ref.io.bags.read import FORMER_LABELS, same_branch
from ifgm_ref.paper.flowchart import (
    DEAD_END_PHASES,
    DECIDED,
    GUARDS,
    Atoms,
    Branch,
    decide,
    figure3,
)

ALL_ATOMS = list(itertools.product([False, True], repeat=len(Atoms.names())))


def guarded(values: tuple[bool, ...]) -> Branch:
    """The one branch whose guard in :data:`GUARDS` holds for the atom ``values`` (numpy
    booleans: ``~`` on ``bool`` is not negation); fails unless exactly one holds."""
    atoms = Atoms(*(np.bool_(value) for value in values))
    holding = [branch for branch, guard in GUARDS.items() if bool(guard(atoms))]
    assert len(holding) == 1, f"guards hold for {holding}, but should for exactly one [{atoms}]"
    return holding[0]


def test_every_decided_branch_has_a_guard() -> None:
    assert set(GUARDS) == set(DECIDED)
    assert set(Branch) == set(DECIDED) | set(DEAD_END_PHASES)


def test_a_former_label_names_the_phases_it_labelled_and_nothing_else() -> None:
    """Traces from before the dead end's phases had labels of their own call every phase
    ``dead_end_turn``: such a label agrees with each phase, and no other label does."""
    for reference in Branch:
        agreeing = {str(b) for b in Branch if same_branch(str(b), reference)}
        expected = {str(reference)} | ({"dead_end_turn"} if reference in FORMER_LABELS else set())
        assert agreeing == expected, reference
    assert not same_branch("dead_end_escape", "dead_end_turn")  # the new label is no old one


@pytest.mark.paper("fig3.partition")
def test_guards_partition_every_combination_of_atoms() -> None:
    """Exhaustive over all 2**10 atom values (the sympy proof is the general statement):
    exactly one guard holds for each, and each decided branch is reached."""
    assert {guarded(values) for values in ALL_ATOMS} == set(DECIDED)


def test_the_partition_check_rejects_guards_that_overlap(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(GUARDS, Branch.CASE1_GAP, lambda a: a.blocked)  # overlaps Case-2
    with pytest.raises(AssertionError, match="exactly one"):
        test_guards_partition_every_combination_of_atoms()


@pytest.mark.paper("fig3.both_conditions")
@pytest.mark.parametrize("values", ALL_ATOMS[::37])
def test_case1_needs_both_conditions_of_section_4(values: tuple[bool, ...]) -> None:
    """Case-1 (FGM) only if max gap > d_th and nearest > d_obs, with obstacles both sides."""
    atoms = Atoms(*values)
    if decide(atoms) is Branch.CASE1_GAP:
        assert atoms.wide and not atoms.close and not atoms.one_sided and atoms.blocked


@pytest.mark.paper("fig3.case2")
def test_widening_the_gap_moves_case2_to_case1_never_back() -> None:
    for values in ALL_ATOMS:
        narrow = Atoms(*values)
        if narrow.wide:
            continue
        wide = Atoms(**{**narrow.__dict__, "wide": True})
        before, after = decide(narrow), decide(wide)
        if before is Branch.CASE2_NARROW_GAP:
            assert after is Branch.CASE1_GAP
        if before is not Branch.CASE2_NARROW_GAP:
            assert after is before, f"{narrow}: {before} -> {after}"


def test_the_diagram_names_every_branch() -> None:
    from pathlib import Path

    diagram = (Path(__file__).resolve().parent.parent / "docs" / "flowchart.md").read_text()
    nodes = set(re.findall(r"\b([a-z0-9_]+)\[", diagram))
    assert nodes == {str(b) for b in Branch}


@pytest.mark.paper("fig3.partition")
def test_sympy_proves_the_guards_partition_the_atoms() -> None:
    from proofs import flowchart

    names = [c.name for c in flowchart.claims()]
    assert names == [
        "pairwise_exclusive",
        "exhaustive",
        "case1_needs_both_conditions",
        "widening_the_gap_moves_case2_to_case1",
        "no_case1_without_a_wide_gap",
        "dead_end_step_is_45_degrees",
        "dead_end_turns_45_90_135_180",
        "dead_end_terminates",
        "no_free_direction_turns_back",
    ]


@pytest.mark.parametrize(
    ("branch", "guard", "failing"),
    [
        (Branch.CASE1_GAP, lambda a: a.blocked & a.wide, "pairwise_exclusive"),
        (Branch.MOVE_TO_GOAL, lambda a: a.blocked & ~a.blocked, "exhaustive"),
    ],
)
def test_the_proof_rejects_broken_guards(branch: Branch, guard: object, failing: str) -> None:
    from proofs import flowchart
    from proofs._util import ClaimFailed

    with pytest.raises(ClaimFailed, match=failing):
        flowchart.build({**GUARDS, branch: guard})  # type: ignore[dict-item]


@pytest.mark.paper("fig3.dead_end")
@pytest.mark.parametrize(("step", "steps"), [(math.pi / 3, 4), (math.pi / 4, 3)])
def test_the_dead_end_proof_rejects_other_turns(
    monkeypatch: pytest.MonkeyPatch, step: float, steps: int
) -> None:
    """60-degree turns, or only three of them, fail the proof (it reads the code's
    constants); the reference's pass it."""
    from proofs import flowchart
    from proofs._util import ClaimFailed, Derivation

    monkeypatch.setattr(flowchart, "DEAD_END_STEP", step)
    monkeypatch.setattr(flowchart, "DEAD_END_MAX_STEPS", steps)
    with pytest.raises(ClaimFailed):
        flowchart._dead_end_claims(Derivation("dead end", "broken"))


def test_the_decision_tree_picks_the_guards_branch_for_every_combination_of_atoms() -> None:
    """:func:`figure3`, the flowchart read as a tree, and :data:`GUARDS`, the form the proofs
    reason about, agree on all 2**10 combinations of atoms: one Figure 3 in two forms."""
    for values in ALL_ATOMS:
        assert figure3(Atoms(*values)) is guarded(values), values


def test_the_tree_comparison_has_teeth(monkeypatch: pytest.MonkeyPatch) -> None:
    """Guards that still partition, but swap Case-1 and Case-2's narrow gap, disagree."""
    case1, narrow = GUARDS[Branch.CASE1_GAP], GUARDS[Branch.CASE2_NARROW_GAP]
    monkeypatch.setitem(GUARDS, Branch.CASE1_GAP, narrow)
    monkeypatch.setitem(GUARDS, Branch.CASE2_NARROW_GAP, case1)
    with pytest.raises(AssertionError):
        test_the_decision_tree_picks_the_guards_branch_for_every_combination_of_atoms()


def test_decide_is_the_decision_tree() -> None:
    """What a planner runs (:func:`decide`) is the flowchart its reader reads
    (:func:`figure3`), for plain and numpy booleans."""
    for values in ALL_ATOMS[::7]:
        branch = figure3(Atoms(*values))
        assert decide(Atoms(*values)) is decide(Atoms(*map(np.bool_, values))) is branch
