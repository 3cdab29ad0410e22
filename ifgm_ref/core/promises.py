"""What a planner promises, declared with the planner (issue 44).

A planner's registration (:data:`ifgm_ref.planners.PLANNERS`) or its class (a ``promises``
attribute) declares a :class:`Promised`; the oracle holds it to exactly that, as
:class:`ifgm_ref.oracle.implementation.Promises`, and generates only the checks that apply
(like scikit-learn's estimator tags). The declaration lives here, below the planners and the
oracle, so that a planner can declare it without importing the simulator or the oracle.
The paper's Table 1 and section 5 say what each of its planners promises.

>>> Promised(converges_in=frozenset({"open"})).converges_in
frozenset({'open'})
>>> Promised(converges_in=frozenset({"maze"}))
Traceback (most recent call last):
...
ifgm_ref.core.errors.ImplementationError: converges_in: unknown world classes ['maze']; \
known: h, mixed, open, symmetric, u
"""

from __future__ import annotations

from dataclasses import dataclass

from ifgm_ref.core.errors import ImplementationError

__all__ = ["ALL_CLASSES", "REFERENCE_NOISE_LEVELS", "Promised"]

#: Every solvable world class of :mod:`ifgm_ref.oracle.strategies`.
ALL_CLASSES = frozenset({"open", "u", "h", "symmetric", "mixed"})
#: The noise levels the reference planners promise, written as ``--noise`` takes them
#: (:meth:`ifgm_ref.sim.noise.NoiseLevels.parse`): Gaussian range noise of 2 % of the range,
#: 5 % of the rays dropping out, odometry drifting by 1 % of the distance. Measured, with their
#: history: ``docs/oracle.md``, "Robustness".
REFERENCE_NOISE_LEVELS = "range=0.02,dropout=0.05,odometry=0.01"


@dataclass(frozen=True)
class Promised:
    """What a planner promises, and so which of the oracle's checks apply to it.

    Each field means what the field of the same name of
    :class:`ifgm_ref.oracle.implementation.Promises` means (documented there, with the check
    that reads it), but ``noise``, which is given here as ``--noise`` and a specification
    file's ``promises.noise`` take it (``"range=0.02,dropout=0.05"``,
    :meth:`ifgm_ref.sim.noise.NoiseLevels.parse`; ``None`` promises no robustness). The
    defaults promise convergence in every class, collision freedom, the use of wide gaps and
    scale invariance, and nothing else.

    Raises
    ------
    ImplementationError
        A world class of ``converges_in`` that is not one of :data:`ALL_CLASSES`.
    """

    converges_in: frozenset[str] = ALL_CLASSES
    reports_unreachable: bool = False
    collision_free: bool = True
    passes_wide_gaps: bool = True
    scale_invariant: bool = True
    noise: str | None = None
    turns_at_dead_ends: bool = False
    reference: str | None = None
    stops_in_time: bool = False

    def __post_init__(self) -> None:
        unknown = set(self.converges_in) - ALL_CLASSES
        if unknown:
            raise ImplementationError(
                f"converges_in: unknown world classes {sorted(unknown)}; "
                f"known: {', '.join(sorted(ALL_CLASSES))}"
            )
        object.__setattr__(self, "converges_in", frozenset(self.converges_in))
