"""ROS 1 nodes as a planner: the simulator's step as ``/odom`` and ``/scan``, ``/cmd_vel`` back.

:class:`RosPlanner` is a :class:`~ifgm_ref.core.protocol.Planner` whose decisions come from
unchanged rospy nodes (``--ros-node`` of ``ifgm-ref simulate`` and ``ifgm-ref oracle``) run
under the stand-in (:mod:`ifgm_ref.io.ros`) by a :class:`~ifgm_ref.io.ros.broker.Broker`.
:class:`RosFactory` makes one for the oracle and can be copied into its worker processes.
``docs/ros-nodes.md`` states the rules; in short, at each step of time ``t``:

1. the nodes run up to ``t`` (their timers, Rate loops and what they publish meanwhile);
2. the simulator publishes ``/odom`` (``nav_msgs/Odometry``, the pose the planner believes, in
   ``odom``, metres) and then ``/scan`` (``sensor_msgs/LaserScan`` in ``base_link``, metres,
   float32), both stamped ``t``, and the nodes run everything due at ``t``;
3. the command executed from ``t`` to ``t + dt`` is the last ``/cmd_vel`` published at or
   before ``t``, held like a base controller holds it, or zero if there was none or it is older
   than :data:`CMD_VEL_TIMEOUT`; a ``/ifgm_ref/stop`` or a node's end ends the episode;
   the branch and behaviour labels published since the step before are the command's.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, TextIO

import numpy as np

from ifgm_ref.core.errors import ImplementationError, ParameterError
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.validate import POSITIVE, require
from ifgm_ref.io.ros.broker import Broker
from ifgm_ref.io.ros.messages import message_class, to_wire
from ifgm_ref.io.ros.names import parse_remap
from ifgm_ref.io.ros.process import SHIMS, SHIMS2, NodeProcess
from ifgm_ref.io.ros.rostime import NS, Time, nanoseconds
from ifgm_ref.io.ros.rules import CMD_VEL_TIMEOUT, GOAL_TOPIC
from ifgm_ref.io.transport.external import TIMEOUT, timeouts

__all__ = ["CMD_VEL_TIMEOUT", "GOAL_TOPIC", "RosFactory", "RosPlanner", "episode_params"]


def episode_params(
    goal: Point, params: EpisodeParams, scale: float
) -> tuple[dict[str, Any], dict[str, Any]]:
    """The parameter server of an episode: global names, and private ones set on every node.

    The goal (``des_pos_x``, ``des_pos_y``; ``~goal_x``, ``~goal_y`` of every node), and
    under ``/ifgm_ref/`` what the JSON protocol's ``reset`` carries: the robot, the sensor,
    ``dt``, the goal tolerance and the planner parameters, in SI units (``scale`` converts the
    world's length unit to metres; a robot that stops at once has no ``braking`` and no
    ``acceleration``).

    >>> glob, private = episode_params(Point(10.0, 0.0), EpisodeParams(), 0.3048)
    >>> round(glob["/des_pos_x"], 4), private["goal_y"], glob["/ifgm_ref/sensor/rays"]
    (3.048, 0.0, 76)
    """
    robot, sensor = params.robot, params.sensor
    x, y = goal.x * scale, goal.y * scale
    glob: dict[str, Any] = {"/des_pos_x": x, "/des_pos_y": y}
    values = {
        "robot/radius": robot.radius * scale,
        "robot/speed": robot.speed * scale,
        "robot/max_turn_rate": robot.max_turn_rate,
        "robot/braking": robot.braking * scale,
        "robot/acceleration": robot.acceleration * scale,
        "robot/response": robot.response,
        "robot/latency": robot.latency,
        "sensor/fov": sensor.fov,
        "sensor/rays": sensor.rays,
        "sensor/range_min": sensor.range_min * scale,
        "sensor/range_max": sensor.range_max * scale,
        "dt": params.dt,
        "goal_tolerance": params.goal_tolerance * scale,
        **{f"params/{k}": v for k, v in params.params.items()},
    }
    glob.update({f"/ifgm_ref/{k}": v for k, v in values.items() if math.isfinite(v)})
    return glob, {"goal_x": x, "goal_y": y}


class RosPlanner:
    """A planner made of ROS 1 nodes (see the module docstring).

    Parameters
    ----------
    commands : sequence of str
        The nodes' command lines (``python3 node.py _rate:=20``), started as given.
    scale : float
        Metres per length unit of the worlds it runs in (0.3048 for feet).
    timeout, startup_timeout : float
        As :class:`~ifgm_ref.io.transport.external.ExternalPlanner`'s: the longest wait for a
        node to block again after it was handed control, and for a node's start, an
        episode's start and the exit after the last.
    remaps : sequence of str
        ``FROM:=TO`` remappings for every node.
    goal_topic : str
        Where the goal is published (latched) at the start of each episode.
    name : str, optional
        The planner's name (default: ``ros:`` and the commands).
    log : text stream, optional
        Where the nodes' output is copied.
    distro : str, default ``"ros1"``
        ``ros1`` for rospy nodes, ``ros2`` for rclpy nodes (ROS 2 Humble's messages).
    """

    def __init__(
        self,
        commands: Sequence[str],
        *,
        scale: float,
        timeout: float = TIMEOUT,
        startup_timeout: float | None = None,
        remaps: Sequence[str] = (),
        goal_topic: str = GOAL_TOPIC,
        name: str | None = None,
        log: TextIO | None = None,
        distro: str = "ros1",
    ) -> None:
        if distro not in ("ros1", "ros2"):
            raise ParameterError(f"`distro` must be ros1 or ros2, got {distro!r}")
        if not commands:
            raise ParameterError("give at least one --ros-node command")
        require("scale", scale, POSITIVE)
        try:
            remapped = dict(parse_remap(text) for text in remaps)
        except ValueError as err:
            raise ParameterError(f"--remap: {err}") from None
        self.timeout, self.startup_timeout = timeouts(timeout, startup_timeout)
        self.scale = scale
        self.goal_topic = goal_topic
        self.name = name or "ros: " + " + ".join(commands)
        self.distro = distro
        shims = SHIMS if distro == "ros1" else SHIMS2
        nodes = [NodeProcess(c, i, log, shims) for i, c in enumerate(commands)]
        self._broker = Broker(
            nodes, timeout=self.timeout, startup_timeout=self.startup_timeout, remaps=remapped
        )
        self._params = EpisodeParams()
        self._episode = False
        self._failure: ImplementationError | None = None
        self._last = (0.0, 0.0)

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Start an episode: fresh node children, the parameters set, the goal published.

        Raises
        ------
        ImplementationError
            When a node cannot start, crashes or hangs (every node is then killed).
        """
        self._guarded(self._reset, start, goal, params)

    def step(self, observation: Observation) -> Command:
        """Publish the step's odometry and scan, run the nodes, return the command in force.

        Raises
        ------
        ImplementationError
            When a node crashes, hangs or breaks the link (every node is then killed).
        """
        result: Command = self._guarded(self._step, observation)
        return result

    def close(self) -> None:
        """End the episode and stop every node's process."""
        try:
            if self._episode and self._failure is None:
                self._broker.end()
        except ImplementationError:
            pass
        finally:
            self._episode = False
            self._broker.close()

    def __enter__(self) -> RosPlanner:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _guarded(self, call: Any, *args: Any) -> Any:
        if self._failure is not None:
            raise self._failure
        try:
            return call(*args)
        except ImplementationError as err:
            self._failure = err
            self._broker.kill()
            raise

    def _reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        if self._episode:
            self._broker.end()
        self._params, self._last = params, (0.0, 0.0)
        glob, private = episode_params(goal, params, self.scale)
        self._broker.begin(glob, private)
        self._episode = True
        pose = message_class("geometry_msgs/PoseStamped", self.distro)()
        self._stamp(pose.header, 0, "map")
        pose.pose.position.x, pose.pose.position.y = goal.x * self.scale, goal.y * self.scale
        pose.pose.orientation.w = 1.0
        self._broker.publish(
            self.goal_topic, "geometry_msgs/PoseStamped", to_wire(pose), latch=True
        )
        self._broker.settle(0, inclusive=True)
        self._broker.labels = {}

    def _step(self, observation: Observation) -> Command:
        t = nanoseconds(observation.t)
        broker = self._broker
        broker.settle(t, inclusive=False)
        broker.publish("/odom", "nav_msgs/Odometry", self._odometry(t, observation.pose))
        broker.publish("/scan", "sensor_msgs/LaserScan", self._scan(t, observation))
        broker.settle(t, inclusive=True)
        velocity = broker.command
        fresh = velocity is not None and t - velocity.t <= nanoseconds(CMD_VEL_TIMEOUT)
        linear, angular = (velocity.linear, velocity.angular) if fresh and velocity else (0.0, 0.0)
        labels = {key: text or None for key, text in broker.labels.items()}  # "": none
        broker.labels = {}
        command = Command.from_twist(
            linear / self.scale, angular, observation.pose, self._params, stop=broker.stop, **labels
        )
        self._last = (
            command.twist(observation.pose, self._params) if not command.problem() else (0.0, 0.0)
        )
        return command

    def _stamp(self, header: Any, t: int, frame: str) -> None:
        """Stamp ``header`` at ``t`` ns in ``frame`` (ROS 1's time, or ROS 2's message)."""
        header.frame_id = frame
        if self.distro == "ros1":
            header.stamp = Time.from_nsec(t)
        else:
            header.stamp.sec, header.stamp.nanosec = divmod(t, NS)

    def _odometry(self, t: int, pose: Pose) -> list[Any]:
        odom = message_class("nav_msgs/Odometry", self.distro)()
        self._stamp(odom.header, t, "odom")
        odom.child_frame_id = "base_link"
        odom.pose.pose.position.x, odom.pose.pose.position.y = (
            pose.x * self.scale,
            pose.y * self.scale,
        )
        orientation = odom.pose.pose.orientation
        orientation.z, orientation.w = math.sin(0.5 * pose.theta), math.cos(0.5 * pose.theta)
        odom.twist.twist.linear.x = self._last[0] * self.scale
        odom.twist.twist.angular.z = self._last[1]
        return to_wire(odom)

    def _scan(self, t: int, observation: Observation) -> list[Any]:
        scan = observation.scan
        f32 = np.float32
        msg = message_class("sensor_msgs/LaserScan", self.distro)()
        self._stamp(msg.header, t, "base_link")
        msg.angle_min, msg.angle_max = float(f32(scan.angle_min)), float(f32(scan.angle_max))
        msg.angle_increment = float(f32(scan.angle_increment))
        msg.scan_time = float(f32(self._params.dt))
        msg.range_min = float(f32(scan.range_min * self.scale))
        msg.range_max = float(f32(scan.range_max * self.scale))
        msg.ranges = (scan.ranges * self.scale).astype(f32).tolist()
        return to_wire(msg)


class RosFactory:
    """A planner factory for the oracle: one :class:`RosPlanner`, started once and handed out
    for every episode. It holds only its arguments until first called, so that it can be
    copied into a worker process."""

    def __init__(self, commands: Sequence[str], **options: Any) -> None:
        self.commands = tuple(commands)
        self.options = options
        RosPlanner(self.commands, **options)  # check the arguments now; starts nothing
        self._planner: RosPlanner | None = None

    def __call__(self) -> RosPlanner:
        if self._planner is None:
            self._planner = RosPlanner(self.commands, **self.options)
        return self._planner

    def close(self) -> None:
        """Stop the nodes (if they were started)."""
        if self._planner is not None:
            planner, self._planner = self._planner, None
            planner.close()

    def __getstate__(self) -> dict[str, Any]:
        return {**self.__dict__, "_planner": None}
