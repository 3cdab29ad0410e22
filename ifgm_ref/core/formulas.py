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

Formulas are written in sympy's syntax (``Max``, ``Min``, ``pi``) and evaluated with
:func:`sympy.lambdify`: the string shown to the reader is the code that runs. This module
sits below the planners and the simulator, which both use it.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from enum import StrEnum
from typing import TYPE_CHECKING, NamedTuple

import sympy

from ifgm_ref.core.errors import ParameterError

if TYPE_CHECKING:
    from ifgm_ref.core.protocol import EpisodeParams

__all__ = ["LENGTH_SYMBOLS", "SYMBOLS", "Scale", "Unit", "evaluate", "formula_expr"]


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


#: The formula symbols, in :class:`Scale`'s order; lengths are declared positive.
SYMBOLS: tuple[sympy.Symbol, ...] = sympy.symbols("r v w dt R res fov", positive=True)
#: The symbols that carry a length (``v`` is a length per second).
LENGTH_SYMBOLS: frozenset[str] = frozenset({"r", "v", "R"})


@functools.cache
def formula_expr(formula: str) -> sympy.Expr:
    """A formula as a sympy expression over :data:`SYMBOLS`; unknown names are an error.

    >>> formula_expr("Max(r, v/w)")
    Max(r, v/w)
    >>> formula_expr("2*d")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: formula '2*d' uses d; a formula may use r, v, w, dt, ...
    """
    names = {s.name: s for s in SYMBOLS}
    expr = sympy.sympify(formula, locals=names)
    unknown = sorted(s.name for s in expr.free_symbols if s.name not in names)
    if unknown:
        raise ParameterError(
            f"formula {formula!r} uses {', '.join(unknown)}; a formula may use {', '.join(names)}"
        )
    return expr


@functools.cache
def _compiled(formula: str) -> Callable[..., float]:
    return sympy.lambdify(SYMBOLS, formula_expr(formula), modules="math")  # type: ignore[no-any-return]


def evaluate(formula: str, scale: Scale) -> float:
    """The value of ``formula`` for ``scale``.

    >>> round(evaluate("r + v*0.5", Scale.paper()), 4)
    1.6611
    """
    return float(_compiled(formula)(*scale))
