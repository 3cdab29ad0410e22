"""Equation (3), the destination angle: where the printed arctan is wrong, and by how much.

Paper (section 4, Case-1)::

    theta_d = tan^-1( (y_d - y_c) / (x_d - x_c) )        (3)

Run ``python -m proofs.eq3`` to read the derivation; :func:`claims` returns the checked claims.
"""

from __future__ import annotations

import functools
import math

import sympy as sp

from ifgm_ref.core.elements import traces
from ifgm_ref.paper.equations import eq3_goal_angle, eq3_goal_angle_literal
from proofs._util import Derivation, entry_points, held_eq

__all__ = ["claims", "derivation", "main"]


@traces("eq3")
@functools.cache
def derivation() -> Derivation:
    """Build the derivation of eq. (3), checking every claim (raises ``ClaimFailed``)."""
    d = Derivation("eq3", "Equation (3): the destination angle")
    dx_ahead = sp.Symbol("Δx", positive=True)
    dx_behind = sp.Symbol("Δx", negative=True)
    dy = sp.Symbol("Δy", real=True)
    dy_left = sp.Symbol("Δy", positive=True)
    dy_right = sp.Symbol("Δy", negative=True)
    step = sp.Symbol("s", real=True)
    u_x, u_y = sp.symbols("u_x u_y")  # display only: the printed heading's unit vector

    def atan2_minus_atan(y: sp.Expr, x: sp.Expr, value: sp.Expr) -> sp.Basic:
        with sp.evaluate(False):
            return sp.Eq(sp.atan2(y, x) - sp.atan(y / x), value)

    d.text(
        """
        Write Delta_x = x_d - x_c and Delta_y = y_d - y_c. The printed form is
        atan(Delta_y / Delta_x), whose values lie in (-pi/2, pi/2): it cannot name a direction
        behind the robot's x axis. The planner runs atan2(Delta_y, Delta_x), the direction of
        the destination (sympy's atan2 is the principal value, in (-pi, pi]).
        """
    )
    d.prove_equal(
        "literal_equals_atan2_ahead",
        sp.atan(dy / dx_ahead),
        sp.atan2(dy, dx_ahead),
        "for x_d > x_c (Delta_x > 0) the printed form is atan2 exactly",
        shown=atan2_minus_atan(dy, dx_ahead, 0),
    )
    d.text("For x_d < x_c (destination behind, Delta_x < 0) the two differ by exactly pi:")
    d.prove_equal(
        "literal_differs_by_pi_behind_left",
        sp.atan2(dy_left, dx_behind) - sp.atan(dy_left / dx_behind),
        sp.pi,
        "Delta_x < 0, Delta_y > 0: atan2 - atan = pi",
        shown=atan2_minus_atan(dy_left, dx_behind, sp.pi),
    )
    d.prove_equal(
        "literal_differs_by_pi_behind_right",
        sp.atan2(dy_right, dx_behind) - sp.atan(dy_right / dx_behind),
        -sp.pi,
        "Delta_x < 0, Delta_y < 0: atan2 - atan = -pi",
        shown=atan2_minus_atan(dy_right, dx_behind, -sp.pi),
    )
    d.prove_equal(
        "literal_differs_by_pi_straight_behind",
        sp.atan2(0, dx_behind) - sp.atan(0 / dx_behind),
        sp.pi,
        "Delta_x < 0, Delta_y = 0: atan2 = pi, the printed form gives 0",
        shown=atan2_minus_atan(sp.Integer(0), dx_behind, sp.pi),
    )

    d.text(
        """
        A difference of pi means the printed angle points straight away from the destination:
        its unit vector is the negative of the unit vector towards the destination, and moving
        along it increases the distance to the destination at unit rate.
        """
    )
    literal = sp.atan(dy / dx_behind)
    toward = sp.Matrix([dx_behind, dy]) / sp.sqrt(dx_behind**2 + dy**2)
    heading = sp.Matrix([sp.cos(literal), sp.sin(literal)])
    with sp.evaluate(False):
        held_heading = sp.Matrix([sp.cos(sp.atan(dy / dx_behind)), sp.sin(sp.atan(dy / dx_behind))])
    heading_shown = held_eq(held_heading, -toward)
    d.prove_equal(
        "literal_points_away_behind",
        heading,
        -toward,
        "(cos, sin) of the printed angle = -(Delta_x, Delta_y)/|(Delta_x, Delta_y)| for "
        "Delta_x < 0",
        shown=heading_shown,
    )
    distance = sp.sqrt((dx_behind - step * heading[0]) ** 2 + (dy - step * heading[1]) ** 2)
    d.prove_equal(
        "literal_heading_increases_distance",
        sp.diff(distance, step).subs(step, 0),
        1,
        "d/ds |destination - (current + s u_printed)| at s = 0 is +1: every step on the "
        "printed heading takes the robot one step further from the destination",
        shown=held_eq(
            sp.Subs(
                sp.Derivative(
                    sp.sqrt((dx_behind - step * u_x) ** 2 + (dy - step * u_y) ** 2), step
                ),
                step,
                0,
            ),
            1,
        ),
    )

    d.text(
        """
        At x_d = x_c the printed form divides by zero, and its one-sided limits disagree: the
        printed heading flips from +pi/2 to -pi/2 as the destination crosses the robot's
        vertical line, while atan2 is continuous there (pi/2 for a destination on the left).
        """
    )
    ahead_limit = sp.limit(sp.atan(dy_left / dx_ahead), dx_ahead, 0, "+")
    behind_limit = sp.limit(sp.atan(dy_left / dx_behind), dx_behind, 0, "-")
    d.prove_equal(
        "literal_limit_from_ahead",
        ahead_limit,
        sp.pi / 2,
        "Delta_y > 0: atan(Delta_y / Delta_x) -> pi/2 as Delta_x -> 0+",
        shown=sp.Eq(sp.Limit(sp.atan(dy_left / dx_ahead), dx_ahead, 0, "+"), sp.pi / 2),
    )
    d.prove_equal(
        "literal_limit_from_behind",
        behind_limit,
        -sp.pi / 2,
        "Delta_y > 0: atan(Delta_y / Delta_x) -> -pi/2 as Delta_x -> 0-",
        shown=sp.Eq(sp.Limit(sp.atan(dy_left / dx_behind), dx_behind, 0, "-"), -sp.pi / 2),
    )
    d.prove_equal(
        "atan2_on_vertical_line",
        sp.atan2(dy_left, 0),
        sp.pi / 2,
        "atan2(Delta_y, 0) = pi/2 for Delta_y > 0",
        shown=held_eq(sp.Function("atan2")(dy_left, 0), sp.pi / 2),
    )

    behind = [
        ((0.0, 0.0), (-1.0, 1.0)),
        ((2.0, 3.0), (-5.0, -1.0)),
        ((0.0, 0.0), (-4.0, 0.0)),
        ((10.0, -2.0), (9.999, 250.0)),
    ]

    def wrapped_difference(current: tuple[float, float], destination: tuple[float, float]) -> float:
        difference = eq3_goal_angle(current, destination) - eq3_goal_angle_literal(
            current, destination
        )
        return abs(difference)

    d.spot_check(
        "library_literal_differs_by_pi_behind",
        wrapped_difference,
        lambda current, destination: math.pi,
        behind,
        "|eq3_goal_angle - eq3_goal_angle_literal| = pi for destinations behind",
        abs_tol=1e-15,
        reason="two angles of magnitude <= pi, each within an ulp or two (ulp(pi) = 4.4e-16)",
    )
    return d


claims, main = entry_points(derivation)


if __name__ == "__main__":
    main()
