"""Equation (2), the gap centre angle: the printed ratio, atan2, and FGM's cosine form.

Paper (section 4, Case-1)::

    theta_g = y_g / x_g        (2)

and section 2.2: FGM finds theta_g "using Cosine and Apollonius theorems". This derivation
proves that the printed form is tan(theta_g), that atan of it is atan2(y_g, x_g) wherever a gap
can be seen, and that FGM's cosine/Apollonius gap centre angle is the direction of the eq. (1)
midpoint.

Run ``python -m proofs.eq2`` to read the derivation; :func:`claims` returns the checked claims.
"""

from __future__ import annotations

import functools
import math

import sympy as sp

from ifgm_ref.core.elements import traces
from ifgm_ref.paper.equations import (
    eq1_gap_midpoint,
    eq2_gap_angle,
    eq2_gap_angle_literal,
    fgm_gap_centre_angle,
)
from proofs._util import Derivation, entry_points, held_eq

__all__ = ["claims", "derivation", "main"]


def expand_trig_then_simplify(expr: sp.Basic) -> sp.Basic:
    """``simplify(expand_trig(expr))``: expand sums of angles before simplifying."""
    return sp.simplify(sp.expand_trig(expr))


@traces("eq2")
@functools.cache
def derivation() -> Derivation:
    """Build the derivation of eq. (2), checking every claim (raises ``ClaimFailed``)."""
    d = Derivation("eq2", "Equation (2): the gap centre angle")
    _printed_form(d)
    _fov(d)
    _invariances(d)
    _fgm_gap_centre(d)
    _library(d)
    return d


def _printed_form(d: Derivation) -> None:
    rho = sp.Symbol("rho", positive=True)
    theta = sp.Symbol("theta_g", real=True)
    x_pos = sp.Symbol("x_g", positive=True)
    y = sp.Symbol("y_g", real=True)

    d.text(
        """
        The printed theta_g = y_g / x_g is a ratio, not an angle. Write the midpoint in polar
        form, x_g = rho cos(theta_g), y_g = rho sin(theta_g), rho > 0:
        """
    )
    d.prove_equal(
        "printed_form_is_tangent",
        rho * sp.sin(theta) / (rho * sp.cos(theta)),
        sp.tan(theta),
        "y_g / x_g = tan(theta_g) (where cos(theta_g) != 0): eq. (2) prints the tangent",
    )
    d.text(
        """
        The ratio equals the angle only for a gap dead ahead: tan(theta) - theta has derivative
        tan(theta)^2 >= 0, zero only at theta = 0, so on (-pi/2, pi/2) it vanishes only at 0;
        near 0 the ratio overestimates the angle by theta^3/3.
        """
    )
    d.prove_equal(
        "ratio_minus_angle_derivative",
        sp.diff(sp.tan(theta) - theta, theta),
        sp.tan(theta) ** 2,
        "d/dtheta (tan(theta) - theta) = tan(theta)^2",
        shown=held_eq(sp.Derivative(sp.tan(theta) - theta, theta), sp.tan(theta) ** 2),
    )
    d.prove_equal(
        "ratio_series",
        sp.series(sp.tan(theta), theta, 0, 5).removeO(),
        theta + theta**3 / 3,
        "tan(theta) = theta + theta^3/3 + O(theta^5)",
        shown=held_eq(sp.tan(theta), sp.series(sp.tan(theta), theta, 0, 5)),
    )
    d.prove_equal(
        "ratio_at_fov_edge",
        sp.tan(3 * sp.pi / 8),
        1 + sp.sqrt(2),
        "at the edge of the 135-degree field of view (67.5 deg = 3 pi/8) the ratio is 1 + sqrt 2",
        shown=held_eq(sp.Function("tan")(3 * sp.pi / 8), 1 + sp.sqrt(2)),
    )
    d.prove_sign(
        "ratio_exceeds_angle_at_fov_edge",
        1 + sp.sqrt(2) - 3 * sp.pi / 8,
        "positive",
        "there the printed ratio (2.414) exceeds the angle (1.178 rad) by more than 2x",
    )
    d.text(
        """
        The planner therefore runs theta_g = atan2(y_g, x_g), the direction of the midpoint.
        On the half-plane x_g > 0 it is exactly atan of the printed ratio (sympy's atan2 is
        the principal two-argument arctangent, in (-pi, pi]):
        """
    )
    d.prove_equal(
        "atan_of_ratio_is_atan2_ahead",
        sp.atan(y / x_pos),
        sp.atan2(y, x_pos),
        "atan(y_g / x_g) = atan2(y_g, x_g) for every x_g > 0",
        shown=held_eq(sp.atan(y / x_pos), sp.Function("atan2")(y, x_pos)),
    )
    d.text("Behind the robot (x_g < 0) they differ by pi; proofs.eq3 proves this for eq. (3).")


def _fov(d: Derivation) -> None:
    d1, d2, c1, c2 = sp.symbols("d_1 d_2 c_1 c_2", positive=True)
    d.text(
        """
        Every gap the paper's sensor sees has x_g > 0: both obstacle points lie at angles a_i
        with |a_i| <= 67.5 deg = 3 pi/8 < pi/2, where cos is at least cos(3 pi/8) > 0, so
        x_i = d_i cos(a_i) = d_i c_i with c_i > 0, and x_g is their mean:
        """
    )
    d.prove_sign(
        "fov_edge_is_ahead",
        sp.cos(3 * sp.pi / 8),
        "positive",
        "cos(3 pi/8) > 0: the edge of the field of view is ahead of the robot",
    )
    d.prove_sign(
        "midpoint_ahead_in_fov",
        (d1 * c1 + d2 * c2) / 2,
        "positive",
        "x_g = (d_1 c_1 + d_2 c_2)/2 > 0 for d_i > 0, c_i = cos(a_i) > 0: the literal "
        "atan(y_g/x_g) and atan2 agree on every visible gap",
    )


def _invariances(d: Derivation) -> None:
    x, y = sp.symbols("x_g y_g", real=True)
    k = sp.Symbol("k", positive=True)
    theta, phi = sp.symbols("theta_g phi", real=True)
    d.text(
        """
        theta_g depends only on the unit vector M/|M| of the midpoint (cos and sin of theta_g).
        That vector does not change when both obstacle points are scaled by k > 0 (eq. (1) is
        linear, so M scales by k), and rotating both points by phi rotates it by phi, so
        theta_g is scale invariant and turns by phi (mod 2 pi):
        """
    )
    m = sp.Matrix([x, y])
    d.prove_equal(
        "direction_scale_invariant",
        k * m / sp.sqrt((k * x) ** 2 + (k * y) ** 2),
        m / sp.sqrt(x**2 + y**2),
        "(k M)/|k M| = M/|M| for k > 0",
    )
    rotation = sp.Matrix([[sp.cos(phi), -sp.sin(phi)], [sp.sin(phi), sp.cos(phi)]])
    d.prove_equal(
        "direction_rotation_equivariant",
        rotation * sp.Matrix([sp.cos(theta), sp.sin(theta)]),
        sp.Matrix([sp.cos(theta + phi), sp.sin(theta + phi)]),
        "R(phi) (cos theta_g, sin theta_g) = (cos(theta_g + phi), sin(theta_g + phi))",
        simplifier=expand_trig_then_simplify,
    )


def _fgm_gap_centre(d: Derivation) -> None:
    d1, d2, t = sp.symbols("d_1 d_2 t", positive=True)
    phi1 = sp.Symbol("phi_1", real=True)
    big_c = sp.Symbol("C", real=True)

    d.text(
        """
        FGM's gap centre angle (Sezer & Gokasan 2012). The gap borders are at distances d_1,
        d_2 > 0; border 1 at angle -phi_1 (phi_1 measured clockwise), border 2 at angle
        phi_2 (counter-clockwise), so the gap's angular width is s = phi_1 + phi_2. FGM gives
        theta_gap = arccos((d_1 + d_2 cos s) / sqrt(d_1^2 + d_2^2 + 2 d_1 d_2 cos s)) - phi_1.
        We prove it is the direction of the eq. (1) midpoint of the two border points. For a
        width s in (0, pi), write s = 2 atan(t) with t > 0, so that sympy knows sin s > 0:
        """
    )
    cos_s = (1 - t**2) / (1 + t**2)
    sin_s = 2 * t / (1 + t**2)
    d.prove_equal(
        "width_parametrisation",
        sp.Matrix([sp.cos(2 * sp.atan(t)), sp.sin(2 * sp.atan(t))]),
        sp.Matrix([cos_s, sin_s]),
        "cos(2 atan t) = (1 - t^2)/(1 + t^2) and sin(2 atan t) = 2t/(1 + t^2): t in (0, oo) "
        "covers every width s in (0, pi)",
    )
    # Border 2 is at angle s - phi_1: expand cos(s - phi_1), sin(s - phi_1).
    border1 = sp.Matrix([d1 * sp.cos(phi1), -d1 * sp.sin(phi1)])
    border2 = d2 * sp.Matrix(
        [cos_s * sp.cos(phi1) + sin_s * sp.sin(phi1), sin_s * sp.cos(phi1) - cos_s * sp.sin(phi1)]
    )
    midpoint = (border1 + border2) / 2

    def sq(v: sp.Matrix) -> sp.Expr:
        return (v.T * v)[0, 0]

    # Display-only symbols: the page shows |B2 - B1|^2, cos s, ... instead of expanded forms.
    s, b1_, b2_, m_, big_d, c_, r_ = sp.symbols("s B_1 B_2 M D c r")

    gap_sq = d1**2 + d2**2 - 2 * d1 * d2 * cos_s
    d.prove_equal(
        "cosine_theorem",
        sq(border2 - border1),
        gap_sq,
        "cosine theorem: the gap width^2 |B2 - B1|^2 = d_1^2 + d_2^2 - 2 d_1 d_2 cos s",
        shown=sp.Eq(sp.Abs(b2_ - b1_) ** 2, d1**2 + d2**2 - 2 * d1 * d2 * sp.cos(s)),
    )
    d.prove_equal(
        "apollonius_theorem",
        sq(midpoint),
        (2 * d1**2 + 2 * d2**2 - sq(border2 - border1)) / 4,
        "Apollonius: the median |M|^2 = (2 d_1^2 + 2 d_2^2 - |B2 - B1|^2)/4",
        shown=sp.Eq(sp.Abs(m_) ** 2, (2 * d1**2 + 2 * d2**2 - sp.Abs(b2_ - b1_) ** 2) / 4),
    )
    median_sq4 = d.define(
        "D", d1**2 + d2**2 + 2 * d1 * d2 * cos_s, shown=d1**2 + d2**2 + 2 * d1 * d2 * sp.cos(s)
    )
    d.prove_equal(
        "median_length",
        sq(midpoint),
        median_sq4 / 4,
        "so |M|^2 = D/4 with D = d_1^2 + d_2^2 + 2 d_1 d_2 cos s (cosine theorem in Apollonius)",
        shown=sp.Eq(sp.Abs(m_) ** 2, big_d / 4),
    )
    positive_form = ((d1 + d2) ** 2 + t**2 * (d1 - d2) ** 2) / (1 + t**2)
    d.prove_equal(
        "median_length_positive_form",
        median_sq4,
        positive_form,
        "D = ((d_1 + d_2)^2 + t^2 (d_1 - d_2)^2)/(1 + t^2)",
    )
    d.prove_sign("median_length_positive", positive_form, "positive", "so D > 0 and |M| > 0")

    norm_m = sp.sqrt(positive_form) / 2
    c = d.define(
        "c",
        (d1 + d2 * cos_s) / sp.sqrt(positive_form),
        shown=(d1 + d2 * sp.cos(s)) / sp.sqrt(big_d),
    )
    r = d.define("r", d2 * sin_s / sp.sqrt(positive_form), shown=d2 * sp.sin(s) / sp.sqrt(big_d))
    d.text("c is FGM's arccos argument. r is sin(arccos c) = sqrt(1 - c^2), as these prove:")
    d.prove_sign("sine_of_arccos_positive", r, "positive", "r > 0 (shown in terms of t)")
    d.prove_equal(
        "sine_of_arccos_squared",
        r**2,
        1 - c**2,
        "r^2 = 1 - c^2; with r > 0 this gives r = sqrt(1 - c^2) = sin(arccos c)",
        shown=sp.Eq(r_**2, 1 - c_**2),
    )
    d.prove_equal(
        "angle_difference_identities",
        sp.Matrix([sp.cos(sp.acos(big_c) - phi1), sp.sin(sp.acos(big_c) - phi1)]),
        sp.Matrix(
            [
                big_c * sp.cos(phi1) + sp.sqrt(1 - big_c**2) * sp.sin(phi1),
                sp.sqrt(1 - big_c**2) * sp.cos(phi1) - big_c * sp.sin(phi1),
            ]
        ),
        "cos(arccos C - phi_1) and sin(arccos C - phi_1) for any C in [-1, 1]",
        simplifier=expand_trig_then_simplify,
    )
    d.text("With C = c and sqrt(1 - c^2) = r, the direction of theta_gap is that of M:")
    d.prove_equal(
        "fgm_angle_is_midpoint_direction",
        sp.Matrix([c * sp.cos(phi1) + r * sp.sin(phi1), r * sp.cos(phi1) - c * sp.sin(phi1)]),
        midpoint / norm_m,
        "(cos theta_gap, sin theta_gap) = M/|M|: FGM's gap centre angle is atan2(y_g, x_g) "
        "(mod 2 pi) of the eq. (1) midpoint of the border points",
        shown=sp.Eq(
            sp.Matrix(
                [c_ * sp.cos(phi1) + r_ * sp.sin(phi1), r_ * sp.cos(phi1) - c_ * sp.sin(phi1)]
            ),
            sp.Matrix([m_]) / sp.Abs(m_),
            evaluate=False,
        ),
    )
    d.text(
        """
        The end points of the width, outside t in (0, oo): s = 0 (both borders on one ray)
        gives c = 1 and theta_gap = -phi_1, their common direction; s = pi with d_1 != d_2
        gives c = +-1, the direction of the farther border, and with d_1 = d_2 the midpoint is
        the robot itself and has no direction. The 135-degree field of view keeps
        s <= 3 pi/4 < pi.
        """
    )


def _library(d: Derivation) -> None:
    ahead = [(2.0, 2.0), (1.0, -0.3), (1e-3, 5.0), (7.5, -7.5), (3.0, 0.0)]
    d.spot_check(
        "library_literal_is_tangent_of_angle",
        lambda x, y: math.atan(eq2_gap_angle_literal(x, y)),
        eq2_gap_angle,
        ahead,
        "atan(eq2_gap_angle_literal) = eq2_gap_angle for x_g > 0",
        abs_tol=4.5e-16,
        reason="atan of a correctly rounded quotient vs atan2: about 1 ulp of an angle <= pi/2",
    )

    def via_midpoint(d1: float, phi1: float, d2: float, phi2: float) -> float:
        b1 = (d1 * math.cos(-phi1), d1 * math.sin(-phi1))
        b2 = (d2 * math.cos(phi2), d2 * math.sin(phi2))
        return eq2_gap_angle(*eq1_gap_midpoint(b1, b2))

    borders = [
        (2.0, math.pi / 4, 2.0, math.pi / 4),
        (1.0, 0.0, 1.0, math.pi / 2),
        (5.0, 1.1, 0.5, -0.2),
        (0.3, -0.5, 12.0, 1.1),
        (3.0, 0.2, 3.0, 1.0),
    ]
    d.spot_check(
        "library_fgm_angle_is_midpoint_angle",
        fgm_gap_centre_angle,
        via_midpoint,
        borders,
        "fgm_gap_centre_angle = eq2_gap_angle(eq1_gap_midpoint(border points))",
        abs_tol=1e-9,
        reason="arccos near +-1 turns a rounding error dc into about sqrt(2 dc)",
    )


claims, main = entry_points(derivation)


if __name__ == "__main__":
    main()
