"""What an oracle check is: its kind, its failure, its evidence, and the check itself.

A :class:`Check` draws an example with a Hypothesis strategy and runs its test, which raises
:class:`CheckFailed` when the implementation breaks the property; a :class:`Recorder` counts
the examples and keeps the :class:`Evidence` of the last failure for the report. Under noise a
check is absolute (the same test on noisy examples) or statistical (it has a ``sample``: its
misses are counted, :mod:`ifgm_ref.oracle.robust`).
The checks themselves are registered in :data:`ifgm_ref.oracle.checks.CHECKS`.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from enum import StrEnum
from typing import TYPE_CHECKING, Any

from ifgm_ref.core.errors import IfgmRefError, ImplementationError
from ifgm_ref.core.params import SensorParams, SimParams
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.sim.convergence import time_bound
from ifgm_ref.sim.simulator import Run
from ifgm_ref.sim.world import World

if TYPE_CHECKING:
    from hypothesis import strategies as st

    from ifgm_ref.sim.worldgen.draws import Draw

__all__ = [
    "Check",
    "CheckFailed",
    "Evidence",
    "Kind",
    "Level",
    "Meets",
    "PlannerFault",
    "Recorder",
    "levels_up_to",
]


class Kind(StrEnum):
    """What a check exercises."""

    SIMULATION = "simulation"
    EQUATION = "equation"


class Level(StrEnum):
    """The two levels of conformance a check belongs to: the paper's properties, which any
    valid reading passes, and agreement with the reference's readings, step by step."""

    PAPER = "paper"
    REFERENCE = "reference"


def levels_up_to(level: Level | str) -> frozenset[Level]:
    """The levels a run at ``level`` checks: the paper's always, the reference's at
    ``"reference"``; an unknown level is an :class:`ImplementationError`.

    >>> sorted(map(str, levels_up_to("reference"))), sorted(map(str, levels_up_to("paper")))
    (['paper', 'reference'], ['paper'])
    """
    if level not in set(Level):
        raise ImplementationError(f"unknown level {level!r}; known: {', '.join(Level)}")
    return frozenset(Level) if level == Level.REFERENCE else frozenset({Level.PAPER})


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
    #: The step of the first run the failure points at (its plot marks it), if any.
    step: int | None = None


@dataclass
class Recorder:
    """Counts the examples a check ran and keeps the evidence of the last failure (and what
    a passing check has to say, ``summary``, from its ``tally``).

    ``sim`` is what every episode of the check starts from: the engine and body of the
    profile (:meth:`~ifgm_ref.oracle.profiles.Profile.sim`; kinematic by default); ``robot``
    the profile's changes to the robot of every world drawn, ``sensor`` (if any) its sensor.
    """

    examples: int = 0
    worlds: set[World] = field(default_factory=set)
    evidence: Evidence | None = None
    summary: str = ""
    tally: Counter[str] = field(default_factory=Counter)
    sim: SimParams = field(default_factory=SimParams)
    robot: tuple[tuple[str, float], ...] = ()
    sensor: SensorParams | None = None

    @property
    def physical(self) -> bool:
        """Whether the check's episodes run on a robot with mass (not the kinematic engine)."""
        return self.sim.engine != SimParams().engine

    def robot_of(self, world: World) -> World:
        """``world`` with the profile's changes to its robot (``--robot``, ``--speed``) and
        its sensor (a declared specification's)."""
        world = world.with_robot(dict(self.robot))
        return world if self.sensor is None else replace(world, sensor=self.sensor)

    def sim_for(self, world: World) -> SimParams:
        """The settings of an episode in ``world``: :attr:`sim` stopped at the world's
        :func:`~ifgm_ref.sim.convergence.time_bound`."""
        return replace(self.sim, max_time=time_bound(world))


@dataclass(frozen=True)
class Meets:
    """What a check has to meet to have tested anything: the :attr:`Recorder.tally` key
    that counts it, and the thing in words ("a dead end reported as dead_end_turn").

    A property of the form "whenever X, then Y" passes vacuously when X never happens: a
    planner that reports no dead end passes "every dead end turns 45 degrees at a time", a
    robot that never moves passes "rotating the problem rotates the trajectory". Such a
    pass is reported apart (issue 42).
    """

    key: str
    what: str

    def missed(self, recorder: Recorder) -> str | None:
        """Why ``recorder``'s examples tested nothing (``None`` if they met the thing)."""
        if recorder.tally[self.key]:
            return None
        examples = f"{recorder.examples} example{'' if recorder.examples == 1 else 's'}"
        return f"nothing to check: {self.what} in none of {examples}"


@dataclass(frozen=True)
class Check:
    """One property: its name, its sentence, its example strategy and its test, and whether
    it applies to an implementation.

    Under noise, ``sample`` (if any) makes the check statistical: it builds one example from
    seeded draws (a world generator of :mod:`ifgm_ref.sim.worldgen.classes`). ``level`` says
    which level of conformance it belongs to; a run checks the paper's level unless asked
    for the reference's too. ``explicit`` gives examples run every time, before the drawn
    ones (noise-free runs only). ``meets`` says what the check must meet to have tested
    anything: a check that passed without meeting it is "not exercised", never "passed".
    """

    name: str
    sentence: str
    kind: Kind
    strategy: Callable[[Implementation], st.SearchStrategy[Any]]
    test: Callable[[Implementation, Any, Recorder], None]
    applies: Callable[[Implementation], str | None]
    sample: Callable[[Draw], Any] | None = None
    level: Level = Level.PAPER
    explicit: Callable[[], Sequence[Any]] | None = None
    meets: Meets | None = None
