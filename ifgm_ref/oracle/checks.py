"""The oracle's properties, one named check each, and which planners each applies to.

A check draws an example with a Hypothesis strategy and raises :class:`CheckFailed` when the
implementation breaks the property on it; the message says what was expected and what
happened (``min_clearance=-0.3 ft, but should be >= 0 [ifgm in u world]``), and the
:class:`Evidence` (world, trace, result) goes with it for the failure report.

``collision_free`` and ``converges_<class>`` (open, u, h, symmetric, mixed) in the classes
a planner promises, ``reports_unreachable``, ``rigid_motion_invariant`` and
``scale_invariant`` (:mod:`ifgm_ref.oracle.invariance`), ``ignores_unseen_obstacles``,
``passes_wide_gaps`` (section 4, Case-1), ``dead_end_turns`` (Case-3's 45-degree steps:
:mod:`ifgm_ref.oracle.dead_end`), ``deterministic``, ``stops_in_time`` (a robot with mass:
:mod:`ifgm_ref.oracle.braking`), the equations' checks
(:mod:`ifgm_ref.oracle.equation_checks`) and, at the reference level only,
``agrees_with_reference`` (:mod:`ifgm_ref.oracle.agreement`). Each check's sentence says
its property; ``docs/oracle.md``, "The properties", says each in full with whom it applies to.

Every simulation check runs with the simulator's defaults (``dt`` 0.1 s, goal tolerance 0.5 ft)
on the profile's engine (``Recorder.sim``; kinematic by default, ``docs/oracle.md``, "On the
physical robot") and stops an episode at :func:`ifgm_ref.sim.convergence.time_bound` of its world.
A planner that raises, or answers an invalid command, fails the check it was running.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import shapely
from hypothesis import currently_in_test_context, note
from hypothesis import strategies as st
from numpy.typing import NDArray

from ifgm_ref.core.elements import traces
from ifgm_ref.core.errors import present
from ifgm_ref.core.protocol import Command
from ifgm_ref.core.recording import RecordingPlanner, replay
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.oracle.agreement import (
    ReferenceEpisode,
    compare,
    divergence_message,
    reference_episode,
)
from ifgm_ref.oracle.braking import stops_in_time
from ifgm_ref.oracle.check_types import (
    Check,
    CheckFailed,
    Evidence,
    Kind,
    Level,
    Meets,
    Recorder,
    levels_up_to,
)
from ifgm_ref.oracle.dead_end import dead_end_turns, turn_errors
from ifgm_ref.oracle.episodes import MOVING, NEAR, _xy, ending, episode, place_of
from ifgm_ref.oracle.equation_checks import (
    equation_checks,
)
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.invariance import (
    EXACT_SCALES,
    ROUNDED_SCALES,
    compare_answers,
    compare_exactly,
    generic,
)
from ifgm_ref.oracle.metamorphic import (
    is_power_of_two,
    moved_recording,
    scale_params,
    scale_sim,
    scale_world,
    scaled_recording,
)
from ifgm_ref.oracle.strategies import (
    SOLVABLE_CLASSES,
    any_solvable_worlds,
    enclosed_worlds,
    gap_walls,
    placements,
    reference_worlds,
)
from ifgm_ref.paper.flowchart import Branch
from ifgm_ref.planners.ifgm.readings import Readings, unrunnable
from ifgm_ref.planners.tuning import ParamInfo
from ifgm_ref.sim.convergence import time_bound
from ifgm_ref.sim.shapes import circle
from ifgm_ref.sim.simulator import Run, TraceStep
from ifgm_ref.sim.world import Polygon, World
from ifgm_ref.sim.worldgen.classes import GENERATORS, enclosed_world, gap_wall, placed

__all__ = ["CHECKS", "FIRST_TURN", "agrees_with", "checks_at", "scale_test"]

#: ``passes_wide_gaps``: a commanded heading this far off the goal bearing (rad, 5 degrees),
#: steering the robot away from the goal bearing or holding it there, is the robot's first
#: turn, which must be towards the gap (Case-1 steers at it). A command that points off the
#: goal bearing while it turns the robot back towards it (a robot started facing away, or a
#: velocity command, whose heading is one step's turn) is not that turn yet.
FIRST_TURN = math.radians(5.0)
# -- simulation helpers ------------------------------------------------------------------------


@traces("s3.safe_near_obstacles")
def _collision_test(impl: Implementation, world: World, recorder: Recorder) -> None:
    run = episode(impl, world, recorder)
    clearance = run.result.min_clearance
    if run.result.collided or clearance < 0.0:
        at = min(run.trace, key=lambda step: step.clearance)
        raise CheckFailed(
            f"min_clearance={clearance:.3f} ft at t={at.t:.1f} s, but should be >= 0 "
            f"[{place_of(impl, world)}]"
        )


@traces("s3.critical_shapes")
def _converges_test(impl: Implementation, world: World, recorder: Recorder) -> None:
    run = episode(impl, world, recorder)
    if not run.result.reached:
        raise CheckFailed(
            f"{ending(run)}, but should be 'goal_reached' within the bound "
            f"{time_bound(world):.1f} s [{place_of(impl, world)}]"
        )


def _unreachable_test(impl: Implementation, world: World, recorder: Recorder) -> None:
    run = episode(impl, world, recorder)
    if run.result.stop_reason != "goal_unreachable":
        raise CheckFailed(
            f"{ending(run)}, but should be 'goal_unreachable' within the bound "
            f"{time_bound(world):.1f} s [{place_of(impl, world)}]"
        )


def _promised_worlds(impl: Implementation) -> st.SearchStrategy[World]:
    """Worlds of the classes ``impl`` converges in (open worlds if none)."""
    classes = [c for c in SOLVABLE_CLASSES if c in impl.promises.converges_in] or ["open"]
    return st.one_of([SOLVABLE_CLASSES[c]() for c in classes])


def _poses(trace: Sequence[TraceStep]) -> NDArray[np.float64]:
    return np.array([(s.x, s.y, s.theta) for s in trace])


def _invariance_test(
    impl: Implementation, example: tuple[World, tuple[float, tuple[float, float]]], rec: Recorder
) -> None:
    """Run ``example``'s world, recording the exchange; replay it moved by the example's rigid
    motion (:mod:`ifgm_ref.oracle.invariance`)."""
    world, (angle, shift) = generic(example[0]), example[1]
    recorder = RecordingPlanner(impl.factory())
    first = episode(impl, world, rec, planner=recorder)
    rec.evidence = Evidence([world, placed(world, angle, shift)], [first], time_bound(world))
    where = f"{place_of(impl, world)}, moved by {angle:.6f} rad and {_xy(shift)}"
    expected = moved_recording(recorder.recording(), angle, shift)
    compare_answers(impl, expected, "moved", where, rec)


def _scale_examples(impl: Implementation) -> st.SearchStrategy[tuple[World, float]]:
    return st.tuples(_promised_worlds(impl), st.sampled_from(EXACT_SCALES + ROUNDED_SCALES))


def _scaled_step(step: TraceStep, k: float) -> tuple[object, ...]:
    """What the scaled run must record at this step: lengths times ``k``, the rest as is."""
    speed = None if step.speed_cmd is None else k * step.speed_cmd
    branch = None if step.branch is None else str(step.branch)
    return (k * step.x, k * step.y, step.theta, step.heading_cmd, speed, branch)


_STEP_FIELDS = ("x", "y", "theta", "heading_cmd", "speed_cmd", "branch")


def scale_test(
    impl: Implementation,
    example: tuple[World, float],
    rec: Recorder,
    *,
    params: dict[str, object] | None = None,
    infos: Sequence[ParamInfo] = (),
) -> None:
    """Run ``example``'s world and compare with the same world scaled by its ``k``: for a
    power of two, run the scaled world too and compare bit for bit; otherwise replay the
    recorded exchange scaled, open loop (:mod:`ifgm_ref.oracle.invariance`).

    ``params`` (planner parameters by name, none by default) are scaled by their units in
    ``infos`` (:func:`ifgm_ref.oracle.metamorphic.scale_params`). Both problems get the
    original world's time bound and ``dt``; the goal tolerance scales. On a robot with mass
    (``rec.sim``'s engine not kinematic) the physics is not scale-free, so a power of two is
    replayed open loop too, and its answers compared bit for bit
    (:func:`~ifgm_ref.oracle.invariance.compare_exactly`).
    """
    world, k = generic(example[0]), example[1]
    scaled = scale_world(world, k)
    sim = rec.sim_for(world)
    scaled_params = None if params is None else scale_params(params, infos, k)
    where = f"{place_of(impl, world)}, scaled by k={k!r}"
    if is_power_of_two(k) and not rec.physical:
        first = episode(impl, world, rec, sim=sim, params=params)
        second = episode(impl, scaled, rec, sim=scale_sim(sim, k), params=scaled_params)
        rec.evidence = Evidence([world, scaled], [first, second], sim.max_time)
        _exactly_scaled(first, second, k, where)
        return
    recorder = RecordingPlanner(impl.factory())
    first = episode(impl, world, rec, planner=recorder, sim=sim, params=params)
    rec.evidence = Evidence([world, scaled], [first], sim.max_time)
    expected = scaled_recording(recorder.recording(), k, scaled_params)
    if is_power_of_two(k):  # on a robot with mass: the planner's half, still exact
        compare_exactly(impl, expected, f"scaled by k={k!r}", where, rec)
        return
    compare_answers(impl, expected, f"scaled by k={k!r}", where, rec)


def _exactly_scaled(first: Run, second: Run, k: float, where: str) -> None:
    """Raise :class:`CheckFailed` unless ``second`` is ``first`` times ``k`` bit for bit."""
    for n, (one, two) in enumerate(zip(first.trace, second.trace, strict=False)):
        want, got = _scaled_step(one, k), _scaled_step(two, 1.0)  # times 1.0: exact
        if want != got:
            diff = ", ".join(
                f"{name}={g!r} (should be {w!r})"
                for name, w, g in zip(_STEP_FIELDS, want, got, strict=True)
                if w != g
            )
            raise CheckFailed(
                f"scaled by k={k!r} (a power of two: exact), the run differs from the "
                f"original times k at step {n} (t={one.t:.1f} s, original branch "
                f"{want[-1]!r}): {diff}; lengths should be exactly k times the "
                f"original's, angles and branches equal [{where}]"
            )
    a, b = first.result, second.result
    if a.stop_reason != b.stop_reason or len(first.trace) != len(second.trace):
        raise CheckFailed(
            f"scaled by k={k!r} (a power of two: exact), the run ended "
            f"{b.stop_reason!r} after {b.steps} steps, but should end like the original, "
            f"{a.stop_reason!r} after {a.steps} steps [{where}]"
        )


@st.composite
def _unseen(draw: st.DrawFn, impl: Implementation) -> tuple[World, float, float, float]:
    world = draw(_promised_worlds(impl))
    direction = draw(st.floats(-math.pi, math.pi), label="unseen direction")
    beyond = draw(st.floats(1.0, 20.0), label="unseen distance beyond sensor range")
    radius = draw(st.floats(0.5, 5.0), label="unseen radius")
    return world, direction, beyond, radius


@traces("s3.no_map")
def _unseen_test(
    impl: Implementation, example: tuple[World, float, float, float], rec: Recorder
) -> None:
    """Run ``world``, then the same world plus a disc placed where no pose of the first run,
    nor the start or the goal, comes within sensor range of it; compare the two runs.

    Whatever the first run did (reach the goal, stop early, collide, run out of time), the
    disc keeps clear of every point the robot occupied and of the goal, so the second world is
    valid and the same planner, seeing the same scans, must drive the same steps; both runs
    get the first world's time bound, so they are comparable step for step.
    """
    world, direction, beyond, radius = example
    sim = rec.sim_for(world)
    first = episode(impl, world, rec, sim=sim)
    xy = np.vstack((_poses(first.trace)[:, :2], world.start.position, tuple(world.goal)))
    centre = xy.mean(axis=0)
    reach = float(np.hypot(*(xy - centre).T).max()) + world.sensor.range_max + radius + beyond
    far = circle(
        (centre[0] + reach * math.cos(direction), centre[1] + reach * math.sin(direction)), radius
    )
    extended = replace(world, obstacles=(*world.obstacles, far))
    second = episode(impl, extended, rec, sim=sim)
    rec.evidence = Evidence([world, extended], [first, second], sim.max_time)
    a, b = _poses(first.trace), _poses(second.trace)
    n = min(len(a), len(b))
    differ = np.flatnonzero(np.any(a[:n] != b[:n], axis=1))
    if len(differ) or len(a) != len(b):
        k = int(differ[0]) if len(differ) else n
        raise CheckFailed(
            f"adding an obstacle {reach - radius - world.sensor.range_max:.1f} ft beyond sensor "
            f"range of every pose changed the trajectory at step {k} (runs of {len(a) - 1} and "
            f"{len(b) - 1} steps, ended {first.result.stop_reason!r} and "
            f"{second.result.stop_reason!r}), but it should not change at all (decisions "
            f"depend on percepts only) [{place_of(impl, world)}]"
        )


@traces("fig3.case1")
def _gap_test(impl: Implementation, example: tuple[World, Polygon], rec: Recorder) -> None:
    world, gap = example
    run = episode(impl, world, rec)
    where = f"{place_of(impl, world)}, gap {_show_polygon(gap)}"
    if not run.result.reached:
        raise CheckFailed(f"{ending(run)}, but should be 'goal_reached' through the gap [{where}]")
    path = shapely.LineString([(s.x, s.y) for s in run.trace])  # reached: 2 or more points
    if not path.intersects(gap.geometry):
        raise CheckFailed(
            f"path passed {path.distance(gap.geometry):.2f} ft from the gap, but should go "
            f"through it [{where}]"
        )
    rec.tally.update(through=1, case1=_check_case1(run.trace, gap, where))
    rec.summary = f"{rec.tally['through']} run(s) through the gap; " + (
        f"the Case-1 rule met in {rec.tally['case1']}"
        if rec.tally["case1"]
        else "its Case-1 part not exercised: no avoidance branch reported before the gap"
    )
    centre = gap.geometry.centroid
    for step in run.trace[:-1]:
        if step.heading_cmd is None:  # no command recorded at this sample
            continue
        # Bearings from where the planner was told it is (odometry noise moves it off the pose).
        x = step.x if step.believed_x is None else step.believed_x
        y = step.y if step.believed_y is None else step.believed_y
        theta = step.theta if step.believed_theta is None else step.believed_theta
        to_goal = math.atan2(world.goal.y - y, world.goal.x - x)
        turn = math.remainder(step.heading_cmd - to_goal, 2.0 * math.pi)
        steer = math.remainder(step.heading_cmd - theta, 2.0 * math.pi)
        if abs(turn) > FIRST_TURN and turn * steer >= 0.0:
            side = math.remainder(math.atan2(centre.y - y, centre.x - x) - to_goal, 2.0 * math.pi)
            if turn * side < 0.0:
                raise CheckFailed(
                    f"first turn off the goal bearing at t={step.t:.1f} s is "
                    f"{math.degrees(turn):+.1f} deg, but should be towards the gap "
                    f"({math.degrees(side):+.1f} deg) [{where}]"
                )
            break


def _check_case1(trace: Sequence[TraceStep], gap: Polygon, where: str) -> bool:
    """A planner that reports its branches and avoids the wall before it reaches the gap
    (a gap wider than ``d_th``, the wall either side) takes Case-1 there: FGM steers
    (section 4). One whose way through the gap is clear never avoids and passes. Whether
    the rule applied: an avoidance branch was reported before the gap (a planner that reports
    no branches never meets it)."""
    before: set[str] = set()
    for a, b in itertools.pairwise(trace):
        if shapely.LineString([(a.x, a.y), (b.x, b.y)]).intersects(gap.geometry):
            break
        before.add(a.branch or Branch.MOVE_TO_GOAL)
    avoided = before - {Branch.MOVE_TO_GOAL, Branch.GOAL_REACHED}
    if avoided and Branch.CASE1_GAP not in avoided:
        raise CheckFailed(
            f"before the gap it avoided the wall by {', '.join(sorted(avoided))}, but never "
            f"case1_gap: a gap wider than d_th with the wall either side is Case-1 [{where}]"
        )
    return bool(avoided)


def _show_polygon(polygon: Polygon) -> str:
    return "[" + ", ".join(_xy(v) for v in polygon.vertices) + "]"


def _determinism_test(impl: Implementation, world: World, rec: Recorder) -> None:
    """Run once, recording; replay the same observations into a fresh planner."""
    recorder = RecordingPlanner(impl.factory())
    episode(impl, world, rec, planner=recorder)
    for k, (observation, command, again) in enumerate(replay(recorder.recording(), impl.factory())):
        if _command_fields(again) != _command_fields(command):
            raise CheckFailed(
                f"replaying the same observations, step {k} (t={observation.t:.1f} s) answered "
                f"{_command_fields(again)}, but the first run answered "
                f"{_command_fields(command)} [{place_of(impl, world)}]"
            )


def _agrees_test(impl: Implementation, world: World, rec: Recorder) -> None:
    """Replay the reference IFGM's episode in ``world`` into ``impl``, open loop, and compare
    step by step (:mod:`ifgm_ref.oracle.agreement`)."""
    sim = rec.sim_for(world)
    reference = reference_episode(world, sim, Readings.declared(impl.promises.readings))
    agrees_with(impl, world, reference, rec)


def agrees_with(
    impl: Implementation, world: World, reference: ReferenceEpisode, rec: Recorder
) -> None:
    """Replay ``reference``, the reference's episode in ``world`` (run, or rebuilt from a
    suite case: :mod:`ifgm_ref.oracle.suite.recorded`), into ``impl`` and compare."""
    rec.examples += 1
    rec.worlds.add(world)
    if currently_in_test_context():
        note(f"world: {world}")
    rec.evidence = Evidence([world], [reference.run], rec.sim_for(world).max_time)
    where = place_of(impl, world)
    found = compare(impl, reference, where)
    total = len(reference.recording.steps)
    rec.tally.update(steps=total, agreed=found.steps, ties=found.tie is not None)
    rec.summary = (
        f"{rec.tally['agreed']} of {rec.tally['steps']} reference steps agreed; "
        f"{rec.tally['ties']} episode(s) ended early at a tie"
    )
    if found.diverged:
        rec.evidence.step = present(found.differs, "the step that differs").step
        raise CheckFailed(divergence_message(reference, found, where))


@traces("fig3.dead_end")
def _dead_end_test(impl: Implementation, world: World, rec: Recorder) -> None:
    """Every dead end the run reports turns 45 degrees at a time (:mod:`.dead_end`).

    The turns are read in parts (:func:`~.dead_end.part_errors`) where they cannot show
    whole: on a robot that brakes before it turns, and for a planner answering velocity
    commands, whose commanded heading is where one step's turn ends."""
    recorder = RecordingPlanner(impl.factory())
    run = episode(impl, world, rec, planner=recorder)
    dt = run.trace[1].t - run.trace[0].t if len(run.trace) > 1 else 0.0
    dead_band = world.robot.max_turn_rate * dt / 2
    velocity = any(command.turn_rate is not None for _, command in recorder.recording().steps)
    in_parts = rec.physical or not world.robot.stops_at_once or velocity
    for start, commanded in dead_end_turns(run.trace):
        rec.tally.update(dead_ends=1)
        if why := turn_errors(start, commanded, dead_band, in_parts=in_parts):
            raise CheckFailed(f"{why} [{place_of(impl, world)}]")
    rec.summary = f"{rec.tally['dead_ends']} dead end(s) met, none turned otherwise"


def _command_fields(command: Command) -> tuple[object, ...]:
    return (command.heading, command.speed, command.behaviour, command.branch, command.stop)


# -- the registry ------------------------------------------------------------------------------


def _collision_applies(impl: Implementation) -> str | None:
    return None if impl.promises.collision_free else "it does not promise collision-freedom"


def _convergence_check(world_class: str) -> Check:
    def applies(impl: Implementation) -> str | None:
        if world_class in impl.promises.converges_in:
            return None
        return f"it does not promise convergence in {world_class} worlds"

    return Check(
        f"converges_{world_class}",
        f"in every solvable {world_class} world the robot reaches the goal within the bound",
        Kind.SIMULATION,
        lambda impl: SOLVABLE_CLASSES[world_class](),
        _converges_test,
        applies,
        sample=GENERATORS[world_class],
    )


def _unreachable_applies(impl: Implementation) -> str | None:
    return None if impl.promises.reports_unreachable else "it does not promise to report it"


def _scale_applies(impl: Implementation) -> str | None:
    return None if impl.promises.scale_invariant else "it does not promise scale invariance"


def _rigid_applies(impl: Implementation) -> str | None:
    if impl.promises.rigid_motion_invariant:
        return None
    return "it does not promise rigid-motion invariance"


def _gaps_apply(impl: Implementation) -> str | None:
    return None if impl.promises.passes_wide_gaps else "it does not promise to use gaps"


def _follows_ifgm(impl: Implementation) -> str | None:
    if impl.promises.reference != "ifgm":
        return "it does not claim to follow the reference IFGM's readings step by step"
    return unrunnable(impl.promises.readings)


def _turns_apply(impl: Implementation) -> str | None:
    return None if impl.promises.turns_at_dead_ends else "it does not promise IFGM's dead end"


def _always(impl: Implementation) -> str | None:
    return None


CHECKS: dict[str, Check] = {
    check.name: check
    for check in [
        Check(
            "collision_free",
            "the swept robot disc never meets an obstacle",
            Kind.SIMULATION,
            lambda impl: st.one_of(any_solvable_worlds(), enclosed_worlds()),
            _collision_test,
            _collision_applies,
            meets=Meets(NEAR, "the robot moved within its sensor's range of an obstacle"),
        ),
        *(_convergence_check(c) for c in SOLVABLE_CLASSES),
        Check(
            "reports_unreachable",
            "with the goal enclosed, the planner stops with goal_unreachable",
            Kind.SIMULATION,
            lambda impl: enclosed_worlds(),
            _unreachable_test,
            _unreachable_applies,
            sample=enclosed_world,
        ),
        Check(
            "rigid_motion_invariant",
            "rotating and translating the problem moves the trajectory the same way",
            Kind.SIMULATION,
            lambda impl: st.tuples(_promised_worlds(impl), placements()),
            _invariance_test,
            _rigid_applies,
            meets=MOVING,
        ),
        Check(
            "scale_invariant",
            "scaling every length of the problem by k scales the trajectory by k",
            Kind.SIMULATION,
            _scale_examples,
            scale_test,
            _scale_applies,
            meets=MOVING,
        ),
        Check(
            "ignores_unseen_obstacles",
            "an obstacle the sensor never sees does not change the trajectory",
            Kind.SIMULATION,
            _unseen,
            _unseen_test,
            _always,
            meets=MOVING,
        ),
        Check(
            "passes_wide_gaps",
            "through a wall with one gap wider than d_th, the robot goes through the gap",
            Kind.SIMULATION,
            lambda impl: gap_walls(),
            _gap_test,
            _gaps_apply,
            sample=gap_wall,
        ),
        Check(
            "deterministic",
            "the same observations give the same commands",
            Kind.SIMULATION,
            _promised_worlds,
            _determinism_test,
            _always,
        ),
        Check(
            "dead_end_turns",
            "at a dead end (reported as dead_end_turn) the robot turns in 45-degree steps, "
            "one way, 180 degrees at most",
            Kind.SIMULATION,
            lambda impl: st.one_of(SOLVABLE_CLASSES["u"](), SOLVABLE_CLASSES["h"]()),
            _dead_end_test,
            _turns_apply,
            explicit=lambda: [resolve_world("u_trap"), resolve_world("h_block")],
            meets=Meets("dead_ends", "a dead end reported as dead_end_turn"),
        ),
        Check(
            "agrees_with_reference",
            "replayed the reference IFGM's observations, it answers each step as the reference",
            Kind.SIMULATION,
            lambda impl: any_solvable_worlds(),
            _agrees_test,
            _follows_ifgm,
            level=Level.REFERENCE,
            explicit=reference_worlds,
        ),
        stops_in_time(),
        *equation_checks(),
    ]
}


def checks_at(level: Level | str) -> list[str]:
    """The names of the checks a run at ``level`` runs: the paper's properties, or those and
    the reference level's ``agrees_with_reference``
    (:func:`~ifgm_ref.oracle.check_types.levels_up_to`).

    >>> "agrees_with_reference" in checks_at("paper"), "agrees_with_reference" in checks_at(
    ...     "reference")
    (False, True)
    """
    levels = levels_up_to(level)
    return [name for name, check in CHECKS.items() if check.level in levels]
