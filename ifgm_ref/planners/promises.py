"""What a planner promises, declared once, with the planner.

A planner's registration (:data:`ifgm_ref.planners.PLANNERS`) or its class (a ``promises``
attribute) declares its :class:`Promises`; the oracle holds it to exactly that and generates
only the checks that apply (like scikit-learn's estimator tags). The paper's Table 1 and
section 5 say what each of its planners promises.

>>> Promises(converges_in=frozenset({"open"})).converges_in
frozenset({'open'})
>>> Promises(noise="range=0.02").noise
'range=0.02'
>>> Promises(converges_in=frozenset({"maze"}))
Traceback (most recent call last):
...
ifgm_ref.core.errors.ImplementationError: converges_in: unknown world classes ['maze']; \
known: h, mixed, open, symmetric, u
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from ifgm_ref.core.errors import ImplementationError, ParameterError
from ifgm_ref.planners.ifgm.readings import known_names

__all__ = ["ALL_CLASSES", "REFERENCE_NOISE_LEVELS", "Promises"]

#: Every solvable world class of :mod:`ifgm_ref.oracle.strategies`.
ALL_CLASSES = frozenset({"open", "u", "h", "symmetric", "mixed"})
#: The noise levels the reference planners promise, written as ``--noise`` takes them
#: (:meth:`ifgm_ref.sim.noise.NoiseLevels.parse`): Gaussian range noise of 2 % of the range,
#: 5 % of the rays dropping out, odometry drifting by 1 % of the distance. Measured, with their
#: history: ``docs/oracle.md``, "Robustness".
REFERENCE_NOISE_LEVELS = "range=0.02,dropout=0.05,odometry=0.01"


@dataclass(frozen=True)
class Promises:
    """What a planner promises, and so which checks apply to it.

    Parameters
    ----------
    converges_in : frozenset of str
        The world classes (names of :data:`ifgm_ref.oracle.strategies.SOLVABLE_CLASSES`) in
        which it reaches the goal within the time bound.
    reports_unreachable : bool, default False
        Whether it stops with ``goal_unreachable`` when the goal is enclosed.
    collision_free : bool, default True
        Whether its swept disc never meets an obstacle (every planner of the paper).
    passes_wide_gaps : bool, default True
        Whether it steers through a gap wider than IFGM's ``d_th`` rather than round the
        obstacles (section 4, Case-1; IFGM only: FGM takes the widest gap, the Bug family
        goes round).
    scale_invariant : bool, default True
        Whether it derives every length from the robot and the sensor, so that scaling every
        length of the problem by ``k`` (the world, the robot's radius and speed, the sensor's
        ranges, the goal tolerance) scales its trajectory by ``k`` (the ``scale_invariant``
        check; :mod:`ifgm_ref.oracle.metamorphic`). Every planner here promises it: their
        parameters are formulas in the robot and the sensor (:mod:`ifgm_ref.planners.tuning`).
    rigid_motion_invariant : bool, default True
        Whether rotating and translating the problem moves its trajectory the same way (the
        ``rigid_motion_invariant`` check). Every planner here promises it but DWA, whose
        costmap's cells are aligned with the world's axes (``docs/oracle.md``).
    noise : str or None, default None
        The noise levels at which it keeps these promises, as ``--noise`` takes them
        (``"range=0.02,dropout=0.05"``; :meth:`ifgm_ref.sim.noise.NoiseLevels.parse`; an
        object with a ``tags()`` method, a ``NoiseLevels``, is taken as its tags): never
        collides, and reaches the goal in at least
        :data:`~ifgm_ref.oracle.robust.SUCCESS_THRESHOLD` of the worlds of each class it
        converges in, with 95 % confidence. The robust profile checks these levels; ``None``
        promises no robustness.
    turns_at_dead_ends : bool, default False
        Whether it meets a dead end by turning in 45-degree steps (section 4, Case-3; IFGM
        only), which the ``dead_end_turns`` check reads from the branches it reports.
    reference : str or None, default None
        The reference planner whose readings it follows step by step: ``"ifgm"`` (the only
        one with the margins that tell a tie from a fault) makes the reference level's
        ``agrees_with_reference`` check apply (:mod:`ifgm_ref.oracle.agreement`).
    stops_in_time : bool, default False
        Whether it honours the robot's dynamics (:class:`~ifgm_ref.core.params.RobotParams`
        ``braking``, ``acceleration`` and ``response``): on a robot that cannot stop at once,
        every command leaves it room to stop before what it sees (the braking governor's
        condition, :mod:`ifgm_ref.planners.governor`), which the ``stops_in_time`` check
        monitors step by step. Every built-in planner promises it but ``straight`` (DWA, which
        keeps its own dynamic window, measured: ``docs/oracle.md``).
    readings : mapping of str to str, default {}
        The readings it takes of the paper's open choices, where they are not ours
        (:data:`~ifgm_ref.planners.ifgm.readings.OPEN_READINGS`: ``{"dead_end_side":
        "left"}``, say): the reference runs the same readings to compare with it, or the
        check says it cannot.
    """

    converges_in: frozenset[str] = ALL_CLASSES
    reports_unreachable: bool = False
    collision_free: bool = True
    passes_wide_gaps: bool = True
    scale_invariant: bool = True
    rigid_motion_invariant: bool = True
    noise: str | None = None
    turns_at_dead_ends: bool = False
    reference: str | None = None
    readings: Mapping[str, str] = field(default_factory=dict)
    stops_in_time: bool = False

    def __post_init__(self) -> None:
        try:
            known_names(self.readings)
        except ParameterError as err:
            raise ImplementationError(f"readings: {err}") from None
        unknown = set(self.converges_in) - ALL_CLASSES
        if unknown:
            raise ImplementationError(
                f"converges_in: unknown world classes {sorted(unknown)}; "
                f"known: {', '.join(sorted(ALL_CLASSES))}"
            )
        object.__setattr__(self, "converges_in", frozenset(self.converges_in))
        tags = getattr(self.noise, "tags", None)  # NoiseLevels, as the oracle's callers give it
        noise = tags() if callable(tags) else self.noise
        object.__setattr__(self, "noise", None if noise in (None, "", "none") else noise)
