"""Figure 3, reconstructed: its guards partition the percept space, proved over all atoms.

The guards are read from the code (:data:`ifgm_ref.flowchart.GUARDS`), evaluated on sympy
Boolean symbols instead of numpy booleans -- the guards use only ``&``, ``|`` and ``~``, which
build sympy ``And``/``Or``/``Not`` -- and every claim is decided by sympy's SAT solver
(``satisfiable``), which is complete for propositional logic: ``False`` means no assignment
of the ten atoms satisfies the formula. Change a guard in the code and this proof re-checks.

Run ``python -m proofs.flowchart`` to read it.
"""

from __future__ import annotations

import functools
import math
from itertools import combinations

import sympy as sp
from sympy.logic.inference import satisfiable

from ifgm_ref.flowchart import GUARDS, Atoms, Branch
from ifgm_ref.planners.ifgm import DEAD_END_MAX_STEPS, DEAD_END_STEP
from proofs._util import Derivation, entry_points

__all__ = ["build", "claims", "derivation", "main"]


def _never(formula: sp.Basic) -> sp.Basic:
    """``sympy.true`` iff no assignment satisfies ``formula`` (SAT), else ``sympy.false``."""
    return sp.true if satisfiable(formula) is False else sp.false


def build(guards: dict[Branch, object] | None = None) -> Derivation:
    """Check every claim about ``guards`` (default: the code's); raises ``ClaimFailed``."""
    guards = GUARDS if guards is None else guards
    d = Derivation("flowchart", "Figure 3: the guards partition the percepts")
    atoms = Atoms(*sp.symbols(" ".join(Atoms.names())))
    g = {branch: guard(atoms) for branch, guard in guards.items()}  # type: ignore[operator]
    d.text(
        f"""
        The decision function reads {len(Atoms.names())} yes/no atoms and has {len(g)}
        branches. Each branch's guard, read from ifgm_ref.flowchart.GUARDS:
        """
    )
    for branch, formula in g.items():
        d.define(str(branch), formula)
    overlapping = [
        (x, y) for (x, gx), (y, gy) in combinations(g.items(), 2) if satisfiable(gx & gy)
    ]
    d.prove_true(
        "pairwise_exclusive",
        sp.true if not overlapping else sp.false,
        f"no two guards hold together: each of the {len(g) * (len(g) - 1) // 2} pairwise "
        f"conjunctions is unsatisfiable{f' (overlapping: {overlapping})' if overlapping else ''}",
    )
    d.prove_true(
        "exhaustive",
        _never(sp.Not(sp.Or(*g.values()))),
        "some guard always holds: the negated disjunction is unsatisfiable",
    )
    a = atoms
    d.prove_true(
        "case1_needs_both_conditions",
        _never(g[Branch.CASE1_GAP] & ~(a.wide & ~a.close & ~a.one_sided)),
        "Case-1 (FGM) only when max gap > d_th, nearest > d_obs and obstacles on both sides "
        "(section 4: 'if both conditions are true ... steered by FGM')",
    )
    d.prove_true(
        "widening_the_gap_moves_case2_to_case1",
        _never(
            g[Branch.CASE2_NARROW_GAP].subs(a.wide, sp.false)
            & ~g[Branch.CASE1_GAP].subs(a.wide, sp.true)
        ),
        "with everything else fixed, a narrow-gap Case-2 becomes Case-1 when the gap widens",
    )
    d.prove_true(
        "no_case1_without_a_wide_gap",
        _never(g[Branch.CASE1_GAP].subs(a.wide, sp.false)),
        "with no gap wider than d_th, Case-1 is never taken, whatever the other atoms",
    )
    d.prove_true(
        "dead_end_turns_end_at_a_half_turn",
        sp.true if math.pi == DEAD_END_MAX_STEPS * DEAD_END_STEP else sp.false,
        f"the dead-end rule turns at most {DEAD_END_MAX_STEPS} steps of 45 degrees: 180 "
        "degrees (exact in floating point: 4 * (pi / 4) == pi); then it goes the 180-degree "
        "way, where it came from",
    )
    return d


@functools.cache
def derivation() -> Derivation:
    """The derivation for the code's guards (built once)."""
    return build()


claims, main = entry_points(derivation)


if __name__ == "__main__":
    main()
