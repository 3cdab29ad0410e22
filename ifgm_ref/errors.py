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
