"""Read a robot's log, a ROS 1 or ROS 2 bag, into the steps a planner would have seen.

A ROS robot logs its scans (``sensor_msgs/LaserScan``), its odometry (``nav_msgs/Odometry``)
and its commands (``geometry_msgs/Twist``, or ``TwistStamped``). :func:`read_log` reads them
with ``rosbags`` (pure Python, no ROS install; ROS 1 ``.bag``, ROS 2 ``.mcap`` files and
rosbag2 folders) and pairs them up, one step per scan:

* the scan's time is its header stamp (the bag's receive time when the stamp is zero), and
  the scans must come in strictly increasing time;
* the pose at that time is the odometry interpolated between the two messages around it
  (position linearly, heading the short way round; a message at the very time is taken as
  it is); a scan outside the odometry's time span has no pose and is an error;
* the command of the step is the first one received at or after the scan and before the
  next scan (``None`` when there is none), and so is the branch of a run recorded by
  ``ifgm-ref simulate --record`` (``/ifgm_ref/branch``).

Lengths stay in metres, as REP-103 has them; :mod:`ifgm_ref.apps.replay` converts them to
the unit of the run. Every fault of the log is one :class:`~ifgm_ref.core.errors.BagError` line
that names the topic, the message and its time.
"""

from __future__ import annotations

import bisect
import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.errors import BagError
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.io.bags.messages import EPISODE_FORMAT, TopicName
from ifgm_ref.paper.flowchart import DEAD_END_PHASES, Branch

__all__ = ["FORMER_LABELS", "BagScan", "LogStep", "RobotLog", "Topics", "read_log", "same_branch"]

#: The label each dead-end phase label replaces: logs, traces and ports from before the
#: phases had labels of their own (issue 29; errata row 35) call all three ``dead_end_turn``.
FORMER_LABELS = {phase: Branch.DEAD_END_TURN for phase in DEAD_END_PHASES[1:]}


def same_branch(reported: str, reference: str) -> bool:
    """Whether a log's (or a port's) branch label ``reported`` names the reference's branch
    ``reference``: the same label, or the one it replaces (:data:`FORMER_LABELS`).

    >>> same_branch("dead_end_turn", "dead_end_escape"), same_branch("follow_edge", "too_close")
    (True, False)
    """
    if reported == reference:
        return True
    return reference in FORMER_LABELS and reported == FORMER_LABELS[Branch(reference)]


#: The message types each topic may carry (rosbags' names: ROS 1 types read the same).
SCAN_TYPES = ("sensor_msgs/msg/LaserScan",)
ODOMETRY_TYPES = ("nav_msgs/msg/Odometry",)
COMMAND_TYPES = ("geometry_msgs/msg/Twist", "geometry_msgs/msg/TwistStamped")
GOAL_TYPES = ("geometry_msgs/msg/PoseStamped",)
TEXT_TYPES = ("std_msgs/msg/String",)


@dataclass(frozen=True)
class Topics:
    """The topics of a log; the defaults are ROS's (REP-105, Nav2) and those ``ifgm-ref
    simulate --record`` writes. ``goal``, ``branch`` and ``episode`` are optional."""

    scan: str = TopicName.SCAN
    odom: str = TopicName.ODOM
    cmd_vel: str = TopicName.CMD_VEL
    goal: str = TopicName.GOAL
    branch: str = TopicName.BRANCH
    episode: str = TopicName.EPISODE


@dataclass(frozen=True)
class BagScan:
    """One scan as logged: its angles and limits (rad, m) and ranges (m, REP 117)."""

    angle_min: float
    angle_max: float
    angle_increment: float
    range_min: float
    range_max: float
    ranges: NDArray[np.float64]


@dataclass(frozen=True)
class LogStep:
    """One step of a log: the scan's time (s, from the first scan), the pose then (m, rad),
    the scan, and the command (``(linear, angular)``, m/s and rad/s) and branch logged for
    it, ``None`` when the log has none."""

    t: float
    pose: Pose
    scan: BagScan
    command: tuple[float, float] | None
    branch: str | None


@dataclass(frozen=True)
class RobotLog:
    """A robot's log, step by step; the goal of ``/goal_pose`` (m) and the episode that
    ``ifgm-ref simulate --record`` writes (its JSON), when the log has them."""

    path: str
    steps: tuple[LogStep, ...]
    goal: Point | None
    episode: dict[str, Any] | None


def read_log(path: str | Path, topics: Topics | None = None) -> RobotLog:
    """Read the log at ``path`` (a ``.bag``, a ``.mcap`` or a rosbag2 folder) step by step.

    Raises
    ------
    BagError
        If the file cannot be read, a needed topic is missing or carries another type, time
        runs backwards, a scan's rays or angles change or a range is NaN, or a scan has no
        odometry around it.
    """
    topics = topics or Topics()
    messages = _read_topics(Path(path), topics)
    scans = _scans(messages[topics.scan], topics.scan)
    odometry = _Odometry(messages[topics.odom], topics.odom)
    start = scans[0][0]
    times = [t for t, _ in scans]
    commands = _bucketed(times, [(t, _twist(m)) for t, m in messages[topics.cmd_vel]])
    branches = _bucketed(times, [(t, m.data) for t, m in messages.get(topics.branch, [])])
    steps = tuple(
        LogStep(round(t - start, 9), odometry.at(t, k), scan, commands[k], branches[k])
        for k, (t, scan) in enumerate(scans)
    )
    goals = messages.get(topics.goal, [])
    goal = Point(goals[0][1].pose.position.x, goals[0][1].pose.position.y) if goals else None
    episodes = messages.get(topics.episode, [])
    episode = _episode(episodes[0][1].data, topics.episode) if episodes else None
    return RobotLog(str(path), steps, goal, episode)


def _read_topics(path: Path, topics: Topics) -> dict[str, list[tuple[float, Any]]]:
    """Every message of the topics, deserialised, with its time (s): the header stamp, or
    the bag's receive time for a message without one (or with a zero stamp)."""
    from rosbags.highlevel import AnyReader, AnyReaderError
    from rosbags.typesys import Stores, get_typestore

    if not path.exists():
        raise BagError(f"{path}: no such file or folder")
    wanted = {
        topics.scan: SCAN_TYPES,
        topics.odom: ODOMETRY_TYPES,
        topics.cmd_vel: COMMAND_TYPES,
        topics.goal: GOAL_TYPES,
        topics.branch: TEXT_TYPES,
        topics.episode: TEXT_TYPES,
    }
    found: dict[str, list[tuple[float, Any]]] = {}
    try:
        with AnyReader([path], default_typestore=get_typestore(Stores.ROS2_HUMBLE)) as reader:
            present = {c.topic: c.msgtype for c in reader.connections}
            for name in (topics.scan, topics.odom, topics.cmd_vel):
                if name not in present:
                    listed = ", ".join(f"{t} ({m})" for t, m in sorted(present.items()))
                    raise BagError(f"{path}: no topic {name}; it has {listed or 'none'}")
            for name, types in wanted.items():
                if name in present and present[name] not in types:
                    raise BagError(
                        f"{path}: topic {name} carries {present[name]}, but should carry "
                        f"{' or '.join(types)}"
                    )
            connections = [c for c in reader.connections if c.topic in wanted]
            for connection, stamp, raw in reader.messages(connections=connections):
                message = reader.deserialize(raw, connection.msgtype)
                found.setdefault(connection.topic, []).append((_time(message, stamp), message))
    except (AnyReaderError, OSError, ValueError, KeyError) as err:
        if isinstance(err, BagError):
            raise
        raise BagError(f"{path}: cannot read it as a ROS bag ({err})") from None
    for name in (topics.scan, topics.odom, topics.cmd_vel):
        found.setdefault(name, [])  # present, but without a message
    return found


def _time(message: Any, received_ns: int) -> float:
    header = getattr(message, "header", None)
    if header is not None and (header.stamp.sec or header.stamp.nanosec):
        return (int(header.stamp.sec) * 1_000_000_000 + int(header.stamp.nanosec)) / 1e9
    return received_ns / 1e9


def _scans(messages: list[tuple[float, Any]], topic: str) -> list[tuple[float, BagScan]]:
    """The scans in time order, checked: the same rays and angles throughout, no NaN."""
    if not messages:
        raise BagError(f"topic {topic} has no message")
    scans: list[tuple[float, BagScan]] = []
    for k, (t, message) in enumerate(messages):
        where = f"{topic} message {k} (t={t:.9f} s)"
        if scans and t <= scans[-1][0]:
            raise BagError(f"{where}: time runs backwards (the one before is at {scans[-1][0]} s)")
        scan = _scan(message, where)
        if scans:
            first = scans[0][1]
            if len(scan.ranges) != len(first.ranges):
                raise BagError(
                    f"{where}: {len(scan.ranges)} ranges, but the first scan has "
                    f"{len(first.ranges)}"
                )
            if (scan.angle_min, scan.angle_increment) != (first.angle_min, first.angle_increment):
                raise BagError(f"{where}: its angles differ from the first scan's")
        scans.append((t, scan))
    return scans


def _scan(message: Any, where: str) -> BagScan:
    ranges = np.asarray(message.ranges, dtype=np.float64)
    bad = np.flatnonzero(np.isnan(ranges))
    if len(bad):
        raise BagError(
            f"{where}: range {int(bad[0])} is NaN ({len(bad)} NaN in all); the reference "
            "reads +inf for no return and -inf for too near (REP 117), never NaN"
        )
    if len(ranges) < 2:
        raise BagError(f"{where}: {len(ranges)} ranges, but a scan needs 2 or more")
    return BagScan(
        float(message.angle_min),
        float(message.angle_max),
        float(message.angle_increment),
        float(message.range_min),
        float(message.range_max),
        ranges,
    )


class _Odometry:
    """The odometry's poses in time order, interpolated at a scan's time."""

    def __init__(self, messages: list[tuple[float, Any]], topic: str) -> None:
        if not messages:
            raise BagError(f"topic {topic} has no message")
        self.topic = topic
        self.times: list[float] = []
        self.poses: list[Pose] = []
        for k, (t, message) in enumerate(messages):
            if self.times and t <= self.times[-1]:
                raise BagError(
                    f"{topic} message {k} (t={t:.9f} s): time runs backwards (the one before "
                    f"is at {self.times[-1]} s)"
                )
            self.times.append(t)
            self.poses.append(_pose(message.pose.pose))

    def at(self, t: float, k: int) -> Pose:
        """The pose at time ``t`` (of scan ``k``, for the error)."""
        i = bisect.bisect_left(self.times, t)
        if i < len(self.times) and self.times[i] == t:
            return self.poses[i]
        if i == 0 or i == len(self.times):
            raise BagError(
                f"scan {k} (t={t:.9f} s) has no odometry around it: {self.topic} runs from "
                f"{self.times[0]:.9f} to {self.times[-1]:.9f} s"
            )
        (t0, a), (t1, b) = (self.times[i - 1], self.poses[i - 1]), (self.times[i], self.poses[i])
        w = (t - t0) / (t1 - t0)
        return Pose(
            a.x + w * (b.x - a.x),
            a.y + w * (b.y - a.y),
            wrap_angle(a.theta + w * wrap_angle(b.theta - a.theta)),
        )


def _pose(pose: Any) -> Pose:
    q = pose.orientation
    yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
    return Pose(float(pose.position.x), float(pose.position.y), wrap_angle(yaw))


def _twist(message: Any) -> tuple[float, float]:
    twist = getattr(message, "twist", message)  # TwistStamped holds a Twist
    return float(twist.linear.x), float(twist.angular.z)


def _bucketed(times: list[float], stamped: list[tuple[float, Any]]) -> list[Any]:
    """For each scan time, the first value stamped at or after it and before the next."""
    bucket: list[Any] = [None] * len(times)
    for t, value in stamped:
        k = bisect.bisect_right(times, t) - 1
        if k >= 0 and bucket[k] is None:
            bucket[k] = value
    return bucket


def _episode(text: str, topic: str) -> dict[str, Any]:
    try:
        episode = json.loads(text)
    except json.JSONDecodeError as err:
        raise BagError(f"{topic}: not JSON ({err.msg} at column {err.colno})") from None
    if not isinstance(episode, dict) or episode.get("format") != EPISODE_FORMAT:
        raise BagError(f"{topic}: not an ifgm-ref episode (its format is not {EPISODE_FORMAT!r})")
    return episode
