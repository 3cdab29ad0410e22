"""The invariance checks' comparison: the original run's exchange, transformed, replayed.

``rigid_motion_invariant`` and ``scale_invariant`` (:mod:`ifgm_ref.oracle.checks`) ask one
question: handed the moved (or scaled) problem, does the planner answer with the moved (or
scaled) answers? Each runs the original problem once, recording what the planner was handed
and what it answered (:class:`~ifgm_ref.core.recording.RecordingPlanner`), transforms that
exchange (:func:`~ifgm_ref.oracle.metamorphic.moved_recording`,
:func:`~ifgm_ref.oracle.metamorphic.scaled_recording`), hands the transformed observations,
in order, to a fresh planner (open loop: its answers move nothing), and compares each answer
with the transformed recorded one (:func:`compare_answers`). A scale by a power of two is
exact and is still run closed loop, bit for bit (``scale_test``); on a robot with mass (the
``mujoco`` engine), whose physics is not scale-free, it is replayed open loop and its answers
compared bit for bit (:func:`compare_exactly`).

**Why open loop.** Handed exactly the transformed observations, the planner meets no
rounding of the simulator's, and with it none of the ties between rays that made two faithful
closed-loop runs part (a round obstacle gives equal ranges; the moved scan's rounding tips
which one is nearest). What is left is the planner's own arithmetic on moved or scaled
numbers, which :data:`HEADING_TOL` and :data:`SPEED_TOL` bound; a frame or sign error shows
at the first step it touches. The closed-loop checks this replaced, the runs that showed why,
and the margins measured: ``docs/oracle.md``, "Invariance".
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace
from typing import NamedTuple

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import Command, Observation
from ifgm_ref.core.recording import Recording, replay
from ifgm_ref.oracle.check_types import CheckFailed, PlannerFault, Recorder
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.sim.world import World

__all__ = [
    "EXACT_SCALES",
    "GENERIC_OFFSET",
    "HEADING_TOL",
    "ROUNDED_SCALES",
    "SPEED_TOL",
    "AnswerError",
    "answer_errors",
    "compare_answers",
    "compare_exactly",
    "generic",
]

#: An answer's heading may differ from the transformed recorded one by this much (rad, 5.7
#: degrees): above what a float32 port's rounding gives (now and then the neighbouring ray,
#: 1.8 degrees), below a frame error (a share of the rotation) or a quadrant error (pi).
#: Measured margins: ``docs/oracle.md``, "Invariance".
HEADING_TOL = 0.1
#: An answer's speed may differ from the transformed recorded one by this fraction of the
#: robot's top speed (in the transformed problem's unit): a planner's speed follows its
#: heading (``v``, 0, or ``v max(0, cos(turn still to make))``), so the heading's 0.1.
SPEED_TOL = 0.1
#: Before an invariance check the goal moves this far (ft) off the drawn start-goal line, and
#: the start heading turns with the line (:func:`generic`). An exactly symmetric problem hands
#: the planner an exact tie (equal gaps, equal side beams) that the rounding of moved or scaled
#: numbers can tip either way, which no implementation can avoid; 0.01 ft over 35 ft turns the
#: start 2.9e-4 rad, far more than any rounding (an example: ``docs/oracle.md``, "Invariance").
GENERIC_OFFSET = 0.01
#: ``scale_invariant``: the factors drawn. Powers of two first (failures shrink to 2): scaling
#: by them is exact in floating point, so the scaled run must be the original times ``k`` bit
#: for bit, closed loop. Then a unit conversion (ft to m), the 0.22 m radius of a small ground
#: robot (BARN's Jackal) over the paper's 1 ft, and an odd factor: every scaled number is
#: rounded, and the answers are compared open loop within :data:`HEADING_TOL` and
#: :data:`SPEED_TOL`.
EXACT_SCALES = (2.0, 0.5, 4.0, 0.25, 8.0)
#: See :data:`EXACT_SCALES`.
ROUNDED_SCALES = (0.3048, 0.22, 3.7)
#: The fields of a command that :func:`compare_exactly` compares: what moves the robot, the
#: branch and the stop (those the closed-loop exact comparison of ``scale_test`` compares).
EXACT_FIELDS = ("heading", "speed", "turn_rate", "branch", "stop")


def generic(world: World) -> World:
    """``world`` with the goal moved :data:`GENERIC_OFFSET` ft to the left of the start-goal
    line, and the start heading turned by the angle that turns the line, so that no obstacle
    lies exactly symmetric about the line or about the start heading.

    >>> moved = generic(World(start=(0, 0, 0), goal=(10, 0)))
    >>> moved.goal, round(moved.start.theta, 6)
    (Point(x=10.0, y=0.01), 0.001)
    """
    sx, sy = world.start.position
    gx, gy = world.goal
    d = math.hypot(gx - sx, gy - sy)
    goal = Point(gx - GENERIC_OFFSET * (gy - sy) / d, gy + GENERIC_OFFSET * (gx - sx) / d)
    turn = math.atan2(GENERIC_OFFSET, d)
    start = Pose(sx, sy, wrap_angle(world.start.theta + turn))
    return replace(world, start=start, goal=goal)


class AnswerError(NamedTuple):
    """One replayed step: what the planner was handed, the answer expected of it (the
    recorded one, transformed), its answer, and how far apart the two are."""

    step: int
    observation: Observation
    expected: Command
    answered: Command
    #: The headings' difference, rad, modulo 2 pi.
    heading: float
    #: The speeds' difference as a fraction of the robot's top speed.
    speed: float


def answer_errors(impl: Implementation, expected: Recording, where: str) -> Iterator[AnswerError]:
    """Hand ``expected``'s observations, in order, to a fresh planner of ``impl`` and yield
    each step's :class:`AnswerError` (lazily: a caller may stop at the first it rejects).

    A planner that raises or answers an invalid command is a :class:`PlannerFault`; ``where``
    names the example in its message.
    """
    top_speed = expected.params.robot.speed
    try:
        for step, (seen, wanted, answered) in enumerate(replay(expected, impl.factory())):
            problem = answered.problem()
            if problem is not None:
                raise PlannerFault(f"invalid command at step {step}: {problem} [{where}]")
            heading = abs(math.remainder(answered.heading - wanted.heading, 2.0 * math.pi))
            speed = abs(answered.speed - wanted.speed) / top_speed
            yield AnswerError(step, seen, wanted, answered, heading, speed)
    except (ImplementationError, CheckFailed):
        raise
    except Exception as err:  # the planner crashed: that is a failure of this example
        raise PlannerFault(
            f"the planner raised {type(err).__name__}: {err} (replaying) [{where}]"
        ) from err


def compare_answers(
    impl: Implementation, expected: Recording, how: str, where: str, rec: Recorder
) -> None:
    """Raise :class:`CheckFailed` at the first replayed step whose answer is not the expected
    one within :data:`HEADING_TOL` and :data:`SPEED_TOL`, with the same ``stop``.

    ``how`` says how the problem was transformed (``"moved"``, ``"scaled by k=0.3048"``);
    ``where`` names the example. The replay counts as a run in ``rec.examples``, as a
    simulation does (:func:`ifgm_ref.oracle.checks.episode`).
    """
    rec.examples += 1
    for error in answer_errors(impl, expected, where):
        want, got = error.expected, error.answered
        if error.heading <= HEADING_TOL and error.speed <= SPEED_TOL and want.stop == got.stop:
            continue
        raise CheckFailed(
            f"{how}, the original run's step {error.step} (t={error.observation.t:.1f} s, "
            f"replayed open loop) was answered with heading {got.heading:.6g} rad, speed "
            f"{got.speed:.6g}, stop {got.stop!r}, but should be answered as the original "
            f"was, {how}: heading {want.heading:.6g} rad, speed {want.speed:.6g}, stop "
            f"{want.stop!r}, within {HEADING_TOL:g} rad and {SPEED_TOL:g} of the top speed "
            f"(off by {error.heading:.3g} rad and {error.speed:.3g}) [{where}]"
        )


def compare_exactly(
    impl: Implementation, expected: Recording, how: str, where: str, rec: Recorder
) -> None:
    """Raise :class:`CheckFailed` at the first replayed step whose answer is not the expected
    one bit for bit (:data:`EXACT_FIELDS`): the planner's half of an exact relation (a scale
    by a power of two), where the simulator's half does not hold (a robot with mass).

    ``how``, ``where`` and the count in ``rec`` as for :func:`compare_answers`; the check's
    summary counts these replays, and says why the closed-loop run was left out.
    """
    rec.examples += 1
    for error in answer_errors(impl, expected, where):
        want, got = error.expected, error.answered
        differ = [
            f"{name}={_shown(getattr(got, name))} (should be {_shown(getattr(want, name))})"
            for name in EXACT_FIELDS
            if getattr(got, name) != getattr(want, name)
        ]
        if differ:
            raise CheckFailed(
                f"{how} (a power of two: exact), the original run's step {error.step} "
                f"(t={error.observation.t:.1f} s, replayed open loop) was answered otherwise: "
                f"{', '.join(differ)}; speeds should be exactly k times the original's, "
                f"headings, branches and stops equal [{where}]"
            )
    rec.tally.update(exact_replays=1)
    rec.summary = (
        f"{rec.tally['exact_replays']} power-of-two scale(s) replayed open loop and answered "
        "bit for bit; the scaled run itself is not compared: on a robot with mass (gravity, "
        "masses, acceleration limits in absolute units) the physics is not scale-free"
    )


def _shown(value: object) -> str:
    """``value`` as a failure message shows it: a branch (a string enum) as its name."""
    return repr(str(value)) if isinstance(value, str) else repr(value)
