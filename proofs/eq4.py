"""Equation (4), the final heading: a convex combination, its limits, and its wrap-around flaw.

Paper (section 4, Case-1)::

    theta_f = ( (w_g / d_th) * theta_g + w_d * theta_d ) / ( w_g / d_th + w_d )        (4)

Run ``python -m proofs.eq4`` to read the derivation; :func:`claims` returns the checked claims.
"""

from __future__ import annotations

import functools
import math

import sympy as sp

from ifgm_ref.core.elements import traces
from ifgm_ref.paper.equations import (
    eq4_final_heading,
    eq4_final_heading_fgm,
    eq4_final_heading_literal,
)
from proofs._util import Derivation, entry_points, held_eq, wrap_exact

__all__ = ["claims", "derivation", "main"]


def final_heading(
    theta_g: sp.Expr, theta_d: sp.Expr, w_g: sp.Expr, w_d: sp.Expr, d_th: sp.Expr
) -> sp.Expr:
    """Equation (4) as printed, as a sympy expression."""
    return ((w_g / d_th) * theta_g + w_d * theta_d) / (w_g / d_th + w_d)


@traces("eq4")
@functools.cache
def derivation() -> Derivation:
    """Build the derivation of eq. (4), checking every claim (raises ``ClaimFailed``)."""
    d = Derivation("eq4", "Equation (4): the final heading")
    theta_g, theta_d = sp.symbols("theta_g theta_d", real=True)
    w_g, w_d, d_th = sp.symbols("w_g w_d d_th", positive=True)
    alpha, beta, d_min = sp.symbols("alpha beta d_min", positive=True)

    theta_f = d.define("theta_f", final_heading(theta_g, theta_d, w_g, w_d, d_th))
    share = d.define("lambda", (w_g / d_th) / (w_g / d_th + w_d))
    _convexity(d, theta_f, share, theta_g, theta_d, w_g, w_d, d_th)
    _limits(d, theta_f, theta_g, theta_d, w_g, w_d, d_th)
    _derivatives(d, theta_f, share, theta_g, theta_d, w_g, w_d, d_th)
    _fgm(d, theta_f, theta_g, theta_d, w_g, w_d, d_th, alpha, beta, d_min)
    _wrap_around(d, theta_f, share, theta_g, theta_d, {w_g: 1, w_d: 1, d_th: 1})
    _library(d)
    return d


def _convexity(
    d: Derivation,
    theta_f: sp.Expr,
    share: sp.Expr,
    theta_g: sp.Expr,
    theta_d: sp.Expr,
    w_g: sp.Expr,
    w_d: sp.Expr,
    d_th: sp.Expr,
) -> None:
    d.text(
        """
        With positive weights, theta_f is a convex combination of theta_g and theta_d: the
        gap's share lambda is strictly between 0 and 1, so theta_f lies strictly between the
        two angles (as numbers) unless they are equal.
        """
    )
    d.prove_equal(
        "convex_combination",
        theta_f,
        share * theta_g + (1 - share) * theta_d,
        "theta_f = lambda theta_g + (1 - lambda) theta_d",
        shown=held_eq(
            sp.Symbol("theta_f"),
            sp.Symbol("lambda") * theta_g + (1 - sp.Symbol("lambda")) * theta_d,
        ),
    )
    d.prove_sign("gap_share_positive", share, "positive", "lambda > 0 for w_g, w_d, d_th > 0")
    goal_share = w_d / (w_g / d_th + w_d)
    d.prove_equal(
        "goal_share_is_complement",
        1 - share,
        goal_share,
        "1 - lambda = w_d / (w_g/d_th + w_d), the goal's share",
        shown=held_eq(1 - sp.Symbol("lambda"), goal_share),
    )
    d.prove_sign("goal_share_positive", goal_share, "positive", "so 1 - lambda > 0 likewise")
    d.prove_equal(
        "offset_from_goal",
        theta_f - theta_d,
        share * (theta_g - theta_d),
        "theta_f - theta_d = lambda (theta_g - theta_d): same sign, smaller size",
        shown=held_eq(sp.Symbol("theta_f") - theta_d, sp.Symbol("lambda") * (theta_g - theta_d)),
    )
    d.prove_equal(
        "offset_from_gap",
        theta_g - theta_f,
        (1 - share) * (theta_g - theta_d),
        "theta_g - theta_f = (1 - lambda)(theta_g - theta_d): so theta_f is between them",
        shown=held_eq(
            theta_g - sp.Symbol("theta_f"), (1 - sp.Symbol("lambda")) * (theta_g - theta_d)
        ),
    )


def _limits(
    d: Derivation,
    theta_f: sp.Expr,
    theta_g: sp.Expr,
    theta_d: sp.Expr,
    w_g: sp.Expr,
    w_d: sp.Expr,
    d_th: sp.Expr,
) -> None:
    d.text("Its limits: the goal alone, the gap alone, and a threshold growing without bound.")
    for name, var, point, expected, statement in (
        ("limit_w_g_to_0", w_g, 0, theta_d, "w_g -> 0+: theta_f -> theta_d (goal only)"),
        ("limit_w_d_to_0", w_d, 0, theta_g, "w_d -> 0+: theta_f -> theta_g (gap only)"),
        (
            "limit_d_th_to_oo",
            d_th,
            sp.oo,
            theta_d,
            "d_th -> oo: theta_f -> theta_d (a large threshold silences the gap)",
        ),
        ("limit_d_th_to_0", d_th, 0, theta_g, "d_th -> 0+: theta_f -> theta_g"),
    ):
        direction = "-" if point is sp.oo else "+"
        d.prove_equal(
            name,
            sp.limit(theta_f, var, point, direction),
            expected,
            statement,
            shown=sp.Eq(sp.Limit(sp.Symbol("theta_f"), var, point, direction), expected),
        )


def _derivatives(
    d: Derivation,
    theta_f: sp.Expr,
    share: sp.Expr,
    theta_g: sp.Expr,
    theta_d: sp.Expr,
    w_g: sp.Expr,
    w_d: sp.Expr,
    d_th: sp.Expr,
) -> None:
    d.text(
        """
        Its partial derivatives. theta_f increases with each angle. A larger w_g, or a smaller
        w_d or d_th, moves theta_f towards theta_g; each derivative is a positive factor times
        the signed difference of the angles.
        """
    )
    d.prove_equal(
        "d_theta_g_is_gap_share",
        sp.diff(theta_f, theta_g),
        share,
        "d theta_f / d theta_g = lambda > 0",
        shown=held_eq(sp.Derivative(sp.Symbol("theta_f"), theta_g), sp.Symbol("lambda")),
    )
    d.prove_equal(
        "d_theta_d_is_goal_share",
        sp.diff(theta_f, theta_d),
        1 - share,
        "d theta_f / d theta_d = 1 - lambda > 0",
        shown=held_eq(sp.Derivative(sp.Symbol("theta_f"), theta_d), 1 - sp.Symbol("lambda")),
    )
    denominator = (w_g + w_d * d_th) ** 2
    for name, var, factor, difference, statement in (
        (
            "d_w_g_sign",
            w_g,
            w_d * d_th / denominator,
            theta_g - theta_d,
            "d theta_f / d w_g = K (theta_g - theta_d), K > 0: w_g pulls towards the gap",
        ),
        (
            "d_w_d_sign",
            w_d,
            w_g * d_th / denominator,
            theta_d - theta_g,
            "d theta_f / d w_d = K (theta_d - theta_g), K > 0: w_d pulls towards the goal",
        ),
        (
            "d_d_th_sign",
            d_th,
            w_g * w_d / denominator,
            theta_d - theta_g,
            "d theta_f / d d_th = K (theta_d - theta_g), K > 0: "
            "a larger d_th pulls towards the goal",
        ),
    ):
        d.prove_equal(
            name,
            sp.diff(theta_f, var),
            factor * difference,
            statement,
            shown=held_eq(sp.Derivative(sp.Symbol("theta_f"), var), factor * difference),
        )
        d.prove_sign(f"{name}_factor_positive", factor, "positive", f"its factor K > 0 ({name})")


def _fgm(
    d: Derivation,
    theta_f: sp.Expr,
    theta_g: sp.Expr,
    theta_d: sp.Expr,
    w_g: sp.Expr,
    w_d: sp.Expr,
    d_th: sp.Expr,
    alpha: sp.Expr,
    beta: sp.Expr,
    d_min: sp.Expr,
) -> None:
    d.text(
        """
        FGM (Sezer & Gokasan 2012), which eq. (4) cites, divides its gap weight alpha by d_min,
        the distance to the nearest obstacle, where the paper prints d_th, a fixed threshold.
        The forms coincide under the renaming w_g -> alpha, w_d -> beta, d_th -> d_min; but
        only FGM's gap share grows as the nearest obstacle comes closer (d_th does not change
        while the robot moves).
        """
    )
    fgm = ((alpha / d_min) * theta_g + beta * theta_d) / (alpha / d_min + beta)
    d.prove_equal(
        "fgm_form_is_renamed_eq4",
        fgm,
        theta_f.subs({w_g: alpha, w_d: beta, d_th: d_min}),
        "FGM's theta_final = eq. (4) with w_g, w_d, d_th renamed alpha, beta, d_min",
        shown=held_eq(sp.Symbol("theta_final_FGM"), fgm),
    )
    fgm_share = (alpha / d_min) / (alpha / d_min + beta)
    rate = -alpha * beta / (alpha + beta * d_min) ** 2
    d.prove_equal(
        "fgm_gap_share_derivative",
        sp.diff(fgm_share, d_min),
        rate,
        "d/d d_min of FGM's gap share (alpha/d_min) / (alpha/d_min + beta)",
        shown=held_eq(sp.Derivative(sp.Symbol("lambda_FGM"), d_min), rate),
    )
    d.prove_sign(
        "fgm_gap_share_falls_with_d_min",
        rate,
        "negative",
        "it is < 0: the nearer the obstacle, the more FGM steers to the gap",
    )


def _wrap_around(
    d: Derivation,
    theta_f: sp.Expr,
    share: sp.Expr,
    theta_g: sp.Expr,
    theta_d: sp.Expr,
    equal_weights: dict[sp.Symbol, int],
) -> None:
    k = sp.Symbol("k", integer=True, nonzero=True)
    d.text(
        """
        The printed mean averages angles as numbers. The same goal direction written as
        theta_d + 2 pi k moves the result by 2 pi k (1 - lambda), which is not a multiple of
        2 pi because 0 < 1 - lambda < 1: the printed mean is not a function of the directions.
        """
    )
    d.prove_equal(
        "literal_depends_on_angle_representation",
        theta_f.subs(theta_d, theta_d + 2 * sp.pi * k) - theta_f,
        2 * sp.pi * k * (1 - share),
        "theta_f(theta_g, theta_d + 2 pi k) - theta_f(theta_g, theta_d) = 2 pi k (1 - lambda)",
    )

    d.text(
        """
        Counterexample near +-pi. The robot faces -x (heading pi). The gap is 5 degrees to its
        right and the goal 5 degrees to its left; wrapped to [-pi, pi) the world angles are
        theta_g = 175 deg and theta_d = -175 deg. With equal weights the printed mean is 0,
        straight back; the robot-frame mean (relative angles -5 and +5 deg, mean 0, heading
        added back) is pi, straight on. Exact values, evaluated by sympy:
        """
    )
    heading = sp.pi
    gap, goal = sp.pi - sp.pi / 36, -(sp.pi - sp.pi / 36)
    literal = theta_f.subs({theta_g: gap, theta_d: goal, **equal_weights})
    relative_g, relative_d = wrap_exact(gap - heading), wrap_exact(goal - heading)
    robot_frame = wrap_exact(heading + (relative_g + relative_d) / 2)
    d.prove_equal(
        "counterexample_literal_mean",
        literal,
        0,
        "printed mean of 175 deg and -175 deg, equal weights = 0",
        shown=held_eq(sp.Function("theta_f")(gap, goal), 0),
    )
    d.prove_equal(
        "counterexample_relative_angles",
        sp.Matrix([relative_g, relative_d]),
        sp.Matrix([-sp.pi / 36, sp.pi / 36]),
        "relative to heading pi the angles wrap to -5 deg and +5 deg",
        shown=held_eq(
            sp.Matrix([sp.Function("wrap")(gap - heading), sp.Function("wrap")(goal - heading)]),
            sp.Matrix([-sp.pi / 36, sp.pi / 36]),
        ),
    )
    d.prove_equal(
        "counterexample_robot_frame_mean",
        robot_frame,
        -sp.pi,
        "robot-frame mean = wrap(pi + 0) = -pi, the same direction as pi",
        shown=held_eq(sp.Symbol("theta_f_robot_frame"), -sp.pi),
    )
    d.prove_equal(
        "counterexample_opposite_directions",
        sp.cos(literal - robot_frame),
        -1,
        "cos(printed - robot-frame) = -1: the printed heading is exactly reversed",
        shown=held_eq(sp.cos(sp.Symbol("theta_f_printed") - sp.Symbol("theta_f_robot_frame")), -1),
    )
    d.prove_sign(
        "counterexample_printed_far_from_gap",
        sp.cos(literal - gap),
        "negative",
        "cos(printed - theta_g) < 0: more than 90 deg from the gap",
    )
    d.prove_sign(
        "counterexample_printed_far_from_goal",
        sp.cos(literal - goal),
        "negative",
        "cos(printed - theta_d) < 0: more than 90 deg from the goal",
    )
    d.prove_sign(
        "counterexample_inputs_close",
        sp.cos(gap - goal),
        "positive",
        "cos(theta_g - theta_d) > 0: yet gap and goal are only 10 deg apart",
    )
    d.text(
        """
        In the robot frame both relative angles lie in [-pi, pi), and the mean is the convex
        combination proved above, so it stays between them; the gap is inside the 135-degree
        field of view, so its relative angle is within +-67.5 deg and never near the wrap.
        """
    )


def _library(d: Derivation) -> None:
    formula = sp.lambdify(
        sp.symbols("theta_g theta_d w_g w_d d_th"),
        final_heading(*sp.symbols("theta_g theta_d w_g w_d d_th")),
        "math",
    )
    points = [(0.5, -0.25, 2.0, 1.0, 2.0), (1.1, 3.0, 0.3, 7.0, 0.9), (-2.0, 2.5, 5.0, 0.1, 3.0)]
    d.spot_check(
        "library_literal_matches_formula",
        lambda *p: eq4_final_heading_literal(p[0], p[1], w_g=p[2], w_d=p[3], d_th=p[4]),
        formula,
        points,
        "eq4_final_heading_literal = the printed formula",
        abs_tol=1e-15,
        reason="the same arithmetic, possibly reordered by lambdify: an ulp or two of |theta|",
    )
    near_pi = [(math.radians(175.0),), (math.radians(179.0),), (math.radians(150.0),)]
    d.spot_check(
        "library_counterexample_literal",
        lambda a: eq4_final_heading_literal(a, -a, w_g=1.0, w_d=1.0, d_th=1.0),
        lambda a: 0.0,
        near_pi,
        "eq4_final_heading_literal(a, -a), equal weights, is 0 (straight back)",
        abs_tol=0.0,
        reason="(a + (-a))/2 is exactly 0 in floating point",
    )
    d.spot_check(
        "library_counterexample_robot_frame",
        lambda a: abs(eq4_final_heading(a, -a, w_g=1.0, w_d=1.0, d_th=1.0, heading=math.pi)),
        lambda a: math.pi,
        near_pi,
        "eq4_final_heading(a, -a, heading=pi), equal weights, is +-pi (straight on)",
        abs_tol=1e-15,
        reason="the relative angles a - pi and -a - pi + 2 pi each carry an ulp of pi",
    )
    d.spot_check(
        "library_fgm_matches_renamed_eq4",
        lambda *p: eq4_final_heading_fgm(
            p[0], p[1], alpha=p[2], beta=p[3], d_min=p[4], heading=0.0
        ),
        lambda *p: eq4_final_heading(p[0], p[1], w_g=p[2], w_d=p[3], d_th=p[4], heading=0.0),
        points,
        "eq4_final_heading_fgm = eq4_final_heading with alpha, beta, d_min for w_g, w_d, d_th",
        abs_tol=0.0,
        reason="one code path",
    )


claims, main = entry_points(derivation)


if __name__ == "__main__":
    main()
