"""The decision function of IFGM: the paper's Figure 3 flowchart, reconstructed.

Figure 3 itself is not in our copy of the paper; section 4 describes it: "After encountering
the obstacles, if both conditions are true (refer to Figure 3), the robot is steered by FGM
otherwise it is steered by IBA" -- the conditions being *max gap > d_th* and *distance to the
nearest obstacle > d_obs* -- with Case-1 (steer through the gap, eqs. (1)-(4)), Case-2 (max
gap <= d_th, or obstacles on one side only: IBA), Case-3 (an obstacle of more impact pre-empts
the one being avoided; avoidance is recursive) and the dead-end rule for U and H shapes (turn
in 45-degree steps until a free direction is found). After avoiding, "the robot regenerates
the reference path and follows it until reaches to the destination."

The flowchart is one function of boolean *atoms* computed from the percepts (:class:`Atoms`).
Each :class:`Branch` has a guard, an expression over the atoms written with ``&``, ``|`` and
``~`` only, so that the same guards evaluate on numpy booleans at run time and on sympy
symbols in the proofs. The guards partition the atom space: exactly one holds for every
percept. :func:`decide` checks that for each combination of atoms it meets (once: the
branch is cached).
"""

from __future__ import annotations

import functools
import operator
from collections.abc import Callable
from dataclasses import dataclass, fields
from enum import StrEnum
from typing import Any

import numpy as np

from ifgm_ref.core.elements import traces
from ifgm_ref.core.errors import InvariantError


class Branch(StrEnum):
    """The branches of the reconstructed Figure 3, as they appear in traces.

    The flowchart decides ``DEAD_END_TURN`` for the whole dead end; a step of it is labelled
    with the phase it carries out (:data:`DEAD_END_PHASES`): turning in place, driving out,
    or handing over to IBA.
    """

    GOAL_REACHED = "goal_reached"
    MOVE_TO_GOAL = "move_to_goal"
    CASE1_GAP = "case1_gap"
    CASE2_NARROW_GAP = "case2_narrow_gap"
    CASE2_ONE_SIDED = "case2_one_sided"
    TOO_CLOSE = "too_close"
    CASE3_PREEMPT = "case3_preempt"
    FOLLOW_EDGE = "follow_edge"
    DEAD_END_TURN = "dead_end_turn"
    PATH_REGENERATED = "path_regenerated"
    DEAD_END_ESCAPE = "dead_end_escape"
    DEAD_END_HANDOVER = "dead_end_handover"


#: The dead end's phases, in order: turn in 45-degree steps, drive out the way found free,
#: hand over to IBA at the end of the wall. Only the first is decided by the flowchart.
DEAD_END_PHASES = (Branch.DEAD_END_TURN, Branch.DEAD_END_ESCAPE, Branch.DEAD_END_HANDOVER)

#: The branches the flowchart decides between (:data:`GUARDS`): all but the dead end's
#: later phases.
DECIDED = tuple(branch for branch in Branch if branch not in DEAD_END_PHASES[1:])

#: The label each phase label replaces: traces written before the phases had labels of their
#: own (issue 29) call all three ``dead_end_turn``.
FORMER_LABELS = {phase: Branch.DEAD_END_TURN for phase in DEAD_END_PHASES[1:]}


def same_branch(reported: str, reference: str) -> bool:
    """Whether a port's (or a log's) branch label ``reported`` names the reference's branch
    ``reference``: the same label, or the one it replaces (:data:`FORMER_LABELS`).

    >>> same_branch("dead_end_turn", "dead_end_escape"), same_branch("follow_edge", "too_close")
    (True, False)
    """
    if reported == reference:
        return True
    return reference in FORMER_LABELS and reported == FORMER_LABELS[Branch(reference)]


@dataclass(frozen=True)
class Atoms:
    """The yes/no facts Figure 3 decides on, computed by the planner from its percepts.

    Attributes
    ----------
    at_goal : the robot is within the goal tolerance.
    turning : a dead-end turn sequence (45, 90, 135, 180 degrees) is under way.
    avoiding : IBA is following an obstacle's edge (*obstacle avoidance* behaviour).
    blocked : an obstacle stands in the robot-wide corridor towards the goal, within the
        encounter distance ("an obstacle is sensed" on the reference path).
    free : IBA's leaving condition: the goal in view and its corridor clear as far as the
        sensor sees or to the goal (section 4.1).
    close : the nearest obstacle is at most ``d_obs`` away.
    wide : the maximum gap between consecutive obstacles is greater than ``d_th``.
    one_sided : every obstacle point is on one side of the heading.
    dead_end : the front beam is blocked within the encounter distance and every ray of the
        field of view returns, with no gap wider than ``d_th``: nowhere to go ahead (inside a
        U or an H). It is consulted only on encountering an obstacle, not while IBA follows
        an edge.
    preempt : while avoiding, another obstacle nearer than the followed edge is sensed.
    """

    at_goal: Any
    turning: Any
    avoiding: Any
    blocked: Any
    free: Any
    close: Any
    wide: Any
    one_sided: Any
    dead_end: Any
    preempt: Any

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The atom names, in declaration order."""
        return tuple(f.name for f in fields(cls))


Guard = Callable[[Atoms], Any]


def _in_avoidance(a: Atoms) -> Any:
    return ~a.at_goal & ~a.turning & a.avoiding


def _encountered(a: Atoms) -> Any:
    return ~a.at_goal & ~a.turning & ~a.avoiding & a.blocked & ~a.dead_end


#: Figure 3 as guards: for every combination of atoms exactly one guard holds. One guard for
#: each of the :data:`DECIDED` branches.
GUARDS: dict[Branch, Guard] = {
    Branch.GOAL_REACHED: lambda a: a.at_goal,
    Branch.DEAD_END_TURN: lambda a: (
        ~a.at_goal & (a.turning | (~a.avoiding & a.blocked & a.dead_end))
    ),
    Branch.PATH_REGENERATED: lambda a: _in_avoidance(a) & a.free,
    Branch.CASE3_PREEMPT: lambda a: _in_avoidance(a) & ~a.free & a.preempt,
    Branch.FOLLOW_EDGE: lambda a: _in_avoidance(a) & ~a.free & ~a.preempt,
    Branch.MOVE_TO_GOAL: lambda a: ~a.at_goal & ~a.turning & ~a.avoiding & ~a.blocked,
    Branch.TOO_CLOSE: lambda a: _encountered(a) & a.close,
    Branch.CASE2_ONE_SIDED: lambda a: _encountered(a) & ~a.close & a.one_sided,
    Branch.CASE2_NARROW_GAP: lambda a: _encountered(a) & ~a.close & ~a.one_sided & ~a.wide,
    Branch.CASE1_GAP: lambda a: _encountered(a) & ~a.close & ~a.one_sided & a.wide,
}


def figure3(atoms: Atoms) -> Branch:
    """Figure 3 read top down as one decision tree: the same branch as :data:`GUARDS` for
    every combination of atoms (``tests/test_flowchart.py`` checks all 1,024), in the order a
    reader follows the flowchart -- and the order the C port decides in.

    >>> base = dict.fromkeys(Atoms.names(), False)
    >>> figure3(Atoms(**{**base, "blocked": True, "wide": True}))
    <Branch.CASE1_GAP: 'case1_gap'>
    """
    a = atoms
    if a.at_goal:
        return Branch.GOAL_REACHED
    if a.turning:  # a dead-end turn under way goes on
        return Branch.DEAD_END_TURN
    if a.avoiding:  # IBA follows an edge: leave it, yield to a nearer obstacle, or go on
        if a.free:
            return Branch.PATH_REGENERATED
        return Branch.CASE3_PREEMPT if a.preempt else Branch.FOLLOW_EDGE
    if not a.blocked:  # nothing sensed on the reference path
        return Branch.MOVE_TO_GOAL
    if a.dead_end:  # inside a U or an H
        return Branch.DEAD_END_TURN
    if a.close:  # nearest <= d_obs: IBA
        return Branch.TOO_CLOSE
    if a.one_sided:  # Case-2: obstacles on one side only
        return Branch.CASE2_ONE_SIDED
    # both conditions: max gap > d_th (Case-1, FGM) or not (Case-2, IBA)
    return Branch.CASE1_GAP if a.wide else Branch.CASE2_NARROW_GAP


@traces("fig3.partition", "fig3.both_conditions")
def decide(atoms: Atoms) -> Branch:
    """The one Figure 3 branch whose guard holds for ``atoms`` (plain or numpy booleans).

    Raises :class:`~ifgm_ref.core.errors.InvariantError` if the guards do not hold for exactly
    one branch -- the partition property, proved for all atom values in
    ``proofs/flowchart.py``. The guards are evaluated, and the partition checked, once per
    combination of atom values in a process (:func:`branch_of`): a planner's step looks the
    branch up.

    Examples
    --------
    >>> base = dict.fromkeys(Atoms.names(), False)
    >>> decide(Atoms(**base))
    <Branch.MOVE_TO_GOAL: 'move_to_goal'>
    >>> decide(Atoms(**{**base, "blocked": True, "wide": True}))
    <Branch.CASE1_GAP: 'case1_gap'>
    >>> decide(Atoms(**{**base, "blocked": True, "wide": True, "close": True}))
    <Branch.TOO_CLOSE: 'too_close'>
    """
    return branch_of(tuple(map(bool, _atom_values(atoms))))


#: The atoms' values, in :meth:`Atoms.names` order.
_atom_values = operator.attrgetter(*Atoms.names())


@functools.cache
def branch_of(values: tuple[bool, ...]) -> Branch:
    """The one branch whose guard holds for the atom ``values`` (in :meth:`Atoms.names`
    order), the guards evaluated on numpy booleans and checked to partition; cached."""
    atoms = Atoms(*(np.bool_(value) for value in values))
    holding = [branch for branch, guard in GUARDS.items() if bool(guard(atoms))]
    if len(holding) != 1:
        raise InvariantError(f"guards hold for {holding}, but should for exactly one [{atoms}]")
    return holding[0]
