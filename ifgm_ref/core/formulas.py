"""The formulas planner parameters and simulator rules are derived from: symbols, units,
evaluation.

A planner holds no absolute length (:mod:`ifgm_ref.planners.tuning`), nor do the simulator's
stall rules (:mod:`ifgm_ref.sim.simulator`, :mod:`ifgm_ref.sim.laps`): each threshold is a *formula*
in the quantities of the robot, the time step and the sensor, with a *unit*. The symbols a
formula may use:

=========  ====================================================================  ==========
symbol     quantity                                                              the paper
=========  ====================================================================  ==========
``r``      robot radius                                                          1 ft
``v``      robot speed                                                           1.322 ft/s
``w``      largest turn rate, rad/s (``v / w`` is the turning radius)            pi/2
``dt``     time step, s                                                          0.1
``R``      sensor range (``range_max``)                                          15 ft
``res``    angle between two rays, rad                                           1.8 deg
``fov``    field of view, rad                                                    135 deg
=========  ====================================================================  ==========

The paper's numbers are what the formulas give for the paper's robot (:meth:`Scale.paper`).
Units follow from the symbols: a *length* is homogeneous of degree 1 in ``r``, ``v`` and
``R`` (scale every length of the world, the robot and the sensor by ``k`` and it scales by
``k``), a *time*, *angle* or *number* of degree 0; ``proofs/scale.py`` proves it of every
declared formula.

Formulas are written in sympy's syntax (``Max``, ``Min``, ``pi``) and run as the Python code
:func:`sympy.lambdify` prints for them (``modules="math"``). Every formula the package declares
(:func:`declare`) has that code pinned in :mod:`ifgm_ref.core.lambdified`, which
``tests/test_formulas.py`` checks against the installed sympy: a process that runs a planner
does not import sympy, and a sympy release that prints a formula otherwise cannot move a
threshold unnoticed. A formula not in the table is printed by sympy at its first use. This
module sits below the planners and the simulator, which both use it.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from enum import StrEnum
from typing import TYPE_CHECKING, Any, NamedTuple

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.lambdified import LAMBDIFIED

if TYPE_CHECKING:
    import sympy

    from ifgm_ref.core.protocol import EpisodeParams

__all__ = [
    "LENGTH_SYMBOLS",
    "SYMBOL_NAMES",
    "Scale",
    "Unit",
    "declare",
    "declared",
    "evaluate",
    "formula_expr",
    "lambdified_code",
]


class Unit(StrEnum):
    """What a planner parameter measures; ``length_power`` is how it scales with lengths."""

    LENGTH = "length"
    #: A length to the fourth power (APF's repulsive gain balancing a quadratic well).
    LENGTH4 = "length^4"
    TIME = "s"
    ANGLE = "rad"
    NUMBER = "1"
    #: A speed (DWA's velocity limits): a length per second.
    SPEED = "length/s"
    #: An acceleration (DWA's acceleration limits): a length per second squared.
    ACCELERATION = "length/s^2"
    #: A turn rate, rad/s.
    TURN_RATE = "rad/s"
    #: An angular acceleration, rad/s^2.
    TURN_ACCELERATION = "rad/s^2"

    @property
    def length_power(self) -> int:
        """The power ``p`` such that scaling every length by ``k`` scales the value by
        ``k ** p``.

        >>> Unit.LENGTH.length_power, Unit.TIME.length_power, Unit.LENGTH4.length_power
        (1, 0, 4)
        >>> Unit.SPEED.length_power, Unit.ACCELERATION.length_power, Unit.TURN_RATE.length_power
        (1, 1, 0)
        """
        return {Unit.LENGTH: 1, Unit.LENGTH4: 4, Unit.SPEED: 1, Unit.ACCELERATION: 1}.get(self, 0)


class Scale(NamedTuple):
    """The quantities every planner parameter is derived from (the formula symbols)."""

    r: float
    v: float
    w: float
    dt: float
    R: float
    res: float
    fov: float

    @classmethod
    def of(cls, params: EpisodeParams) -> Scale:
        """The scale of an episode: its robot, time step and sensor."""
        robot, sensor = params.robot, params.sensor
        return cls(
            robot.radius,
            robot.speed,
            robot.max_turn_rate,
            params.dt,
            sensor.range_max,
            sensor.angle_increment,
            sensor.fov,
        )

    @classmethod
    def paper(cls) -> Scale:
        """The paper's robot with our defaults (:mod:`ifgm_ref.core.params`)."""
        from ifgm_ref.core.protocol import EpisodeParams

        return cls.of(EpisodeParams())


#: The names of the formula symbols, in :class:`Scale`'s order.
SYMBOL_NAMES: tuple[str, ...] = Scale._fields
#: The symbols that carry a length (``v`` is a length per second).
LENGTH_SYMBOLS: frozenset[str] = frozenset({"r", "v", "R"})

#: Every formula declared so far (:func:`declare`), in the order of declaration.
_DECLARED: dict[str, None] = {}


@functools.cache
def _symbols() -> tuple[sympy.Symbol, ...]:
    import sympy

    return sympy.symbols(" ".join(SYMBOL_NAMES), positive=True)  # type: ignore[no-any-return]


def __getattr__(name: str) -> Any:
    """``SYMBOLS``: the formula symbols as sympy symbols, in :class:`Scale`'s order, lengths
    declared positive (made at first use, so that importing this module does not import
    sympy)."""
    if name == "SYMBOLS":
        return _symbols()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


@functools.cache
def formula_expr(formula: str) -> sympy.Expr:
    """A formula as a sympy expression over ``SYMBOLS``; unknown names are an error.

    >>> formula_expr("Max(r, v/w)")
    Max(r, v/w)
    >>> formula_expr("2*d")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: formula '2*d' uses d; a formula may use r, v, w, dt, ...
    """
    import sympy

    names = {s.name: s for s in _symbols()}
    expr = sympy.sympify(formula, locals=names)
    unknown = sorted(s.name for s in expr.free_symbols if s.name not in names)
    if unknown:
        raise ParameterError(
            f"formula {formula!r} uses {', '.join(unknown)}; a formula may use {', '.join(names)}"
        )
    return expr


def lambdified_code(formula: str) -> str:
    """The Python expression :func:`sympy.lambdify` prints for ``formula`` over the symbols
    (``modules="math"``): what :mod:`ifgm_ref.core.lambdified` pins.

    >>> lambdified_code("2*r/4.4"), lambdified_code("Max(6*pi/w, 10*r/v, 20*dt)")
    ('0.454545454545455*r', 'max(20*dt, 6*pi/w, 10*r/v)')
    """
    import inspect

    import sympy

    function = sympy.lambdify(_symbols(), formula_expr(formula), modules="math")
    head, body = inspect.getsource(function).rstrip("\n").split("\n")
    if head != f"def _lambdifygenerated({', '.join(SYMBOL_NAMES)}):" or not body.startswith(
        "    return "
    ):
        raise ParameterError(f"formula {formula!r}: sympy printed more than one expression")
    return body.removeprefix("    return ")


def declare(formula: str) -> str:
    """``formula``, checked (a bad one is a :class:`ParameterError` at import) and noted as one
    the package evaluates (:func:`declared`).

    >>> declare("v*dt") in declared()
    True
    """
    if formula not in LAMBDIFIED:
        formula_expr(formula)
    _DECLARED[formula] = None
    return formula


def declared() -> tuple[str, ...]:
    """Every formula declared so far, in the order of declaration: those of the modules
    imported (the planners' parameters, the simulator's stall rules)."""
    return tuple(_DECLARED)


@functools.cache
def _compiled(formula: str) -> Callable[..., float]:
    code = LAMBDIFIED.get(formula) or lambdified_code(formula)
    compiled = eval(f"lambda {', '.join(SYMBOL_NAMES)}: {code}", dict(vars(math)))
    return compiled  # type: ignore[no-any-return]


def evaluate(formula: str, scale: Scale) -> float:
    """The value of ``formula`` for ``scale``.

    >>> round(evaluate("r + v*0.5", Scale.paper()), 4)
    1.6611
    """
    return float(_compiled(formula)(*scale))
