"""``stops_in_time``: at every step, a robot with mass can still stop before what it sees.

A runtime monitor, in the manner of ModelPlex (Mitsch & Platzer, "ModelPlex: verified runtime
validation of verified cyber-physical system models", FMSD 49, 2016), for the braking
governor's condition (:mod:`ifgm_ref.planners.governor`, proved in ``proofs/braking.py``):
the robot gets a finite braking ``b``, acceleration ``A`` and response time, drawn with the
world, and every command the implementation answers must be one from which it can still stop
in the region it may sweep, measured in the scan it was handed
(:func:`~ifgm_ref.planners.governor.admissible`). The monitor keeps the bound on the robot's
speed from the implementation's own commands, as the governor does; it keeps no margin
beyond the robot's disc. The episode must not collide either: ``collision_free`` on a robot
that cannot stop at once.

The dynamics are drawn relative to the robot, so that the check is scale-free: the braking
``b`` gives a stop from top speed ``v`` in ``v^2 / (2 b)``, drawn among :data:`STOPS` robot
radii; ``A`` is ``b`` times one of :data:`ACCELERATIONS`; the response time one of
:data:`RESPONSES` time steps. A robot given its own dynamics (``--robot braking=...``) keeps
them, and so does a robot with mass (``--engine mujoco``: its body's).

It applies to implementations that promise to stop in time
(:attr:`~ifgm_ref.oracle.implementation.Promises.stops_in_time`), the reference planners
but DWA (which keeps its own dynamic window) and ``straight``.
"""

from __future__ import annotations

from dataclasses import replace

from hypothesis import strategies as st

from ifgm_ref.core.recording import Recording, RecordingPlanner
from ifgm_ref.oracle.check_types import Check, CheckFailed, Kind, Recorder
from ifgm_ref.oracle.episodes import MOVING, episode, place_of
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.strategies import any_solvable_worlds
from ifgm_ref.planners.governor import GovernorState, Limits, admissible, next_state
from ifgm_ref.sim.world import World

__all__ = ["ACCELERATIONS", "RESPONSES", "STOPS", "TOLERANCE", "late_step", "stops_in_time"]

#: The stop from top speed, in robot radii (``v^2 / (2 b)``): a quarter radius (a robot
#: that brakes hard) to two (one that needs a long way), the first the simplest.
STOPS = (1.0, 0.25, 0.5, 2.0)
#: The acceleration ``A`` as a multiple of ``b``.
ACCELERATIONS = (1.0, 0.5, 2.0)
#: The response time, in time steps.
RESPONSES = (0.0, 0.5)
#: A stop may exceed the room by this much, in robot radii: rounding (a float32 port's
#: speed is 6e-8 off, a few 1e-9 r of distance).
TOLERANCE = 1e-6


def with_dynamics(world: World, stop: float, ratio: float, response: float, dt: float) -> World:
    """``world`` with its robot stopping from top speed in ``stop`` radii, accelerating at
    ``ratio`` times its braking and responding within ``response`` time steps of ``dt``.

    >>> robot = with_dynamics(World(start=(0, 0, 0), goal=(9, 0)), 1.0, 2.0, 0.5, 0.1).robot
    >>> round(robot.braking, 6), round(robot.acceleration, 6), robot.response
    (0.874037, 1.748074, 0.05)
    """
    robot = world.robot
    braking = robot.speed**2 / (2 * stop * robot.radius)
    told = replace(robot, braking=braking, acceleration=ratio * braking, response=response * dt)
    return replace(world, robot=told)


def late_step(recording: Recording) -> tuple[int, float, float] | None:
    """The first step of ``recording`` whose command the robot cannot stop from in the
    region it may sweep: its index, the stopping distance and the room; ``None`` if none."""
    limits = Limits.of(recording.params)
    state = GovernorState()
    tolerance = TOLERANCE * limits.radius
    for k, (observation, command) in enumerate(recording.steps):
        if command.stop is not None:
            break
        ok, needed, room = admissible(command, observation, state, limits)
        if not ok and needed > room + tolerance:
            return k, needed, room
        state = next_state(state, command.heading, command.speed, limits, observation.pose.theta)
    return None


def _stops_test(
    impl: Implementation, example: tuple[World, tuple[float, float, float]], rec: Recorder
) -> None:
    world, (stop, ratio, response) = example
    if world.robot.stops_at_once and not rec.physical:  # else its own dynamics, or the body's
        world = with_dynamics(world, stop, ratio, response, rec.sim.dt)
    recorder = RecordingPlanner(impl.factory())
    run = episode(impl, world, rec, planner=recorder)
    recording = recorder.recording()
    rec.tally.update(steps=len(recording.steps))
    late = late_step(recording)
    if late is not None:
        k, needed, room = late
        command = recording.steps[k][1]
        rec.evidence.step = k  # type: ignore[union-attr]
        raise CheckFailed(
            f"at t={recording.steps[k][0].t:.2f} s the command's stop needs {needed:.4f}, but "
            f"should fit in the {room:.4f} free in the way it may sweep (speed "
            f"{command.executed_speed(world.robot)}, braking {world.robot.braking:.4g}) "
            f"[{place_of(impl, world)}]"
        )
    if run.result.collided or run.result.min_clearance < 0.0:
        raise CheckFailed(
            f"min_clearance={run.result.min_clearance:.4f}, but should be >= 0 with braking "
            f"{world.robot.braking:.4g} [{place_of(impl, world)}]"
        )
    rec.summary = f"{rec.tally['steps']} steps monitored, each able to stop in time"


def _applies(impl: Implementation) -> str | None:
    return None if impl.promises.stops_in_time else "it does not promise to stop in time"


def stops_in_time() -> Check:
    """The ``stops_in_time`` check (module docstring)."""
    dynamics = st.tuples(
        st.sampled_from(STOPS), st.sampled_from(ACCELERATIONS), st.sampled_from(RESPONSES)
    )
    return Check(
        "stops_in_time",
        "on a robot with finite braking, every command leaves room to stop before what it sees",
        Kind.SIMULATION,
        lambda impl: st.tuples(any_solvable_worlds(), dynamics),
        _stops_test,
        _applies,
        meets=MOVING,
    )
