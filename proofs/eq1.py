"""Equation (1), the gap midpoint: what it is, proved with sympy.

Paper (section 4, Case-1)::

    (x_g, y_g = (x_1 + x_2)/2, (y_1 + y_2)/2)        (1)

Run ``python -m proofs.eq1`` to read the derivation; :func:`claims` returns the checked claims.
"""

from __future__ import annotations

import functools

import sympy as sp

from ifgm_ref.core.elements import traces
from ifgm_ref.paper.equations import eq1_gap_midpoint
from proofs._util import Derivation, entry_points

__all__ = ["claims", "derivation", "main"]


def _rotation(phi: sp.Expr) -> sp.Matrix:
    return sp.Matrix([[sp.cos(phi), -sp.sin(phi)], [sp.sin(phi), sp.cos(phi)]])


def _sq(v: sp.Matrix) -> sp.Expr:
    """Squared Euclidean norm of a column vector."""
    return (v.T * v)[0, 0]


@traces("eq1")
@functools.cache
def derivation() -> Derivation:
    """Build the derivation of eq. (1), checking every claim (raises ``ClaimFailed``)."""
    d = Derivation("eq1", "Equation (1): the gap midpoint")
    x1, y1, x2, y2 = sp.symbols("x_1 y_1 x_2 y_2", real=True)
    lam = sp.Symbol("lambda", real=True)
    k, r, gap = sp.symbols("k r L", positive=True)
    phi = sp.Symbol("phi", real=True)
    p1, p2 = sp.Matrix([x1, y1]), sp.Matrix([x2, y2])

    d.text(
        """
        The paper prints "(x_g, y_g = (x_1 + x_2)/2, (y_1 + y_2)/2)": the closing parenthesis
        of the left-hand side is misplaced. We read it as the midpoint of the two saved
        obstacle points P1 = (x_1, y_1) and P2 = (x_2, y_2), robot frame:
        """
    )
    midpoint = d.define("M", (p1 + p2) / 2)

    d.text("It lies on the segment P1 P2, halfway (the parameter lambda = 1/2 is in [0, 1]):")
    sym_p1, sym_p2 = sp.symbols("P_1 P_2")
    with sp.evaluate(False):
        on_segment_shown = sp.Eq(sp.Symbol("M"), sym_p1 + sp.Rational(1, 2) * (sym_p2 - sym_p1))
    d.prove_equal(
        "midpoint_on_segment",
        midpoint,
        p1 + sp.Rational(1, 2) * (p2 - p1),
        "M = P1 + (1/2)(P2 - P1): M is on the segment between the obstacle points",
        shown=on_segment_shown,
    )
    d.prove_equal(
        "midpoint_equidistant",
        _sq(midpoint - p1),
        _sq(midpoint - p2),
        "|M - P1|^2 = |M - P2|^2: M is equidistant from both obstacle points",
    )
    d.prove_equal(
        "midpoint_half_gap",
        _sq(midpoint - p1),
        _sq(p2 - p1) / 4,
        "|M - P1|^2 = |P2 - P1|^2 / 4: each point is half the gap away",
    )

    d.text(
        """
        Largest circle through the gap. A point C(lambda) = P1 + lambda (P2 - P1) of the
        segment is lambda L from P1 and (1 - lambda) L from P2, where L = |P2 - P1| is the gap.
        The largest disc centred at C with neither obstacle point inside has radius
        L min(lambda, 1 - lambda); over lambda in [0, 1] that is largest, L/2, at lambda = 1/2
        only: the midpoint, and the disc is the one with P1 P2 as diameter.
        """
    )
    on_segment = p1 + lam * (p2 - p1)
    d.prove_equal(
        "segment_point_distance_to_p1",
        _sq(on_segment - p1),
        lam**2 * _sq(p2 - p1),
        "|C(lambda) - P1|^2 = lambda^2 L^2",
    )
    d.prove_equal(
        "segment_point_distance_to_p2",
        _sq(on_segment - p2),
        (1 - lam) ** 2 * _sq(p2 - p1),
        "|C(lambda) - P2|^2 = (1 - lambda)^2 L^2",
    )
    free_radius = sp.Min(lam, 1 - lam)
    unit = sp.Interval(0, 1)
    d.prove_equal(
        "largest_free_disc_radius",
        sp.calculus.util.maximum(free_radius, lam, unit),
        sp.Rational(1, 2),
        "max over lambda in [0, 1] of min(lambda, 1 - lambda) = 1/2: the largest free disc "
        "centred on the segment has radius L/2",
        shown=sp.Eq(
            sp.Symbol("max(min(λ, 1 - λ), 0 <= λ <= 1)"), sp.Rational(1, 2), evaluate=False
        ),
    )
    d.prove_true(
        "largest_free_disc_centre_is_midpoint",
        sp.Eq(
            sp.solveset(sp.Eq(free_radius, sp.Rational(1, 2)), lam, unit),
            sp.FiniteSet(sp.Rational(1, 2)),
        ),
        "min(lambda, 1 - lambda) = 1/2 on [0, 1] only at lambda = 1/2: its centre is M",
        shown=sp.Eq(
            sp.Symbol("{0 <= λ <= 1 : min(λ, 1 - λ) = 1/2}"),
            sp.FiniteSet(sp.Rational(1, 2)),
            evaluate=False,
        ),
    )

    d.text(
        """
        Consequence for the threshold d_th (section 4: "greater than the robot's operational
        radius ... radius of a cylindrical shaped robot"): a disc robot of radius r centred at
        M keeps clear of both points iff L/2 - r >= 0, i.e. iff the gap is at least the
        robot's diameter 2r, not its radius.
        """
    )
    d.prove_true(
        "robot_fits_iff_gap_at_least_diameter",
        sp.Eq(
            sp.solve_univariate_inequality(gap / 2 - r >= 0, gap, relational=False),
            sp.Interval(2 * r, sp.oo),
        ),
        "for L, r > 0: L/2 - r >= 0 exactly when L is in [2r, oo)",
        shown=sp.Eq(sp.Symbol("{L > 0 : L/2 - r >= 0}"), sp.Interval(2 * r, sp.oo), evaluate=False),
    )

    d.text("The midpoint commutes with rotating and scaling the two points about the robot:")
    rot = _rotation(phi)
    d.prove_equal(
        "rotation_equivariant",
        (rot * p1 + rot * p2) / 2,
        rot * midpoint,
        "M(R P1, R P2) = R M(P1, P2) for every rotation R(phi) about the robot",
    )
    d.prove_equal(
        "scaling_equivariant",
        (k * p1 + k * p2) / 2,
        k * midpoint,
        "M(k P1, k P2) = k M(P1, P2) for every k > 0",
    )

    formula = sp.lambdify((x1, y1, x2, y2), list(midpoint), "math")
    points = [(4.0, -1.0, 2.0, 3.0), (0.5, 0.25, 7.0, -3.5), (-1e3, 2e-3, 3.0, 1e3)]
    for axis, name in ((0, "x"), (1, "y")):
        d.spot_check(
            f"library_midpoint_{name}_matches_formula",
            lambda a, b, c, e, axis=axis: eq1_gap_midpoint((a, b), (c, e))[axis],
            lambda a, b, c, e, axis=axis: float(formula(a, b, c, e)[axis]),
            points,
            f"ifgm_ref.paper.equations.eq1_gap_midpoint gives M's {name} coordinate",
            abs_tol=0.0,
            reason="halving is exact in binary floating point, so x1/2 + x2/2 and "
            "(x1 + x2)/2 round identically",
        )
    return d


claims, main = entry_points(derivation)


if __name__ == "__main__":
    main()
