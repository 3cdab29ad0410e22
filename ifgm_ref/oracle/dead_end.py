"""The dead end's turns as the paper words them: 45 degrees at a time, one way, 180 at most.

Section 4, Case-3: the robot "recursively turns in steps of 45° until it finds obstacle free
path (on 180°)"; section 5.2: it "turns the robot about 45° and then 90° (if obstacle is not
avoided) and so on". An implementation that reports its branches shows where it turns at a
dead end (``dead_end_turn``, docs/oracle-protocol.md); :func:`turn_errors` checks that the
headings it commands there step by 45 degrees from the heading at which it met the dead
end, all the same way, four steps at most.

Which way it turns is a reading (errata row 17): either passes. So does a port that counts
each step from where its last turn ended rather than from the first heading: a turn is done
within ``turn_done = w dt / 2`` of its target (errata row 32), and each step may be off by
that much. An implementation that reports no branches has no dead-end turns to check, and
the check's summary says how many it saw.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence

from ifgm_ref.core.pose import wrap_angle
from ifgm_ref.paper.flowchart import DEAD_END_STEP, Branch
from ifgm_ref.sim.simulator import TraceStep

__all__ = ["STEP", "STEPS", "dead_end_turns", "part_errors", "turn_errors"]

#: One turn, rad (section 4): the flowchart's dead-end step.
STEP = DEAD_END_STEP
#: The most turns in one dead end: 180 degrees (section 4, "on 180°").
STEPS = 4
#: Rounding allowed beside the dead band, rad.
SLACK = 1e-3


def dead_end_turns(trace: Sequence[TraceStep]) -> Iterator[tuple[float, list[float]]]:
    """Each dead end of ``trace``: the heading the robot had at its first ``dead_end_turn``
    step (the one the planner was told, under odometry noise), and the headings commanded
    over its consecutive ``dead_end_turn`` steps."""
    start: float | None = None
    commanded: list[float] = []
    for step in (*trace, None):
        turning = step is not None and step.branch == Branch.DEAD_END_TURN
        if turning and step is not None and step.heading_cmd is not None:
            if start is None:
                start = step.theta if step.believed_theta is None else step.believed_theta
            commanded.append(step.heading_cmd)
        elif not turning and start is not None:
            yield start, commanded
            start, commanded = None, []


def turn_errors(
    start: float, commanded: Sequence[float], dead_band: float, *, in_parts: bool = False
) -> str:
    """What is wrong with one dead end's turns (``""``: nothing): each commanded heading
    holds the current target, or moves on to the next, 45 degrees further the same way,
    each within ``dead_band + SLACK``; the first target is 45 degrees from ``start``, and
    there are at most :data:`STEPS` targets.

    ``in_parts`` reads the turns of a robot that cannot stop at once: :func:`part_errors`.
    """
    tol = dead_band + SLACK
    if in_parts:
        return part_errors(start, commanded, tol)
    target, sign, steps = start, 0, 0
    for k, heading in enumerate(commanded):
        if abs(wrap_angle(heading - target)) <= tol and steps:
            continue
        turn = wrap_angle(heading - target)
        way = 1 if turn > 0 else -1
        if abs(abs(turn) - STEP) > tol or (sign and way != sign):
            wanted = "45 degrees either way" if not sign else f"45 degrees {_way(sign)}"
            return (
                f"dead-end step {k}: commanded heading {heading:.4f} rad, "
                f"{math.degrees(turn):+.1f} degrees from the last target {target:.4f} rad, "
                f"but a turn goes {wanted} (within {math.degrees(tol):.1f} degrees)"
            )
        target, sign, steps = heading, way, steps + 1
        if steps > STEPS:
            return (
                f"dead-end step {k}: a turn of {45 * steps} degrees in all, but the turns "
                f"stop at 180 (section 4)"
            )
    return ""


def part_errors(start: float, commanded: Sequence[float], tol: float) -> str:
    """What is wrong with one dead end's turns on a robot that cannot stop at once (``""``:
    nothing), each within ``tol``: the headings commanded turn one way, never back, 180
    degrees at most from ``start``, and every heading held (commanded twice running, or
    last) is a multiple of 45 degrees from ``start``.

    A robot with mass brakes before it turns in place, and its braking governor caps the
    turn at ``u w <= b`` while it moves (:mod:`ifgm_ref.planners.governor`): the commands
    on the way to a target are parts of the turn, and one may pass a target the planner has
    already moved on from. Where the turns rest is what the paper fixes: 45 degrees apart,
    one way, 180 at most.

    >>> parts = [0.0, 0.1, 0.4, math.pi / 4, math.pi / 4, 1.0, 1.9, math.pi / 2 + 0.7854]
    >>> part_errors(0.0, parts, 0.05)
    ''
    >>> part_errors(0.0, [0.4, 0.3], 0.05)  # back: a part never undoes one  # doctest: +ELLIPSIS
    'dead-end step 1: commanded heading 0.3000 rad turns back (-5.7 degrees), but the turns ...'
    >>> part_errors(0.0, [0.4, 0.6, 0.6], 0.05)  # doctest: +ELLIPSIS
    'dead-end step 1: holds heading 0.6000 rad, 34.4 degrees from where it began, but ...'
    """
    turned, sign, last = 0.0, 0, start
    for k, heading in enumerate(commanded):
        moved = wrap_angle(heading - last)
        way = 0 if abs(moved) <= tol else (1 if moved > 0 else -1)
        if sign and way == -sign:
            return (
                f"dead-end step {k}: commanded heading {heading:.4f} rad turns back "
                f"({math.degrees(moved):+.1f} degrees), but the turns go one way"
            )
        sign, turned, last = sign or way, turned + moved, heading
        if abs(turned) > STEPS * STEP + tol:
            return (
                f"dead-end step {k}: {math.degrees(abs(turned)):.0f} degrees in all, but the "
                f"turns stop at 180 (section 4)"
            )
        held = k + 1 == len(commanded) or abs(wrap_angle(commanded[k + 1] - heading)) <= SLACK
        off = abs(turned - STEP * round(turned / STEP))
        if held and off > tol:
            return (
                f"dead-end step {k}: holds heading {heading:.4f} rad, "
                f"{math.degrees(abs(turned)):.1f} degrees from where it began, but a turn "
                f"rests at a multiple of 45 (within {math.degrees(tol):.1f} degrees)"
            )
    return ""


def _way(sign: int) -> str:
    return "counter-clockwise, as the first" if sign > 0 else "clockwise, as the first"
