"""Replay a robot's log into the reference, open loop, and compare the commands step by step.

``ifgm-ref replay BAG`` answers an implementer's question: given what *my* robot saw, would
the reference have decided what my robot did? :func:`replay_log` hands the reference each
logged scan with the pose at its time (:mod:`ifgm_ref.io.bags.read`), in order; the reference's
commands move nothing (open loop), so every step sees exactly what the robot saw.

**The setting.** A log written by ``ifgm-ref simulate --record`` carries its episode (the
``reset`` of the JSON-lines protocol: robot, sensor, ``dt``, start, goal, parameters) and its
unit: the replay runs in that unit with those parameters, so the reference meets the
recorded run on the recorded terms. Any other log is replayed in metres with BARN's robot
(:data:`ifgm_ref.io.barn.ROBOT`: the Jackal-sized disc) unless options say otherwise,
``dt`` the median time between scans (to the microsecond), the sensor read off the first
scan (its field of view must be centred on the heading), and the goal from an option or
``/goal_pose``.

**The comparison.** Commands of the two forms meet as velocities: the reference's heading
and speed become the speed and turn rate the robot executes over one step
(:meth:`Command.twist`); the logged ``(linear, angular)`` is taken within the same limits
(the speed no faster than the robot's, the turn rate within ``max_turn_rate``; a negative
speed stays negative, and differs). A step agrees when the headings the two turns lead to
after one step ``dt`` differ by at most :data:`~ifgm_ref.oracle.invariance.HEADING_TOL`
(0.1 rad), the speeds by at most :data:`~ifgm_ref.oracle.invariance.SPEED_TOL` (0.1) of the
robot's, and, where both name one, the branches are the same (:data:`BRANCH_RULE`): the
oracle's tolerances for "the same answer", which a float32 port meets and a broken rule does
not. A log is such a port: its ranges are float32, and the reference, handed them, now and
then follows the neighbouring ray or edge point that the rounding makes the nearer
(measured: 0.00054 rad the most, IFGM's own run in ``u_trap``). A step may break any of the
three rules: :class:`ReplayReport` counts the steps that differ in motion (heading or speed
beyond its tolerance) apart from those whose branches differ, and each rule's. The first
step that differs is the *first divergence*; the replay goes on to the end and counts the
others, which may follow from the first (the reference's own state has then taken another
way).
"""

from __future__ import annotations

import csv
import io
import math
import statistics
from dataclasses import dataclass
from itertools import pairwise
from typing import Any

import numpy as np

from ifgm_ref.core.errors import BagError, ProtocolError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.progress import progress_bar
from ifgm_ref.core.protocol import EpisodeParams, Observation, Planner
from ifgm_ref.io.bags.read import BagScan, LogStep, RobotLog, same_branch
from ifgm_ref.io.transport.wire import parse_reset
from ifgm_ref.oracle.invariance import HEADING_TOL, SPEED_TOL

__all__ = [
    "BRANCH",
    "BRANCH_RULE",
    "HEADING",
    "MOTION",
    "SPEED",
    "ReplayReport",
    "ReplayStep",
    "Setting",
    "Tolerance",
    "difference",
    "replay_log",
    "setting_of",
]

#: How far a foreign scan's field of view may be off centre, rad (float32 angles round).
CENTRE_TOLERANCE = 1e-4

#: The rules a step may break: the heading's and the speed's tolerance, and the branch rule.
HEADING, SPEED, BRANCH = "heading", "speed", "branch"
#: The rules of motion: a step breaking one differs in what the robot does.
MOTION = (HEADING, SPEED)
#: The branch rule, as ``--help`` states it (:func:`~ifgm_ref.io.bags.read.same_branch`).
BRANCH_RULE = (
    "where the log and the reference both name a branch, it is the same one (a logged "
    "dead_end_turn also matches dead_end_escape and dead_end_handover)"
)


@dataclass(frozen=True)
class Setting:
    """How a log is replayed: the episode, start and goal in ``unit``, and the unit's length
    in metres."""

    params: EpisodeParams
    start: Pose
    goal: Point
    unit: str
    metres_per_unit: float


@dataclass(frozen=True)
class Tolerance:
    """How far a logged step may be from the reference's and still agree: ``heading``, rad,
    between the headings the two turns lead to after one step; ``speed``, a share of the
    robot's speed. The defaults are the oracle's (module docstring)."""

    heading: float = HEADING_TOL
    speed: float = SPEED_TOL


@dataclass(frozen=True)
class ReplayStep:
    """One replayed step: its index, time (s) and pose (``unit``); the logged and the
    reference's ``(speed, turn rate)`` within the robot's limits and branches; whether they
    agree (``None`` when nothing was logged for the step) and, if not, what differs and the
    rules it ``broke`` (of :data:`HEADING`, :data:`SPEED`, :data:`BRANCH`, in that order)."""

    k: int
    t: float
    pose: Pose
    logged: tuple[float, float] | None
    logged_branch: str | None
    reference: tuple[float, float]
    reference_branch: str | None
    agrees: bool | None
    differs: str = ""
    broke: tuple[str, ...] = ()

    @property
    def motion_agrees(self) -> bool | None:
        """Whether heading and speed agree (``None`` when nothing was logged)."""
        return None if self.agrees is None else not set(MOTION) & set(self.broke)

    @property
    def branch_agrees(self) -> bool | None:
        """Whether the branches agree (``None`` when not compared: nothing logged, or one of
        the two steps names no branch)."""
        if self.agrees is None or not (self.logged_branch and self.reference_branch):
            return None
        return BRANCH not in self.broke


@dataclass(frozen=True)
class ReplayReport:
    """The replay of a log: every step and what it was compared with."""

    path: str
    planner: str
    setting: Setting
    tolerance: Tolerance
    steps: tuple[ReplayStep, ...]
    scans: tuple[LaserScan, ...]

    @property
    def compared(self) -> int:
        """The steps with a logged command."""
        return sum(s.agrees is not None for s in self.steps)

    @property
    def disagreeing(self) -> int:
        """The steps whose logged command differs from the reference's, in motion or branch."""
        return sum(s.agrees is False for s in self.steps)

    @property
    def motion_disagreeing(self) -> int:
        """The steps whose heading or speed differs beyond its tolerance."""
        return sum(s.motion_agrees is False for s in self.steps)

    @property
    def branch_compared(self) -> int:
        """The steps with a logged command where the log and the reference both name a branch."""
        return sum(s.branch_agrees is not None for s in self.steps)

    @property
    def branch_disagreeing(self) -> int:
        """The steps whose branches differ (:data:`BRANCH_RULE`)."""
        return self.breaking(BRANCH)

    def breaking(self, rule: str) -> int:
        """The steps that break ``rule`` (:data:`HEADING`, :data:`SPEED` or :data:`BRANCH`)."""
        return sum(rule in s.broke for s in self.steps)

    @property
    def first_divergence(self) -> ReplayStep | None:
        """The first step that differs, or ``None`` when every compared step agrees."""
        return next((s for s in self.steps if s.agrees is False), None)

    @property
    def first_motion_divergence(self) -> ReplayStep | None:
        """The first step whose heading or speed differs, or ``None`` when none does."""
        return next((s for s in self.steps if s.motion_agrees is False), None)

    def text(self) -> str:
        """A few lines: the verdict, the steps that differ in motion and in branch with the
        tolerance or rule each broke, and the first divergence (and the first in motion, when
        that is a later step), lengths in the log's unit."""
        heading, speed = self.tolerance.heading, self.tolerance.speed
        verb = "differs" if self.disagreeing == 1 else "differ"
        lines = [
            f"{self.planner} replayed on {self.path}: {_steps(len(self.steps))}, "
            f"{self.compared} with a logged command, {self.disagreeing} {verb}"
        ]
        if self.first_divergence is None:
            lines[0] += (
                f" (heading after a step within {heading:g} rad, speed within {speed:g} of the "
                "robot's, the same branch where both name one)"
            )
            lines.append("every logged command agrees with the reference")
            return "\n".join(lines)
        lines[0] += f": {self.motion_disagreeing} in motion, {self.branch_disagreeing} in branch"
        lines += [
            f"  heading: {_steps(self.breaking(HEADING))} off by more than {heading:g} rad "
            "after a step (--heading-tolerance)",
            f"  speed:   {_steps(self.breaking(SPEED))} off by more than {speed:g} of the "
            "robot's speed (--speed-tolerance)",
            f"  branch:  {_steps(self.branch_disagreeing)} with another branch, of the "
            f"{self.branch_compared} where both name one (the branch rule)",
        ]
        lines += self._divergence("first divergence", self.first_divergence)
        motion = self.first_motion_divergence
        if motion is not None and motion is not self.first_divergence:
            lines += self._divergence("first divergence in motion", motion)
        return "\n".join(lines)

    def _divergence(self, title: str, step: ReplayStep) -> list[str]:
        """The lines of a divergence: where, what differs, the two commands and branches."""
        unit = self.setting.unit
        x, y, theta = step.pose
        return [
            f"{title} at step {step.k} (t={step.t:.3f} s), pose ({x:.3f} {unit}, "
            f"{y:.3f} {unit}, {math.degrees(theta):.1f} deg): {step.differs}",
            f"  logged:    {_show(step.logged, unit)}, branch {step.logged_branch or '-'}",
            f"  reference: {_show(step.reference, unit)}, branch {step.reference_branch or '-'}",
        ]

    def to_json_dict(self) -> dict[str, Any]:
        """The verdict as a JSON-ready mapping (a first divergence ``None`` when none):
        ``disagreeing`` counts the steps that differ in anything, ``motion_disagreeing`` those
        off in heading or speed, ``heading_disagreeing`` and ``speed_disagreeing`` each
        tolerance's breaches, ``branch_disagreeing`` the branch rule's among the
        ``branch_compared`` steps."""
        first, motion = self.first_divergence, self.first_motion_divergence
        return {
            "bag": self.path,
            "planner": self.planner,
            "unit": self.setting.unit,
            "steps": len(self.steps),
            "compared": self.compared,
            "disagreeing": self.disagreeing,
            "heading_tolerance": self.tolerance.heading,
            "speed_tolerance": self.tolerance.speed,
            "first_divergence": None if first is None else _row(first),
            "motion_disagreeing": self.motion_disagreeing,
            "heading_disagreeing": self.breaking(HEADING),
            "speed_disagreeing": self.breaking(SPEED),
            "branch_compared": self.branch_compared,
            "branch_disagreeing": self.branch_disagreeing,
            "branch_rule": BRANCH_RULE,
            "first_motion_divergence": None if motion is None else _row(motion),
        }

    def steps_csv(self) -> str:
        """Every step as CSV: logged and reference command and branch side by side."""
        out = io.StringIO()
        writer = csv.DictWriter(out, fieldnames=list(_row(self.steps[0])), lineterminator="\n")
        writer.writeheader()
        for step in self.steps:
            writer.writerow({k: "" if v is None else v for k, v in _row(step).items()})
        return out.getvalue()


def _row(step: ReplayStep) -> dict[str, Any]:
    logged = step.logged or (None, None)
    return {
        "step": step.k,
        "t": step.t,
        "x": step.pose.x,
        "y": step.pose.y,
        "theta": step.pose.theta,
        "logged_speed": logged[0],
        "logged_turn_rate": logged[1],
        "logged_branch": step.logged_branch,
        "reference_speed": step.reference[0],
        "reference_turn_rate": step.reference[1],
        "reference_branch": step.reference_branch,
        "agrees": step.agrees,
        "differs": step.differs,
        "motion_agrees": step.motion_agrees,
        "branch_agrees": step.branch_agrees,
    }


def _steps(n: int) -> str:
    """``n`` steps, in words.

    >>> _steps(1), _steps(0)
    ('1 step', '0 steps')
    """
    return f"{n} step{'' if n == 1 else 's'}"


def _show(command: tuple[float, float] | None, unit: str) -> str:
    if command is None:
        return "none"
    return f"speed {command[0]:.4f} {unit}/s, turn rate {command[1]:.4f} rad/s"


def setting_of(
    log: RobotLog,
    *,
    goal: Point | None = None,
    robot: RobotParams | None = None,
    dt: float | None = None,
    params: dict[str, float] | None = None,
) -> Setting:
    """The setting of ``log`` (module docstring); ``goal`` in metres. ``robot``, ``dt`` and
    ``params`` replace the recorded ones."""
    if log.episode is not None:
        return _recorded_setting(log, goal, robot, dt, params)
    from ifgm_ref.io.barn import ROBOT, SIM

    goal = goal or log.goal
    if goal is None:
        raise BagError(f"{log.path}: no goal: the log has no /goal_pose; give --goal X,Y")
    sensor = _sensor_of(log.steps[0].scan, log.path)
    gaps = [b.t - a.t for a, b in pairwise(log.steps)]
    period = round(statistics.median(gaps), 6) if gaps else SIM.dt  # to the microsecond
    episode = EpisodeParams(
        robot or ROBOT, sensor, dt or period, dict(params or {}), SIM.goal_tolerance
    )
    return Setting(episode, log.steps[0].pose, goal, "m", 1.0)


def _recorded_setting(
    log: RobotLog,
    goal: Point | None,
    robot: RobotParams | None,
    dt: float | None,
    params: dict[str, float] | None,
) -> Setting:
    episode = log.episode or {}
    try:
        reset = parse_reset(episode.get("reset", {}))
        unit = str(episode["length_unit"])
        scale = float(episode["metres_per_unit"])
    except (ProtocolError, KeyError, TypeError, ValueError) as err:
        raise BagError(f"{log.path}: its episode cannot be read ({err})") from None
    recorded = reset.params
    rays = len(log.steps[0].scan.ranges)
    if rays != recorded.sensor.rays:
        raise BagError(
            f"{log.path}: its scans have {rays} ranges, but its episode's sensor "
            f"{recorded.sensor.rays} rays"
        )
    chosen = EpisodeParams(
        robot or recorded.robot,
        recorded.sensor,
        dt or recorded.dt,
        dict(recorded.params if params is None else params),
        recorded.goal_tolerance,
    )
    target = reset.goal if goal is None else Point(goal.x / scale, goal.y / scale)
    return Setting(chosen, reset.start, target, unit, scale)


def _sensor_of(scan: BagScan, path: str) -> SensorParams:
    if abs(scan.angle_min + scan.angle_max) > CENTRE_TOLERANCE:
        raise BagError(
            f"{path}: the scans run from {scan.angle_min:.6f} to {scan.angle_max:.6f} rad, "
            "but the reference's sensor is centred on the heading (angle_min = -angle_max)"
        )
    return SensorParams(
        fov=scan.angle_max - scan.angle_min,
        rays=len(scan.ranges),
        range_min=scan.range_min,
        range_max=scan.range_max,
    )


def replay_log(
    log: RobotLog,
    planner: Planner,
    setting: Setting,
    *,
    tolerance: Tolerance | None = None,
    progress: bool | None = False,
) -> ReplayReport:
    """Reset ``planner`` in ``setting``, step it through ``log`` and compare (module
    docstring). ``progress`` shows a bar on stderr (``None``: on a terminal only)."""
    tolerance = tolerance or Tolerance()
    planner.reset(setting.start, setting.goal, setting.params)
    steps: list[ReplayStep] = []
    scans: list[LaserScan] = []
    with progress_bar(total=len(log.steps), unit="step", desc="replay", progress=progress) as bar:
        for step in log.steps:
            replayed, scan = _replay_step(step, len(steps), planner, setting, tolerance)
            steps.append(replayed)
            scans.append(scan)
            bar.update()
    return ReplayReport(log.path, planner.name, setting, tolerance, tuple(steps), tuple(scans))


def _replay_step(
    step: LogStep, k: int, planner: Planner, setting: Setting, tolerance: Tolerance
) -> tuple[ReplayStep, LaserScan]:
    """Step ``k`` of the log handed to ``planner``, and compared; and its scan, as handed."""
    params, scale = setting.params, setting.metres_per_unit
    robot = params.robot
    pose = Pose(step.pose.x / scale, step.pose.y / scale, step.pose.theta)
    scan = _scan_in(step.scan, params.sensor, scale)
    command = planner.step(Observation(step.t, pose, setting.goal, scan))
    reference = command.twist(pose, params)
    logged = None
    if step.command is not None:
        linear, angular = step.command
        limit = robot.max_turn_rate
        logged = (min(linear / scale, robot.speed), min(max(angular, -limit), limit))
    branches = (step.branch, command.branch)
    found = {} if logged is None else _differences(logged, reference, branches, params, tolerance)
    replayed = ReplayStep(
        k=k,
        t=step.t,
        pose=pose,
        logged=logged,
        logged_branch=step.branch or None,
        reference=reference,
        reference_branch=command.branch,
        agrees=None if logged is None else not found,
        differs="; ".join(found.values()),
        broke=tuple(found),
    )
    return replayed, scan


def _scan_in(scan: BagScan, sensor: SensorParams, scale: float) -> LaserScan:
    """The logged scan in the run's unit, with the angles of the episode's sensor (the
    log's float32 angles would move rays off the beam borders the sensor puts them on)."""
    return LaserScan(
        angle_min=-0.5 * sensor.fov,
        angle_max=0.5 * sensor.fov,
        angle_increment=sensor.angle_increment,
        range_min=sensor.range_min,
        range_max=sensor.range_max,
        ranges=np.asarray(scan.ranges) / scale,
    )


def difference(
    logged: tuple[float, float],
    reference: tuple[float, float],
    branches: tuple[str | None, str | None],
    params: EpisodeParams,
    tolerance: Tolerance,
) -> str:
    """What differs between a logged step and the reference's, ``""`` when they agree:
    speeds and turn rates within the robot's limits, and the two steps' branches (compared
    when both name one: :func:`~ifgm_ref.io.bags.read.same_branch`). The logged speed is
    compared as the robot executes it, clipped to its top speed; the message gives the speed
    asked beside it when it was clipped.

    >>> params = EpisodeParams()  # dt 0.1 s: 0.1 rad of heading is 1 rad/s of turn rate
    >>> difference((1.0, 0.5), (1.0, 1.2), ("a", "a"), params, Tolerance())
    ''
    >>> difference((1.0, 0.5), (0.0, 1.6), ("a", "b"), params, Tolerance())
    'heading after a step off by 0.11 rad (more than 0.1); speed off by 1 (more than 0.132; \
as executed); branch a against b'
    >>> difference((6.0, 0.5), (0.3, 0.5), ("a", "a"), params, Tolerance())  # top speed 1.32
    'speed off by 1.02 (more than 0.132; as executed, asked 6)'
    >>> difference((6.0, 0.5), (1.3, 0.5), ("a", "a"), params, Tolerance())
    ''
    """
    return "; ".join(_differences(logged, reference, branches, params, tolerance).values())


def _differences(
    logged: tuple[float, float],
    reference: tuple[float, float],
    branches: tuple[str | None, str | None],
    params: EpisodeParams,
    tolerance: Tolerance,
) -> dict[str, str]:
    """:func:`difference`'s findings by the rule each breaks (:data:`HEADING`,
    :data:`SPEED`, :data:`BRANCH`, in that order); empty when the steps agree."""
    found: dict[str, str] = {}
    heading = abs(logged[1] - reference[1]) * params.dt
    if heading > tolerance.heading:
        found[HEADING] = (
            f"heading after a step off by {heading:.3g} rad (more than {tolerance.heading:g})"
        )
    asked, limit = logged[0], tolerance.speed * params.robot.speed
    executed = min(asked, params.robot.speed)  # what the robot was driven at
    speed = abs(executed - reference[0])
    if speed > limit:
        clipped = f", asked {asked:.3g}" if executed < asked else ""
        found[SPEED] = f"speed off by {speed:.3g} (more than {limit:.3g}; as executed{clipped})"
    logged_branch, reference_branch = branches
    if logged_branch and reference_branch and not same_branch(logged_branch, reference_branch):
        found[BRANCH] = f"branch {logged_branch} against {reference_branch}"
    return found
