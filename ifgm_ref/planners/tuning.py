"""Planner parameters: read by name from :attr:`EpisodeParams.params`, validated on entry.

Every planner keeps its tunables in a frozen dataclass that mixes in :class:`Tuning`: the
fields are the parameter names (``ifgm-ref planners`` lists them, ``--param NAME=VALUE`` sets
them), the defaults and their reasons are in the dataclass's docstring.
"""

from __future__ import annotations

import math
from dataclasses import fields
from typing import Any, ClassVar, Self

from ifgm_ref.errors import ParameterError


def positive_param(name: str, value: object, *, allow_zero: bool = False) -> float:
    """``value`` as a float if it is a finite number > 0 (>= 0 with ``allow_zero``).

    >>> positive_param("d_th", 3)
    3.0
    >>> positive_param("d_th", 0.0)
    Traceback (most recent call last):
    ...
    ifgm_ref.errors.ParameterError: `d_th` must be a finite number > 0, got 0.0
    """
    ok = (
        not isinstance(value, bool)
        and isinstance(value, int | float)
        and math.isfinite(value)
        and (value >= 0 if allow_zero else value > 0)
    )
    if not ok:
        bound = ">= 0" if allow_zero else "> 0"
        raise ParameterError(f"`{name}` must be a finite number {bound}, got {value!r}")
    return float(value)  # type: ignore[arg-type]


class Tuning:
    """Mixin for a frozen dataclass of planner parameters (all positive numbers).

    A field whose default is ``None`` may be ``None``, meaning "derived from the robot at
    reset"; a field named in ``NON_NEGATIVE`` may also be 0.
    """

    NON_NEGATIVE: ClassVar[frozenset[str]] = frozenset()

    def __post_init__(self) -> None:
        for f in fields(self):  # type: ignore[arg-type]
            value = getattr(self, f.name)
            if not (value is None and f.default is None):
                positive_param(f.name, value, allow_zero=f.name in self.NON_NEGATIVE)

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The parameter names, in declaration order."""
        return tuple(f.name for f in fields(cls))  # type: ignore[arg-type]

    @classmethod
    def from_params(cls, params: dict[str, Any]) -> Self:
        """Take this class's fields from a planner ``params`` mapping; ignore the other keys
        (they belong to another part of the same planner)."""
        known = set(cls.names())
        return cls(**{k: v for k, v in params.items() if k in known})
