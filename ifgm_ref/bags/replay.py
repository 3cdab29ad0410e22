"""Replay a robot's log into the reference, open loop, and compare the commands step by step.

``ifgm-ref replay BAG`` answers an implementer's question: given what *my* robot saw, would
the reference have decided what my robot did? :func:`replay_log` hands the reference each
logged scan with the pose at its time (:mod:`ifgm_ref.bags.read`), in order; the reference's
commands move nothing (open loop), so every step sees exactly what the robot saw.

**The setting.** A log written by ``ifgm-ref simulate --record`` carries its episode (the
``reset`` of the JSON-lines protocol: robot, sensor, ``dt``, start, goal, parameters) and its
unit: the replay runs in that unit with those parameters, so the reference meets the
recorded run on the recorded terms. Any other log is replayed in metres with BARN's robot
(:data:`ifgm_ref.barn.ROBOT`: the Jackal-sized disc) unless options say otherwise,
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
robot's, and, where both name one, the branches are the same: the oracle's tolerances for
"the same answer", which a float32 port meets and a broken rule does not. A log is such a
port: its ranges are float32, and the reference, handed them, now and then follows the
neighbouring ray or edge point that the rounding makes the nearer (measured: 0.00054 rad
the most, IFGM's own run in ``u_trap``). The first step that differs is the *first
divergence*; the replay goes on to the end and counts the others, which may follow from the
first (the reference's own state has then taken another way).
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

from ifgm_ref.bags.read import BagScan, LogStep, RobotLog
from ifgm_ref.errors import BagError, ProtocolError
from ifgm_ref.flowchart import same_branch
from ifgm_ref.laserscan import LaserScan
from ifgm_ref.oracle.invariance import HEADING_TOL, SPEED_TOL
from ifgm_ref.params import RobotParams, SensorParams
from ifgm_ref.pose import Point, Pose
from ifgm_ref.progress import progress_bar
from ifgm_ref.protocol import EpisodeParams, Observation, Planner
from ifgm_ref.transport.wire import parse_reset

__all__ = [
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
    agree (``None`` when nothing was logged for the step) and, if not, what differs."""

    k: int
    t: float
    pose: Pose
    logged: tuple[float, float] | None
    logged_branch: str | None
    reference: tuple[float, float]
    reference_branch: str | None
    agrees: bool | None
    differs: str = ""


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
        """The steps whose logged command differs from the reference's."""
        return sum(s.agrees is False for s in self.steps)

    @property
    def first_divergence(self) -> ReplayStep | None:
        """The first step that differs, or ``None`` when every compared step agrees."""
        return next((s for s in self.steps if s.agrees is False), None)

    def text(self) -> str:
        """A few lines: the verdict and the first divergence, lengths in the log's unit."""
        unit = self.setting.unit
        lines = [
            f"{self.planner} replayed on {self.path}: {len(self.steps)} steps, "
            f"{self.compared} with a logged command, {self.disagreeing} differ "
            f"(tolerance {self.tolerance.heading:g} rad of heading after a step, "
            f"{self.tolerance.speed:g} of the robot's speed)"
        ]
        first = self.first_divergence
        if first is None:
            lines.append("every logged command agrees with the reference")
            return "\n".join(lines)
        x, y, theta = first.pose
        lines += [
            f"first divergence at step {first.k} (t={first.t:.3f} s), pose ({x:.3f} {unit}, "
            f"{y:.3f} {unit}, {math.degrees(theta):.1f} deg): {first.differs}",
            f"  logged:    {_show(first.logged, unit)}, branch {first.logged_branch or '-'}",
            f"  reference: {_show(first.reference, unit)}, branch {first.reference_branch or '-'}",
        ]
        return "\n".join(lines)

    def to_json_dict(self) -> dict[str, Any]:
        """The verdict as a JSON-ready mapping (the first divergence ``None`` when none)."""
        first = self.first_divergence
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
    }


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
    from ifgm_ref.barn import ROBOT, SIM

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
    differs = "" if logged is None else difference(logged, reference, branches, params, tolerance)
    replayed = ReplayStep(
        k=k,
        t=step.t,
        pose=pose,
        logged=logged,
        logged_branch=step.branch or None,
        reference=reference,
        reference_branch=command.branch,
        agrees=None if logged is None else not differs,
        differs=differs,
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
    when both name one: :func:`~ifgm_ref.flowchart.same_branch`). The logged speed is
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
    found: list[str] = []
    heading = abs(logged[1] - reference[1]) * params.dt
    if heading > tolerance.heading:
        found.append(
            f"heading after a step off by {heading:.3g} rad (more than {tolerance.heading:g})"
        )
    asked, limit = logged[0], tolerance.speed * params.robot.speed
    executed = min(asked, params.robot.speed)  # what the robot was driven at
    speed = abs(executed - reference[0])
    if speed > limit:
        clipped = f", asked {asked:.3g}" if executed < asked else ""
        found.append(f"speed off by {speed:.3g} (more than {limit:.3g}; as executed{clipped})")
    logged_branch, reference_branch = branches
    if logged_branch and reference_branch and not same_branch(logged_branch, reference_branch):
        found.append(f"branch {logged_branch} against {reference_branch}")
    return "; ".join(found)
