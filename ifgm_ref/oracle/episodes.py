"""One example's episode, as every simulation check runs it, and how a failure says where.

A check runs a fresh planner of the implementation in the example's world on the check's
engine, up to the world's time bound (:func:`ifgm_ref.convergence.time_bound`), keeping the
evidence for a failure report; a planner that raises or answers an invalid command fails the
example (:class:`~ifgm_ref.oracle.check_types.PlannerFault`).
"""

from __future__ import annotations

from collections.abc import Sequence

from hypothesis import currently_in_test_context, note

from ifgm_ref.errors import ImplementationError
from ifgm_ref.oracle.check_types import CheckFailed, Evidence, PlannerFault, Recorder
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.params import SimParams
from ifgm_ref.protocol import Planner
from ifgm_ref.simulator import Run, StopReason, simulate
from ifgm_ref.world import World

__all__ = ["episode", "place_of"]


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
    if run.result.stop_reason == StopReason.INVALID_COMMAND:
        raise PlannerFault(f"invalid command: {run.result.detail} [{place_of(impl, world)}]")
    return run


def place_of(impl: Implementation, world: World) -> str:
    """Where an example ran, for a failure message: the implementation, world, start, goal."""
    start, goal = _xyt(world.start), _xy(world.goal)
    return f"{impl.label} in {world.name or 'a'} world from {start} to {goal}"


def _xy(p: Sequence[float]) -> str:
    return f"({p[0]:.3f}, {p[1]:.3f})"


def _xyt(p: Sequence[float]) -> str:
    return f"({p[0]:.3f}, {p[1]:.3f}, {p[2]:.3f})"
