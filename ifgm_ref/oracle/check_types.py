"""What an oracle check is: its kind, its failure, its evidence, and the check itself.

A :class:`Check` draws an example with a Hypothesis strategy and runs its test, which raises
:class:`CheckFailed` when the implementation breaks the property; a :class:`Recorder` counts
the examples and keeps the :class:`Evidence` of the last failure for the report. The checks
themselves are registered in :data:`ifgm_ref.oracle.checks.CHECKS`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

from hypothesis import strategies as st

from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.simulator import Run
from ifgm_ref.world import World

__all__ = ["Check", "CheckFailed", "Evidence", "Kind", "Recorder"]


class Kind(StrEnum):
    """What a check exercises."""

    SIMULATION = "simulation"
    EQUATION = "equation"


class CheckFailed(AssertionError):
    """An implementation broke a property; the message says how."""


@dataclass
class Evidence:
    """What the last failing example left behind, for the failure report."""

    worlds: list[World] = field(default_factory=list)
    runs: list[Run] = field(default_factory=list)
    max_time: float | None = None
    inputs: dict[str, Any] | None = None


@dataclass
class Recorder:
    """Counts the examples a check ran and keeps the evidence of the last failure."""

    examples: int = 0
    worlds: set[World] = field(default_factory=set)
    evidence: Evidence | None = None


@dataclass(frozen=True)
class Check:
    """One property: its name, its sentence, its example strategy and its test."""

    name: str
    sentence: str
    kind: Kind
    strategy: Callable[[Implementation], st.SearchStrategy[Any]]
    test: Callable[[Implementation, Any, Recorder], None]
    applies: Callable[[Implementation], str | None]
