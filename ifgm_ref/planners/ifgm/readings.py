"""The readings the paper leaves open, as options of the reference IFGM.

Where the paper is silent or ambiguous the errata table records the reading we run
(``docs/errata.md``). Some of those choices are free: another reading is as true to the
text, and a port may take it. For each of these the reference IFGM runs any of the readings
listed here, chosen by :class:`Readings` (ours by default), so that reference agreement
(``agrees_with_reference``, :mod:`ifgm_ref.oracle.agreement`) can compare a port with the
reading it declares (``ifgm-ref oracle --reading NAME=VALUE``).

The names are a closed list, :data:`OPEN_READINGS`: a name not on it is a mistake, said at
once. The values are open: a port may declare a reading the reference cannot run, and the
check then says so (:func:`unrunnable`) instead of failing the port.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from enum import StrEnum
from typing import Any, Self

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.paper.percepts.clusters import GapReading

__all__ = [
    "OPEN_READINGS",
    "DeadEndSide",
    "GapChoice",
    "GapReading",
    "LeavingRule",
    "OpenReading",
    "Readings",
    "known_names",
    "parse_readings",
    "unrunnable",
]


class DeadEndSide(StrEnum):
    """Which way the dead end's 45-degree turns go (section 4, Case-3; errata row 17)."""

    FREER = "freer"  # towards the freer side beam, ties to the goal's side (ours)
    LEFT = "left"  # always counter-clockwise
    RIGHT = "right"  # always clockwise


class GapChoice(StrEnum):
    """Which gap Case-1 steers through (section 4; errata row 19)."""

    KEEP = "keep"  # the gap chosen at the last step while it stays wider than d_th (ours)
    WIDEST = "widest"  # the maximum gap, chosen anew at every step (the text alone)


class LeavingRule(StrEnum):
    """When IFGM's IBA leaves an edge (section 4.1; errata rows 24 and 31)."""

    FREE_PATH_OR_PROGRESS = "free_path_or_progress"  # a free path, or DistBug's progress (ours)
    FREE_PATH = "free_path"  # a free path only, as section 4.1 prints it


@dataclass(frozen=True)
class Readings:
    """The reading the reference IFGM runs of each open choice (see the module docstring).

    Attributes
    ----------
    dead_end_side : DeadEndSide
        Which way the dead end turns.
    gap_points : GapReading
        Which points of two obstacles a gap runs between (errata row 15): the nearest pair
        (ours) or their average positions (the printed "average clustered value").
    gap_choice : GapChoice
        Whether Case-1 keeps the gap it chose or takes the widest at every step.
    leaving_rule : LeavingRule
        Whether IBA also leaves by DistBug's progress rule.
    """

    dead_end_side: DeadEndSide = DeadEndSide.FREER
    gap_points: GapReading = GapReading.NEAREST
    gap_choice: GapChoice = GapChoice.KEEP
    leaving_rule: LeavingRule = LeavingRule.FREE_PATH_OR_PROGRESS

    @classmethod
    def declared(cls, choices: Mapping[str, str]) -> Self:
        """The readings ``choices`` names (by :data:`OPEN_READINGS`), ours for the rest.

        Raises
        ------
        ParameterError
            A name not in :data:`OPEN_READINGS`, or a value the reference cannot run.

        >>> Readings.declared({"dead_end_side": "left"}).dead_end_side
        <DeadEndSide.LEFT: 'left'>
        >>> Readings.declared({"dead_end_side": "random"})
        Traceback (most recent call last):
        ...
        ifgm_ref.core.errors.ParameterError: the reference cannot run dead_end_side=random; \
it runs: freer, left, right
        """
        known_names(choices)
        why = unrunnable(choices)
        if why is not None:
            raise ParameterError(why)
        chosen: dict[str, Any] = {n: OPEN_READINGS[n].kind(v) for n, v in choices.items()}
        return cls(**chosen)


@dataclass(frozen=True)
class OpenReading:
    """One open choice: its errata row and the readings of it the reference runs."""

    name: str
    rows: tuple[int, ...]
    kind: type[StrEnum]

    @property
    def values(self) -> tuple[str, ...]:
        """The readings the reference runs, ours first."""
        return tuple(str(value) for value in self.kind)


#: Every open choice by name, with the errata rows that record it.
OPEN_READINGS: dict[str, OpenReading] = {
    reading.name: reading
    for reading in (
        OpenReading("dead_end_side", (17,), DeadEndSide),
        OpenReading("gap_points", (15,), GapReading),
        OpenReading("gap_choice", (19,), GapChoice),
        OpenReading("leaving_rule", (24, 31), LeavingRule),
    )
}


def parse_readings(items: Iterable[str]) -> dict[str, str]:
    """``NAME=VALUE`` items (``--reading``) as a mapping, each name checked
    (:func:`known_names`); the values are left to whoever runs them.

    >>> parse_readings(["dead_end_side=left", "gap_points=means"])
    {'dead_end_side': 'left', 'gap_points': 'means'}
    >>> parse_readings(["dead_end_side"])
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: a reading is NAME=VALUE, got 'dead_end_side'
    """
    choices: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name or not value:
            raise ParameterError(f"a reading is NAME=VALUE, got {item!r}")
        choices[name.strip()] = value.strip()
    known_names(choices)
    return choices


def known_names(choices: Mapping[str, str]) -> None:
    """Raise :class:`ParameterError` if ``choices`` names a choice not in
    :data:`OPEN_READINGS` (a typo: said at once, never taken for a reading)."""
    unknown = sorted(set(choices) - set(OPEN_READINGS))
    if unknown:
        raise ParameterError(
            f"no open reading named {', '.join(unknown)}; the open readings are: "
            + ", ".join(OPEN_READINGS)
        )


def unrunnable(choices: Mapping[str, str]) -> str | None:
    """Why the reference cannot run the readings ``choices`` declares, or ``None`` if it can
    run every one (the names must be known: :func:`known_names`)."""
    for name, value in choices.items():
        values = OPEN_READINGS[name].values
        if value not in values:
            return f"the reference cannot run {name}={value}; it runs: {', '.join(values)}"
    return None
