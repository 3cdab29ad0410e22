"""The fan of the braking derivation (``proofs/braking.py``): where the robot may go until it
stops, and the margin :func:`ifgm_ref.planners.governor.fan_room` keeps.

Helpers that :func:`proofs.braking.build` calls, in its order; they add their claims to the
one derivation ``braking``. Not a derivation of its own.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import sympy as sp
from sympy.calculus.util import function_range

from ifgm_ref.laserscan import LaserScan
from ifgm_ref.planners import governor as gov
from ifgm_ref.planners.governor import GovernorState, Limits
from ifgm_ref.pose import Point, Pose
from ifgm_ref.protocol import Command, Observation
from proofs._util import Derivation, held_eq

__all__ = [
    "fan_cone",
    "fan_edge",
    "fan_margin",
    "headings",
    "library_fan_room",
    "library_headings",
    "margin_odometry",
    "wall",
]

#: The robot radius.
R = sp.Symbol("r", positive=True)
#: The robot of the spot checks (as ``proofs.braking.LIMITS``).
LIMITS = Limits(radius=0.2, top_speed=2.0, braking=4.0, acceleration=2.0, period=0.1)


def _e(angle: sp.Expr) -> sp.Matrix:
    return sp.Matrix([sp.cos(angle), sp.sin(angle)])


def fan_cone(d: Derivation) -> None:
    """A path whose heading stays in the fan stays in its cone, no farther than its length."""
    low, high, phi, p1, p2, alpha = sp.symbols("low high phi phi_1 phi_2 alpha", real=True)
    l1, l2 = sp.symbols("l_1 l_2", nonnegative=True)
    d.text(
        """
        The fan (fan_room). A path of length D with headings phi in [low, high], high - low < pi, is
        displaced by the integral of e(phi) = (cos phi, sin phi). Each step is on the inner side of
        both edges: the cross products are sines of angles in [0, high - low]:
        """
    )
    cross = [sp.Matrix.hstack(*pair).det() for pair in ((_e(low), _e(phi)), (_e(phi), _e(high)))]
    d.prove_equal(
        "step_cross_products",
        sp.Matrix(cross),
        sp.Matrix([sp.sin(phi - low), sp.sin(high - phi)]),
        "cross(e(low), e(phi)) = sin(phi - low), cross(e(phi), e(high)) = sin(high - phi)",
    )
    sines = function_range(sp.sin(alpha), alpha, sp.Interval(0, sp.pi))
    d.prove_true(
        "step_between_the_edges",
        sines.is_subset(sp.Interval(0, sp.oo)),
        "sin(alpha) >= 0 for alpha in [0, pi]: every step is on the inner side of both edges",
        shown=sp.Eq(sp.Symbol("sin([0, pi])"), sines, evaluate=False),
    )
    d.text(
        """
        Cross products are linear, so every sum of steps lies in the cone of [low, high], convex as
        it spans less than pi, and no longer than the path: for two steps,
        """
    )
    step = l1 * _e(p1) + l2 * _e(p2)
    slack = 4 * l1 * l2 * sp.sin((p1 - p2) / 2) ** 2
    d.prove_equal(
        "displacement_no_longer_than_path",
        (l1 + l2) ** 2 - (step.T * step)[0],
        slack,
        "(l_1 + l_2)^2 - |l_1 e(phi_1) + l_2 e(phi_2)|^2 = 4 l_1 l_2 sin((phi_1 - phi_2)/2)^2",
    )
    d.prove_sign("displacement_no_longer_than_path_sign", slack, "nonnegative", "which is >= 0")


def fan_edge(d: Derivation) -> None:
    """Where the disc moving along the fan's edge first touches a point beside it."""
    delta = sp.Symbol("delta", nonnegative=True)
    rho = sp.Symbol("rho", positive=True)
    d.text(
        """
        So the centre stays in the sector of radius D and angles [low, high] (all the plane when
        they span pi or more: fan_room then counts every point as inside). A point at distance rho
        and angle delta < pi/2 outside it is nearest to the edge ray; along it (direction (1, 0),
        the point at rho e(delta)) the squared distance minus k^2 is a quadratic in t with leading
        coefficient 1: the disc of radius k (r, or r + m for a point kept a margin m farther) first
        touches it at the smaller root, fan_room's room. A point with delta >= pi/2 is never
        approached (every step has a nonpositive component towards it).
        """
    )
    touch = rho * sp.cos(delta) - sp.sqrt(R**2 - rho**2 * sp.sin(delta) ** 2)
    offset = rho * _e(delta) - touch * sp.Matrix([1, 0])
    d.prove_equal(
        "fan_edge_touch",
        (offset.T * offset)[0],
        R**2,
        "|rho e(delta) - t (1, 0)| = k at t = rho cos(delta) - sqrt(k^2 - rho^2 sin(delta)^2) "
        "(k = r shown)",
        shown=held_eq(
            (rho * sp.cos(delta) - sp.Symbol("t")) ** 2 + (rho * sp.sin(delta)) ** 2, R**2
        ),
    )
    d.prove_equal(
        "fan_inside_touch", touch.subs(delta, 0), rho - R, "inside the fan (delta = 0): rho - k"
    )


def fan_margin(d: Derivation) -> None:
    """The margin: it only shrinks the room, and it has half a margin of hysteresis."""
    across, gap, k = sp.symbols("a g k", positive=True)
    along = sp.Symbol("rho", positive=True) * sp.cos(sp.Symbol("delta", nonnegative=True))
    m = sp.Rational(Limits.MARGIN) * R  # the code's margin, exactly
    d.text(
        """
        The margin (fan_room's rule). A point ahead -- its distance a across the fan below r, so
        that the disc would meet it -- is kept k = r + m away, m = Limits.MARGIN r, unless it is
        already within r + m/2 of the centre; every other point is kept k = r (a point beside is
        passed).
        A larger k only takes room away: where the disc meets the point, k^2 = a^2 + g^2 with g >
        0, and the touch rho cos(delta) - sqrt(k^2 - a^2) falls with k:
        """
    )
    slope = sp.diff(along - sp.sqrt(k**2 - across**2), k)
    d.prove_sign(
        "margin_only_shrinks_the_room",
        slope.subs(k, sp.sqrt(across**2 + gap**2)),
        "negative",
        "d(touch)/dk = -k/sqrt(k^2 - a^2) = -k/g < 0: the room with the margin is at most the "
        "room from the disc (what admissible, the oracle's monitor, counts)",
    )
    d.text(
        """
        A point the governor kept k = r + m away is, at the next decision, still at least r + m
        from the centre, beyond r + m/2: it keeps its margin as long as it stays ahead. A point
        first seen, or passed beside, within r + m/2 is kept only r; one between r + m/2 and r + m
        ahead leaves no room (the robot brakes, or stands and may turn). So the margin cannot be
        lost at its own boundary: half a margin of hysteresis.
        """
    )
    d.prove_sign(
        "margin_hysteresis",
        (R + m) - (R + m / 2),
        "positive",
        "(r + m) - (r + m/2) = m/2 > 0 with the code's m = Limits.MARGIN r",
    )


def headings(d: Derivation) -> None:
    """Prose: the path from a decision to the stand keeps its heading in the decision's fan."""
    d.text(
        """
        The path from a decision to the stand keeps its heading in the decision's fan (_fan: the
        present heading, the command's and the last command's): for tau the robot turns towards
        the last command's heading, then towards the new one, and a short turn between headings
        of a fan narrower than pi stays in it (a wider fan is all the plane). The stop from the
        next decision starts at a heading in this fan and turns towards the command just given,
        in it too, for tau; the governor's fallback (speed 0 when not even braking fits in the
        planner's fan) keeps to that heading after tau too. At rest -- speed bound 0 and, with
        tau > 0, last command 0, else the robot still moves for tau -- it turns in place and
        sweeps nothing.
        """
    )


def margin_odometry(d: Derivation) -> None:
    """The margin covers an odometry error of up to a quarter radius, for a point kept m away."""
    d.text(
        """
        Odometry: the room is measured from the scan in the robot frame, so a position error does
        not enter and a heading error enters only through the fan; where scan and pose disagree by
        e_odo, the robot must keep e_odo beyond its disc:
        """
    )
    spare = sp.Symbol("spare", nonnegative=True)
    margin = sp.Rational(Limits.MARGIN) * R
    d.prove_sign(
        "margin_covers_odometry",
        (R + margin - (R / 4 - spare)) - R,
        "nonnegative",
        "for a point kept r + m away: true clearance >= measured - e_odo >= r + Limits.MARGIN r "
        "- e_odo >= r for every e_odo = r/4 - spare <= r/4: the code's margin is at least r/4",
    )


def _touch(rho: float, angle: float, low: float, high: float, kept: float) -> float:
    """The proved room for a point at ``rho``, ``angle`` kept ``kept`` from the centre."""
    delta = max(0.0, angle - high, low - angle)
    across = rho * math.sin(min(delta, math.pi / 2))
    if delta >= math.pi / 2 or across >= kept:
        return 0.0 if rho < kept else math.inf
    return max(0.0, rho * math.cos(delta) - math.sqrt(kept**2 - across**2))


def library_fan_room(d: Derivation) -> None:
    """Spot checks of ``fan_room``: the edge formula, and the margin rule."""

    def room(rho: float, angle: float, low: float, high: float, r: float, m: float = 0.0) -> float:
        point = np.array([[rho * math.cos(angle), rho * math.sin(angle)]])
        return gov.fan_room(point, low, high, r, m)

    d.spot_check(
        "library_fan_room_edge",
        room,
        _touch,
        [(2.0, 0.4, -0.2, 0.3, 0.5), (3.0, -0.55, -0.5, 1.0, 0.3), (1.5, 0.2, -0.5, 0.5, 0.4)],
        "fan_room = rho cos(delta) - sqrt(r^2 - rho^2 sin(delta)^2) beside and inside the fan",
        abs_tol=1e-12,
        reason="the point's polar angle recovered by arctan2: ulps",
    )
    d.spot_check(
        "library_fan_room_margin",
        lambda rho, angle, low, high, r, m, kept: room(rho, angle, low, high, r, m),
        lambda rho, angle, low, high, r, m, kept: _touch(rho, angle, low, high, kept),
        [
            (2.0, 0.0, 0.0, 0.0, 0.5, 0.25, 0.75),  # ahead, far: kept r + m
            (2.0, 0.4, -0.2, 0.3, 0.5, 0.25, 0.75),  # ahead of the fan's edge: kept r + m
            (0.6, 0.0, 0.0, 0.0, 0.5, 0.25, 0.5),  # ahead, within r + m/2: kept r
            (0.7, 0.0, 0.0, 0.0, 0.5, 0.25, 0.75),  # ahead, within r + m: no room
            (2.0, 0.3, 0.0, 0.0, 0.5, 0.25, 0.5),  # beside (0.59 across): passed
            (2.0, 0.24, 0.0, 0.0, 0.5, 0.25, 0.75),  # just ahead (0.48 across): kept r + m
        ],
        "fan_room keeps r + m from a point ahead (across below r) no nearer than r + m/2, "
        "and r from every other point (the last value of each sample is the kept radius)",
        abs_tol=1e-12,
        reason="the point's polar angle recovered by arctan2: ulps",
    )


def wall(distance: float, x: float = 0.0) -> Observation:
    """The robot at ``x`` facing +x, a wall ``distance`` ahead of the origin, three rays."""
    ranges = (distance - x) / np.cos(np.array([-0.1, 0.0, 0.1]))
    scan = LaserScan(-0.1, 0.1, 0.1, 0.0, 10.0, ranges)
    return Observation(0.0, Pose(x, 0.0, 0.0), Point(20.0, 0.0), scan)


def library_headings(d: Derivation, limits: Limits = LIMITS) -> None:
    """Spot checks of the heading ``govern`` lets through when it cannot let the planner's."""

    def governed(heading: float, last: float, tau: float, bound: float, distance: float) -> float:
        state = GovernorState(bound, last, bound)
        told = gov.govern(
            Command(heading, 2.0), wall(distance), state, replace(limits, response=tau)
        )
        return math.hypot(told[0].heading - (last if bound else heading), told[0].speed)

    d.spot_check(
        "library_failed_check_brakes_along_last_heading",
        lambda heading, last, tau: governed(heading, last, tau, 1.8, 0.55),
        lambda heading, last, tau: 0.0,
        [(1.0, 0.3, 0.0), (0.0, -0.2, 0.05), (-0.5, 0.0, 0.1)],
        "when not even braking fits in the planner's fan, govern commands speed 0 along the "
        "last heading it let through",
        abs_tol=0.0,
        reason="the governor copies the heading",
    )
    d.spot_check(
        "library_standing_turns_in_place",
        lambda heading, last, tau: governed(heading, last, tau, 0.0, limits.radius),
        lambda heading, last, tau: 0.0,
        [(1.0, 0.0, 0.0), (-2.0, 0.5, 0.05), (3.0, -1.0, 0.1)],
        "at rest (bound 0, last command 0) with no room, govern lets the planner's turn through "
        "at speed 0",
        abs_tol=0.0,
        reason="the governor copies the heading",
    )
