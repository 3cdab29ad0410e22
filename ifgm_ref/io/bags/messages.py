"""A recorded run as standard ROS 2 messages: which topic carries what, in which frame and unit.

Units are SI (REP-103): every length, in the project's feet or metres, is converted to metres
by ``metres_per_unit`` (:data:`METRES_PER_UNIT`); angles stay in radians. Frames follow
REP-105: ``map`` is the world (obstacles, goal, the true pose), ``odom`` holds the pose the
planner believed (it differs from the true one only under odometry noise,
:mod:`ifgm_ref.sim.noise`), ``base_link`` is the robot (its origin the disc's centre, x ahead,
y left), and ``map -> odom`` is the identity. A step at time ``t`` s is stamped
``round(t * 1e9)`` ns from 0, in the headers and in the bag alike.

=======================  ======================================  ==================================
topic                    type                                    when
=======================  ======================================  ==================================
``/tf_static``           ``tf2_msgs/msg/TFMessage``              once, ``map -> odom``
``/ifgm_ref/episode``    ``std_msgs/msg/String``                 once, JSON (below)
``/goal_pose``           ``geometry_msgs/msg/PoseStamped``       once, in ``map``
``/obstacles``           ``visualization_msgs/msg/MarkerArray``  once, in ``map``
``/scan``                ``sensor_msgs/msg/LaserScan``           each observation, ``base_link``
``/tf``                  ``tf2_msgs/msg/TFMessage``              each sample, ``odom -> base_link``
``/odom``                ``nav_msgs/msg/Odometry``               each sample, believed, ``odom``
``/ground_truth``        ``nav_msgs/msg/Odometry``               each sample, true, ``map``
``/cmd_vel``             ``geometry_msgs/msg/Twist``             each executed command
``/ifgm_ref/branch``     ``std_msgs/msg/String``                 each executed command
``/ifgm_ref/behaviour``  ``std_msgs/msg/String``                 each executed command
=======================  ======================================  ==================================

A "sample" is a trace sample (:class:`ifgm_ref.sim.simulator.TraceStep`): one per step and one
more where the episode ended. The episode topic carries :data:`EPISODE_FORMAT` and the
``reset`` message of the JSON-lines protocol (:func:`ifgm_ref.io.transport.wire.reset_message`,
lengths in the project's unit, not converted), from which a reader restores the robot, the
sensor, the time step and the goal exactly.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from enum import StrEnum

import numpy as np
from rosbags.typesys.stores.ros2_humble import (
    builtin_interfaces__msg__Duration as Duration,
)
from rosbags.typesys.stores.ros2_humble import (
    builtin_interfaces__msg__Time as Time,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__Point as PointMsg,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__Pose as PoseMsg,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__PoseStamped as PoseStamped,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__PoseWithCovariance as PoseWithCovariance,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__Quaternion as Quaternion,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__Transform as Transform,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__TransformStamped as TransformStamped,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__Twist as Twist,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__TwistWithCovariance as TwistWithCovariance,
)
from rosbags.typesys.stores.ros2_humble import (
    geometry_msgs__msg__Vector3 as Vector3,
)
from rosbags.typesys.stores.ros2_humble import (
    nav_msgs__msg__Odometry as Odometry,
)
from rosbags.typesys.stores.ros2_humble import (
    sensor_msgs__msg__CompressedImage as CompressedImage,
)
from rosbags.typesys.stores.ros2_humble import (
    sensor_msgs__msg__LaserScan as LaserScanMsg,
)
from rosbags.typesys.stores.ros2_humble import (
    std_msgs__msg__ColorRGBA as ColorRGBA,
)
from rosbags.typesys.stores.ros2_humble import (
    std_msgs__msg__Header as Header,
)
from rosbags.typesys.stores.ros2_humble import (
    std_msgs__msg__String as String,
)
from rosbags.typesys.stores.ros2_humble import (
    tf2_msgs__msg__TFMessage as TFMessage,
)
from rosbags.typesys.stores.ros2_humble import (
    visualization_msgs__msg__Marker as Marker,
)
from rosbags.typesys.stores.ros2_humble import (
    visualization_msgs__msg__MarkerArray as MarkerArray,
)
from rosbags.typesys.stores.ros2_humble import (
    visualization_msgs__msg__MeshFile as MeshFile,
)

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.recording import Recording
from ifgm_ref.io.transport.wire import reset_message
from ifgm_ref.sim.simulator import Run, TraceStep
from ifgm_ref.sim.world import Circle, Obstacle, World

#: Metres per length unit of a world: feet for the built-in and JSON worlds, metres for the
#: Gazebo and BARN worlds (``ifgm-ref simulate`` knows which).
METRES_PER_UNIT = {"ft": 0.3048, "m": 1.0}
#: The ``format`` field of the episode topic's JSON; a reader refuses any other.
EPISODE_FORMAT = "ifgm-ref episode 1"
#: Height of the obstacle markers, m: the world is 2D; this only gives them a body to see.
OBSTACLE_HEIGHT = 0.5
#: Width of a polygon obstacle's outline (a ``LINE_STRIP`` marker), m.
OUTLINE_WIDTH = 0.05
#: Colour of the obstacle markers (opaque grey), RGBA in [0, 1].
OBSTACLE_COLOUR = (0.5, 0.5, 0.5, 1.0)
#: The marker namespace of the obstacles (ids 0 to n - 1, in the world's order).
OBSTACLE_NAMESPACE = "obstacles"


class Frame(StrEnum):
    """The REP-105 frames of a recorded run."""

    MAP = "map"
    ODOM = "odom"
    BASE_LINK = "base_link"


class TopicName(StrEnum):
    """The topics of a recorded run (the module docstring says what each carries)."""

    TF_STATIC = "/tf_static"
    EPISODE = "/ifgm_ref/episode"
    GOAL = "/goal_pose"
    OBSTACLES = "/obstacles"
    SCAN = "/scan"
    TF = "/tf"
    ODOM = "/odom"
    GROUND_TRUTH = "/ground_truth"
    CMD_VEL = "/cmd_vel"
    BRANCH = "/ifgm_ref/branch"
    BEHAVIOUR = "/ifgm_ref/behaviour"


@dataclass(frozen=True)
class Topic:
    """A topic: its name, its ROS 2 message type, and whether it is latched (published once,
    offered transient-local so that a late subscriber still gets it)."""

    name: TopicName
    msgtype: str
    latched: bool = False


#: Every topic of a recorded run, in the order the bag lists them.
TOPICS = (
    Topic(TopicName.TF_STATIC, "tf2_msgs/msg/TFMessage", latched=True),
    Topic(TopicName.EPISODE, "std_msgs/msg/String", latched=True),
    Topic(TopicName.GOAL, "geometry_msgs/msg/PoseStamped", latched=True),
    Topic(TopicName.OBSTACLES, "visualization_msgs/msg/MarkerArray", latched=True),
    Topic(TopicName.SCAN, "sensor_msgs/msg/LaserScan"),
    Topic(TopicName.TF, "tf2_msgs/msg/TFMessage"),
    Topic(TopicName.ODOM, "nav_msgs/msg/Odometry"),
    Topic(TopicName.GROUND_TRUTH, "nav_msgs/msg/Odometry"),
    Topic(TopicName.CMD_VEL, "geometry_msgs/msg/Twist"),
    Topic(TopicName.BRANCH, "std_msgs/msg/String"),
    Topic(TopicName.BEHAVIOUR, "std_msgs/msg/String"),
)

#: A ROS 2 message of one of :data:`TOPICS`' types.
Message = TFMessage | String | PoseStamped | MarkerArray | LaserScanMsg | Odometry | Twist


@dataclass(frozen=True)
class Stamped:
    """One message of a recorded run: its bag time stamp (ns), its topic and the message."""

    stamp: int
    topic: TopicName
    message: Message


def metres_per_unit(unit: str) -> float:
    """The metres in one ``unit`` (``"ft"`` or ``"m"``); a ParameterError for any other.

    >>> metres_per_unit("ft"), metres_per_unit("m")
    (0.3048, 1.0)
    >>> metres_per_unit("yd")
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: length unit 'yd': must be one of ft, m
    """
    if unit not in METRES_PER_UNIT:
        raise ParameterError(f"length unit {unit!r}: must be one of {', '.join(METRES_PER_UNIT)}")
    return METRES_PER_UNIT[unit]


def nanoseconds(t: float) -> int:
    """The time stamp of time ``t`` s from the episode's start, ns.

    >>> nanoseconds(0.0), nanoseconds(0.3), nanoseconds(12.1)
    (0, 300000000, 12100000000)
    """
    return round(t * 1e9)


def header(stamp: int, frame: Frame) -> Header:
    """The ``std_msgs/Header`` of a message stamped ``stamp`` ns in ``frame``."""
    sec, nanosec = divmod(stamp, 1_000_000_000)
    return Header(stamp=Time(sec=sec, nanosec=nanosec), frame_id=str(frame))


def quaternion(theta: float) -> Quaternion:
    """The rotation by ``theta`` rad about z (a heading in the plane).

    >>> q = quaternion(math.pi / 2)
    >>> round(q.z, 12), round(q.w, 12), q.x, q.y
    (0.707106781187, 0.707106781187, 0.0, 0.0)
    """
    return Quaternion(x=0.0, y=0.0, z=math.sin(0.5 * theta), w=math.cos(0.5 * theta))


def pose_message(pose: Pose, scale: float) -> PoseMsg:
    """``pose`` (lengths in the project's unit) as a ``geometry_msgs/Pose`` in metres."""
    position = PointMsg(x=pose.x * scale, y=pose.y * scale, z=0.0)
    return PoseMsg(position=position, orientation=quaternion(pose.theta))


def twist(linear: float, angular: float, scale: float, lateral: float = 0.0) -> Twist:
    """The velocity ``linear`` ahead and ``lateral`` to the left (the project's unit per s)
    and ``angular`` rad/s to the left, as a ``geometry_msgs/Twist`` in m/s and rad/s."""
    return Twist(
        linear=Vector3(x=linear * scale, y=lateral * scale, z=0.0),
        angular=Vector3(x=0.0, y=0.0, z=angular),
    )


def laser_scan(scan: LaserScan, stamp: int, dt: float, scale: float) -> LaserScanMsg:
    """``scan`` as a ``sensor_msgs/LaserScan`` in ``base_link``, ranges in metres (float32).

    Non-finite ranges keep their meaning (REP 117): ``+inf`` no return, ``-inf`` nearer than
    ``range_min``, ``nan`` a sensor error. The sweep is instantaneous (``time_increment``
    0) and repeats every step (``scan_time`` = ``dt``); there are no intensities.
    """
    return LaserScanMsg(
        header=header(stamp, Frame.BASE_LINK),
        angle_min=scan.angle_min,
        angle_max=scan.angle_max,
        angle_increment=scan.angle_increment,
        time_increment=0.0,
        scan_time=dt,
        range_min=scan.range_min * scale,
        range_max=scan.range_max * scale,
        ranges=(scan.ranges * scale).astype(np.float32),
        intensities=np.zeros(0, dtype=np.float32),
    )


def odometry(stamp: int, frame: Frame, pose: Pose, velocity: Twist, scale: float) -> Odometry:
    """The robot (``base_link``) at ``pose`` in ``frame``, moving at ``velocity`` (in
    ``base_link``), as a ``nav_msgs/Odometry``; covariances 0 (not estimated)."""
    return Odometry(
        header=header(stamp, frame),
        child_frame_id=str(Frame.BASE_LINK),
        pose=PoseWithCovariance(pose=pose_message(pose, scale), covariance=np.zeros(36)),
        twist=TwistWithCovariance(twist=velocity, covariance=np.zeros(36)),
    )


def transform(stamp: int, parent: Frame, child: Frame, pose: Pose, scale: float) -> TFMessage:
    """The transform from ``parent`` to ``child`` (``child``'s origin at ``pose`` in
    ``parent``) as a one-transform ``tf2_msgs/TFMessage``."""
    return TFMessage(
        transforms=[
            TransformStamped(
                header=header(stamp, parent),
                child_frame_id=str(child),
                transform=Transform(
                    translation=Vector3(x=pose.x * scale, y=pose.y * scale, z=0.0),
                    rotation=quaternion(pose.theta),
                ),
            )
        ]
    )


def goal_pose(goal: Point, stamp: int, scale: float) -> PoseStamped:
    """The goal as a ``geometry_msgs/PoseStamped`` in ``map`` (no heading: identity)."""
    return PoseStamped(
        header=header(stamp, Frame.MAP), pose=pose_message(Pose(goal.x, goal.y, 0.0), scale)
    )


def obstacle_markers(obstacles: Sequence[Obstacle], stamp: int, scale: float) -> MarkerArray:
    """The obstacles as a ``visualization_msgs/MarkerArray`` in ``map``: a circle as a
    ``CYLINDER`` :data:`OBSTACLE_HEIGHT` m high standing on the floor, a polygon as its closed
    outline on the floor (a ``LINE_STRIP`` :data:`OUTLINE_WIDTH` m wide); namespace
    :data:`OBSTACLE_NAMESPACE`, ids in the world's order, shown until deleted."""
    markers = [_marker(k, ob, stamp, scale) for k, ob in enumerate(obstacles)]
    # rosbags annotates Humble's MarkerArray.markers with ROS 2 Dashing's Marker class; the
    # serializer goes by the type names of the Humble store, whose Marker this is.
    return MarkerArray(markers=markers)  # type: ignore[arg-type]


def _marker(number: int, obstacle: Obstacle, stamp: int, scale: float) -> Marker:
    """Obstacle ``number`` as a marker (see :func:`obstacle_markers`)."""
    if isinstance(obstacle, Circle):
        kind = Marker.CYLINDER
        x, y = obstacle.center
        centre = PointMsg(x=x * scale, y=y * scale, z=0.5 * OBSTACLE_HEIGHT)
        diameter = 2.0 * obstacle.radius * scale
        size = Vector3(x=diameter, y=diameter, z=OBSTACLE_HEIGHT)
        points = []
    else:
        kind = Marker.LINE_STRIP
        centre = PointMsg(x=0.0, y=0.0, z=0.0)
        size = Vector3(x=OUTLINE_WIDTH, y=0.0, z=0.0)
        ring = (*obstacle.vertices, obstacle.vertices[0])
        points = [PointMsg(x=x * scale, y=y * scale, z=0.0) for x, y in ring]
    r, g, b, a = OBSTACLE_COLOUR
    empty = np.zeros(0, dtype=np.uint8)
    return Marker(
        header=header(stamp, Frame.MAP),
        ns=OBSTACLE_NAMESPACE,
        id=number,
        type=kind,
        action=Marker.ADD,
        pose=PoseMsg(position=centre, orientation=quaternion(0.0)),
        scale=size,
        color=ColorRGBA(r=r, g=g, b=b, a=a),
        lifetime=Duration(sec=0, nanosec=0),
        frame_locked=False,
        points=points,
        colors=[],
        texture_resource="",
        texture=CompressedImage(header=header(stamp, Frame.MAP), format="", data=empty),
        uv_coordinates=[],
        text="",
        mesh_resource="",
        mesh_file=MeshFile(filename="", data=empty),
        mesh_use_embedded_materials=False,
    )


def episode_text(recording: Recording, planner: str, world_name: str | None, unit: str) -> str:
    """The episode topic's JSON: :data:`EPISODE_FORMAT`, the planner's and the world's
    names, the length unit and its metres, and the episode's ``reset`` message (lengths in
    ``unit``).

    >>> from ifgm_ref.core.protocol import EpisodeParams
    >>> recording = Recording(Pose(0.0, 0.0, 0.0), Point(3.0, 0.0), EpisodeParams(), ())
    >>> episode = json.loads(episode_text(recording, "straight", "free", "ft"))
    >>> episode["format"], episode["planner"], episode["metres_per_unit"], episode["reset"]["goal"]
    ('ifgm-ref episode 1', 'straight', 0.3048, [3.0, 0.0])
    """
    return json.dumps(
        {
            "format": EPISODE_FORMAT,
            "planner": planner,
            "world": world_name,
            "length_unit": unit,
            "metres_per_unit": metres_per_unit(unit),
            "reset": reset_message(recording.start, recording.goal, recording.params),
        }
    )


def run_messages(run: Run, recording: Recording, world: World, unit: str) -> Iterator[Stamped]:
    """Every message of a run, in time order (the module docstring lists them).

    Parameters
    ----------
    run : Run
        The run: its planner's name and its trace.
    recording : Recording
        What the planner was handed and answered in the run
        (:class:`~ifgm_ref.core.recording.RecordingPlanner`): its reset and its steps.
    world : World
        The world of the run (its name and its obstacles).
    unit : str
        The world's length unit, ``"ft"`` or ``"m"``.

    Raises
    ------
    ValueError
        When the recording's steps do not line up with the run's trace (another run's
        recording); raised by the call, before any message.
    ParameterError
        For an unknown ``unit``.
    """
    scale = metres_per_unit(unit)
    _check_lined_up(recording, run.trace)
    return _messages(run, recording, world, unit, scale)


def _messages(
    run: Run, recording: Recording, world: World, unit: str, scale: float
) -> Iterator[Stamped]:
    """The messages of :func:`run_messages`, lengths times ``scale``."""
    trace, steps = run.trace, recording.steps
    episode = String(data=episode_text(recording, run.result.planner, world.name, unit))
    yield Stamped(
        0, TopicName.TF_STATIC, transform(0, Frame.MAP, Frame.ODOM, Pose(0.0, 0.0, 0.0), scale)
    )
    yield Stamped(0, TopicName.EPISODE, episode)
    yield Stamped(0, TopicName.GOAL, goal_pose(recording.goal, 0, scale))
    yield Stamped(0, TopicName.OBSTACLES, obstacle_markers(world.obstacles, 0, scale))
    for k, sample in enumerate(trace):
        step = steps[k] if k < len(steps) else None
        after = trace[k + 1] if k + 1 < len(trace) else None
        yield from _sample_messages(recording.params, sample, step, after, scale)


def _sample_messages(
    params: EpisodeParams,
    sample: TraceStep,
    step: tuple[Observation, Command] | None,
    after: TraceStep | None,
    scale: float,
) -> Iterator[Stamped]:
    """The messages of one trace sample: the scan the planner saw there (if it was asked),
    the believed and the true pose, and the command executed from there (if any)."""
    stamp = nanoseconds(sample.t)
    if step is not None:
        yield Stamped(stamp, TopicName.SCAN, laser_scan(step[0].scan, stamp, params.dt, scale))
    believed = _believed(sample)
    command = step[1] if step is not None and sample.heading_cmd is not None else None
    linear, angular = (0.0, 0.0) if command is None else command.twist(believed, params)
    velocity = twist(linear, angular, scale)
    true_pose = Pose(sample.x, sample.y, sample.theta)
    tf = transform(stamp, Frame.ODOM, Frame.BASE_LINK, believed, scale)
    yield Stamped(stamp, TopicName.TF, tf)
    yield Stamped(stamp, TopicName.ODOM, odometry(stamp, Frame.ODOM, believed, velocity, scale))
    truth = odometry(stamp, Frame.MAP, true_pose, _mean_velocity(sample, after, scale), scale)
    yield Stamped(stamp, TopicName.GROUND_TRUTH, truth)
    if command is not None:
        yield Stamped(stamp, TopicName.CMD_VEL, velocity)
        yield Stamped(stamp, TopicName.BRANCH, String(data=command.branch or ""))
        yield Stamped(stamp, TopicName.BEHAVIOUR, String(data=command.behaviour or ""))


def _check_lined_up(recording: Recording, trace: Sequence[TraceStep]) -> None:
    """Raise ValueError unless step ``k`` of ``recording`` was decided at sample ``k`` of
    ``trace``, for every commanded sample, with at most one step more (a planner's stop)."""
    commanded = sum(sample.heading_cmd is not None for sample in trace)
    steps = recording.steps
    if len(steps) not in (commanded, commanded + 1) or len(steps) > len(trace):
        raise ValueError(
            f"the recording holds {len(steps)} steps, but should hold {commanded} or "
            f"{commanded + 1} for a trace of {len(trace)} samples: record the run with it"
        )
    for sample, (observation, _) in zip(trace, steps, strict=False):
        if sample.t != observation.t:
            raise ValueError(
                f"recorded step at t={observation.t!r}, but the trace's sample is at "
                f"t={sample.t!r}: record the run with it"
            )


def _believed(sample: TraceStep) -> Pose:
    """The pose the planner was told at ``sample`` (the true one in a trace without it)."""
    if sample.believed_x is None or sample.believed_y is None or sample.believed_theta is None:
        return Pose(sample.x, sample.y, sample.theta)
    return Pose(sample.believed_x, sample.believed_y, sample.believed_theta)


def _mean_velocity(sample: TraceStep, after: TraceStep | None, scale: float) -> Twist:
    """The true mean velocity from ``sample`` to the sample ``after`` it, in ``base_link``
    at ``sample`` (zero at the last sample)."""
    if after is None:
        return twist(0.0, 0.0, scale)
    dt = after.t - sample.t
    dx, dy = after.x - sample.x, after.y - sample.y
    cos, sin = math.cos(sample.theta), math.sin(sample.theta)
    return twist(
        (cos * dx + sin * dy) / dt,
        wrap_angle(after.theta - sample.theta) / dt,
        scale,
        lateral=(cos * dy - sin * dx) / dt,
    )
