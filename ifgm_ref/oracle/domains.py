"""The input domains of equations (1)-(4): every argument defined once, with its reasons.

Three things draw inputs for the functions of :mod:`ifgm_ref.paper.equations`: the oracle's equation
checks (:mod:`ifgm_ref.oracle.equation_checks`), the property tests of
``tests/test_equations.py`` and the seeded random cases of the test vectors
(:mod:`ifgm_ref.oracle.vectors`). They take their intervals from here. Each :class:`Argument`
holds two, each with its reason:

``domain``
    Where every implementation must agree with the reference, so where the oracle checks and
    the property tests draw (with Hypothesis: :func:`floats`, :func:`inputs`). It is the
    equation's own domain (``docs/errata.md`` row 9: weights finite, ``>= 0`` and not both 0,
    ``d_th > 0``; row 13: the printed forms' divisions by zero) bounded so that floats stay
    normal: coordinates within 1000 ft (a world a few times the paper's 197 ft run), sensor
    distances 0.1-15 ft (:class:`~ifgm_ref.core.params.SensorParams`), weights in ``{0}`` or
    ``[1e-3, 1e3]``. Magnitudes below ``smallest`` are left out (0 itself stays in): products
    with weights and scale factors near 1e-308 would go subnormal and lose relative precision.
``vectors``
    The sub-range the vectors' random cases are drawn from, uniformly, by a seeded numpy
    generator (:mod:`ifgm_ref.oracle.vectors.cases`). Inside it a float32 port's errors stay
    near 1e-6, which the file's float32 tolerances rely on (``docs/vectors-format.md``: inputs
    of eq. (1) within 20 ft, random eq. (3) points at least :data:`EQ3_MIN_DISTANCE` apart,
    FGM's border angles at least :data:`FGM_MIN_WIDTH` apart). These bounds are frozen: the
    committed vectors file is drawn from them, and moving one changes its bytes.

The paper's symbols for every argument are in the table of :mod:`ifgm_ref.paper.equations`.

Examples
--------
>>> d_th = DOMAINS["eq4_final_heading"].argument("d_th")
>>> d_th.unit, d_th.domain, d_th.vectors
('ft', Interval(low=0.01, high=100.0, smallest=0.0), Interval(low=2.5, high=6.0, smallest=0.0))
>>> weights = DOMAINS["eq4_final_heading"].argument("w_g").domain
>>> weights.contains(0.0), weights.contains(5e-4), weights.contains(9.0)
(True, False, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from hypothesis import strategies as st

from ifgm_ref.core.validate import NON_NEGATIVE, require

__all__ = [
    "DOMAINS",
    "EQ3_MIN_DISTANCE",
    "FGM_MIN_WIDTH",
    "HALF_FOV",
    "Argument",
    "EquationDomain",
    "Interval",
    "floats",
    "inputs",
]

#: Half the paper's 135-degree field of view, rad (section 4): gap borders lie within it.
HALF_FOV = math.radians(67.5)
#: Vectors only: random eq. (3) points are at least this far apart, ft, so that a float32
#: rounding of a 200 ft coordinate (7.6e-6 ft) turns the direction by under 2e-6 rad.
EQ3_MIN_DISTANCE = 10.0
#: Vectors only: random FGM gaps are at least this wide, rad. FGM's arccos form is
#: ill-conditioned as its argument nears 1 (narrow gaps); 0.1 rad keeps float32's 1e-7 in the
#: argument within 1e-6 rad of angle.
FGM_MIN_WIDTH = 0.1


@dataclass(frozen=True)
class Interval:
    """The floats ``x`` with ``low <= x <= high`` and ``x == 0`` or ``|x| >= smallest``."""

    low: float
    high: float
    smallest: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.low) and math.isfinite(self.high) and self.low < self.high):
            raise ValueError(f"an interval needs finite low < high, got [{self.low}, {self.high}]")
        require("smallest", self.smallest, NON_NEGATIVE)

    def contains(self, value: float) -> bool:
        """Whether ``value`` lies in the interval.

        >>> Interval(-1.0, 1.0, smallest=0.5).contains(-0.25)
        False
        """
        in_range = self.low <= value <= self.high
        return in_range and (value == 0.0 or abs(value) >= self.smallest)


@dataclass(frozen=True)
class Argument:
    """One argument of an equation: its unit, its domain and the vectors' sub-range.

    A point argument (``p1``, ``current`` ...) has both coordinates in the intervals.
    """

    name: str
    unit: str
    domain: Interval
    vectors: Interval
    point: bool = False


@dataclass(frozen=True)
class EquationDomain:
    """The arguments of one equation (its interpreted function's name), in call order.

    ``singular`` names the points of the domain where the reference raises anyway
    (:class:`~ifgm_ref.core.errors.ParameterError`); a drawn input may hit one, and every user of
    the domain skips it.
    """

    name: str
    arguments: tuple[Argument, ...]
    singular: str

    def argument(self, name: str) -> Argument:
        """The argument called ``name``."""
        for argument in self.arguments:
            if argument.name == name:
                return argument
        raise KeyError(f"{self.name} has no argument {name!r}")


_COORDINATES = Interval(-1e3, 1e3, smallest=1e-6)
_ANGLES = Interval(-math.pi, math.pi, smallest=1e-9)
_BORDER_ANGLES = Interval(-HALF_FOV, HALF_FOV, smallest=1e-9)
_RANGES = Interval(0.1, 15.0)
_WEIGHTS = Interval(0.0, 1e3, smallest=1e-3)
_DIVISORS = Interval(1e-2, 1e2)
_FULL_TURN = Interval(-math.pi, math.pi)


def _point(name: str, half: float) -> Argument:
    return Argument(name, "ft", _COORDINATES, Interval(-half, half), point=True)


def _angle(name: str) -> Argument:
    return Argument(name, "rad", _ANGLES, _FULL_TURN)


#: Every equation's domain, by its interpreted function's name (the vectors' group names).
#: The ``vectors`` bounds: eq. (1) within 20 ft (the sensor's 15 ft and a margin), eq. (2)'s
#: midpoint within the sensor's 15 ft, eq. (3) positions within 200 ft (the paper's 197 ft
#: run); eq. (4)'s weights around the defaults (``w_g = 9 r``, ``w_d = 1``, ``d_th = 3 r``
#: for the paper's r = 1 ft; FGM's ``beta = 1``); FGM's border distances within 10x of each
#: other, ``d_min`` within the sensor's range.
DOMAINS: dict[str, EquationDomain] = {
    domain.name: domain
    for domain in (
        EquationDomain("eq1_gap_midpoint", (_point("p1", 20.0), _point("p2", 20.0)), "none"),
        EquationDomain(
            "eq2_gap_angle",
            (
                Argument("x_g", "ft", _COORDINATES, Interval(-15.0, 15.0)),
                Argument("y_g", "ft", _COORDINATES, Interval(-15.0, 15.0)),
            ),
            "(x_g, y_g) = (0, 0); the printed form also x_g = 0",
        ),
        EquationDomain(
            "fgm_gap_centre_angle",
            (
                Argument("d1", "ft", _RANGES, Interval(1.0, 10.0)),
                Argument("phi1", "rad", _BORDER_ANGLES, Interval(-HALF_FOV, HALF_FOV)),
                Argument("d2", "ft", _RANGES, Interval(1.0, 10.0)),
                Argument("phi2", "rad", _BORDER_ANGLES, Interval(-HALF_FOV, HALF_FOV)),
            ),
            "a negative width phi1 + phi2",
        ),
        EquationDomain(
            "eq3_goal_angle",
            (_point("current", 200.0), _point("destination", 200.0)),
            "destination == current; the printed form also x_d == x_c",
        ),
        EquationDomain(
            "eq4_final_heading",
            (
                _angle("theta_g"),
                _angle("theta_d"),
                Argument("w_g", "ft", _WEIGHTS, Interval(0.5, 12.0)),
                Argument("w_d", "1", _WEIGHTS, Interval(0.1, 2.0)),
                Argument("d_th", "ft", _DIVISORS, Interval(2.5, 6.0)),
                _angle("heading"),
            ),
            "w_g == w_d == 0 (0/0)",
        ),
        EquationDomain(
            "eq4_final_heading_fgm",
            (
                _angle("theta_g"),
                _angle("theta_d"),
                Argument("alpha", "ft", _WEIGHTS, Interval(0.1, 5.0)),
                Argument("beta", "1", _WEIGHTS, Interval(0.1, 2.0)),
                Argument("d_min", "ft", _DIVISORS, Interval(0.2, 15.0)),
                _angle("heading"),
            ),
            "alpha == beta == 0 (0/0)",
        ),
    )
}


def floats(interval: Interval) -> st.SearchStrategy[float]:
    """The Hypothesis strategy of the floats of ``interval`` (no NaN, infinity or subnormal).

    It shrinks towards 0 where 0 is in the interval, else towards the bound nearer 0.
    """
    low, high, smallest = interval.low, interval.high, interval.smallest
    if smallest == 0.0:
        return _finite(low, high)
    parts: list[st.SearchStrategy[float]] = []
    if low <= 0.0 <= high:
        parts.append(st.just(0.0))
    if high >= smallest:
        parts.append(_finite(max(low, smallest), high))
    if low <= -smallest:
        parts.append(_finite(low, min(high, -smallest)))
    return st.one_of(parts)


def _finite(low: float, high: float) -> st.SearchStrategy[float]:
    return st.floats(
        min_value=low,
        max_value=high,
        allow_nan=False,
        allow_infinity=False,
        allow_subnormal=False,
    )


def inputs(equation: str, args: tuple[str, ...] | None = None) -> st.SearchStrategy[dict[str, Any]]:
    """The Hypothesis strategy of keyword arguments of ``equation`` drawn from its domain.

    ``args`` picks some of the arguments (a printed form takes fewer: no ``heading``), in
    their order; points are tuples. Draws may hit the domain's singular points
    (``EquationDomain.singular``).
    """
    domain = DOMAINS[equation]
    names = args if args is not None else tuple(a.name for a in domain.arguments)
    values = st.tuples(*(_argument(domain.argument(name)) for name in names))
    return values.map(lambda drawn: dict(zip(names, drawn, strict=True)))


def _argument(argument: Argument) -> st.SearchStrategy[Any]:
    coordinate = floats(argument.domain)
    return st.tuples(coordinate, coordinate) if argument.point else coordinate
