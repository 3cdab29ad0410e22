"""Figure 3, reconstructed: its guards partition the percept space, proved over all atoms.

The guards are read from the code (:data:`ifgm_ref.paper.flowchart.GUARDS`), evaluated on sympy
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

from ifgm_ref.core.elements import traces
from ifgm_ref.paper.flowchart import GUARDS, Atoms, Branch
from ifgm_ref.planners.ifgm.planner import DEAD_END_MAX_STEPS, DEAD_END_STEP
from proofs._util import Derivation, entry_points

__all__ = ["build", "claims", "derivation", "main"]


def _never(formula: sp.Basic) -> sp.Basic:
    """``sympy.true`` iff no assignment satisfies ``formula`` (SAT), else ``sympy.false``."""
    return sp.true if satisfiable(formula) is False else sp.false


@traces("fig3.partition", "fig3.both_conditions", "fig3.dead_end", "fig3.case2")
def build(guards: dict[Branch, object] | None = None) -> Derivation:
    """Check every claim about ``guards`` (default: the code's); raises ``ClaimFailed``."""
    guards = GUARDS if guards is None else guards
    d = Derivation("flowchart", "Figure 3: the guards partition the percepts")
    atoms = Atoms(*sp.symbols(" ".join(Atoms.names())))
    g = {branch: guard(atoms) for branch, guard in guards.items()}  # type: ignore[operator]
    d.text(
        f"""
        The decision function reads {len(Atoms.names())} yes/no atoms and has {len(g)}
        branches. Each branch's guard, read from ifgm_ref.paper.flowchart.GUARDS:
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
    _dead_end_claims(d)
    return d


def _dead_end_claims(d: Derivation) -> None:
    """The 45-degree rule (section 4, section 5.2) as the code runs it
    (``IFGMPlanner.dead_end``): step ``k`` turns to ``theta_0 + s * k * DEAD_END_STEP``; while
    the way ahead is not free and ``k < DEAD_END_MAX_STEPS`` it takes the next step, else it
    drives the way it faces."""
    step = sp.nsimplify(DEAD_END_STEP / math.pi) * sp.pi  # the code's float, as a multiple of pi
    steps = sp.Integer(DEAD_END_MAX_STEPS)
    k, theta0 = sp.symbols("k theta_0", real=True)
    d.text(
        f"""
        The dead-end rule, from the code's constants: a step of {step} rad, at most {steps}
        steps. Turn k faces theta_0 + s k step (s = +1 or -1, towards the freer side); it
        turns again only while the way ahead is not free and k < {steps}.
        """
    )
    d.prove_equal(
        "dead_end_step_is_45_degrees", step, sp.pi / 4, "each turn is 45 degrees (section 4)"
    )
    turns = sp.Matrix([j * step for j in range(1, DEAD_END_MAX_STEPS + 1)])
    d.prove_true(
        "dead_end_turns_45_90_135_180",
        sp.Eq(turns, sp.Matrix([sp.pi / 4, sp.pi / 2, 3 * sp.pi / 4, sp.pi])),
        "the turns face 45, 90, 135 and 180 degrees from the heading at the dead end, and no more",
        shown=turns,
    )
    variant = steps - k
    half = steps * step  # the last turn, either way
    d.prove_equal(
        "dead_end_terminates",
        variant.subs(k, k + 1) - variant,
        sp.Integer(-1),
        f"the variant {steps} - k, a natural number while k <= {steps}, drops by 1 at every "
        f"turn that finds no free way: the rule ends after at most {steps} turns",
    )
    d.prove_equal(
        "no_free_direction_turns_back",
        sp.Matrix([[sp.cos(theta0 + a), sp.sin(theta0 + a)] for a in (half, -half)]),
        -sp.Matrix([[sp.cos(theta0), sp.sin(theta0)]] * 2),
        "when no direction is free, the last turn faces exactly back the way the robot came "
        "(for either turning side), and the robot drives that way (section 5.2: 'starts "
        "moving back')",
    )


@functools.cache
def derivation() -> Derivation:
    """The derivation for the code's guards (built once)."""
    return build()


claims, main = entry_points(derivation)


if __name__ == "__main__":
    main()
