"""Conformance vectors: equation test vectors and reference traces in one JSON file.

For implementations that cannot run Python -- a microcontroller C port, say -- the oracle's
checks are written down as data: ``ifgm-ref vectors --out vectors.json`` writes

* **equation vectors**: inputs of every function of :mod:`ifgm_ref.equations` with the output
  of the printed (*literal*) and of the interpreted form, or the error each raises: hand-picked
  cases for every errata row that touches an equation (``docs/errata.md``) and seeded random
  ones;
* **reference traces**: short IFGM and IBA episodes in built-in worlds, each step's
  observation exactly as the JSON-lines protocol sends it (:mod:`ifgm_ref.transport.wire`)
  with the command the reference planner answered, together covering every branch of
  Figure 3.

``docs/vectors-format.md`` specifies the file. The same data checks Python implementations:
:func:`check_vectors` runs any object with the equation functions' names against the vectors,
:func:`replay_traces` steps a planner through the traces; both answer a list of mismatches in
the oracle's ``quantity = actual, but should be expected [where]`` style.

Everything is deterministic -- explicit seeds, noise-free simulations, no dates, no machine
facts -- so rebuilding gives the same bytes (another platform's math library may move a last
bit, far inside every tolerance); floats are written with ``repr`` and read back bit for bit.
"""

from __future__ import annotations

import dataclasses
import json
import math
import numbers
import os
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ifgm_ref import equations as reference
from ifgm_ref.errors import ParameterError
from ifgm_ref.oracle.recording import RecordingPlanner
from ifgm_ref.params import SimParams
from ifgm_ref.planners import PLANNERS, make_planner
from ifgm_ref.planners.tuning import episode_values
from ifgm_ref.pose import Pose
from ifgm_ref.protocol import EpisodeParams, Planner
from ifgm_ref.scenarios import resolve_world
from ifgm_ref.simulator import simulate
from ifgm_ref.transport.wire import (
    command_message,
    observe_message,
    parse_observe,
    parse_reset,
    reset_message,
)

__all__ = [
    "FORMAT_NAME",
    "FORMAT_VERSION",
    "GROUPS",
    "PRECISIONS",
    "QUANTITIES",
    "TRACES",
    "Case",
    "EquationGroup",
    "Form",
    "Quantity",
    "Tolerance",
    "TraceSpec",
    "VectorsSummary",
    "build_vectors",
    "check_vectors",
    "dumps_vectors",
    "replay_traces",
    "summarize",
    "write_vectors",
]

#: The ``format.name`` of the file; a reader checks it before anything else.
FORMAT_NAME = "ifgm-ref-vectors"
#: The ``format.version``: raised whenever a key changes meaning or disappears (adding cases,
#: traces or keys a reader may ignore keeps the version).
FORMAT_VERSION = 1
#: Seeded random cases per equation group, on top of the hand-picked ones.
RANDOM_CASES = 20
#: The tolerance sets of every quantity: IEEE double, and the looser one for a float32 port.
PRECISIONS = ("double", "float32")


# ---- tolerances ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Tolerance:
    """Pass when ``|actual - expected| <= absolute + relative * |expected|``.

    >>> Tolerance(1e-9).allows(1.0, 1.0 + 1e-10), Tolerance(1e-9).allows(1.0, 1.1)
    (True, False)

    Directions are compared modulo 2 pi:

    >>> Tolerance(1e-9).allows(math.pi, -math.pi, periodic=True)
    True
    """

    absolute: float
    relative: float = 0.0

    def allows(self, expected: float, actual: float, *, periodic: bool = False) -> bool:
        """Whether ``actual`` is within this tolerance of ``expected`` (modulo 2 pi if
        ``periodic``)."""
        if not math.isfinite(actual):
            return False
        difference = actual - expected
        if periodic:
            difference = math.remainder(difference, 2.0 * math.pi)
        return abs(difference) <= self.absolute + self.relative * abs(expected)

    def describe(self, *, periodic: bool = False) -> str:
        """The tolerance as a message fragment.

        >>> Tolerance(1e-9).describe(), Tolerance(1e-9, 1e-6).describe(periodic=True)
        ('tolerance 1e-09', 'tolerance 1e-09 + 1e-06 * |expected|, modulo 2 pi')
        """
        text = f"tolerance {self.absolute!r}"
        if self.relative:
            text += f" + {self.relative!r} * |expected|"
        return text + (", modulo 2 pi" if periodic else "")

    def to_json(self) -> dict[str, float]:
        """``{"abs": ..., "rel": ...}``."""
        return {"abs": self.absolute, "rel": self.relative}


@dataclass(frozen=True)
class Quantity:
    """A kind of output, its unit, how it is compared and within what, and why.

    ``periodic`` quantities are directions: the difference is taken modulo 2 pi (into
    ``[-pi, pi]``) before it is compared, so ``pi`` and ``-pi`` agree.
    """

    unit: str
    periodic: bool
    double: Tolerance
    float32: Tolerance
    reason: str

    def tolerance(self, precision: str) -> Tolerance:
        """The tolerance of ``precision`` (``"double"`` or ``"float32"``)."""
        _check_precision(precision)
        return self.double if precision == "double" else self.float32

    def to_json(self) -> dict[str, Any]:
        """The quantity as the file's ``tolerances`` entry."""
        return {
            "unit": self.unit,
            "periodic": self.periodic,
            "double": self.double.to_json(),
            "float32": self.float32.to_json(),
            "reason": self.reason,
        }


_DOUBLE_REASON = (
    "double: the reference's own results are exact to the last bit for anyone who evaluates "
    "the same IEEE 754 operations, and other math libraries' atan, atan2, acos, cos and sqrt "
    "differ from it by an ulp or two (1e-15 here); 1e-9 is far above that and far below the "
    "effect of any misreading (a wrong quadrant is off by pi, a flipped sign by twice the "
    "angle). "
)

#: Every compared quantity, by the name the equation forms and the traces use.
QUANTITIES: dict[str, Quantity] = {
    "length": Quantity(
        unit="ft",
        periodic=False,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-4),
        reason=_DOUBLE_REASON
        + "float32 (24-bit significand): every input (|x|, |y| <= 20 ft in these cases) is "
        "stored within 1e-6 ft, and the midpoint adds one rounding; 1e-4 ft leaves room for "
        "world-scale inputs up to 256 ft (half an ulp there: 7.6e-6 ft).",
    ),
    "ratio": Quantity(
        unit="1",
        periodic=False,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-6, 1e-6),
        reason=_DOUBLE_REASON
        + "float32: the printed eq. (2) is a ratio, unbounded near x_g = 0, so its float32 "
        "tolerance is relative: the two inputs and the quotient are rounded once each "
        "(3 x 6e-8 of the value); 1e-6 of the value, plus 1e-6 near 0, leaves margin.",
    ),
    "angle": Quantity(
        unit="rad",
        periodic=False,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-4),
        reason=_DOUBLE_REASON
        + "Compared as plain numbers: the printed forms return numbers that are not wrapped "
        "(atan in (-pi/2, pi/2), the mean of two numbers). float32: world positions of up to "
        "200 ft are stored within 7.6e-6 ft each, which moves the direction between two "
        "points at least 10 ft apart (as in every eq. (3) case with large coordinates) by "
        "under 2e-6 rad; a weighted mean of angles of a few pi adds a few roundings of 5e-7 "
        "rad; 1e-4 rad leaves margin.",
    ),
    "direction": Quantity(
        unit="rad",
        periodic=True,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-4),
        reason=_DOUBLE_REASON
        + "Compared modulo 2 pi: the interpreted forms return directions, and pi and -pi are "
        "the same direction (float32(pi) > pi, so a float32 port may land on either side of "
        "the wrap). float32 as for `angle`; FGM's arccos form (fgm_gap_centre_angle) is "
        "ill-conditioned where its argument nears 1 -- an argument error dc moves the angle "
        "by dc / sin(angle), and by sqrt(2 dc) at 0 -- so its cases keep the angle between "
        "border 1 and the midpoint above 0.1 rad (bar the zero-width case, whose argument is "
        "exactly 1), where float32's 1e-7 becomes 1e-6 rad. A numpy float32 evaluation of "
        "every equation passes within 1e-4 with a margin of 80 or more "
        "(tests/test_vectors.py).",
    ),
    "heading": Quantity(
        unit="rad",
        periodic=True,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-3),
        reason="Trace command heading, world frame, compared modulo 2 pi. double: the replay "
        "is open loop -- every step's observation is recorded, so a difference cannot grow "
        "through the robot's motion, only through the planner's own memory (obstacle points "
        "kept in the world frame by odometry), where an ulp stays an ulp; 1e-9 rad as for "
        "the equations. float32: world positions of up to 200 ft are stored within 7.6e-6 "
        "ft, remembered points and the edge follower's targets (about 2 ft away) are then "
        "good to about 1e-5 rad; 1e-3 rad leaves margin. Either precision may take another "
        "discrete decision where a decision quantity (a gap width against d_th, the nearest "
        "obstacle against d_obs, a corridor length) lies within its rounding of the "
        "threshold: that shows as a branch or a large heading mismatch, to be examined, not "
        "loosened away.",
    ),
    "speed": Quantity(
        unit="ft/s",
        periodic=False,
        double=Tolerance(1e-9),
        float32=Tolerance(1e-3),
        reason="Trace command speed. The planners command the robot's speed v, 0 (turning in "
        "place), v times max(0, cos(turn still to make)), or, at the goal, the distance left "
        "over dt: the error is at most the heading's times v (1.32 ft/s), or "
        "a position error over dt (1e-4 ft/s in float32); the tolerances are the heading's.",
    ),
}


def _check_precision(precision: str) -> None:
    if precision not in PRECISIONS:
        raise ParameterError(
            f"`precision` must be one of {', '.join(PRECISIONS)}, got {precision!r}"
        )


# ---- equation groups -------------------------------------------------------------------------


@dataclass(frozen=True)
class Form:
    """One function of a group: its name, the case inputs it takes, what it returns."""

    function: str
    args: tuple[str, ...]
    quantity: str

    def to_json(self) -> dict[str, Any]:
        """The form as the file's ``forms`` entry."""
        return {"function": self.function, "args": list(self.args), "quantity": self.quantity}


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


def _uniform(rng: np.random.Generator, low: float, high: float) -> float:
    return float(rng.uniform(low, high))


def _point(rng: np.random.Generator, half: float) -> tuple[float, float]:
    return (_uniform(rng, -half, half), _uniform(rng, -half, half))


_PI = math.pi
_DEG = math.pi / 180.0
_HALF_FOV = 67.5 * _DEG


def _draw_eq1(rng: np.random.Generator) -> dict[str, Any]:
    return {"p1": _point(rng, 20.0), "p2": _point(rng, 20.0)}


def _draw_eq2(rng: np.random.Generator) -> dict[str, Any]:
    x_g, y_g = _point(rng, 15.0)
    return {"x_g": x_g, "y_g": y_g}


def _draw_fgm(rng: np.random.Generator) -> dict[str, Any]:
    """Borders inside the field of view, at least 0.1 rad apart, distances within 10x."""
    while True:
        low, high = sorted(_uniform(rng, -_HALF_FOV, _HALF_FOV) for _ in range(2))
        d1, d2 = _uniform(rng, 1.0, 10.0), _uniform(rng, 1.0, 10.0)
        if high - low >= 0.1:
            return {"d1": d1, "phi1": -low, "d2": d2, "phi2": high}


def _draw_eq3(rng: np.random.Generator) -> dict[str, Any]:
    while True:
        current, destination = _point(rng, 200.0), _point(rng, 200.0)
        if math.dist(current, destination) >= 10.0:
            return {"current": current, "destination": destination}


def _draw_eq4(rng: np.random.Generator) -> dict[str, Any]:
    return {
        "theta_g": _uniform(rng, -_PI, _PI),
        "theta_d": _uniform(rng, -_PI, _PI),
        "w_g": _uniform(rng, 0.5, 12.0),
        "w_d": _uniform(rng, 0.1, 2.0),
        "d_th": _uniform(rng, 2.5, 6.0),
        "heading": _uniform(rng, -_PI, _PI),
    }


def _draw_eq4_fgm(rng: np.random.Generator) -> dict[str, Any]:
    return {
        "theta_g": _uniform(rng, -_PI, _PI),
        "theta_d": _uniform(rng, -_PI, _PI),
        "alpha": _uniform(rng, 0.1, 5.0),
        "beta": _uniform(rng, 0.1, 2.0),
        "d_min": _uniform(rng, 0.2, 15.0),
        "heading": _uniform(rng, -_PI, _PI),
    }


def _cases(names: tuple[str, ...], rows: tuple[tuple[Any, ...], ...]) -> tuple[Case, ...]:
    """Cases from rows ``(id, errata rows, note, *inputs)``, inputs in the order of ``names``."""
    return tuple(
        Case(row[0], dict(zip(names, row[3:], strict=True)), row[2], row[1]) for row in rows
    )


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
     math.cos(_HALF_FOV), math.sin(_HALF_FOV)),
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
        _draw_eq1,
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
        _draw_eq2,
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
        _draw_eq4,
    ),
    _group(
        "eq4_final_heading_fgm",
        "eq. (4) in FGM's form: alpha / d_min in place of w_g / d_th (Sezer & Gokasan 2012)",
        _HEADING_FRAME,
        (("output", Form("eq4_final_heading_fgm", _EQ4_FGM_ARGS, "direction")),),
        6,
        _EQ4_FGM_ROWS,
        _draw_eq4_fgm,
    ),
)


def _evaluate(function: Callable[..., Any], form: Form, inputs: Mapping[str, Any]) -> Any:
    """The reference output of ``form`` on ``inputs``, JSON-ready, or ``{"error": message}``."""
    try:
        value = function(**{name: inputs[name] for name in form.args})
    except ParameterError as err:
        return {"error": str(err)}
    if isinstance(value, tuple):
        return [float(v) for v in value]
    return float(value)


def _group_json(group: EquationGroup) -> dict[str, Any]:
    rng = np.random.default_rng(group.seed)
    cases = list(group.cases) + [
        Case(f"random-{i:02d}", group.draw(rng)) for i in range(RANDOM_CASES)
    ]
    out = []
    for case in cases:
        entry: dict[str, Any] = {
            "id": case.id,
            "inputs": {name: _to_json(case.inputs[name]) for name in group.inputs},
        }
        for key, form in group.forms:
            entry[key] = _evaluate(getattr(reference, form.function), form, case.inputs)
        if case.note is not None:
            entry["note"] = case.note
        if case.errata:
            entry["errata"] = list(case.errata)
        out.append(entry)
    return {
        "paper": group.paper,
        "frame": group.frame,
        "seed": group.seed,
        "forms": {key: form.to_json() for key, form in group.forms},
        "cases": out,
    }


def _to_json(value: Any) -> Any:
    if isinstance(value, tuple | list):
        return [float(v) for v in value]
    return float(value)


def _from_json(value: Any) -> Any:
    return tuple(value) if isinstance(value, list) else value


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


def _effective_params(planner_name: str, episode: EpisodeParams) -> dict[str, float]:
    """Every parameter of the planner with the value it takes at reset (derived ones too)."""
    return episode_values(PLANNERS[planner_name].tunings, episode)


def _trace_json(spec: TraceSpec) -> dict[str, Any]:
    world = dataclasses.replace(resolve_world(spec.world), start=spec.start)
    sim = SimParams()
    sim = SimParams(dt=sim.dt, max_time=spec.steps * sim.dt, goal_tolerance=sim.goal_tolerance)
    default = EpisodeParams(world.robot, world.sensor, sim.dt, {}, sim.goal_tolerance)
    params = _effective_params(spec.planner, default)
    recorder = RecordingPlanner(make_planner(spec.planner))
    run = simulate(world, recorder, sim, params=params)
    assert recorder.reset_args is not None
    branches: list[str] = []
    steps = []
    for observation, command in recorder.steps:
        steps.append({"observe": observe_message(observation), "command": command_message(command)})
        if command.branch is not None and str(command.branch) not in branches:
            branches.append(str(command.branch))
    return {
        "id": spec.id,
        "planner": spec.planner,
        "world": spec.world,
        "note": spec.note,
        "stop_reason": run.result.stop_reason,
        "branches": branches,
        "reset": reset_message(*recorder.reset_args),
        "steps": steps,
    }


# ---- the file --------------------------------------------------------------------------------


def build_vectors() -> dict[str, Any]:
    """Build the conformance vectors (deterministic and JSON-ready: no NaN or infinity).

    Returns
    -------
    dict
        The document ``docs/vectors-format.md`` specifies: ``format``, ``units``, ``frames``,
        ``tolerances``, ``equations`` (by group) and ``traces``.

    Examples
    --------
    >>> vectors = build_vectors()
    >>> vectors["format"]
    {'name': 'ifgm-ref-vectors', 'version': 1}
    >>> case = vectors["equations"]["eq3_goal_angle"]["cases"][1]
    >>> case["id"], case["inputs"]
    ('q2-behind', {'current': [0.0, 0.0], 'destination': [-1.0, 1.0]})
    >>> case["literal"], case["interpreted"]
    (-0.7853981633974483, 2.356194490192345)
    >>> vectors["equations"]["eq2_gap_angle"]["cases"][8]["literal"]  # doctest: +ELLIPSIS
    {'error': 'eq. (2) as printed is undefined for x_g == 0 (division by zero); got ...'}
    """
    vectors: dict[str, Any] = {
        "format": {"name": FORMAT_NAME, "version": FORMAT_VERSION},
        "generator": "ifgm-ref vectors --out FILE.json (ifgm_ref.oracle.vectors.build_vectors)",
        "units": {"length": "ft", "angle": "rad", "time": "s", "speed": "ft/s"},
        "frames": {
            "robot": "REP-103 robot frame: x forward along the heading, y to the left, angles "
            "counter-clockwise from the heading; eq. (1) and (2) inputs and outputs, FGM's "
            "border angles, scan ray angles",
            "world": "REP-103 world frame: x east, y north, angles counter-clockwise from +x; "
            "eq. (3) positions and angle, trace poses, goals and command headings",
        },
        "tolerances": {name: q.to_json() for name, q in QUANTITIES.items()},
        "equations": {group.name: _group_json(group) for group in GROUPS},
        "traces": [_trace_json(spec) for spec in TRACES],
    }
    _check_json_ready(vectors, "vectors")
    return vectors


def _check_json_ready(value: Any, where: str) -> None:
    """Raise ``AssertionError`` on anything JSON cannot carry exactly (NaN, inf, tuples...)."""
    if isinstance(value, dict):
        for key, item in value.items():
            assert isinstance(key, str), f"{where}: key {key!r} is not a string"
            _check_json_ready(item, f"{where}.{key}")
    elif isinstance(value, list):
        for i, item in enumerate(value):
            _check_json_ready(item, f"{where}[{i}]")
    elif isinstance(value, float):
        assert math.isfinite(value), f"{where}={value!r}, but should be finite"
    else:
        assert value is None or type(value) in (str, int, bool), (
            f"{where}: {type(value).__name__} {value!r}, but should be a JSON value"
        )


def dumps_vectors(vectors: Mapping[str, Any]) -> str:
    """Write ``vectors`` as JSON: one space of indent per level, arrays of plain values on one
    line (a scan's ranges, a point), keys in insertion order, a final newline.

    >>> print(dumps_vectors({"a": [1.0, None], "b": {"c": [{"d": "e"}]}}), end="")
    {
     "a": [1.0, null],
     "b": {
      "c": [
       {
        "d": "e"
       }
      ]
     }
    }
    """
    return _dumps(vectors, 0) + "\n"


def _dumps(value: Any, level: int) -> str:
    pad, inner = " " * level, " " * (level + 1)
    if isinstance(value, Mapping) and value:
        items = (f"{inner}{json.dumps(k)}: {_dumps(v, level + 1)}" for k, v in value.items())
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list) and any(isinstance(v, Mapping | list) for v in value):
        items = (f"{inner}{_dumps(v, level + 1)}" for v in value)
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return json.dumps(value, allow_nan=False)


def write_vectors(path: str | os.PathLike[str]) -> dict[str, Any]:
    """Build the vectors, write them to ``path`` (:func:`dumps_vectors`) and return them."""
    vectors = build_vectors()
    Path(path).write_text(dumps_vectors(vectors), encoding="utf-8")
    return vectors


@dataclass(frozen=True)
class VectorsSummary:
    """How much a vectors document holds."""

    groups: int
    cases: int
    traces: int
    steps: int
    branches: tuple[str, ...]

    def __str__(self) -> str:
        return (
            f"{self.cases} equation cases in {self.groups} groups, {self.traces} traces of "
            f"{self.steps} steps covering {len(self.branches)} branches"
        )


def summarize(vectors: Mapping[str, Any]) -> VectorsSummary:
    """Count the groups, cases, traces, steps and distinct branches of ``vectors``."""
    groups = vectors["equations"]
    branches: list[str] = []
    for trace in vectors["traces"]:
        branches.extend(b for b in trace["branches"] if b not in branches)
    return VectorsSummary(
        groups=len(groups),
        cases=sum(len(g["cases"]) for g in groups.values()),
        traces=len(vectors["traces"]),
        steps=sum(len(t["steps"]) for t in vectors["traces"]),
        branches=tuple(branches),
    )


# ---- checking implementations ----------------------------------------------------------------


def _check_format(vectors: Mapping[str, Any]) -> None:
    found = vectors.get("format")
    expected = {"name": FORMAT_NAME, "version": FORMAT_VERSION}
    if found != expected:
        raise ParameterError(f"vectors format={found!r}, but should be {expected!r}")


def _call_text(function: str, args: Sequence[str], inputs: Mapping[str, Any]) -> str:
    shown = ", ".join(f"{name}={_from_json(inputs[name])!r}" for name in args)
    return f"{function}({shown})"


def _values(value: Any) -> list[float] | None:
    """An implementation's output as a list of floats, or ``None`` if it is not numeric.

    A number (any real: ``float``, ``int``, ``numpy.float32``...) is a list of one; a
    sequence of numbers (a point) is itself.

    >>> _values(np.float32(0.5)), _values((1, 2.5)), _values("1.0"), _values(True)
    ([0.5], [1.0, 2.5], None, None)
    """
    if _is_real(value):
        return [float(value)]
    if isinstance(value, str | bytes):
        return None
    try:
        items = list(value)
    except TypeError:
        return None
    return [float(v) for v in items] if all(map(_is_real, items)) else None


def _is_real(value: Any) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _tolerance(quantity: Mapping[str, Any], precision: str) -> tuple[Tolerance, bool]:
    """The tolerance of ``precision`` from a file's quantity entry, and its ``periodic``."""
    bounds = quantity[precision]
    return Tolerance(float(bounds["abs"]), float(bounds["rel"])), bool(quantity["periodic"])


def _compare_case(
    function: Callable[..., Any],
    form: Mapping[str, Any],
    case: Mapping[str, Any],
    expected: Any,
    tolerances: Mapping[str, Any],
    precision: str,
) -> str | None:
    """One mismatch message, or ``None`` when the implementation agrees on this case."""
    inputs = case["inputs"]
    call = _call_text(form["function"], form["args"], inputs)
    where = f"[case {case['id']}]"
    try:
        actual = function(**{name: _from_json(inputs[name]) for name in form["args"]})
    except Exception as err:
        if isinstance(expected, dict):
            return None  # any exception is the error the vector asks for
        return f"{call} raised {type(err).__name__}: {err}, but should be {expected!r} {where}"
    values = _values(actual)
    if isinstance(expected, dict):
        if values is not None and not all(map(math.isfinite, values)):
            return None  # NaN or inf is an error signal too
        return f"{call} = {actual!r}, but should fail: {expected['error']} {where}"
    tolerance, periodic = _tolerance(tolerances[form["quantity"]], precision)
    wanted = [float(v) for v in (expected if isinstance(expected, list) else [expected])]
    if (
        values is not None
        and len(values) == len(wanted)
        and all(
            tolerance.allows(e, a, periodic=periodic) for e, a in zip(wanted, values, strict=True)
        )
    ):
        return None
    return (
        f"{call} = {actual!r}, but should be {expected!r} "
        f"({tolerance.describe(periodic=periodic)}) {where}"
    )


def check_vectors(
    vectors: Mapping[str, Any],
    equations: object,
    *,
    precision: str = "double",
    skipped: list[str] | None = None,
) -> list[str]:
    """Check an implementation's equation functions against the vectors.

    Parameters
    ----------
    vectors : dict
        A vectors document (:func:`build_vectors`, or the JSON file read back).
    equations : object
        Anything with attributes named like the reference functions (a module, a namespace,
        an instance): ``eq1_gap_midpoint``, ``eq2_gap_angle``, ``eq2_gap_angle_literal``, ...
        Each is called with the case inputs as keyword arguments (points as tuples).
    precision : {"double", "float32"}, default "double"
        Which tolerance set of the file to apply.
    skipped : list, optional
        If given, the names of the functions ``equations`` lacks are appended to it; if not,
        a :class:`UserWarning` names them. A missing function is skipped, not failed.

    Returns
    -------
    list of str
        One message per mismatching case: ``call = actual, but should be expected (tolerance)
        [case id]``. Where the vector holds an error, any exception -- or a NaN or infinite
        result -- counts as the error; the message text is the reference's, for people.

    Examples
    --------
    >>> import types
    >>> from ifgm_ref import equations
    >>> vectors = build_vectors()
    >>> check_vectors(vectors, equations)
    []
    >>> blind = types.SimpleNamespace(
    ...     eq3_goal_angle=lambda current, destination: math.atan(
    ...         (destination[1] - current[1]) / (destination[0] - current[0])))
    >>> names = []
    >>> problems = check_vectors(vectors, blind, skipped=names)
    >>> print(problems[0].replace(", but", ",\\n but"))
    eq3_goal_angle(current=(0.0, 0.0), destination=(-1.0, 1.0)) = -0.7853981633974483,
     but should be 2.356194490192345 (tolerance 1e-09, modulo 2 pi) [case q2-behind]
    >>> len(names)
    8
    """
    _check_format(vectors)
    _check_precision(precision)
    tolerances = vectors["tolerances"]
    problems: list[str] = []
    missing: list[str] = []
    for group in vectors["equations"].values():
        for key, form in group["forms"].items():
            function = getattr(equations, form["function"], None)
            if function is None:
                missing.append(form["function"])
                continue
            for case in group["cases"]:
                problem = _compare_case(function, form, case, case[key], tolerances, precision)
                if problem is not None:
                    problems.append(problem)
    if skipped is not None:
        skipped.extend(missing)
    elif missing:
        warnings.warn(
            f"check_vectors skipped {len(missing)} function(s) the implementation lacks: "
            + ", ".join(missing),
            stacklevel=2,
        )
    return problems


def _replayed(
    trace: Mapping[str, Any], planner: Planner, precision: str, tolerances: Any
) -> str | None:
    """The first mismatch of ``planner`` on ``trace``, or ``None``."""
    compared = [(name, *_tolerance(tolerances[name], precision)) for name in ("heading", "speed")]
    reset = parse_reset(trace["reset"])
    try:
        planner.reset(reset.start, reset.goal, reset.params)
    except Exception as err:
        return f"reset() raised {type(err).__name__}: {err} [trace {trace['id']}]"
    for i, step in enumerate(trace["steps"]):
        expected = step["command"]
        observation = parse_observe(step["observe"])
        where = (
            f"[trace {trace['id']} step {i}, t={observation.t!r} s, "
            f"branch {expected.get('branch')}]"
        )
        try:
            command = planner.step(observation)
        except Exception as err:
            return f"step() raised {type(err).__name__}: {err} {where}"
        for name, tol, periodic in compared:
            actual = getattr(command, name, None)
            values = _values(actual)
            if (
                values is None
                or len(values) != 1
                or not tol.allows(expected[name], values[0], periodic=periodic)
            ):
                return (
                    f"{name}={actual!r}, but should be {expected[name]!r} "
                    f"({tol.describe(periodic=periodic)}) {where}"
                )
        branch = getattr(command, "branch", None)
        if branch is not None and "branch" in expected and str(branch) != expected["branch"]:
            return f"branch={str(branch)!r}, but should be {expected['branch']!r} {where}"
    return None


def replay_traces(
    vectors: Mapping[str, Any],
    factory: Callable[[], Planner],
    *,
    planner: str | None = None,
    precision: str = "double",
) -> list[str]:
    """Step fresh planners from ``factory`` through the reference traces; report mismatches.

    Each trace's planner is reset with the trace's ``reset`` message and fed its recorded
    observations in order (open loop: the planner's commands do not move anything); every
    command is compared with the recorded one -- heading modulo 2 pi and speed within the
    file's ``heading`` and ``speed`` tolerances, and the branch when the planner reports one.

    Parameters
    ----------
    vectors : dict
        A vectors document.
    factory : callable
        Makes a new planner (:class:`~ifgm_ref.protocol.Planner`); called once per trace.
    planner : str, optional
        Which traces to replay, by their ``planner`` name; default: the new planner's ``name``.
    precision : {"double", "float32"}, default "double"
        Which tolerance set of the file to apply.

    Returns
    -------
    list of str
        The first mismatch of each trace that has one, with its step, time and reference
        branch; a single message if no trace is for ``planner``.

    Examples
    --------
    >>> from ifgm_ref.planners import IBAPlanner
    >>> vectors = build_vectors()
    >>> replay_traces(vectors, IBAPlanner)
    []
    >>> replay_traces(vectors, IBAPlanner, planner="bug3")
    ["no trace is for planner 'bug3', but traces exist for: iba, ifgm"]
    """
    _check_format(vectors)
    _check_precision(precision)
    name = planner if planner is not None else factory().name
    traces = [t for t in vectors["traces"] if t["planner"] == name]
    if not traces:
        known = ", ".join(sorted({t["planner"] for t in vectors["traces"]}))
        return [f"no trace is for planner {name!r}, but traces exist for: {known}"]
    problems = []
    for trace in traces:
        problem = _replayed(trace, factory(), precision, vectors["tolerances"])
        if problem is not None:
            problems.append(problem)
    return problems
