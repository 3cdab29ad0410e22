"""Confidence intervals for the rates the benchmark and the oracle report.

A success rate measured on ``n`` episodes is an estimate of a binomial proportion. Its
**Wilson score interval** (Wilson, "Probable inference, the law of succession, and
statistical inference", JASA 22(158):209-212, 1927) is the set of proportions ``p`` whose
normal test does not reject the ``k`` successes seen:

    centre = (k + z**2 / 2) / (n + z**2)
    half   = z / (n + z**2) * sqrt(k (n - k) / n + z**2 / 4)

with ``z`` the standard normal quantile of ``1 - (1 - confidence) / 2`` (1.95996 for 95 %).
Unlike the textbook ``p +- z sqrt(p (1 - p) / n)`` it never leaves [0, 1] and does not shrink
to a point at 0 or ``n`` successes: 50 successes in 50 episodes give [92.9 %, 100 %], not
[100 %, 100 %]. Brown, Cai and DasGupta ("Interval estimation for a binomial proportion",
Statistical Science 16(2):101-133, 2001) recommend it for small ``n``, where its coverage stays
near the nominal level.
"""

from __future__ import annotations

import math
from statistics import NormalDist
from typing import NamedTuple

from ifgm_ref.core.errors import ParameterError


class Interval(NamedTuple):
    """A confidence interval ``[low, high]``."""

    low: float
    high: float


def wilson_interval(successes: int, trials: int, confidence: float = 0.95) -> Interval:
    """The Wilson score interval of a binomial proportion (the module docstring).

    Parameters
    ----------
    successes : int
        Successes seen, ``0 <= successes <= trials``.
    trials : int
        Trials, at least 1.
    confidence : float, default 0.95
        The two-sided confidence level, in (0, 1).

    Examples
    --------
    >>> wilson_interval(0, 10).low, round(wilson_interval(0, 10).high, 4)  # z**2 / (n + z**2)
    (0.0, 0.2775)
    >>> [round(v, 4) for v in wilson_interval(5, 10)]
    [0.2366, 0.7634]
    >>> round(wilson_interval(50, 50).low, 4), wilson_interval(50, 50).high
    (0.9287, 1.0)
    >>> wilson_interval(3, 2)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `successes` must be in [0, trials = 2], got 3
    """
    if isinstance(trials, bool) or not isinstance(trials, int) or trials < 1:
        raise ParameterError(f"`trials` must be an integer >= 1, got {trials!r}")
    if isinstance(successes, bool) or not isinstance(successes, int):
        raise ParameterError(f"`successes` must be an integer, got {successes!r}")
    if not 0 <= successes <= trials:
        raise ParameterError(f"`successes` must be in [0, trials = {trials}], got {successes}")
    if not 0.0 < confidence < 1.0:
        raise ParameterError(f"`confidence` must be in (0, 1), got {confidence!r}")
    z = NormalDist().inv_cdf(1.0 - (1.0 - confidence) / 2.0)
    z2 = z * z
    centre = (successes + z2 / 2.0) / (trials + z2)
    half = z / (trials + z2) * math.sqrt(successes * (trials - successes) / trials + z2 / 4.0)
    # At 0 and at n successes the bound is 0 or 1 exactly (centre and half agree), not the
    # few ulps away that rounding leaves.
    low = 0.0 if successes == 0 else centre - half
    high = 1.0 if successes == trials else centre + half
    return Interval(low, high)
