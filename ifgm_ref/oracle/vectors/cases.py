"""What the vectors file holds: the equation groups with their cases, and the trace specs.

Every function of :mod:`ifgm_ref.paper.equations` belongs to one :class:`EquationGroup` (the printed
and the interpreted form of one equation together), with hand-picked cases -- one per errata
row that touches the equation (``docs/errata.md``), each with its note -- and
:data:`RANDOM_CASES` seeded random ones, drawn uniformly from the ``vectors`` sub-ranges of
the equation's domain (:data:`ifgm_ref.oracle.domains.DOMAINS`). :data:`TRACES` names the
reference episodes. :mod:`ifgm_ref.oracle.vectors.build` evaluates and runs them.

>>> [group.name for group in GROUPS][:3]
['eq1_gap_midpoint', 'eq2_gap_angle', 'fgm_gap_centre_angle']
>>> draw = GROUPS[0].draw
>>> draw(np.random.default_rng(1)) == draw(np.random.default_rng(1))
True
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ifgm_ref.core.pose import Pose
from ifgm_ref.oracle.domains import DOMAINS, EQ3_MIN_DISTANCE, FGM_MIN_WIDTH, HALF_FOV, Argument
from ifgm_ref.oracle.vectors.schema import Form, Value
from ifgm_ref.sim.worldgen.draws import Draw, RandomDraw

__all__ = ["GROUPS", "RANDOM_CASES", "TRACES", "Case", "EquationGroup", "TraceSpec"]

#: Seeded random cases per equation group, on top of the hand-picked ones.
RANDOM_CASES = 20


# ---- equation groups -------------------------------------------------------------------------


@dataclass(frozen=True)
class Case:
    """One case: an id, the inputs by name, and (hand-picked ones) why it is there."""

    id: str
    inputs: Mapping[str, Any]
    note: str | None = None
    errata: tuple[int, ...] = ()


@dataclass(frozen=True)
class EquationGroup:
    """An equation with its forms (``literal`` and ``interpreted``, or the single ``output``).

    ``draw`` makes the inputs of one random case from a generator; ``cases`` are the
    hand-picked ones.
    """

    name: str
    paper: str
    frame: str
    forms: tuple[tuple[str, Form], ...]
    inputs: tuple[str, ...]
    seed: int
    cases: tuple[Case, ...]
    draw: Callable[[np.random.Generator], dict[str, Any]]


def _drawn(d: Draw, argument: Argument) -> Value:
    """One argument from its ``vectors`` interval (a point: x, then y)."""
    low, high = argument.vectors.low, argument.vectors.high
    if argument.point:
        return (
            d.floats(low, high, f"{argument.name}.x"),
            d.floats(low, high, f"{argument.name}.y"),
        )
    return d.floats(low, high, argument.name)


def _uniform(equation: str) -> Callable[[np.random.Generator], dict[str, Any]]:
    """Draw every argument of ``equation``, in call order, uniformly from its ``vectors``
    interval."""
    arguments = DOMAINS[equation].arguments

    def draw(rng: np.random.Generator) -> dict[str, Any]:
        d = RandomDraw(rng)
        return {argument.name: _drawn(d, argument) for argument in arguments}

    return draw


def _draw_eq3(rng: np.random.Generator) -> dict[str, Any]:
    """Positions at least :data:`~ifgm_ref.oracle.domains.EQ3_MIN_DISTANCE` apart."""
    uniform = _uniform("eq3_goal_angle")
    while True:
        inputs = uniform(rng)
        if math.dist(inputs["current"], inputs["destination"]) >= EQ3_MIN_DISTANCE:
            return inputs


def _draw_fgm(rng: np.random.Generator) -> dict[str, Any]:
    """Two border angles in the field of view, at least
    :data:`~ifgm_ref.oracle.domains.FGM_MIN_WIDTH` apart (clockwise one first), then the two
    distances."""
    domain, d = DOMAINS["fgm_gap_centre_angle"], RandomDraw(rng)
    angle, near, far = (domain.argument(n).vectors for n in ("phi2", "d1", "d2"))
    while True:
        low, high = sorted(d.floats(angle.low, angle.high, "border angle") for _ in range(2))
        d1, d2 = d.floats(near.low, near.high, "d1"), d.floats(far.low, far.high, "d2")
        if high - low >= FGM_MIN_WIDTH:
            return {"d1": d1, "phi1": -low, "d2": d2, "phi2": high}


def _cases(names: tuple[str, ...], rows: tuple[tuple[Any, ...], ...]) -> tuple[Case, ...]:
    """Cases from rows ``(id, errata rows, note, *inputs)``, inputs in the order of ``names``."""
    return tuple(
        Case(row[0], dict(zip(names, row[3:], strict=True)), row[2], row[1]) for row in rows
    )


_PI = math.pi
_DEG = math.pi / 180.0
_EQ4_ARGS = ("theta_g", "theta_d", "w_g", "w_d", "d_th")
_EQ4_FGM_ARGS = ("theta_g", "theta_d", "alpha", "beta", "d_min", "heading")
_ORIGIN = (0.0, 0.0)

# The hand-picked cases, one row each: id, the errata rows it exercises, a note, the inputs.
# fmt: off
_EQ1_ROWS = (
    ("doc-example", (1,), "the docstring's example", (4.0, -1.0), (2.0, 3.0)),
    ("coincident", (1,), "a gap of width 0 is its own midpoint", (1.0, 1.0), (1.0, 1.0)),
    ("symmetric-ahead", (1, 3), "symmetric about the heading: y_g = 0", (5.0, -2.5), (5.0, 2.5)),
    ("behind-left", (1, 3), "both points behind and left", (-4.0, 1.0), (-2.0, 5.0)),
    ("opposite-quadrants", (1, 13), "quadrants 1 and 3: the midpoint is the robot",
     (3.0, 4.0), (-3.0, -4.0)),
)
_EQ2_ROWS = (
    ("q1-ahead-left", (2, 3), "45 deg left: the printed ratio is 1, the angle pi/4", 2.0, 2.0),
    ("q2-behind-left", (2, 3), "behind and left: the ratio's sign says right", -2.0, 2.0),
    ("q3-behind-right", (2, 3), "behind and right: the ratio's sign says left", -2.0, -2.0),
    ("q4-ahead-right", (2, 3), "45 deg right", 2.0, -2.0),
    ("fov-edge-left", (2,), "edge of the 135-deg view: ratio 2.414, angle 1.178 rad",
     math.cos(HALF_FOV), math.sin(HALF_FOV)),
    ("dead-ahead", (2,), "straight ahead: both 0", 3.0, 0.0),
    ("straight-behind", (2, 3), "straight behind: ratio -0.0, angle pi", -3.0, 0.0),
    ("straight-behind-negative-zero", (2, 3), "y_g = -0.0: atan2 gives -pi, the direction of pi",
     -3.0, -0.0),
    ("x_g-zero-left", (2, 13), "x_g = 0: the printed form divides by zero", 0.0, 1.0),
    ("x_g-zero-right", (2, 13), "x_g = 0, to the right", 0.0, -1.0),
    ("midpoint-at-robot", (13,), "(0, 0) has no direction: both forms fail", 0.0, 0.0),
)
_FGM_ROWS = (
    ("symmetric", (10,), "symmetric about the heading: straight ahead (to rounding)",
     2.0, _PI / 4, 2.0, _PI / 4),
    ("border-ahead-and-left", (10,), "borders ahead and 90 deg left at 1 ft: pi/4",
     1.0, 0.0, 1.0, _PI / 2),
    ("zero-width", (10,), "a zero-width gap points at its border", 3.0, 0.5, 1.0, -0.5),
    ("unequal-distances", (1, 10), "the direction of the eq. (1) midpoint of the borders",
     2.0, 0.3, 6.0, 0.6),
    ("half-turn-unequal", (10,), "width pi, unequal distances: the midpoint is at pi/2",
     1.0, _PI / 2, 3.0, _PI / 2),
    ("midpoint-at-robot", (10, 13), "width pi, equal distances: the midpoint is the robot",
     2.0, _PI / 2, 2.0, _PI / 2),
    ("width-over-pi", (10,), "wider than a half turn: fails", 2.0, 2.0, 2.0, 1.5),
    ("negative-width", (10,), "border 2 clockwise of border 1: fails", 2.0, 0.5, 2.0, -0.6),
    ("d1-zero", (10,), "a border at the robot: fails", 0.0, 0.2, 2.0, 0.2),
)
_EQ3_ROWS = (
    ("q1-ahead", (5,), "ahead and left: both pi/4", _ORIGIN, (1.0, 1.0)),
    ("q2-behind", (5,), "behind and left: the printed form is off by pi", _ORIGIN, (-1.0, 1.0)),
    ("q3-behind", (5,), "behind and right: off by pi", _ORIGIN, (-1.0, -1.0)),
    ("q4-ahead", (5,), "ahead and right: both -pi/4", _ORIGIN, (1.0, -1.0)),
    ("q3-behind-shallow", (5,), "behind, a little right, off the origin",
     (30.0, 4.0), (12.5, 1.5)),
    ("straight-behind", (5,), "straight behind: printed -0.0, atan2 pi", (5.0, 0.0), (-5.0, 0.0)),
    ("vertical-up", (5, 13), "x_d == x_c: the printed form divides by zero",
     (1.0, 2.0), (1.0, 7.0)),
    ("vertical-down", (5, 13), "x_d == x_c, below", (1.0, 2.0), (1.0, -3.0)),
    ("reached", (13,), "destination == current: both forms fail", (1.0, 2.0), (1.0, 2.0)),
    ("paper-scenario1", (5,), "the paper's 197 ft run along +x", _ORIGIN, (197.0, 0.0)),
)
_EQ4_ROWS = (
    # id, errata, note, theta_g, theta_d, w_g, w_d, d_th, heading
    ("doc-example", (6,), "robot frame, in [-pi, pi): the forms agree",
     0.5, -0.25, 2.0, 1.0, 2.0, 0.0),
    ("default-weights", (9,), "IFGMParams defaults: the gap counts 3x the goal",
     0.3, -0.2, 9.0, 1.0, 3.0, 0.0),
    ("asymmetric-weights", (9,), "weights 2 : 0.5 on angles far apart",
     0.9, -0.6, 6.0, 0.5, 3.0, 0.0),
    ("wrap-175", (4, 6), "facing -x, gap and goal either side of +-pi: printed mean 0, back",
     175 * _DEG, -175 * _DEG, 1.0, 1.0, 1.0, _PI),
    ("extra-turn", (6,), "the goal written with an extra turn: the printed mean moves",
     0.5, -0.25 + 2 * _PI, 2.0, 1.0, 2.0, 0.0),
    ("world-frame", (4,), "world angles with a world heading of 2 rad",
     2.3, 1.8, 9.0, 1.0, 3.0, 2.0),
    ("heading-two-turns", (4, 6), "a heading written with two extra turns",
     0.5, -0.25, 2.0, 1.0, 2.0, 4 * _PI),
    ("goal-straight-behind", (7,), "goal exactly behind: relative -pi, turns clockwise",
     0.5, _PI, 9.0, 1.0, 3.0, 0.0),
    ("goal-behind-hair-left", (7,), "goal 1 mrad left of behind: turns counter-clockwise",
     0.5, _PI - 1e-3, 9.0, 1.0, 3.0, 0.0),
    ("goal-behind-hair-right", (7,), "goal 1 mrad right of behind: turns clockwise",
     0.5, -_PI + 1e-3, 9.0, 1.0, 3.0, 0.0),
    ("gap-weight-zero", (9,), "w_g = 0: the destination angle", 0.5, -0.25, 0.0, 1.0, 2.0, 0.0),
    ("goal-weight-zero", (9,), "w_d = 0: the gap angle", 0.5, -0.25, 2.0, 0.0, 2.0, 0.0),
    ("d_th-large", (8,), "a large d_th only rescales w_g", 0.5, -0.25, 9.0, 1.0, 300.0, 0.0),
    ("weights-both-zero", (9,), "0/0: both forms fail", 0.5, -0.25, 0.0, 0.0, 2.0, 0.0),
    ("negative-weight", (9,), "a negative weight: both forms fail",
     0.5, -0.25, -1.0, 1.0, 2.0, 0.0),
    ("d_th-zero", (9,), "d_th = 0: both forms fail", 0.5, -0.25, 2.0, 1.0, 0.0, 0.0),
)
_EQ4_FGM_ROWS = (
    # id, errata, note, theta_g, theta_d, alpha, beta, d_min, heading
    ("obstacle-far", (8,), "d_min = 4 ft: the gap counts little", 0.5, 0.0, 1.0, 1.0, 4.0, 0.0),
    ("obstacle-near", (8,), "d_min = 0.25 ft: the gap counts more",
     0.5, 0.0, 1.0, 1.0, 0.25, 0.0),
    ("renamed-eq4", (8,), "eq4_final_heading's doc-example under FGM's names",
     0.5, -0.25, 2.0, 1.0, 2.0, 0.0),
    ("wrap-175", (6, 8), "averaged in the robot frame like eq. (4)",
     175 * _DEG, -175 * _DEG, 1.0, 1.0, 1.0, _PI),
    ("d_min-zero", (8, 9), "an obstacle at the robot: fails", 0.5, 0.0, 1.0, 1.0, 0.0, 0.0),
    ("weights-both-zero", (9,), "0/0: fails", 0.5, 0.0, 0.0, 0.0, 1.0, 0.0),
)
# fmt: on


def _group(
    name: str,
    paper: str,
    frame: str,
    forms: tuple[tuple[str, Form], ...],
    seed: int,
    rows: tuple[tuple[Any, ...], ...],
    draw: Callable[[np.random.Generator], dict[str, Any]],
) -> EquationGroup:
    inputs = tuple(dict.fromkeys(arg for _, form in forms for arg in form.args))
    return EquationGroup(name, paper, frame, forms, inputs, seed, _cases(inputs, rows), draw)


_HEADING_FRAME = "the frame of `heading`: world angles with the world heading"

#: The equation groups, in the order of the paper, with their forms and hand-picked cases.
GROUPS: tuple[EquationGroup, ...] = (
    _group(
        "eq1_gap_midpoint",
        "eq. (1)",
        "robot",
        (("output", Form("eq1_gap_midpoint", ("p1", "p2"), "length")),),
        1,
        _EQ1_ROWS,
        _uniform("eq1_gap_midpoint"),
    ),
    _group(
        "eq2_gap_angle",
        "eq. (2)",
        "robot",
        (
            ("literal", Form("eq2_gap_angle_literal", ("x_g", "y_g"), "ratio")),
            ("interpreted", Form("eq2_gap_angle", ("x_g", "y_g"), "direction")),
        ),
        2,
        _EQ2_ROWS,
        _uniform("eq2_gap_angle"),
    ),
    _group(
        "fgm_gap_centre_angle",
        "section 2.2: FGM's gap centre angle (Sezer & Gokasan 2012)",
        "robot",
        (("output", Form("fgm_gap_centre_angle", ("d1", "phi1", "d2", "phi2"), "direction")),),
        3,
        _FGM_ROWS,
        _draw_fgm,
    ),
    _group(
        "eq3_goal_angle",
        "eq. (3)",
        "world",
        (
            ("literal", Form("eq3_goal_angle_literal", ("current", "destination"), "angle")),
            ("interpreted", Form("eq3_goal_angle", ("current", "destination"), "direction")),
        ),
        4,
        _EQ3_ROWS,
        _draw_eq3,
    ),
    _group(
        "eq4_final_heading",
        "eq. (4)",
        _HEADING_FRAME,
        (
            ("literal", Form("eq4_final_heading_literal", _EQ4_ARGS, "angle")),
            ("interpreted", Form("eq4_final_heading", (*_EQ4_ARGS, "heading"), "direction")),
        ),
        5,
        _EQ4_ROWS,
        _uniform("eq4_final_heading"),
    ),
    _group(
        "eq4_final_heading_fgm",
        "eq. (4) in FGM's form: alpha / d_min in place of w_g / d_th (Sezer & Gokasan 2012)",
        _HEADING_FRAME,
        (("output", Form("eq4_final_heading_fgm", _EQ4_FGM_ARGS, "direction")),),
        6,
        _EQ4_FGM_ROWS,
        _uniform("eq4_final_heading_fgm"),
    ),
)


# ---- traces ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class TraceSpec:
    """A reference trace: ``planner`` in built-in ``world`` from ``start``, ``steps`` long.

    The start is moved from the world's own so that the robot meets the obstacles within a
    few steps; ``steps`` is an upper bound (an episode that reaches the goal ends sooner).
    """

    id: str
    planner: str
    world: str
    start: Pose
    steps: int
    note: str


#: The reference traces; together the IFGM ones take every branch of Figure 3.
# fmt: off
TRACES: tuple[TraceSpec, ...] = (
    TraceSpec("fig7a-ifgm", "ifgm", "fig7a", Pose(32.0, 0.0, 0.0), 70,
              "Case-1 through a 4.5 ft gap beside the middle disc (eqs. (1)-(4)), too close "
              "to the disc, IBA round it, path regenerated"),
    TraceSpec("u_trap-ifgm", "ifgm", "u_trap", Pose(28.8, 0.0, 0.0), 82,
              "inside the U: dead end, 45-degree turns in place, escape, IBA along the wall"),
    TraceSpec("post-ifgm", "ifgm", "post", Pose(22.0, 0.0, 0.0), 60,
              "Case-2 (one obstacle, no gap); DistBug's progress rule hands back at once "
              "(errata row 24), the post is met again at IBA's short distance and followed"),
    TraceSpec("wall_posts-ifgm", "ifgm", "wall_posts", Pose(26.9, 7.9, -0.28), 55,
              "Case-2 at the upper post, IBA along it, then Case-3: a nearer obstacle "
              "pre-empts"),
    TraceSpec("offset_box-ifgm", "ifgm", "offset_box", Pose(21.0, 0.0, 0.0), 32,
              "Case-2 with obstacles on one side only, IBA, path regenerated"),
    TraceSpec("free-ifgm", "ifgm", "free", Pose(194.0, -1.0, 2.5), 40,
              "no obstacle: turn towards the goal 3 ft away while driving, goal reached"),
    TraceSpec("post-iba", "iba", "post", Pose(25.5, 0.0, 0.0), 30,
              "IBA: move to goal, follow the post's edge, leave at the first free path"),
)
# fmt: on
