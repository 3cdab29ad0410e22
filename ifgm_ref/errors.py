"""The project's error hierarchy.

Every error that bad input can cause derives from :class:`IfgmRefError`, so the command line
can report it as one line and a non-zero exit status instead of a traceback.
"""

from __future__ import annotations


class IfgmRefError(Exception):
    """Base class of every error this package raises on bad input."""


class WorldError(IfgmRefError, ValueError):
    """A world (obstacles, start, goal, bounds, robot or sensor block) is invalid."""


class ParameterError(IfgmRefError, ValueError):
    """A robot, sensor, simulation or planner parameter is out of its domain."""


class PlannerError(IfgmRefError):
    """A planner name is unknown or a planner broke its protocol."""
