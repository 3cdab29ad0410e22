"""Run a planner in a world: sense, decide, move, check, until the episode ends.

Each step the sensor scans from the current pose, the planner answers a command from that
observation alone (no map), the robot moves by one time step (:func:`ifgm_ref.sim.robot.advance`)
and the disc swept between the two poses is checked for collision exactly
(:class:`ifgm_ref.sim.collision.ClearanceChecker`). That is the default, ``kinematic`` engine;
``SimParams(engine="mujoco")`` senses and moves a robot with mass on MuJoCo instead, under
the same loop and rules (:mod:`ifgm_ref.sim.engine`). An episode ends when the robot's centre is
within ``goal_tolerance`` of the goal, the swept disc meets an obstacle, the robot's centre
leaves the world's bounds, the planner sends an invalid command or asks to stop, the robot
stalls, or the time limit passes.

Two stall rules end an episode with stop reason ``stalled`` (the result's ``detail`` says
which), both derived from the robot so they fire at the same step at any scale:

* the disc rule: the centre stays within ``r`` of where it was ``T`` seconds before, over all
  of those seconds, with ``T`` = :attr:`SimParams.stall_time
  <ifgm_ref.core.params.SimParams.stall_time>`, by default :data:`STALL_TIME`
  (``Max(6*pi/w, 10*r/v, 20*dt)``);
* the lap rule (:mod:`ifgm_ref.sim.laps`): ``K`` =
  :attr:`SimParams.stall_laps <ifgm_ref.core.params.SimParams.stall_laps>` laps back to one
  place without progress towards the goal.

Why these numbers, and what each rule ends in the measured worlds: ``docs/oracle.md``, "Why
the stall rules' numbers", and ``docs/benchmark.md``, "The stall rules, measured".
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections import deque
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field, replace
from enum import StrEnum
from itertools import pairwise
from typing import Any

from ifgm_ref.core.formulas import Scale, declare, evaluate
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Pose, distance, wrap_angle
from ifgm_ref.core.progress import progress_bar
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner
from ifgm_ref.sim.engine import Engine, make_engine
from ifgm_ref.sim.laps import LapRule, LapWatch
from ifgm_ref.sim.noise import Actuation, Odometry
from ifgm_ref.sim.world import World


class StopReason(StrEnum):
    """Why the simulator ended an episode (a planner may also stop with its own reason)."""

    GOAL_REACHED = "goal_reached"
    COLLISION = "collision"
    TIME_LIMIT = "time_limit"
    OUT_OF_BOUNDS = "out_of_bounds"
    INVALID_COMMAND = "invalid_command"
    #: No progress: the centre stayed within ``r`` of one point for the stall time (the disc
    #: rule), or came back to one place after laps that brought it no nearer the goal (the lap
    #: rule).
    STALLED = "stalled"


#: The default stall time, s: a formula in the robot and the time step (reasons:
#: ``docs/oracle.md``; :func:`ifgm_ref.core.formulas.evaluate` computes it).
STALL_TIME = declare("Max(6*pi/w, 10*r/v, 20*dt)")


@dataclass(frozen=True)
class TraceStep:
    """One sample of an episode: the state at time ``t`` and the command decided there.

    The last sample of a trace has no command (its command fields are ``None``).
    ``clearance`` is that of the disc swept from this sample to the next (or standing here,
    for the last sample), in ft. ``x``, ``y`` and ``theta`` are the true pose; the
    ``believed_`` ones the pose the planner was told, which differs with odometry noise
    (:mod:`ifgm_ref.sim.noise`). ``speed_cmd`` is the speed the planner asked for,
    ``speed_executed`` the one the robot was driven at: clipped to the robot's top speed.
    """

    t: float
    x: float
    y: float
    theta: float
    heading_cmd: float | None
    speed_cmd: float | None
    behaviour: str | None
    branch: str | None
    clearance: float
    believed_x: float | None = None
    believed_y: float | None = None
    believed_theta: float | None = None
    speed_executed: float | None = None


TRACE_FIELDS = tuple(TraceStep.__dataclass_fields__)


def total_turning(trace: Sequence[TraceStep]) -> float:
    """Smoothness: the total absolute heading change along a trace, rad (turns on the spot too).

    >>> headings = [0.0, 0.5, -0.5, 3.0, -3.0]
    >>> trace = [TraceStep(0.1 * k, 0, 0, th, None, None, None, None, 1.0)
    ...          for k, th in enumerate(headings)]
    >>> round(total_turning(trace), 6)  # 0.5 + 1.0 + (2 pi - 3.5) + (2 pi - 6): the short way
    4.566371
    """
    return float(sum(abs(wrap_angle(b.theta - a.theta)) for a, b in pairwise(trace)))


@dataclass(frozen=True)
class Result:
    """The outcome of one episode (the fields of ``ifgm-ref simulate --json``).

    ``min_clearance`` is ``None`` in JSON (``inf`` here) when the world has no obstacle;
    ``detail`` explains an ``invalid_command`` stop, and names the rule of a ``stalled`` one
    (``disc rule: ...`` or ``lap rule: ...``).
    """

    planner: str
    world: str | None
    reached: bool
    collided: bool
    stop_reason: str
    time_s: float
    path_length: float
    min_clearance: float
    steps: int
    detail: str | None = None

    def to_json_dict(self) -> dict[str, Any]:
        """The result as a JSON-ready mapping (infinite clearance as ``None``)."""
        data = asdict(self)
        if not math.isfinite(self.min_clearance):
            data["min_clearance"] = None
        return data


@dataclass
class Run:
    """A finished episode: its result and its trace."""

    result: Result
    trace: list[TraceStep] = field(default_factory=list)

    def trace_csv(self) -> str:
        """The trace as CSV text, one row per sample, empty cells for missing values."""
        out = io.StringIO()
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(TRACE_FIELDS)
        for step in self.trace:
            writer.writerow(["" if v is None else v for v in asdict(step).values()])
        return out.getvalue()

    def trace_json(self) -> str:
        """The result and the trace as one JSON document (``{"result": ..., "trace": [...]}``)."""
        rows = []
        for step in self.trace:
            row = asdict(step)
            if not math.isfinite(row["clearance"]):
                row["clearance"] = None
            rows.append(row)
        return json.dumps({"result": self.result.to_json_dict(), "trace": rows}, indent=1)


def episode_params(
    world: World, sim: SimParams, params: Mapping[str, Any] | None = None
) -> EpisodeParams:
    """What a planner is told at reset when ``world`` is run with ``sim``: the world's robot
    and sensor, the time step, the goal tolerance and the planner's ``params``."""
    return EpisodeParams(world.robot, world.sensor, sim.dt, dict(params or {}), sim.goal_tolerance)


def simulate(
    world: World,
    planner: Planner,
    sim: SimParams | None = None,
    *,
    params: dict[str, Any] | None = None,
    progress: bool | None = False,
) -> Run:
    """Run ``planner`` in ``world`` until the episode ends; return the result and trace.

    Parameters
    ----------
    world : World
        The obstacles, start, goal, robot and sensor.
    planner : Planner
        Any object with ``name``, ``reset`` and ``step`` (see :mod:`ifgm_ref.core.protocol`).
    sim : SimParams, optional
        Time step, time limit, goal tolerance and stall time (defaults of :class:`SimParams`).
    params : dict, optional
        Planner-specific settings handed to ``planner.reset`` unchanged.
    progress : bool or None, default False
        Show a progress bar over simulated time on stderr; ``None`` shows it only on a terminal.
    """
    sim = sim or SimParams()
    engine = make_engine(world, sim)
    world = replace(world, robot=engine.robot)  # as the engine's body makes it
    episode = episode_params(world, sim, params)
    planner.reset(world.start, world.goal, episode)
    stall = stall_steps(sim, episode)
    laps = lap_rule(sim, episode)
    pose = Pose(*world.start)
    recent = deque([pose], maxlen=(stall or 0) + 1)  # the last stall + 1 positions
    state = _Episode(pose, recent, engine.pose_clearance(pose), Odometry(world.robot), engine)
    if laps is not None:
        state.laps = LapWatch.start(laps, world.goal)
    stop, detail = _drive(state, world, planner, sim, stall, progress)
    end = round(state.steps * sim.dt, 12)
    last = _sample(end, state.pose, None, engine.pose_clearance(state.pose), state.believed)
    state.trace.append(last)
    result = Result(
        planner=planner.name,
        world=world.name,
        reached=stop == StopReason.GOAL_REACHED,
        collided=stop == StopReason.COLLISION,
        stop_reason=str(stop),
        time_s=end,
        path_length=state.path_length,
        min_clearance=state.min_clearance,
        steps=state.steps,
        detail=detail,
    )
    return Run(result, state.trace)


@dataclass
class _Episode:
    """An episode in progress: the robot's pose, the last few positions (for the disc rule),
    its odometry's noise, the engine, the positions logged for the lap rule (``None`` when it
    is off), the trace so far, the path length, the least clearance and the steps taken."""

    pose: Pose
    recent: deque[Pose]
    min_clearance: float
    odometry: Odometry
    engine: Engine
    laps: LapWatch | None = None
    trace: list[TraceStep] = field(default_factory=list)
    path_length: float = 0.0
    steps: int = 0

    @property
    def believed(self) -> Pose:
        """The pose the planner is told: the engine's odometry, with odometry noise."""
        return self.odometry.believed(self.engine.odometry(self.pose))

    def move(
        self, t: float, command: Command, believed: Pose, new_pose: Pose, clearance: float
    ) -> None:
        """Record the step decided at time ``t`` (told ``believed``) from :attr:`pose` to
        ``new_pose``."""
        top = self.engine.robot.speed
        self.trace.append(_sample(t, self.pose, command, clearance, believed, top))
        self.min_clearance = min(self.min_clearance, clearance)
        moved = distance(self.pose, new_pose)
        self.path_length += moved
        self.odometry.moved(moved)
        self.pose = new_pose
        self.recent.append(new_pose)
        self.steps += 1


def _drive(
    state: _Episode,
    world: World,
    planner: Planner,
    sim: SimParams,
    stall: int | None,
    progress: bool | None,
) -> tuple[str, str | None]:
    """Sense, decide and move from ``state`` until the episode ends (see :func:`simulate`);
    return the stop reason and, for an invalid command, what is wrong with it."""
    max_steps = math.ceil(sim.max_time / sim.dt - 1e-9)
    actuation = Actuation(world.robot)
    with progress_bar(
        total=max_steps, unit="step", desc=planner.name, progress=progress, leave=False
    ) as bar:
        while True:
            t = round(state.steps * sim.dt, 12)
            if distance(state.pose, world.goal) <= sim.goal_tolerance:
                return StopReason.GOAL_REACHED, None
            if state.steps >= max_steps:
                return StopReason.TIME_LIMIT, None
            if stall is not None and _stalled(state.recent, world.robot.radius):
                return (
                    StopReason.STALLED,
                    f"disc rule: within r of one point for {stall * sim.dt:g} s",
                )
            if state.laps is not None and state.laps.stalled(state.pose, state.path_length):
                return StopReason.STALLED, state.laps.detail
            believed = state.believed
            scan = state.engine.scan(state.pose)
            command = planner.step(Observation(t, believed, world.goal, scan))
            detail = _problem(command)
            if detail is not None:
                return StopReason.INVALID_COMMAND, detail
            if command.stop is not None:
                return command.stop, None
            executed, turn, speed = actuation.executed(command, believed)
            if state.odometry.drift:  # the heading controller knows the believed heading only
                heading = state.odometry.true_heading(executed.heading)
                executed = replace(executed, heading=heading)
            new_pose, clearance, collided = state.engine.move(state.pose, executed, turn, speed)
            state.move(t, command, believed, new_pose, clearance)
            if state.steps % 100 == 0:
                bar.update(100)
            if collided:
                return StopReason.COLLISION, None
            if world.bounds is not None and not world.bounds.contains(state.pose):
                return StopReason.OUT_OF_BOUNDS, None


def stall_steps(sim: SimParams, episode: EpisodeParams) -> int | None:
    """The stall time of ``sim`` for ``episode``'s robot and time step, in whole steps
    (rounded up); ``None`` when the stall rule is off.

    >>> stall_steps(SimParams(), EpisodeParams())  # Max(6 pi/w, 10 r/v, 20 dt) = 12 s
    120
    >>> stall_steps(SimParams(stall_time=2.05), EpisodeParams()), stall_steps(
    ...     SimParams(stall_time=None), EpisodeParams())
    (21, None)
    """
    if isinstance(sim.stall_time, str):  # AUTO, the one string SimParams allows
        seconds = evaluate(STALL_TIME, Scale.of(episode))
    elif sim.stall_time:
        seconds = sim.stall_time
    else:
        return None
    return math.ceil(seconds / sim.dt - 1e-9)


def lap_rule(sim: SimParams, episode: EpisodeParams) -> LapRule | None:
    """The lap rule of ``sim`` for ``episode``'s robot, time step and sensor: its thresholds
    (:data:`~ifgm_ref.sim.laps.LAP_RADIUS`, :data:`~ifgm_ref.sim.laps.LAP_LENGTH` and
    :data:`~ifgm_ref.sim.laps.LAP_PROGRESS`) and ``sim.stall_laps`` laps; ``None`` when the rule
    is off.

    >>> rule = lap_rule(SimParams(), EpisodeParams())  # r, 2 pi r and v dt: 1, 6.28 and 0.13 ft
    >>> rule.radius, round(rule.length, 2), round(rule.progress, 2), rule.laps
    (1.0, 6.28, 0.13, 2)
    >>> lap_rule(SimParams(stall_laps=None), EpisodeParams())
    """
    if not sim.stall_laps:
        return None
    return LapRule.of(Scale.of(episode), sim.stall_laps)


def _stalled(recent: deque[Pose], radius: float) -> bool:
    """Whether ``recent`` is full and every position in it lies within ``radius`` of the first
    (newest first: a robot on the move fails at once, before any generator is made)."""
    if len(recent) != recent.maxlen:
        return False
    first = recent[0]
    if distance(first, recent[-1]) > radius:
        return False
    return all(distance(first, p) <= radius for p in reversed(recent))


def _problem(command: object) -> str | None:
    if not isinstance(command, Command):
        return f"step() returned {type(command).__name__}, but should return a Command"
    return command.problem()


def _sample(
    t: float,
    pose: Pose,
    command: Command | None,
    clearance: float,
    believed: Pose,
    top_speed: float = math.inf,
) -> TraceStep:
    return TraceStep(
        t=t,
        x=pose.x,
        y=pose.y,
        theta=pose.theta,
        heading_cmd=None if command is None else command.heading,
        speed_cmd=None if command is None else command.speed,
        behaviour=None if command is None else command.behaviour,
        branch=None if command is None else command.branch,
        clearance=clearance,
        believed_x=believed.x,
        believed_y=believed.y,
        believed_theta=believed.theta,
        speed_executed=None if command is None else min(command.speed, top_speed),
    )
