"""The fan and the window of the braking derivation (``proofs/braking.py``): where the robot
may go until it stops, the margin :func:`ifgm_ref.planners.governor.fan_room` keeps, and which
commands the robot may still follow; the spot checks of the governor's code, and where the
proof stops.

Helpers that :func:`proofs.braking.build` calls, in its order; they add their claims to the
one derivation ``braking``. Not a derivation of its own.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import replace
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp
from sympy.calculus.util import function_range

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, Observation
from ifgm_ref.planners import governor as gov
from ifgm_ref.planners.governor import GovernorState, Limits
from proofs._util import Derivation, held_eq

__all__ = [
    "fan_cone",
    "fan_edge",
    "fan_margin",
    "headings",
    "library",
    "library_fan_room",
    "library_headings",
    "margin_odometry",
    "wall",
    "window",
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
        present heading, the command's, the last command's, and the present heading turned on at the
        last period's rate for max(tau, eps), from state.theta, the heading at the last decision: a
        robot that brakes while it turns may carry its turn past the command, which the model of the
        turn assumes it does no faster than it turned): for tau <= eps the robot turns for tau
        towards the last command's heading, then towards the new one, and a short turn between
        headings of a fan narrower than pi stays in it (a wider fan is all the plane). The stop from
        the next decision starts at a heading in this fan and turns towards the command just given,
        in it too, for tau; the governor's fallback (speed 0 when not even braking fits in the
        planner's fan) keeps to that heading after tau too. For tau > eps the robot may also turn
        towards the earlier commands' headings, which the fan does not hold (state.earlier keeps
        their speeds only): the path keeps to the fan where they lie in it, as on a straight run. At
        rest (rest_rule, below) it turns in place, sweeping nothing.
        """
    )


def window(d: Derivation) -> None:
    """Which commands the robot may still follow for ``tau`` after a decision."""
    k, x, z = sp.Symbol("k", integer=True), *sp.symbols("x z", positive=True)
    oldest, newest = sp.floor(k - x), sp.floor(k - z)
    first = oldest.rewrite(sp.ceiling) - (k - sp.ceiling(x))
    last = (k - 1 - newest).rewrite(sp.ceiling)
    d.text(
        """
        Which commands are in effect: c_j takes effect at t_j + tau at the latest (sooner only if
        it is no faster) and gives way to c_{j+1} at t_{j+1} + tau at the latest. So at an instant t
        of [t_k, t_k + tau) the robot follows c_j, j = floor((t - tau)/eps), the command in effect
        at t - tau, or a newer one no faster; t - tau runs over [t_k - tau, t_k), so with x =
        tau/eps > 0 the index j runs from floor(k - x) to floor(k - z) for some z > 0:
        """
    )
    d.prove_true(
        "window_holds_the_commands_in_effect",
        sp.And(sp.Eq(sp.simplify(first), 0), sp.simplify(last) >= 0),
        "floor(k - x) = k - ceil(x) and floor(k - z) = k - ceil(z) <= k - 1: for tau after t_k "
        "the robot follows one of c_{k - ceil(tau/eps)}, ..., c_{k-1} or a command no faster, "
        "ceil(tau/eps) of them: the last (state.speed) and the ceil(tau/eps) - 1 before it that "
        "next_state keeps (state.earlier: none for tau <= eps); state.following is the fastest",
        shown=sp.And(
            sp.Eq(sp.floor(k - x, evaluate=False), k - sp.ceiling(x), evaluate=False),
            sp.LessThan(sp.floor(k - z, evaluate=False), k - 1, evaluate=False),
            evaluate=False,
        ),
    )
    _long_period(d)


def _long_period(d: Derivation) -> None:
    """``next_state``'s bound over a period no longer than the response time."""
    u, c = sp.symbols("u c", nonnegative=True)
    a, b, eps, y, w = sp.symbols("A b epsilon y w", positive=True)
    d.text(
        """
        (Before the first decision the robot stands: the commands it never had are 0.) With tau >=
        eps the period lies in [t_k, t_k + tau): the speed at t_{k+1} is at most the worst case's
        end over eps towards c_0. next_state ramps for min(tau, eps) towards state.following, then
        for eps - min(tau, eps) = 0 towards the new command: _ramp's ramp is then min(0, (c -
        u)/rate) = 0, up (c = u + w, rate A) or down (c = u - w, rate -b), w > 0:
        """
    )
    rest, rows = eps - sp.Min(eps + y, eps), []
    for rate, target in ((a, u + w), (-b, u - w)):
        ramp = sp.Min(rest, (target - u) / rate)
        rows += [u * ramp + rate * ramp**2 / 2 + (u + rate * ramp) * (rest - ramp), u + rate * ramp]
    d.prove_equal(
        "next_state_with_long_response",
        sp.Matrix([rest, *rows]),
        sp.Matrix([0, 0, u, 0, u]),
        "with tau = eps + y, eps - min(tau, eps) = 0, and _ramp over it travels 0 and ends at "
        "u: next_state's bound is the worst case's end over the period towards state.following",
        shown=sp.And(
            sp.Eq(eps - sp.Function("min")(eps + y, eps), 0, evaluate=False),
            sp.Eq(sp.Function("ramp")(u, c, 0), sp.Tuple(0, u), evaluate=False),
            evaluate=False,
        ),
    )
    d.text(
        """
        And the window moves on: next_state keeps c_k as state.speed and the ceil(tau/eps) - 1
        commands before it in state.earlier, the window of decision k + 1.
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
        [(1.0, 0.0, 0.0), (-2.0, 0.5, 0.05), (3.0, -1.0, 0.1), (1.5, 0.2, 0.25)],
        "at rest (bound 0, last command 0) with no room, govern lets the planner's turn through "
        "at speed 0",
        abs_tol=0.0,
        reason="the governor copies the heading",
    )


def _carried_room(rho: float, angle: float, turn: float, tau: float) -> float:
    """``_room`` for a robot facing 0, commanded 0 as before, that turned ``turn`` in the last
    period, with one point at ``rho``, ``angle``."""
    scan = LaserScan(angle, angle + 1.0, 1.0, 0.0, 10.0, [rho, math.inf])
    seen = Observation(0.0, Pose(0.0, 0.0, 0.0), Point(20.0, 0.0), scan)
    state = GovernorState(1.0, 0.0, 1.0, (), -turn)
    return gov._room(0.0, seen, state, replace(LIMITS, response=tau))


def _library_carried_turn(d: Derivation, limits: Limits = LIMITS) -> None:
    """Spot check of the fan's carried turn."""

    def proved(rho: float, angle: float, turn: float, tau: float) -> float:
        carried = turn * max(1.0, tau / limits.period)
        room = _touch(rho, angle, min(0.0, carried), max(0.0, carried), limits.radius)
        return min(room, 10.0 - limits.radius)

    d.spot_check(
        "library_fan_holds_the_carried_turn",
        _carried_room,
        proved,
        _table("1 .25 .3 0, 1 .25 .1 0, 1 .25 .1 .25, 1 -.4 -.15 .2, 2 .6 .1 .1, 1 .25 0 .3"),
        "a robot that turned w in the last period, facing its command, has the room of the fan "
        "from its heading to w max(1, tau/eps) beyond it (a point the command's fan alone "
        "would pass is met), within the sensor's range",
        abs_tol=1e-12,
        reason="the point's polar angle recovered by arctan2: ulps",
    )


def _library_rest_rule(d: Derivation, limits: Limits = LIMITS) -> None:
    """Spot check of the rest rule: a robot that may still move keeps the last heading."""

    def governed(tau: float, steps: float) -> float:
        late, state = replace(limits, response=tau), GovernorState()
        for _ in range(int(steps)):  # from rest, commands of 0.2 along 0.3
            state = gov.next_state(state, 0.3, 0.2, late)
        told = gov.govern(Command(-1.0, 2.0), wall(limits.radius), state, late)[0]
        return math.hypot(told.heading - 0.3, told.speed)

    d.spot_check(
        "library_fallback_keeps_heading_while_moving",
        governed,
        lambda tau, steps: 0.0,
        [(0.1, 1.0), (0.05, 1.0), (0.25, 1.0), (0.25, 3.0), (0.15, 2.0)],
        "with no room, a robot that may still move (stopping_distance(state, 0) > 0) brakes "
        "along the last heading: after a first command from rest with tau = eps (speed bound 0, "
        "the command in effect: the case left open before), or 1 to 3 with tau 0.5 to 2.5 eps",
        abs_tol=0.0,
        reason="the governor copies the heading",
    )


#: The proved worst case over ``t`` from ``u`` towards ``c`` (``proofs.braking``): travel, end.
Worst = Callable[[float, float, float, Limits], tuple[float, float]]


def _table(rows: str) -> list[tuple[float, ...]]:
    """Sample points written ``"1 0 0.5, 2 0 0"``."""
    return [tuple(float(x) for x in row.split()) for row in rows.split(",")]


def _code(u: float, c0: float, e: float, tau: float, *command: float) -> tuple[Any, ...]:
    """State (bound ``u``, last command ``c0``, earlier ``e``), ``command``, LIMITS with ``tau``."""
    return GovernorState(u, 0.0, c0, (e,)), *command, replace(LIMITS, response=tau)


def _library_formulas(d: Derivation, worst: Worst) -> None:
    """Spot checks of ``stopping_distance`` and ``safe_speed`` against the proved forms."""

    def stop(u: float, c0: float, e: float, tau: float, c: float) -> float:
        """The tau-stretch towards the fastest command in effect, a period towards c, braking."""
        late, u1 = worst(u, max(c0, e), tau, LIMITS)
        travel, end = worst(u1, c, LIMITS.period, LIMITS)
        return late + travel + end**2 / (2 * LIMITS.braking)

    d.spot_check(
        "library_stopping_distance_pieces",
        lambda u, c0, e, tau, c: gov.stopping_distance(*_code(u, c0, e, tau, c)),
        stop,
        _table("1 0 0 0 0, 1 0 0 0 .8, 1 0 0 0 1.1, 1 0 0 0 2, 0 0 0 0 0, 1.9 0 0 0 2.5")
        + _table("1.8 0 0 .25 0, 1.95 0 0 0 .1, 1 1 0 .05 0, 1 1 0 .05 .8, 1 1 0 .05 2")
        + _table(".5 1.5 0 .05 0, .5 1.5 0 .05 .8, .5 1.5 0 .05 2, 1 1.05 0 .05 0, 1 1.05 0 .05 2")
        + _table("1.5 0 0 .1 0, 1.5 0 0 .1 .8, 1.5 0 0 .1 2, 1 .9 0 .1 2.5, 0 .2 0 .1 .2")
        + _table("1 .5 1.2 .25 0, 0 .2 0 .15 .2, 1 .5 1.2 .25 .8, 1 .5 1.2 .25 2, .5 0 .4 .15 2")
        + _table("0 0 .2 .25 .2, 1.5 1 0 .3 0, 1 1.5 .5 .25 1"),
        "stopping_distance(state, c) = the tau-stretch towards state.following (the last command "
        "or an earlier one still in effect), then a period towards c from where it ends, then "
        "braking, each in its proved form (braking, slowing down, speeding up, (M))",
        abs_tol=1e-12,
        reason="the same formulas, the travel summed piece by piece: ulps of distances below 1",
    )
    d.spot_check(
        "library_safe_speed_is_root",
        lambda room, u, c0, e, tau: stop(
            u, c0, e, tau, gov.safe_speed(room, *_code(u, c0, e, tau)) or 0
        ),
        lambda room, u, c0, e, tau: room,
        _table("0.13 1 0 0 0, 0.2 1 0 0 0, 0.26 1 0 0 0, 0.01 0 0 0 0, 0.5 1.7 0 0 0")
        + _table("0.2 1 1 0 0.05, 0.15 0.5 1.5 0 0.05, 0.2 1 0 0 0.1, 0.5 1 .5 1.2 .25")
        + _table("0.6 1 .5 1.2 .25, 0.12 .5 0 .4 .15, 0.06 0 0 .2 .25"),
        "the proved stopping distance of safe_speed(d, state) is d, between that of 0 and of V",
        abs_tol=1e-12,
        reason="a square root and its square: ulps of d",
    )
    d.spot_check(
        "library_no_speed_when_braking_does_not_fit",
        lambda room, u, c0, e, tau: float(gov.safe_speed(room, *_code(u, c0, e, tau)) is None),
        lambda room, u, c0, e, tau: float(stop(u, c0, e, tau, 0.0) > room),
        _table("0.1 1 0 0 0, 0.13 1 0 0 0, 0 0 0 0 0, 0.4 1.8 0 0 0, 0.41 1.8 0 0 0")
        + _table("0.17 1 1 0 0.05, 0.18 1 1 0 0.05, 0 0 0.2 0 0.1, 0.01 0 0.2 0 0.1")
        + _table("0.02 0 0.2 0 0.1, 0.4 1 .5 1.2 .25, 0.5 1 .5 1.2 .25, 0.01 0 0 .2 .25"),
        "safe_speed is None exactly when the tau-stretch and braking, late + u_1^2/(2b), exceed "
        "the room",
        abs_tol=0.0,
        reason="a yes or no",
    )


def _window_missed(tau: float, eps: float) -> float:
    """How many of the last ``ceil(tau/eps)`` of ten commands (at least one) ``next_state`` does
    not keep, plus 1 if it keeps another number (``tau/eps`` exact, from the decimals)."""
    limits, sent = replace(LIMITS, period=eps, response=tau), [0.1 * (j + 1) for j in range(10)]
    state, n = GovernorState(), math.ceil(Fraction(str(tau)) / Fraction(str(eps)))
    for c in sent:
        state = gov.next_state(state, 0.0, c, limits)
    kept, wanted = (*state.earlier, state.speed), sent[len(sent) - max(n, 1) :]
    return float(len(kept) != len(wanted)) + sum(a != b for a, b in zip(kept, wanted, strict=False))


def _library_next_state(d: Derivation, worst: Worst) -> None:
    """Spot checks of ``next_state``: its bound, and the window of commands it keeps."""

    def bound(u: float, c0: float, e: float, tau: float, c: float) -> float:
        """The worst case's end: over eps towards the fastest in effect, or tau, then c."""
        eps, fastest = LIMITS.period, max(c0, e)
        if tau >= eps:
            return worst(u, fastest, eps, LIMITS)[1]
        return worst(worst(u, fastest, tau, LIMITS)[1], c, eps - tau, LIMITS)[1]

    d.spot_check(
        "library_next_state",
        lambda u, c0, e, tau, c: gov.next_state(*_code(u, c0, e, tau, 0.0, c)).speed_bound,
        bound,
        _table("0 0 0 0 2, 1 1 0 0 0, 1 1 0 0 0.9, 1 1 0 0 1.1, 1.9 1.9 0 0 2.5, 1 2 0 0.05 0")
        + _table("0.5 0 0 0.05 2, 0 0.2 0 0.1 2, 0 .2 0 .25 2, 1 .5 1.5 .25 0, 1.5 0 0 .15 2")
        + _table(".5 .2 .8 .3 0, 1 1.2 .6 .15 .2"),
        "next_state's bound = the worst case's end: tau towards the fastest command in effect, "
        "then eps - tau towards the new one; for tau >= eps the whole period towards the former",
        abs_tol=1e-12,
        reason="a sum of two floats each way",
    )
    d.spot_check(
        "library_window_kept",
        _window_missed,
        lambda tau, eps: 0.0,
        _table("0 .1, .05 .1, .1 .1, .15 .1, .25 .1, .3 .1, .08 .05, .25 .05, .2 .05"),
        "after ten commands next_state keeps the last ceil(tau/eps): the last (state.speed) and "
        "ceil(tau/eps) - 1 before it (state.earlier; the last alone for tau = 0)",
        abs_tol=0.0,
        reason="a count",
    )


def _delay_line(tau: float, eps: float) -> tuple[int, float]:
    """``n = ceil(tau/eps)`` (exact) and how long from a decision ``c_{k-n}`` stays in effect."""
    steps = Fraction(str(tau)) / Fraction(str(eps))
    return math.ceil(steps), float(steps - math.ceil(steps) + 1) * eps


def _stop_of_delay_line(u: float, sent: list[float], lim: Limits, worst: Worst) -> float:
    """The stop from a decision of the delay-line robot ``u`` fast: the commands still in
    effect and the last of ``sent`` (issued now), each in turn, then braking."""
    n, first = _delay_line(lim.response, lim.period)
    k, travel = len(sent) - 1, 0.0
    for j in range(k - n, k + 1):
        step, u = worst(u, sent[j] if j >= 0 else 0.0, first if j == k - n else lim.period, lim)
        travel += step
    return travel + u**2 / (2 * lim.braking)


def _approach(distance: float, top: float, braking: float, tau: float, worst: Worst
              ) -> tuple[float, int, int]:  # fmt: skip
    """The delay-line robot (``A`` up, exactly ``b`` down) governed 200 periods towards a wall:
    its least clearance, the commands admissible rejects, and those of them not the fallback
    along the last heading whose stop (:func:`_stop_of_delay_line`) fits in the room."""
    lim = Limits(0.2, top, braking, 2.0, 0.1, tau)
    n, first = _delay_line(tau, lim.period)
    x, speed, state, sent = 0.0, 0.0, GovernorState(), []
    gap, rejected, unfit = math.inf, 0, 0
    for k in range(200):
        seen = wall(distance, x)
        command, after = gov.govern(Command(0.0, top), seen, state, lim)
        fits, _, room = gov.admissible(command, seen, state, lim)
        sent.append(command.speed)
        fallback = command.speed == 0.0 and command.heading == state.heading
        stops = _stop_of_delay_line(speed, sent, lim, worst) <= room
        rejected, unfit = rejected + (not fits), unfit + (not fits and not (fallback and stops))
        for j in range(k - n, k - n + 2 if first < lim.period else k - n + 1):  # delay line
            t = first if j == k - n else lim.period - first
            step, speed = worst(speed, sent[j] if j >= 0 else 0.0, t, lim)
            x += step
        state, gap = after, min(gap, distance - x - lim.radius)
    return gap, rejected, unfit


def _missed(worst: Worst, counted: int, distance: float, top: float, b: float, tau: float) -> float:
    """How near :func:`_approach`'s robot came to touching (<= 0), less the ``counted`` misses."""
    approach = _approach(distance, top, b, tau, worst)
    return min(0.0, approach[0]) - approach[counted]


def _library_governor(d: Derivation, worst: Worst) -> None:
    """Spot checks of ``govern`` in a closed loop: a robot driven at a wall never touches it."""
    walls = [(0.6, 2.0, 4.0), (1.5, 2.0, 4.0), (3.0, 2.0, 8.0), (6.0, 2.0, 8.0), (3.0, 2.0, 1.0)]
    more = [*walls, (2.2, 2.0, 1.0)]
    points = {
        "": [(*w, 0.0) for w in [*more, (1.0, 3.0, 0.5)]],
        "_responding_late": [(*w, t) for w in walls for t in (0.05, 0.1)],
        "_steps_late": [(*w, t) for w in more for t in (0.25, 0.16)],
    }
    said = {
        "": "at once",
        "_responding_late": "tau = 0.05 or eps = 0.1 late (the last command until then)",
        "_steps_late": "tau = 2.5 or 1.6 periods late (the command issued floor(tau/eps) or "
        "ceil(tau/eps) periods before: a delay line)",
    }
    but = ", but the fallback along the last heading whose stop (the rest of the delay line from "
    but += "the robot's speed, then braking) fits in admissible's room"
    for name, samples in points.items():
        d.spot_check(
            f"library_governed_robot{name}_never_touches",
            functools.partial(_missed, worst, 2 if name == "_steps_late" else 1),
            lambda distance, top, b, tau: 0.0,
            samples,
            f"the extreme robot (A up, exactly b down) that follows each command {said[name]}, "
            "governed while its planner asks for the top speed towards a wall, ends no nearer to "
            "it than its radius, and admissible accepts every command"
            + (but if name == "_steps_late" else ""),
            abs_tol=1e-12,
            reason="200 periods of travel summed",
        )


def _where_it_stops(d: Derivation) -> None:
    """Prose: what the proof does not cover."""
    d.text(
        """
        Where the proof stops: obstacles outside the sensor's field of view or range (the IR
        sensor's 135 degrees cannot see beside the robot, where a sharp turn's fan reaches) or
        between two rays; moving obstacles; a deceleration below b (a skidding wheel, load moved off
        its driven wheels: the MuJoCo Jackal's b is chosen for that, docs/physics.md); a robot that
        takes up a faster command sooner than tau after it is issued (a response anywhere within
        tau, a lag that starts at once): for tau the governor counts only the commands before it
        (state.following), and for tau >= eps its bound after the period leaves it out (the
        simulator's latency, a delay line, is in the model; a servo's response only as far as
        docs/physics.md measures its stops); other actuation beyond the model (a speed noise factor
        above 1); a heading controller that carries its turn farther than the last period's rate for
        max(tau, eps) (library_fan_holds_the_carried_turn), and for tau > eps a turn while earlier
        commands in effect head outside the fan; a tau within 1e-9 periods above n eps (next_state
        keeps n commands, not n + 1). For tau > eps admissible (the oracle's monitor) may reject the
        governor's fallback, safe as it is (the closed loop steps late, above). And it is for the
        disc: a box-shaped robot is covered by the disc that circumscribes it.
        """
    )


def library(d: Derivation, worst: Worst) -> None:
    """The spot checks of the code, against the proved ``worst`` case, and where the proof stops."""
    _library_formulas(d, worst)
    _library_next_state(d, worst)
    for check in (library_fan_room, library_headings, _library_carried_turn, _library_rest_rule):
        check(d)
    _library_governor(d, worst)
    _where_it_stops(d)
