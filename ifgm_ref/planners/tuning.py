"""Planner parameters: one scale-free model for every planner.

A planner holds no absolute length. Each of its parameters is a field of a frozen dataclass
that mixes in :class:`Tuning`, declared with :func:`derived`: a *formula* in the quantities
of the robot, the time step and the sensor, and a *unit* (:mod:`ifgm_ref.core.formulas`: the
symbols, the units and how a formula is evaluated). The formula gives the default; a value
set by name in :attr:`EpisodeParams.params <ifgm_ref.core.protocol.EpisodeParams>` (or with
``--param NAME=VALUE``) replaces it. ``ifgm-ref planners`` prints every formula and its value
for the paper's robot; ``proofs/scale.py`` proves each scales with its unit, and the
oracle's ``scale_invariant`` check tests the consequence on whole episodes.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any, Self

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.formulas import Scale, Unit, declare, evaluate
from ifgm_ref.core.validate import NON_NEGATIVE, POSITIVE, require, violation

if TYPE_CHECKING:
    from ifgm_ref.core.protocol import EpisodeParams


def derived(formula: str, unit: Unit, *, zero: bool = False) -> Any:
    """A parameter field whose default is ``formula`` (see the module docstring).

    ``zero`` allows the value 0; otherwise every value must be > 0.
    """
    return field(default=None, metadata={"formula": declare(formula), "unit": unit, "zero": zero})


@dataclass(frozen=True)
class ParamInfo:
    """One declared parameter: its name, default formula and unit."""

    name: str
    formula: str
    unit: Unit

    def value(self, scale: Scale) -> float:
        """The default for ``scale``."""
        return evaluate(self.formula, scale)


class Tuning:
    """Mixin for a frozen dataclass of planner parameters declared with :func:`derived`.

    A field left ``None`` takes its formula's value in :meth:`for_episode`; a field given a
    value must be a finite number > 0 (>= 0 where declared with ``zero=True``).
    """

    def __post_init__(self) -> None:
        for f in fields(self):  # type: ignore[arg-type]
            value = getattr(self, f.name)
            if value is not None:
                require(f.name, value, NON_NEGATIVE if f.metadata["zero"] else POSITIVE)

    @classmethod
    def violation(cls, name: str, value: float) -> str:
        """Why ``value`` cannot be the parameter ``name`` of this class (``""``: it can)."""
        (found,) = [f for f in fields(cls) if f.name == name]  # type: ignore[arg-type]
        return violation(value, NON_NEGATIVE if found.metadata["zero"] else POSITIVE)

    @classmethod
    def infos(cls) -> tuple[ParamInfo, ...]:
        """Every parameter with its formula and unit, in declaration order."""
        return tuple(
            ParamInfo(f.name, f.metadata["formula"], f.metadata["unit"])
            for f in fields(cls)  # type: ignore[arg-type]
        )

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The parameter names, in declaration order."""
        return tuple(f.name for f in fields(cls))  # type: ignore[arg-type]

    @classmethod
    def for_episode(cls, params: EpisodeParams) -> Self:
        """The parameters of an episode: the values set by name in ``params.params`` (other
        keys belong to another part of the same planner and are ignored here), every other
        one from its formula."""
        known = set(cls.names())
        for name, value in params.params.items():
            if name in known and value is None:  # a value given must be a number
                require(name, value, POSITIVE)
        given = cls(**{k: v for k, v in params.params.items() if k in known})
        scale = Scale.of(params)
        return cls(
            **{
                info.name: evaluate(info.formula, scale)
                if getattr(given, info.name) is None
                else float(getattr(given, info.name))
                for info in cls.infos()
            }
        )

    @classmethod
    def paper(cls) -> Self:
        """The defaults for the paper's robot (:meth:`Scale.paper`), every field a number."""
        from ifgm_ref.core.protocol import EpisodeParams

        return cls.for_episode(EpisodeParams())


def check_names(params: Mapping[str, object], allowed: Iterable[str], planner: str) -> None:
    """Raise :class:`ParameterError` if ``params`` names a parameter ``planner`` does not have.

    >>> check_names({"d_th": 3.0}, ("d_th", "d_obs"), "ifgm")
    >>> check_names({"dth": 3.0}, ("d_th", "d_obs"), "ifgm")
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: ifgm has no parameter `dth`; it has: d_th, d_obs
    """
    allowed = tuple(allowed)
    unknown = [name for name in params if name not in allowed]
    if unknown:
        has = ", ".join(allowed) if allowed else "none"
        names = ", ".join(f"`{n}`" for n in unknown)
        raise ParameterError(f"{planner} has no parameter {names}; it has: {has}")


def parameter_names(tunings: Iterable[type[Tuning]]) -> tuple[str, ...]:
    """The names of every parameter of ``tunings``, in order: a planner's ``parameters``,
    derived from its ``tunings`` so that the two cannot disagree."""
    return tuple(name for tuning in tunings for name in tuning.names())


def parameter_infos(tunings: Iterable[type[Tuning]]) -> tuple[ParamInfo, ...]:
    """Every parameter of ``tunings`` (a planner's :class:`Tuning` classes), in order."""
    return tuple(info for tuning in tunings for info in tuning.infos())


def episode_values(tunings: Iterable[type[Tuning]], params: EpisodeParams) -> dict[str, float]:
    """Every parameter of ``tunings`` with the value it takes in the episode ``params``."""
    values: dict[str, float] = {}
    for tuning in tunings:
        resolved = tuning.for_episode(params)
        values.update({name: getattr(resolved, name) for name in tuning.names()})
    return values
