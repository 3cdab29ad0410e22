"""The decision function of IFGM: the paper's Figure 3, reconstructed (errata row 18).

:func:`decide` reads the flowchart top down (:func:`figure3`) over yes/no atoms
(:class:`Atoms`). :data:`GUARDS`, the same flowchart as one guard a branch, is the form that
``proofs/flowchart.py`` proves to partition the atoms and ``tests/test_flowchart.py`` checks
against :func:`figure3`. The reconstruction and its choices: ``docs/flowchart.md``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, fields
from enum import StrEnum
from typing import TYPE_CHECKING, Any, Generic

from ifgm_ref.core.elements import traces

if TYPE_CHECKING:  # a default keeps a bare ``Atoms`` an ``Atoms[bool]`` (PEP 696; 3.13's typing)
    from typing_extensions import TypeVar

    L = TypeVar("L", covariant=True, default=bool)
else:
    from typing import TypeVar

    L = TypeVar("L", covariant=True)


class Branch(StrEnum):
    """The branches of Figure 3, as traces label them.

    The flowchart decides ``DEAD_END_TURN`` for the whole dead end; its steps are labelled
    with the phase they carry out (:data:`DEAD_END_PHASES`, errata row 35).
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

#: The dead end's turn, rad: "it recursively turns in steps of 45 degrees" (section 4).
DEAD_END_STEP = math.pi / 4

#: The branches the flowchart decides between (:data:`GUARDS`): all but the dead end's
#: later phases.
DECIDED = tuple(branch for branch in Branch if branch not in DEAD_END_PHASES[1:])


@dataclass(frozen=True)
class Atoms(Generic[L]):
    """The yes/no facts Figure 3 decides on, each of type ``L``: ``bool`` in a planner,
    numpy or sympy booleans where :data:`GUARDS` are evaluated.

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
        U or an H). Consulted only on meeting an obstacle, not while IBA follows an edge.
    preempt : while avoiding, another obstacle nearer than the followed edge is sensed.
    """

    at_goal: L
    turning: L
    avoiding: L
    blocked: L
    free: L
    close: L
    wide: L
    one_sided: L
    dead_end: L
    preempt: L

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The atom names, in declaration order."""
        return tuple(f.name for f in fields(cls))


#: A guard: a formula over the atoms in ``&``, ``|`` and ``~`` only, so that it evaluates on
#: numpy booleans and builds a sympy formula (never on ``bool``: ``~True`` is ``-2``).
Guard = Callable[[Atoms[Any]], Any]


def _in_avoidance(a: Atoms[Any]) -> Any:
    return ~a.at_goal & ~a.turning & a.avoiding


def _encountered(a: Atoms[Any]) -> Any:
    return ~a.at_goal & ~a.turning & ~a.avoiding & a.blocked & ~a.dead_end


#: Figure 3 as guards, one for each of the :data:`DECIDED` branches: for every combination of
#: atoms exactly one holds (``proofs/flowchart.py``), the branch :func:`figure3` picks
#: (``tests/test_flowchart.py``).
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


def figure3(atoms: Atoms[object]) -> Branch:
    """Read Figure 3 top down, in the order of ``docs/flowchart.md``'s diagram and of the C
    port's ``decide``: the branch (of :data:`DECIDED`) whose guard in :data:`GUARDS` holds for
    ``atoms`` (of any type with a truth value).

    Examples
    --------
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
def decide(atoms: Atoms[object]) -> Branch:
    """Choose the Figure 3 branch for one step's ``atoms``: :func:`figure3`'s.

    That exactly one guard of :data:`GUARDS` holds, the branch :func:`figure3` takes, is not
    checked here, at every step: ``proofs/flowchart.py`` proves it for all atom values and
    ``tests/test_flowchart.py`` checks it for each of the 1,024 combinations.

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
    return figure3(atoms)
