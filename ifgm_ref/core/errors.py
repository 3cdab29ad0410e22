"""The project's error hierarchy.

Every error this package raises derives from :class:`IfgmRefError`, so the command line can
report it as one line and a non-zero exit status instead of a traceback: bad input (most of
them), an oracle's verdict (:class:`~ifgm_ref.oracle.check_types.CheckFailed`), or a broken
invariant of the reference (:class:`InvariantError`, a bug here).
"""

from __future__ import annotations

from typing import TypeVar

_T = TypeVar("_T")


class IfgmRefError(Exception):
    """Base class of every error this package raises."""


class WorldError(IfgmRefError, ValueError):
    """A world (obstacles, start, goal, bounds, robot or sensor block) is invalid."""


class ParameterError(IfgmRefError, ValueError):
    """A robot, sensor, simulation or planner parameter is out of its domain."""


class PlannerError(IfgmRefError):
    """A planner name is unknown or a planner broke its protocol."""


class ProtocolError(IfgmRefError, ValueError):
    """A JSON-lines protocol message is malformed (``docs/oracle-protocol.md``)."""


class ImplementationError(IfgmRefError):
    """An implementation under test cannot be loaded, or crashed, hung or answered garbage.

    The oracle reports it as such, apart from property failures: it is not a counterexample
    to a property but a program that could not be checked.
    """


class BagError(IfgmRefError, ValueError):
    """A robot log (a ROS bag) cannot be read or replayed: a topic is missing, time runs
    backwards, a scan changes its ray count or holds NaN, ..."""


class InvariantError(IfgmRefError, RuntimeError):
    """The reference broke one of its own invariants: a bug in this package, never bad input
    (Figure 3's guards not partitioning the atoms, a branch without what it acts on)."""


def present(value: _T | None, what: str) -> _T:
    """``value``, which an invariant says is there; :class:`InvariantError` naming ``what``
    if it is ``None`` (an ``assert`` would vanish under ``python -O``).

    >>> present(3, "the gap")
    3
    >>> present(None, "the gap Case-1 steers through")
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.InvariantError: the gap Case-1 steers through is missing
    """
    if value is None:
        raise InvariantError(f"{what} is missing")
    return value
