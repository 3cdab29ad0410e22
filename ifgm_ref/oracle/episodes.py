"""One example's episode, as every simulation check runs it, and how a failure says where.

A check runs a fresh planner of the implementation in the example's world on the check's
engine, up to the world's time bound (:func:`ifgm_ref.sim.convergence.time_bound`), keeping the
evidence for a failure report; a planner that raises or answers an invalid command fails the
example (:class:`~ifgm_ref.oracle.check_types.PlannerFault`). Every episode is counted in the
check's tally by what it met (:data:`MOVED`, :data:`NEAR`), for the checks that pass vacuously
when nothing was met (:class:`~ifgm_ref.oracle.check_types.Meets`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from hypothesis import currently_in_test_context, note

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.protocol import Planner
from ifgm_ref.oracle.check_types import CheckFailed, Evidence, Meets, PlannerFault, Recorder
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.sim.simulator import Run, StopReason, simulate
from ifgm_ref.sim.world import World

__all__ = ["MOVED", "MOVING", "NEAR", "ending", "episode", "place_of"]

#: The tally of the episodes in which the robot moved at all (a path longer than 0).
MOVED = "moved"
#: The tally of the episodes in which the robot moved and came within its sensor's range of
#: an obstacle: an obstacle it had to be kept off. Its own radius would be too strict a mark, as
#: a planner keeping a margin never comes that close.
NEAR = "near"
#: What a check about the robot's motion must meet: a robot that never moves passes it vacuously.
MOVING = Meets(MOVED, "the robot moved")


def episode(
    impl: Implementation,
    world: World,
    recorder: Recorder,
    *,
    planner: Planner | None = None,
    sim: SimParams | None = None,
    params: dict[str, object] | None = None,
) -> Run:
    """Run a fresh planner of ``impl`` (or ``planner``) in ``world`` up to its time bound
    on the check's engine (``recorder.sim``), or under ``sim``, with the planner parameters
    ``params`` (none by default)."""
    recorder.examples += 1
    recorder.worlds.add(world)
    sim = sim or recorder.sim_for(world)
    max_time = sim.max_time
    if currently_in_test_context():  # not in a statistical check's seeded examples
        note(f"world: {world}")
    try:
        run = simulate(world, planner or impl.factory(), sim, params=params)
    except (ImplementationError, CheckFailed):
        raise
    except Exception as err:  # the planner crashed: that is a failure of this example
        recorder.evidence = Evidence([world], [], max_time)
        raise PlannerFault(
            f"the planner raised {type(err).__name__}: {err} [{place_of(impl, world)}]"
        ) from err
    recorder.evidence = Evidence([world], [run], max_time)
    result = run.result
    moved = result.path_length > 0.0
    recorder.tally[MOVED] += moved
    recorder.tally[NEAR] += moved and result.min_clearance < world.sensor.range_max
    if run.result.stop_reason == StopReason.INVALID_COMMAND:
        raise PlannerFault(f"invalid command: {run.result.detail} [{place_of(impl, world)}]")
    return run


def place_of(impl: Implementation, world: World) -> str:
    """Where an example ran, for a failure message: the implementation, world, start, goal;
    a world with no obstacle (as shrinking may leave one) says so."""
    start, goal = _xyt(world.start), _xy(world.goal)
    empty = "" if world.obstacles else " with no obstacle"
    return f"{impl.label} in {world.name or 'a'} world{empty} from {start} to {goal}"


def ending(run: Run) -> str:
    """How an episode ended, for a failure message: its stop reason, the rule that fired for
    a stall (:attr:`~ifgm_ref.sim.simulator.Result.detail`), the time, and the least clearance
    (none in a world with no obstacle)."""
    result = run.result
    rule = f" ({result.detail})" if result.stop_reason == StopReason.STALLED else ""
    text = f"stop_reason={result.stop_reason!r}{rule} after {result.time_s:.1f} s"
    if math.isfinite(result.min_clearance):
        text += f", min clearance {result.min_clearance:.3f} ft"
    return text


def _xy(p: Sequence[float]) -> str:
    return f"({p[0]:.3f}, {p[1]:.3f})"


def _xyt(p: Sequence[float]) -> str:
    return f"({p[0]:.3f}, {p[1]:.3f}, {p[2]:.3f})"
