"""The braking governor keeps a robot passively safe: it never drives into an obstacle it sees.

Claim: a robot governed by :func:`ifgm_ref.planners.governor.govern` stands still before its
disc touches any obstacle point it has seen, whatever the planner commands: passive safety as in
Mitsch, Ghorbal, Vogelbacher & Platzer, IJRR 36(12):1312-1340, 2017, Theorem 1, for a robot told
a speed that follows each command within its response time ``tau >= 0``, a period or longer
(the model: the derivation's first paragraph; the fan's geometry and the spot checks of
``govern``: ``proofs/braking_fan.py``). The ``library_*`` claims are numeric spot checks of the
code; every other claim is proved. Run ``python -m proofs.braking`` to read it.
"""

from __future__ import annotations

import functools
from collections.abc import Callable

import sympy as sp

from ifgm_ref.core.elements import traces
from ifgm_ref.planners.governor import Limits
from proofs import braking_fan as fan
from proofs._util import Derivation, entry_points

__all__ = ["build", "claims", "derivation", "main", "mitsch_bound", "pieces", "stretch"]

#: The speed bound, the command, a time, the fastest command in effect (``following``), tau.
U, C, T, C0, TAU = sp.symbols("u c t c_0 tau", nonnegative=True)
#: Top speed, largest acceleration, guaranteed braking, control period.
V, A, B, EPS = sp.symbols("V A b epsilon", positive=True)
#: The robot of the spot checks (its response time varies).
LIMITS = fan.LIMITS
#: The names of the four forms of a stretch (:func:`stretch`).
UP_REACHING, UP, DOWN_REACHING, DOWN = "up, reaching", "up", "down, reaching", "down"


def mitsch_bound(u: sp.Expr) -> sp.Expr:
    """Mitsch et al.'s stopping distance (M): a period at ``A``, then braking at ``b``."""
    return u**2 / (2 * B) + (A / B + 1) * (A * EPS**2 / 2 + EPS * u)


def pieces(u: sp.Expr, c: sp.Expr) -> tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]:
    """The stopping distance from ``u`` commanded ``c``, no response time, on its four pieces:
    ``c <= u - b eps``, ``u - b eps <= c <= u``, ``u <= c <= u + A eps``, ``c >= u + A eps``."""
    return (
        u**2 / (2 * B),
        c * EPS + (u - c) ** 2 / (2 * B) + c**2 / (2 * B),
        c * EPS - (c - u) ** 2 / (2 * A) + c**2 / (2 * B),
        mitsch_bound(u),
    )


def stretch(u: sp.Expr, c: sp.Expr, t: sp.Expr) -> dict[str, tuple[sp.Expr, sp.Expr]]:
    """The worst case's travel and end speed over ``t`` from ``u`` towards ``c``: up at ``A``
    reaching ``c`` (``c - u <= A t``) or not, down at ``b`` reaching it or not."""
    return {
        UP_REACHING: (c * t - (c - u) ** 2 / (2 * A), c),
        UP: (u * t + A * t**2 / 2, u + A * t),
        DOWN_REACHING: (c * t + (u - c) ** 2 / (2 * B), c),
        DOWN: (u * t - B * t**2 / 2, u - B * t),
    }


def _flat(forms: dict[str, tuple[sp.Expr, sp.Expr]]) -> sp.Matrix:
    return sp.Matrix([x for pair in forms.values() for x in pair])


def _nonnegative(*exprs: sp.Expr) -> tuple[sp.Basic, sp.Basic]:
    """``expr >= 0`` for every expr (expanded), as sympy evaluates it, and as it is shown."""
    expanded = [sp.expand(e) for e in exprs]
    shown = [sp.GreaterThan(e, 0, evaluate=False) for e in expanded]
    return sp.And(*(e >= 0 for e in expanded)), sp.And(*shown, evaluate=False)


def _limit(d: Derivation, name: str, expr: sp.Expr, label: str, to: sp.Expr) -> None:
    """Prove ``expr -> to`` as ``b -> oo``, then ``A -> oo`` too when ``label`` has ``V``."""
    value, shown = sp.limit(expr, B, sp.oo), sp.Limit(sp.Symbol(label) if label else expr, B, sp.oo)
    if "V" in label:
        value, shown = sp.limit(value, A, sp.oo), sp.Limit(shown, A, sp.oo)
    said = f"{label or expr} -> {to} as b -> oo" + (", then A -> oo" if "V" in label else "")
    said = said.replace("epsilon", "eps").replace("**", "^")
    d.prove_equal(name, value, to, said, shown=sp.Eq(shown, to))


def _kinematics(d: Derivation) -> None:
    d.text(
        """
        The model: static obstacles, all the robot may sweep seen in the scan (field of view,
        range); a disc of radius r deciding at the start of each period eps (command c_k at t_k =
        k eps); a robot that follows each command within its response time tau >= 0, a period or
        longer too (Limits.response: the robot's response plus its latency in steps): at any
        instant t it follows one of the commands of the last tau seconds (the one in effect at t
        - tau, or a newer one), none faster than the one in effect at t - tau (a command that
        speeds it up takes effect tau after it is issued, as with the simulator's latency, a delay
        line; one that slows it down may take effect sooner); speed in [0, V];
        acceleration at most A > 0; commanded slower, deceleration at least b > 0 until it reaches
        the command; never faster than the larger of its speed and the command; headings turned
        the short way round without overshoot; odometry off by at most e_odo. It is the model of
        Mitsch et al.'s Theorem 1 (machine-checked in KeYmaera X, robix.kyx), told a speed capped
        at V, with a response time and a fan of headings for any curve in place of its arcs.
        """
    )
    d.prove_equal(
        "braking_distance",
        sp.integrate(U - B * T, (T, 0, U / B)),
        U**2 / (2 * B),
        "braking at b from u stops after u/b, having travelled u^2/(2b)",
    )
    d.text(
        """
        With no response time the worst period commanded c <= V moves from the speed bound u
        towards c as hard as allowed, then brakes. Accelerating throughout (u + A eps <= c), that
        is Mitsch et al.'s bound (M):
        """
    )
    d.define("M(u)", mitsch_bound(U))
    d.prove_equal(
        "mitsch_bound",
        sp.integrate(U + A * T, (T, 0, EPS)) + (U + A * EPS) ** 2 / (2 * B),
        mitsch_bound(U),
        "a period at A from u, then braking: u^2/(2b) + (A/b + 1)(A eps^2/2 + eps u)",
    )
    _response(d)


def _response(d: Derivation) -> None:
    late, u1 = stretch(U, C0, TAU)[UP]
    up, down = (C0 - U) / A, (U - C0) / B
    d.text(
        """
        For tau after a decision the robot may still follow commands issued before it, none
        faster than c_0 = state.following (the last for tau <= eps; the window: below). The worst
        case of that stretch moves from u towards c_0 as hard as allowed (at every instant the
        robot is no faster: bound_when_* below): up at A, reaching c_0 at (c_0 - u)/A or not
        within tau; down at b, likewise.
        """
    )
    rows = []  # the profile u + A t or u - b t until c_0 or tau, then c_0 until tau
    for v, until in ((U + A * T, up), (U + A * T, TAU), (U - B * T, down), (U - B * T, TAU)):
        rows += [sp.integrate(v, (T, 0, until)) + C0 * (TAU - until), v.subs(T, until)]
    d.prove_equal(
        "response_stretch",
        sp.Matrix(rows),
        _flat(stretch(U, C0, TAU)),
        "the tau-stretch from u towards c_0 travels c_0 tau - (c_0 - u)^2/(2A) and ends at c_0 "
        "(reaching it), or u tau + A tau^2/2 and ends at u + A tau (up); c_0 tau + (u - c_0)^2/"
        "(2b) ending at c_0, or u tau - b tau^2/2 ending at u - b tau (down)",
    )
    rate, ramp = sp.symbols("rate ramp", real=True)
    end = U + rate * ramp
    code = sp.Matrix([U * ramp + rate * ramp**2 / 2 + end * (T - ramp), end])
    cases = [(A, (C - U) / A), (A, T), (-B, (C - U) / -B), (-B, T)]
    d.prove_equal(
        "ramp_formula",
        sp.Matrix([code.subs({rate: r, ramp: k}) for r, k in cases]),
        _flat(stretch(U, C, T)),
        "_ramp's travel u ramp + rate ramp^2/2 + end (t - ramp) and end u + rate ramp, with "
        "ramp = min(t, (c - u)/rate), rate = A or -b, is that worst case over any t (tau, "
        "eps - min(tau, eps), eps)",
    )
    d.text(
        """
        stopping_distance(state, c) = late + the piece of c (below) at the speed u_1 the tau-stretch
        ends at. Accelerating throughout, that is tau + eps at A, then braking: (M) with eps + tau
        for eps, and (M) itself when tau = 0:
        """
    )
    whole = sp.integrate(U + A * T, (T, 0, TAU + EPS)) + (U + A * (TAU + EPS)) ** 2 / (2 * B)
    longer = mitsch_bound(U).subs(EPS, EPS + TAU)
    d.prove_equal(
        "stopping_distance_with_response",
        sp.Matrix([whole, late + mitsch_bound(u1), (late + mitsch_bound(u1)).subs(TAU, 0)]),
        sp.Matrix([longer, longer, mitsch_bound(U)]),
        "c_0 >= u + A tau, c >= u + A (tau + eps): u tau + A tau^2/2 + M(u + A tau) = M(u) with "
        "eps + tau for eps = the travel at A for tau + eps, then braking; at tau = 0, M(u)",
    )
    _period_pieces(d)


def _period_pieces(d: Derivation) -> None:
    p1, p2, p3, _ = pieces(U, C)
    rise, fall = (C - U) / A, (U - C) / B
    d.text("The period from u (= u_1), reaching c at t_c, then holding it, then braking:")
    d.prove_equal(
        "speeding_up_period",
        sp.integrate(U + A * T, (T, 0, rise)) + C * (EPS - rise) + C**2 / (2 * B),
        p3,
        "u <= c <= u + A eps: c eps - (c - u)^2/(2A) + c^2/(2b); c = V is the top speed's cap",
    )
    d.prove_equal(
        "slowing_down_period",
        sp.integrate(U - B * T, (T, 0, fall)) + C * (EPS - fall) + C**2 / (2 * B),
        p2,
        "u - b eps <= c <= u: c eps + (u - c)^2/(2b) + c^2/(2b)",
    )
    d.prove_equal(
        "braking_period",
        U * EPS - B * EPS**2 / 2 + (U - B * EPS) ** 2 / (2 * B),
        p1,
        "c <= u - b eps: braking the whole period and on spends exactly u^2/(2b)",
    )


def _shape(d: Derivation) -> None:
    s, g, j, y = sp.symbols("s g j y", nonnegative=True)
    p1, p2, p3, p4 = pieces(U, C)
    joins = [(p1 - p2).subs(C, U - B * EPS), (p2 - p3).subs(C, U), (p3 - p4).subs(C, U + A * EPS)]
    d.text("The four pieces join where they meet:")
    d.prove_equal(
        "continuous_pieces",
        sp.Matrix(joins),
        sp.zeros(3, 1),
        "at c = u - b eps, c = u and c = u + A eps",
    )
    d.text("Reaching c (or the top speed) only tightens (M): let c = u + s, u + A eps = c + g:")
    gain = g**2 / (2 * A) + g * (2 * (U + s) + g) / (2 * B)
    d.prove_equal(
        "cap_only_tightens",
        (p4 - p3).subs({C: U + s, EPS: (s + g) / A}),
        gain,
        "M(u) - stopping_distance(u, c) = g^2/(2A) + g (2c + g)/(2b), g = u + A eps - c",
    )
    d.prove_sign("cap_only_tightens_sign", gain, "nonnegative", "so it is at most M(u)")
    d.text(
        """
        It grows with c: the outer pieces are constant; on the inner ones write u - c = b (eps - j),
        and c - u = A (eps - j), with j in [0, eps]:
        """
    )
    slope, inner = j + C / B, (sp.diff(p2, C), sp.diff(p3, C))
    d.prove_equal(
        "increasing_in_command",
        sp.Matrix([inner[0].subs(U, C + B * (EPS - j)), inner[1].subs(U, C - A * (EPS - j))]),
        sp.Matrix([slope, slope]),
        "d/dc = j + c/b on both inner pieces",
    )
    d.prove_sign("increasing_in_command_sign", slope, "nonnegative", "which is >= 0")
    forms = stretch(U, C0, TAU)
    grows, shown = _nonnegative(
        sp.diff(p1, U),
        sp.diff(p2, U).subs(U, C + y),
        sp.diff(p3, U).subs(U, C - y),
        sp.diff(p4, U),
        *(sp.diff(x, U).subs(C0, U + y) for x in forms[UP_REACHING]),
        *(sp.diff(x, U) for x in forms[UP]),
        *(sp.diff(x, U).subs(U, C0 + y) for x in forms[DOWN_REACHING]),
        *(sp.diff(x, U) for x in forms[DOWN]),
    )
    d.prove_true(
        "increasing_in_speed",
        grows,
        "and with the speed: d/du = u/b, (u - c)/b, (c - u)/A, u/b + (A/b + 1) eps on the pieces; "
        "the tau-stretch's travel and end: (c_0 - u)/A and 0, tau and 1, (u - c_0)/b and 0, tau "
        "and 1; each >= 0 on its piece (u - c = y >= 0, c - u = y >= 0)",
        shown=shown,
    )


def _safe_speed(d: Derivation) -> None:
    a, p, q = sp.symbols("a p q", real=True)
    n, k, s = sp.symbols("n k s", nonnegative=True)
    pp, pa = sp.symbols("p a", positive=True)
    room = sp.Symbol("d", positive=True)
    _, p2, p3, _ = pieces(U, C)
    root = sp.sqrt(p**2 - 4 * a * q)
    plus, minus = -2 * q / (p + root), (root - p) / (2 * a)
    d.text(
        """
        safe_speed(d, state): a command fits in d when its piece at u_1 fits in d - late. The
        largest is V, or the root of piece = d - late on its piece (speeding up if c = u_1 fits,
        else slowing down), or None if not even late + u_1^2/(2b), the least of all, fits. _root
        takes the root of a c^2 + p c + q where it rises, as the stopping distance does, in two
        forms: -2q/(p + s) where p > 0, (s - p)/(2a) where p <= 0, s = sqrt(p^2 - 4 a q):
        """
    )
    value, slope = (lambda c: a * c**2 + p * c + q), (lambda c: 2 * a * c + p)
    d.prove_equal(
        "root_of_quadratic",
        sp.Matrix([value(plus), slope(plus), value(minus), slope(minus), plus - minus]),
        sp.Matrix([0, root, 0, root, 0]),
        "both forms are roots, the same one, where the slope 2 a c + p is s >= 0",
    )
    grows, shown = _nonnegative((-2 * q / (pp + s)).subs(q, -n), ((s - p) / (2 * pa)).subs(p, -k))
    d.prove_true(
        "root_has_no_cancellation",
        grows,
        "with q = -n <= 0: 2n/(p + s) for p > 0, (s + k)/(2a) for p = -k <= 0 (a > 0 there): "
        "every sum is of nonnegative terms, so nothing cancels, and the root is >= 0",
        shown=shown,
    )
    up = (1 / B - 1 / A) / 2 * C**2 + (EPS + U / A) * C - U**2 / (2 * A)
    down = C**2 / B + (EPS - U / B) * C + U**2 / (2 * B)
    d.prove_equal(
        "code_quadratics",
        sp.Matrix([p3 - room, p2 - room]),
        sp.Matrix([up - room, down - room]),
        "the code's coefficients, u the bound after tau and d the room less late: speeding up "
        "a = (1/b - 1/A)/2, p = eps + u/A > 0, q = -u^2/(2A) - d; slowing down a = 1/b > 0, "
        "p = eps - u/b, q = u^2/(2b) - d",
    )


def _speed_bound(d: Derivation) -> None:
    x, z, h, rise = sp.symbols("x z h t_c", nonnegative=True)
    a, bound = sp.symbols("a u_k", positive=True)
    d.text(
        """
        The governor keeps a bound u_k on the speed from its own commands (next_state), 0 at rest
        at the start. In a stretch towards a command c (the tau-stretch towards c_0, then the rest
        of the period, if any, towards the new command), let the speed be u_k - x (x >= 0) at
        its start. Commanded c >= u_k, it speeds up at a <= A (A = a + z) until it reaches c: at
        time t it has not (c = u + a (t + h)) or has, at t_c (t = t_c + h, ending at c):
        """
    )
    u0 = bound - x
    proof, shown = _nonnegative(
        u0 + a * (T + h) - (u0 + a * T),
        bound + (a + z) * T - (u0 + a * T),
        bound + (a + z) * (rise + h) - (u0 + a * rise),
    )
    d.prove_true(
        "bound_when_speeding_up",
        proof,
        "c >= u_k: the speed at every time t is <= c, and <= u_k + A t either way",
        shown=shown,
    )
    d.text(
        "Commanded c < u_k: above c it slows at beta = b + z until it reaches c (c = u - beta "
        "(t + h) if not yet); at or below c it stays so:"
    )
    slowed = u0 - (B + z) * T
    proof, shown = _nonnegative(bound - B * T - slowed, slowed - (u0 - (B + z) * (T + h)))
    d.prove_true(
        "bound_when_slowing_down",
        proof,
        "c < u_k: the speed at every time t is <= max(c, u_k - b t)",
        shown=shown,
    )
    _composition(d)


def _composition(d: Derivation) -> None:
    t1, t2 = sp.symbols("t_1 t_2", nonnegative=True)
    rows = []
    for reaching, plain, rate in ((UP_REACHING, UP, A), (DOWN_REACHING, DOWN, -B)):
        at = U + rate * t1  # where the first stretch ends when it does not reach c
        for first, second, whole in (
            (stretch(U, C, t1)[reaching], stretch(C, C, t2)[reaching], reaching),
            (stretch(U, C, t1)[plain], stretch(at, C, t2)[reaching], reaching),
            (stretch(U, C, t1)[plain], stretch(at, C, t2)[plain], plain),
        ):
            both = stretch(U, C, t1 + t2)[whole]
            rows += [first[0] + second[0] - both[0], second[1] - both[1]]
    d.text(
        """
        So for tau <= eps the bound after a period is the worst case's end: tau towards the last
        command, then eps - tau towards the new one (a longer tau: below). The worst case has no
        memory: over t_1, then over t_2 from where it ended, it is the worst case over t_1 + t_2:
        """
    )
    d.prove_equal(
        "ramp_composes",
        sp.Matrix(rows),
        sp.zeros(len(rows), 1),
        "towards the same c, the travels over t_1 and then t_2 add up to the travel over t_1 + "
        "t_2, and the ends agree (c reached within t_1, within t_1 + t_2, or not; up and down)",
    )


def _fastest(d: Derivation) -> None:
    y = sp.Symbol("y", nonnegative=True)
    forms = stretch(U, C, T)
    joins = [
        (forms[UP_REACHING], forms[UP], U + A * T),
        (forms[UP_REACHING], forms[DOWN_REACHING], U),
        (forms[DOWN_REACHING], forms[DOWN], U - B * T),
    ]
    d.text(
        """
        A response longer than a period. At any instant the robot follows one of the commands in
        effect, switching among them at any times; the fastest of them bounds its travel and its
        end speed, as the worst case grows with its target c. Its forms join where they meet:
        """
    )
    gaps = [(x - z).subs(C, at) for a, b, at in joins for x, z in zip(a, b, strict=True)]
    d.prove_equal(
        "ramp_continuous_in_target",
        sp.Matrix(gaps),
        sp.zeros(6, 1),
        "the travel and end of the forms agree at c = u + A t (up, reaching or not), c = u (up "
        "or down) and c = u - b t (down, reaching or not)",
    )
    grows, shown = _nonnegative(
        *(sp.diff(x, C).subs(C, U + A * T - y) for x in forms[UP_REACHING]),
        *(sp.diff(x, C) for x in forms[UP]),
        *(sp.diff(x, C).subs(C, U - B * T + y) for x in forms[DOWN_REACHING]),
        *(sp.diff(x, C) for x in forms[DOWN]),
    )
    d.prove_true(
        "ramp_increasing_in_target",
        grows,
        "and on each form d/dc of the travel and of the end is y/A and 1 (up, reaching: c = u + "
        "A t - y), 0 and 0 (up), y/b and 1 (down, reaching: c = u - b t + y), 0 and 0 (down), "
        "y >= 0: the worst case over any t grows with its target",
        shown=shown,
    )
    d.text(
        """
        So a robot whose target switches, at any instants, among commands no faster than c_0
        travels no farther and ends no faster than the worst case towards c_0: stretch by stretch,
        from a speed no higher (increasing_in_speed) towards a target no higher (above; min(c, V)
        keeps the order), and those worst stretches make up the worst case (ramp_composes).
        """
    )
    fan.window(d)


def _induction(d: Derivation) -> None:
    late, t1, t2, end, m, sigma = sp.symbols("l t_1 t_2 W m sigma", nonnegative=True)
    a = sp.Symbol("a", real=True)
    travel = U * EPS + a * EPS**2 / 2
    d.text(
        """
        Passive safety, by induction over the decisions. A robot below the bound needs no more
        (increasing_in_speed), and an admissible profile is below the worst at every instant, as
        speed and distance grow with the acceleration a in [-b, A]:
        """
    )
    d.prove_true(
        "profile_increases_with_acceleration",
        sp.And(sp.diff(travel, a) > 0, sp.diff(U + a * EPS, a) > 0),
        "the travel u eps + a eps^2/2 and the end speed u + a eps increase with a",
        shown=sp.And(sp.Derivative(travel, a) > 0, sp.Derivative(U + a * EPS, a) > 0),
    )
    d.text(
        """
        The invariant at decision k: the robot is no faster than u_k, the state holds the commands
        in effect (window_holds_the_commands_in_effect), and every path the robot may take if all
        commands from t_k on are speed 0 along state.heading -- the stop from here -- keeps its
        disc clear; at the start it stands. A decision whose room d in the fan holds the governed
        command's stopping distance (safe_speed's, or a slower one: increasing_in_command) has
        every path under that command, then the stop, clear; the robot takes one for the period,
        and the rest is the stop from the next decision. For tau <= eps: d = l + t_1 + t_2 +
        W^2/(2b) + m, m >= 0, where l is the tau-stretch's travel towards the last command and, by
        ramp_composes, the period towards c from where it ends is t_1 over eps - tau (ending at
        next_state's bound u') and t_2 over tau, ending at W. The period travels s = l + t_1 -
        sigma, sigma >= 0. The stop from the next decision (command 0) has its own tau-stretch,
        towards the command just given from u': t_2 again, ending at W; then it brakes from W
        (slowing_down_period at c = 0, or braking_period): W^2/(2b).
        """
    )
    room = late + t1 + t2 + end**2 / (2 * B) + m
    moved = late + t1 - sigma
    stops = [t2 + pieces(end, 0)[1], t2 + pieces(end, 0)[0]]
    d.prove_equal(
        "one_period_leaves_the_stop",
        sp.Matrix([room - moved - stop for stop in stops]),
        sp.Matrix([m + sigma, m + sigma]),
        "d - s - stopping_distance(next_state, 0) = m + sigma, whether W <= b eps or not",
    )
    said = "so the stop from the next decision still fits in the room the previous one checked"
    d.prove_sign("one_period_leaves_the_stop_sign", m + sigma, "nonnegative", said)
    _long_induction(d)


def _long_induction(d: Derivation) -> None:
    l1, l2, p, end, m, sigma = sp.symbols("l_1 l_2 p W m sigma", nonnegative=True)
    d.text(
        """
        For tau > eps: d = l_1 + l_2 + p + W^2/(2b) + m, m >= 0, where, by ramp_composes, the
        tau-stretch towards c_0 is l_1 over the period, ending at next_state's bound u'
        (next_state_with_long_response), and l_2 over the remaining tau - eps from u'; p is the
        period towards c from where that ends, ending at W. The period travels s = l_1 - sigma,
        sigma >= 0. The stop from the next decision follows the commands still in effect -- none
        faster than c_0 until t_k + tau, from a speed at most u': at most l_2 -- then c until
        t_{k+1} + tau (at most p, ending at most at W: increasing_in_speed), then brakes from W:
        """
    )
    room = l1 + l2 + p + end**2 / (2 * B) + m
    stops = [l2 + p + pieces(end, 0)[1], l2 + p + pieces(end, 0)[0]]
    d.prove_equal(
        "long_response_leaves_the_stop",
        sp.Matrix([room - (l1 - sigma) - stop for stop in stops]),
        sp.Matrix([m + sigma, m + sigma]),
        "d - s - (the stop from the next decision) = m + sigma >= 0, whether W <= b eps or not",
    )
    _rest_rule(d)


def _rest_rule(d: Derivation) -> None:
    c0, z, tau, y = sp.Symbol("c_0", positive=True), *sp.symbols("z tau y", positive=True)
    g, S = sp.Symbol("g", nonnegative=True), sp.Function("S")

    def count(u: sp.Expr, c: sp.Expr, t: sp.Expr, form: str) -> sp.Expr:
        """stopping_distance(state, 0): the tau-stretch, then braking (pieces at c = 0)."""
        travel, u1 = stretch(u, c, t)[form]
        return sp.expand(travel + u1**2 / (2 * B))

    moving = [count(0, c0, c0 / A + z, UP_REACHING), count(0, A * tau + z, tau, UP)]
    moving += [count(U + y, U + y + g, g / A + TAU, UP_REACHING), count(y, C, TAU, DOWN)]
    moving += [count(U + y, U + y + A * TAU + z, TAU, UP)]
    moving += [count(C + y, C, y / B + TAU, DOWN_REACHING)]
    still = [count(0, 0, TAU, UP_REACHING), count(0, c0, 0, UP)]
    d.text(
        """
        At rest. When not even braking fits (safe_speed None), the governor keeps the last heading
        while S = stopping_distance(state, 0) > 0 and lets the planner's turn through at speed 0
        only at S = 0: S bounds every path's travel, so the robot then turns in place. S, the
        tau-stretch towards c_0 then braking, is 0 exactly when nothing moves the robot: from u =
        0 with c_0 = 0 or tau = 0; positive from u = 0 with c_0 > 0 and tau > 0 (reaching c_0: tau
        = c_0/A + z; not: c_0 = A tau + z), and from u = y > 0 (up, reaching c = u + g or not;
        down, reaching c = u - y or not: u^2/(2b)):
        """
    )
    d.prove_true(
        "rest_rule",
        sp.And(*(e > 0 for e in moving), *(sp.Eq(e, 0) for e in still)),
        "stopping_distance(state, 0) = 0 exactly when the bound u = 0 and c_0 tau = 0: "
        "with tau = eps, a first command c > 0 from rest leaves u = 0 but c_0 = c, and the "
        "robot, still moving for tau, keeps its heading",
        shown=sp.And(
            *(sp.StrictGreaterThan(e, 0, evaluate=False) for e in moving[:2]),
            sp.Eq(S(0, 0, TAU), 0, evaluate=False),
            sp.Eq(S(0, c0, 0), 0, evaluate=False),
            evaluate=False,
        ),
    )
    _conclusion(d)


def _conclusion(d: Derivation) -> None:
    d.text(
        """
        So at the next decision, if not even braking fits in the planner's fan (safe_speed None;
        for tau > eps the next decision counts tau towards the fastest command in effect, c_k among
        them, more than the rest of the stop that fitted), the governor commands speed 0 along the
        heading it let through last: the stop from there, the rest of the one that fitted
        (one_period_leaves_the_stop, long_response_leaves_the_stop), each braking period spending
        exactly its share (braking_period); standing (rest_rule), it turns in place. Either way the
        invariant holds
        at the next decision, and the path from the last decision whose check held to the stand is
        no longer than its room, with headings in its fan, where the disc (widened by the margin
        for points ahead) meets no point of the scan. By induction the distance from the disc to
        every obstacle seen stays >= 0. admissible (the oracle's monitor) checks the same stop in
        the same fan from the disc alone, which leaves no less room (margin_only_shrinks_the_room).
        """
    )
    fan.margin_odometry(d)


def _paper_robot(d: Derivation) -> None:
    d.text(
        """
        The paper's robot stops at once (b infinite): the braking term vanishes, and govern returns
        every command unchanged (Limits.stops_at_once). What (M) still asks, one period's travel (V
        eps once A is infinite too; S: stopping_distance), is left to the planners' thresholds.
        """
    )
    _limit(d, "no_braking_term_at_infinite_b", U**2 / (2 * B), "", sp.Integer(0))
    _limit(d, "one_period_left_at_infinite_b", mitsch_bound(U), "M(u)", U * EPS + A * EPS**2 / 2)
    _limit(d, "one_period_at_top_speed_at_infinite_a", pieces(U, V)[2], "S(u, V)", V * EPS)


@functools.cache
def _forms() -> dict[str, Callable[..., tuple[float, float]]]:
    """The proved stretch forms, in ``u, c, t, A, b``."""
    return {key: sp.lambdify((U, C, T, A, B), f, "math") for key, f in stretch(U, C, T).items()}


def _worst(u: float, c: float, t: float, lim: Limits = LIMITS) -> tuple[float, float]:
    """The proved worst case over ``t`` from ``u`` towards ``c`` (capped at ``V``)."""
    c, a, b = min(c, lim.top_speed), lim.acceleration, lim.braking
    if c >= u:
        return _forms()[UP_REACHING if c - u <= a * t else UP](u, c, t, a, b)
    return _forms()[DOWN_REACHING if u - c <= b * t else DOWN](u, c, t, a, b)


@traces("s3.safe_near_obstacles")
def build() -> Derivation:
    """Check every claim about the braking governor; raises ``ClaimFailed``."""
    d = Derivation("braking", "The braking governor keeps the robot passively safe")
    for step in (_kinematics, _shape, _safe_speed, _speed_bound, _fastest, fan.fan_cone):
        step(d)
    for step in (fan.fan_edge, fan.fan_margin, fan.headings, _induction, _paper_robot):
        step(d)
    fan.library(d, _worst)  # the spot checks of the code, and where the proof stops
    return d


@functools.cache
def derivation() -> Derivation:
    """The derivation for the code's governor (built once)."""
    return build()


claims, main = entry_points(derivation)


if __name__ == "__main__":
    main()
