"""The invariance checks' comparison: the original run's exchange, transformed, replayed.

``rigid_motion_invariant`` and ``scale_invariant`` (:mod:`ifgm_ref.oracle.checks`) ask one
question: handed the moved (or scaled) problem, does the planner answer with the moved (or
scaled) answers? Each runs the original problem once, recording what the planner was handed
and what it answered (:class:`~ifgm_ref.recording.RecordingPlanner`), transforms that
exchange (:func:`~ifgm_ref.oracle.metamorphic.moved_recording`,
:func:`~ifgm_ref.oracle.metamorphic.scaled_recording`), hands the transformed observations,
in order, to a fresh planner (open loop: its answers move nothing), and compares each answer
with the transformed recorded one (:func:`compare_answers`). A scale by a power of two is
exact and is still run closed loop, bit for bit (``scale_test``).

**Why open loop** (issue 24). The invariance checks used to run the moved or scaled problem
itself and compare the two trajectories, within two steps of travel and turning (moved) or 1 %
of the path length (scaled). That rejects faithful runs: the simulator rounds the moved
problem's scans differently (1e-16), a decision that sits on a tie (two rays with equal ranges,
as a round obstacle gives) tips, the runs part by a ray for a step, and on a long run such
partings add up. The C IFGM, circling for 9,502 steps in a generated mixed world
(``tests/worlds/rigid_motion_long_mixed.json``; since Bug1's round, errata row 34, it arrives
there in 900), was 0.28 ft and 0.31 rad off its moved twin at 161 s; the reference IFGM
circling a post for 287 s parted beyond the tolerance in each of three placements tried, at
0.8, 77 and 86 s. Comparing only up to the first tie, found with a control run (the problem
under another tiny motion), does not help: the control meets other ties than the moved run --
the last of those three placements is a shift by 0.001 ft, and as a control it would have
cleared the moved run of the second up to 86 s, 85 s past its parting.

Replayed open loop, every observation the planner is handed is exactly what the simulator
would hand it in the transformed problem in exact arithmetic: a rigid motion moves poses and
goal and leaves each scan as it is (taken in the robot's frame), a scale multiplies lengths.
The simulator's rounding is gone, and with it every tie between rays: the planner sees
the same scan bit for bit (moved) or each range times ``k`` (scaled; multiplying by ``k``
keeps equal ranges equal). What is left is the planner's own arithmetic on moved or scaled
numbers: within 1e-12 in double, and in float32 the odd neighbouring choice
(:data:`HEADING_TOL`). A trajectory is the planner's answers driven by the simulator, so
answers that are the transformed answers at every step make the transformed trajectory, in
exact arithmetic: nothing the old check asked is lost, and a frame or sign error shows at
the first step it touches. Measured in the runs above: every answer of the reference and of
the C port within 5e-14 rad, however long the run. The cost per example is one simulation
and one replay (planner steps only, no ray casting), where the closed-loop check ran two
simulations.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace
from typing import NamedTuple

from ifgm_ref.errors import ImplementationError
from ifgm_ref.oracle.check_types import CheckFailed, PlannerFault, Recorder
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.pose import Point, Pose, wrap_angle
from ifgm_ref.protocol import Command, Observation
from ifgm_ref.recording import Recording, replay
from ifgm_ref.world import World

__all__ = [
    "EXACT_SCALES",
    "GENERIC_OFFSET",
    "HEADING_TOL",
    "ROUNDED_SCALES",
    "SPEED_TOL",
    "AnswerError",
    "answer_errors",
    "compare_answers",
    "generic",
]

#: An answer's heading may differ from the transformed recorded one by this much (rad, 5.7
#: degrees). An implementation in double answers within 1e-12: measured, the reference IFGM,
#: its faithful variants and the C port, 20 drawn worlds per check (runs of up to 9,044
#: steps) and the 9,502-step mixed world (the planners before errata row 34), at most
#: 5.1e-14 rad; the other reference planners
#: at most 1.8e-13 (APF). A float32 port rounds the moved or scaled numbers differently (1e-7
#: relative) and now and then takes a neighbouring discrete choice that lies within that
#: rounding -- the next ray (1.8 degrees, 0.031 rad), the next remembered point of the edge
#: it follows: measured at most 0.022 rad (the float32 variant, circling a post for 2,871
#: steps) and 0.015 rad (the C port's float build). A frame error is off by a share of the
#: rotation (eq. (2)'s angle as a world heading: three quarters of it, over 0.1 rad for 96 %
#: of the drawn rotations), a quadrant error by pi.
HEADING_TOL = 0.1
#: An answer's speed may differ from the transformed recorded one by this fraction of the
#: robot's top speed (in the transformed problem's unit). A planner's speed follows its
#: heading -- ``v``, 0, or ``v max(0, cos(turn still to make))``: an error of at most the
#: heading's times ``v`` (as the conformance vectors' tolerances say) -- so the same 0.1;
#: measured in the same runs: double at most 1.4e-13, float32 at most 0.0045.
SPEED_TOL = 0.1
#: Before an invariance check the goal moves this far (ft) off the drawn start-goal line, and
#: the start heading turns with the line (:func:`generic`). An exactly symmetric problem (an
#: obstacle centred on the line, the start facing along it: shrinking finds them) hands the
#: planner an exactly symmetric scan, a tie (equal gaps, equal side beams) that it breaks by a
#: fixed rule; the rounding of moved or scaled numbers (1e-16, 1e-7 in a float32 port) can
#: tip such a tie either way, which no implementation can avoid (measured: the float32 port
#: took the other of two mirror gaps round a post on the line, scaled by 0.3048, at the first
#: step). A 0.01 ft offset breaks every exact symmetry by far more than the rounding: 0.01 ft
#: over 35 ft turns the start 2.9e-4 rad, and a post 7 ft ahead lies 0.002 ft off the heading.
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
