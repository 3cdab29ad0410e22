"""The one validator: the rule for the numbers the project is handed, and its wording.

A robot's radius, a planner's ``d_th``, a protocol message's ``dt``, a ``--timeout`` on the
command line: each is a finite number (``bool`` is not one, though Python counts it an
``int``), and most must also be ``> 0`` or ``>= 0``. :func:`violation` says why a value is
not; :func:`require` raises it as the caller's error. Every configuration class
(:mod:`ifgm_ref.core.params`, :class:`~ifgm_ref.planners.tuning.Tuning`,
:class:`~ifgm_ref.core.protocol.EpisodeParams`), the protocol's reader and the command line's
argument types check through these two, so one value is refused in the same words wherever
it comes from.
"""

from __future__ import annotations

import math
import numbers
from enum import StrEnum

from ifgm_ref.core.errors import IfgmRefError, ParameterError

__all__ = ["NON_NEGATIVE", "POSITIVE", "REAL", "Domain", "require", "violation"]


class Domain(StrEnum):
    """Where a finite number must lie, as a message says it."""

    REAL = ""
    POSITIVE = "> 0"
    NON_NEGATIVE = ">= 0"

    def holds(self, value: float) -> bool:
        """Whether the finite ``value`` lies in this domain."""
        match self:
            case Domain.POSITIVE:
                return value > 0
            case Domain.NON_NEGATIVE:
                return value >= 0
        return True


#: The three domains by name, as the configuration classes write them.
REAL, POSITIVE, NON_NEGATIVE = Domain.REAL, Domain.POSITIVE, Domain.NON_NEGATIVE


def violation(value: object, domain: Domain = Domain.REAL, *, shown: str | None = None) -> str:
    """Why ``value`` is not a finite number in ``domain``, or ``""`` if it is; the value is
    quoted as ``shown`` (its ``repr`` by default).

    >>> violation(3), violation(0.0, Domain.POSITIVE), violation(True)
    ('', 'must be a finite number > 0, got 0.0', 'must be a finite number, got True')
    >>> violation(float("nan"), Domain.NON_NEGATIVE, shown="'nan'")
    "must be a finite number >= 0, got 'nan'"
    """
    if _finite(value) and domain.holds(float(value)):  # type: ignore[arg-type]
        return ""
    bound = f" {domain}" if domain else ""
    got = repr(value) if shown is None else shown
    return f"must be a finite number{bound}, got {got}"


def _finite(value: object) -> bool:
    """Whether ``value`` is a real number (not a ``bool``) that a float holds finitely."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    try:
        return math.isfinite(value)
    except OverflowError:  # an integer beyond the float range
        return False


def require(
    name: str,
    value: object,
    domain: Domain = Domain.REAL,
    *,
    error: type[IfgmRefError] = ParameterError,
) -> float:
    """``value`` as a float if it is a finite number in ``domain``; else ``error`` naming it.

    >>> require("d_th", 3, Domain.POSITIVE)
    3.0
    >>> require("d_th", -1.0, Domain.POSITIVE)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `d_th` must be a finite number > 0, got -1.0
    """
    if why := violation(value, domain):
        raise error(f"`{name}` {why}")
    return float(value)  # type: ignore[arg-type]
