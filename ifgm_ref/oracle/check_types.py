"""What an oracle check is: its kind, its failure, its evidence, and the check itself.

A :class:`Check` draws an example with a Hypothesis strategy and runs its test, which raises
:class:`CheckFailed` when the implementation breaks the property; a :class:`Recorder` counts
the examples and keeps the :class:`Evidence` of the last failure for the report. Under noise a
check is absolute (the same test on noisy examples) or statistical (it has a ``sample``: its
misses are counted, :mod:`ifgm_ref.oracle.robust`).
The checks themselves are registered in :data:`ifgm_ref.oracle.checks.CHECKS`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

from hypothesis import strategies as st

from ifgm_ref.errors import IfgmRefError
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.simulator import Run
from ifgm_ref.world import World
from ifgm_ref.worldgen.draws import Draw

__all__ = ["Check", "CheckFailed", "Evidence", "Kind", "PlannerFault", "Recorder"]


class Kind(StrEnum):
    """What a check exercises."""

    SIMULATION = "simulation"
    EQUATION = "equation"


class CheckFailed(IfgmRefError):
    """An implementation broke a property; the message says how."""


class PlannerFault(CheckFailed):
    """The planner raised or answered an invalid command: a failure in every check, never a
    miss that a statistical check counts."""


@dataclass
class Evidence:
    """What the last failing example left behind, for the failure report."""

    worlds: list[World] = field(default_factory=list)
    runs: list[Run] = field(default_factory=list)
    max_time: float | None = None
    inputs: dict[str, Any] | None = None


@dataclass
class Recorder:
    """Counts the examples a check ran and keeps the evidence of the last failure (and a
    statistical check's tally: ``summary``)."""

    examples: int = 0
    worlds: set[World] = field(default_factory=set)
    evidence: Evidence | None = None
    summary: str = ""


@dataclass(frozen=True)
class Check:
    """One property: its name, its sentence, its example strategy and its test, and whether
    it applies to an implementation.

    Under noise, ``sample`` (if any) makes the check statistical: it builds one example from
    seeded draws (a world generator of :mod:`ifgm_ref.worldgen.classes`).
    """

    name: str
    sentence: str
    kind: Kind
    strategy: Callable[[Implementation], st.SearchStrategy[Any]]
    test: Callable[[Implementation, Any, Recorder], None]
    applies: Callable[[Implementation], str | None]
    sample: Callable[[Draw], Any] | None = None
