"""Every planner parameter is homogeneous in the lengths: no absolute length anywhere.

A parameter's default is a formula in the robot radius ``r``, speed ``v``, turn rate ``w``,
time step ``dt``, sensor range ``R``, ray spacing ``res`` and field of view ``fov``
(:mod:`ifgm_ref.planners.tuning`), declared with a unit whose ``length_power`` ``p`` says how
it scales: 1 for a length, 4 for APF's repulsive gain, 0 for a time, angle or number.
Measuring every length in another unit multiplies ``r``, ``v`` (a length per second) and ``R``
by ``k > 0`` and leaves ``w``, ``dt``, ``res`` and ``fov`` as they are; the claim, for every
parameter of every registered planner (:data:`ifgm_ref.planners.PLANNERS`), is

    f(k r, k v, w, dt, k R, res, fov) = k**p * f(r, v, w, dt, R, res, fov)

proved by ``simplify(lhs - rhs) == 0`` with ``k`` and every symbol positive; the same for the
simulator's default stall time (:data:`ifgm_ref.sim.simulator.STALL_TIME`, a time, ``p = 0``),
after which a robot that makes no progress ends its episode, and for the lap rule's
thresholds (:mod:`ifgm_ref.sim.laps`: the radius of a place, the shortest lap and the progress
that counts, lengths, ``p = 1``). A formula with an
absolute constant (``r + 1`` declared a length) leaves a remainder and fails. The formulas are
read from the code, so a changed formula is re-proved. The oracle's ``scale_invariant`` check
(:mod:`ifgm_ref.oracle.checks`) tests the consequence on whole episodes.

A second kind of claim ties each formula to the number the paper gives for the paper's robot
(:data:`PAPER_VALUES`), proved exactly with the paper's robot as exact numbers (r = 1 ft,
v = 197/149 ft/s, w = pi/2, R = 15 ft, 1.8-degree rays over 135 degrees).

Run ``python -m proofs.scale`` to read it.
"""

from __future__ import annotations

import functools
from collections.abc import Iterable, Mapping

import sympy as sp

from ifgm_ref.core.elements import traces
from ifgm_ref.core.formulas import LENGTH_SYMBOLS, SYMBOLS, Unit, formula_expr
from ifgm_ref.planners import PLANNERS
from ifgm_ref.planners.tuning import ParamInfo
from ifgm_ref.sim.laps import LAP_LENGTH, LAP_PROGRESS, LAP_RADIUS
from ifgm_ref.sim.simulator import STALL_TIME
from proofs._util import Derivation, entry_points

__all__ = ["PAPER_ROBOT", "PAPER_VALUES", "build", "claims", "derivation", "main"]

#: The scale factor: every length is multiplied by it.
K = sp.Symbol("k", positive=True)

#: The paper's robot as exact numbers (:meth:`ifgm_ref.core.formulas.Scale.paper`, section
#: 5.1's 197 ft in 149 s; our choices for what the paper leaves open, :mod:`ifgm_ref.core.params`).
PAPER_ROBOT: dict[str, sp.Expr] = {
    "r": sp.Integer(1),
    "v": sp.Rational(197, 149),
    "w": sp.pi / 2,
    "dt": sp.Rational(1, 10),
    "R": sp.Integer(15),
    "res": sp.pi / 100,
    "fov": 3 * sp.pi / 4,
}

#: Parameter values the paper documents for its robot: ``(planner, parameter) -> value``. The
#: paper prints eq. (4)'s weights only by name; section 4 says ``d_th`` exceeds the robot's
#: diameter, and FGM's ``beta`` is Sezer & Gokasan's 1 (section 2.2).
PAPER_VALUES: dict[tuple[str, str], sp.Expr] = {
    ("fgm", "beta"): sp.Integer(1),
}


def pull_scale(expr: sp.Expr) -> sp.Expr:
    """``expr`` with the factor :data:`K` taken out of every ``Min`` and ``Max`` whose
    arguments all carry it: ``Min(k a, k b) = k Min(a, b)`` for ``k > 0`` (the claims
    ``min_commutes_with_scaling`` and ``max_commutes_with_scaling``); then simplified.

    >>> r, R = sp.symbols("r R", positive=True)
    >>> pull_scale(sp.Min(K * R, 15 * K * r) - K * sp.Min(R, 15 * r))
    0
    >>> pull_scale(sp.Max(K * r, 1) - K * sp.Max(r, 1)) == 0  # an absolute constant stays
    False
    """

    def pull(node: sp.Expr) -> sp.Expr:
        factor = sp.Integer(1)
        args = list(node.args)
        while all(a.has(K) for a in args):
            reduced = [sp.cancel(a / K) for a in args]
            if any(sp.simplify(a - b) == 0 for a, b in zip(args, reduced, strict=True)):
                break
            args, factor = reduced, factor * K
        return factor * node.func(*args) if factor != 1 else node

    return sp.simplify(expr.replace(lambda e: isinstance(e, sp.Min | sp.Max), pull))


def _scaled(expr: sp.Expr) -> sp.Expr:
    """``expr`` with every length symbol (``r``, ``v``, ``R``) multiplied by :data:`K`."""
    return expr.subs({s: K * s for s in SYMBOLS if s.name in LENGTH_SYMBOLS}, simultaneous=True)


def prove_homogeneous(d: Derivation, planner: str, info: ParamInfo) -> None:
    """Add the claim that ``info``'s formula scales by ``k ** length_power``."""
    f = formula_expr(info.formula)
    p = info.unit.length_power
    d.prove_equal(
        f"{planner}_{info.name}_scales_as_length_power_{p}",
        _scaled(f),
        K**p * f,
        f"{planner}.{info.name} = {info.formula} ({info.unit}) is homogeneous of degree {p} "
        "in the lengths r, v, R",
        simplifier=pull_scale,
    )


@traces("s3.robot_dimensions")
def build(
    planners: Mapping[str, Iterable[ParamInfo]] | None = None,
    paper_values: Mapping[tuple[str, str], sp.Expr] | None = None,
) -> Derivation:
    """Check every claim for ``planners`` (default: every registered planner's parameters)
    and ``paper_values`` (default :data:`PAPER_VALUES`); raises ``ClaimFailed``."""
    if planners is None:
        planners = {name: info.infos for name, info in PLANNERS.items()}
    paper_values = PAPER_VALUES if paper_values is None else paper_values
    d = Derivation("scale", "Every planner parameter scales with the unit of length")
    d.text(
        """
        Measure every length in a unit k times smaller: the robot radius r, its speed v and
        the sensor range R are multiplied by k; the turn rate w, the time step dt, the ray
        spacing res and the field of view fov do not change. A parameter of unit length^p
        must then be multiplied by k^p, exactly, whatever the robot: that is what makes a
        planner's behaviour independent of the unit and of the robot's size.
        """
    )
    d.define("k", K)
    a, b = sp.symbols("a b", real=True)
    gap = sp.Symbol("delta", nonnegative=True)
    for lemma in (sp.Min, sp.Max):
        # Either argument may be the smaller: b = a + delta or a = b + delta, delta >= 0.
        d.prove_equal(
            f"{lemma.__name__.lower()}_commutes_with_scaling",
            sp.Matrix([lemma(K * a, K * (a + gap)), lemma(K * (b + gap), K * b)]),
            sp.Matrix([K * lemma(a, a + gap), K * lemma(b + gap, b)]),
            f"{lemma.__name__}(k a, k b) = k {lemma.__name__}(a, b) for k > 0, whichever of a "
            "and b is the smaller (k > 0 keeps their order)",
        )
    # The simulator's stall time (a trapped robot's episode ends after it) is held to the
    # same rule: it must not depend on the unit either.
    prove_homogeneous(d, "simulator", ParamInfo("stall_time", STALL_TIME, Unit.TIME))
    # So are the lap rule's place, lap and progress (lengths): it fires at the same step.
    for name, formula in (
        ("lap_radius", LAP_RADIUS),
        ("lap_length", LAP_LENGTH),
        ("lap_progress", LAP_PROGRESS),
    ):
        prove_homogeneous(d, "simulator", ParamInfo(name, formula, Unit.LENGTH))
    for planner, infos in planners.items():
        for info in infos:
            prove_homogeneous(d, planner, info)
    ifgm = {i.name: i for i in planners.get("ifgm", ())}
    if "d_th" in ifgm:
        r = SYMBOLS[0]
        d.prove_sign(
            "ifgm_d_th_exceeds_the_robot_diameter",
            formula_expr(ifgm["d_th"].formula) - 2 * r,
            "positive",
            f"IFGM's d_th = {ifgm['d_th'].formula} exceeds the robot's diameter 2 r for every "
            "robot (section 4: greater than the robot's operational size)",
        )
    if paper_values:
        d.text("The formulas give the paper's numbers for the paper's robot:")
        at = {s: PAPER_ROBOT[s.name] for s in SYMBOLS}
        infos_of = {name: {i.name: i for i in infos} for name, infos in planners.items()}
        for (planner, name), value in paper_values.items():
            info = infos_of[planner][name]
            d.prove_equal(
                f"{planner}_{name}_is_the_paper_value",
                formula_expr(info.formula).subs(at),
                value,
                f"{planner}.{name} = {info.formula} is {value} for the paper's robot",
            )
    return d


@functools.cache
def derivation() -> Derivation:
    """The derivation for the registered planners (built once)."""
    return build()


claims, main = entry_points(derivation)


if __name__ == "__main__":
    main()
