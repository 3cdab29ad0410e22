"""The ``mujoco`` engine: a differential-drive robot with mass, on the MuJoCo physics engine.

One episode step of ``dt`` seconds (the planner's decision period) is:

1. **Heading controller**, the kinematic robot's (:func:`ifgm_ref.sim.robot.advance`) run at every
   physics substep: the turn wanted is the command's heading minus the odometry's, turned at
   ``w = e / dt`` within ``max_turn_rate`` (a velocity command's turn rate is taken as it
   is, within the same limit), and also within ``sqrt(2 alpha |e|)``, the fastest rate from
   which the body's angular acceleration ``alpha`` can still stop the turn at the heading
   (infinite for the kinematic robot; why: ``docs/physics.md``, "Why these choices"). The
   speed is the command's, within the robot's top speed
   ``v``. The kinematic robot turns, then drives; a wheeled robot does both at once, along
   an arc.
2. **Acceleration limits**: at every physics substep the commanded ``(v, w)`` moves towards
   that target by at most the body's linear and angular acceleration times the substep
   (ROS ``diff_drive_controller`` does so, with the Jackal's limits in its
   ``control.yaml``).
3. **Wheels**: ``(v, w)`` becomes the two wheel speeds ``(v -+ w b / 2) / R`` (track ``b``,
   wheel radius ``R``), the setpoints of the wheels' velocity servos, whose torque is
   limited (:mod:`ifgm_ref.sim.physics.mjcf`). MuJoCo integrates the rest: mass, inertia, tyre
   friction, the caster, contacts.
4. **Checks**: a contact between the chassis and an obstacle, at any substep, is a
   collision. The clearance recorded is the least clearance of the disc the planners are told
   (:attr:`MujocoEngine.robot`), swept along the path of the substeps' positions
   (:class:`~ifgm_ref.sim.collision.ClearanceChecker`, exact). Where the chassis is that disc, a
   negative clearance is a collision too, so that a trace's clearance and collision agree as
   in the kinematic engine; a box chassis collides only where the box touches (its
   circumscribed disc may overlap an obstacle that the box does not reach).

**Odometry** is the Jackal's (``jackal_control/config/control.yaml``: its
``ekf_localization`` fuses the wheels' velocities with the IMU's yaw): the heading is the
IMU's, the chassis' true heading (an ideal gyro), and the position advances by the distance
the wheels' encoders count, ``R (dphi_l + dphi_r) / 2`` per substep, along the mean heading
of the substep. Tyre slip makes the position drift from the truth; the heading does not
drift (why not encoders alone: ``docs/physics.md``). **Sensing** casts the
scan's rays with MuJoCo's ray function (``mj_multiRay``) from the sensor site at the robot's
centre, horizontally along the chassis' heading, against the obstacles only; the ranges then
go through the same noise and REP 117 encoding as the kinematic sensor
(:meth:`ifgm_ref.sim.sensor.IRSensor.reading`).

Deterministic: the same world, body and commands give the same trace (MuJoCo's stepping is
deterministic on one machine and build).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Pose, wrap_angle
from ifgm_ref.core.protocol import Command
from ifgm_ref.sim.collision import ClearanceChecker
from ifgm_ref.sim.physics.bodies import Body, body_for, body_named
from ifgm_ref.sim.physics.mjcf import OBSTACLE_GROUP, model_xml, substeps
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.world import World


def _toward(value: float, target: float, step: float) -> float:
    """``value`` moved towards ``target`` by at most ``step``."""
    return min(max(target, value - step), value + step)


def _yaw(quaternion: NDArray[np.float64]) -> float:
    """The heading of a body whose orientation is ``quaternion`` (w, x, y, z)."""
    w, x, y, z = quaternion
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


class MujocoEngine:
    """The robot of ``world`` as ``body`` on MuJoCo, stepped at ``dt`` (module docstring).

    Examples
    --------
    Driving straight at 1 ft/s from rest, the robot reaches the commanded speed within half a
    second (the acceleration limit, then the body rocking on its casters as the wheels' torque
    changes) and then holds it; odometry counts 0.04 ft less than the truth: the rocking, and
    the tyres slipping as the wheels spin up:

    >>> from ifgm_ref.io.scenarios import resolve_world
    >>> world = resolve_world("free")
    >>> engine = MujocoEngine(world, 0.1)
    >>> pose = world.start
    >>> for _ in range(10):
    ...     before = pose
    ...     pose, clearance, collided = engine.move(pose, Command(pose.theta, 1.0), 1.0, 1.0)
    >>> round((pose.x - before.x) / 0.1, 2), collided
    (1.0, False)
    >>> round(pose.x - engine.odometry(pose).x, 2), abs(pose.y) < 1e-9, abs(pose.theta) < 1e-9
    (0.04, True, True)
    """

    def __init__(self, world: World, dt: float, body: str | Body | None = None) -> None:
        self.body = (
            body_for(world.robot)
            if body is None
            else body
            if isinstance(body, Body)
            else body_named(body)
        )
        #: The robot the planners are told: the body's outline and dynamics
        #: (:meth:`~ifgm_ref.sim.physics.bodies.Body.told`).
        self.robot = self.body.told(world.robot)
        self._scale = world.robot
        self.dt = dt
        self.model = mujoco.MjModel.from_xml_string(model_xml(world, self.body, dt))
        self.data = mujoco.MjData(self.model)
        mujoco.mj_forward(self.model, self.data)
        self.substeps = substeps(dt)
        self.sensor = IRSensor(world)
        self.checker = ClearanceChecker(world, self.robot.radius)
        self._robot_body = self.model.body("robot").id
        self._chassis = self.model.geom("chassis").id
        self._sensor_site = self.model.site("sensor").id
        self._wheels = [self.model.joint(f"wheel_{s}").qposadr[0] for s in ("left", "right")]
        self._groups = np.zeros(6, dtype=np.uint8)
        self._groups[OBSTACLE_GROUP] = 1
        angles = self.sensor.angles
        self._angles = angles
        self._geomid = np.zeros(len(angles), dtype=np.int32)
        self._dist = np.zeros(len(angles))
        self._velocity = (0.0, 0.0)
        self._odometry = world.start
        self._wheel_angles = self._read_wheels()

    def _read_wheels(self) -> tuple[float, float]:
        qpos = self.data.qpos
        return float(qpos[self._wheels[0]]), float(qpos[self._wheels[1]])

    def true_pose(self) -> Pose:
        """The chassis' pose: its centre's x and y, and its heading."""
        qpos = self.data.qpos
        return Pose(float(qpos[0]), float(qpos[1]), _yaw(qpos[3:7]))

    def scan(self, pose: Pose) -> LaserScan:
        """The scan cast by MuJoCo from the sensor site (``pose`` is the true pose, which the
        engine knows already)."""
        heading = self.true_pose().theta + self._angles
        directions = np.zeros((len(heading), 3))
        directions[:, 0] = np.cos(heading)
        directions[:, 1] = np.sin(heading)
        origin = self.data.site_xpos[self._sensor_site].copy()
        mujoco.mj_multiRay(
            self.model,
            self.data,
            origin,
            directions.ravel(),
            self._groups,
            1,
            self._robot_body,
            self._geomid,
            self._dist,
            None,
            len(heading),
            self.sensor.params.range_max,
        )
        ranges = self._dist.copy()
        ranges[(ranges < 0.0) | (ranges > self.sensor.params.range_max)] = np.inf
        return self.sensor.reading(ranges)

    def odometry(self, pose: Pose) -> Pose:
        """The odometry's pose: encoders and gyro (module docstring; ``pose``, the true one,
        is not used)."""
        return self._odometry

    def move(
        self, pose: Pose, command: Command, turn_scale: float, speed_scale: float
    ) -> tuple[Pose, float, bool]:
        """One episode step under ``command`` (module docstring): the new true pose, the
        clearance of the path of the substeps, and whether the chassis touched an
        obstacle."""
        speed = min(command.speed, self.robot.speed) * speed_scale
        body = self.body
        h = self.model.opt.timestep
        track = body.scaled_track(self._scale)
        wheel = body.scaled_wheel(self._scale)
        collided = False
        clearance = math.inf
        previous = pose
        for _ in range(self.substeps):
            v = _toward(self._velocity[0], speed, body.max_accel * h)
            turn = self._turn_rate(command) * turn_scale
            w = _toward(self._velocity[1], turn, body.max_angular_accel * h)
            self._velocity = (v, w)
            self.data.ctrl[0] = (v - w * track / 2) / wheel
            self.data.ctrl[1] = (v + w * track / 2) / wheel
            mujoco.mj_step(self.model, self.data)
            now = self.true_pose()
            self._update_odometry(wheel, now.theta)
            clearance = min(clearance, self.checker.segment_clearance(previous, now))
            previous = now
            collided = collided or self._touching()
        if self.body.outline is None:  # the chassis is the disc: its clearance decides too
            collided = collided or clearance < 0.0
        return previous, clearance, collided

    def _turn_rate(self, command: Command) -> float:
        """The turn rate the heading controller asks for now (module docstring, step 1)."""
        limit = self.robot.max_turn_rate
        if command.turn_rate is not None:
            return min(max(command.turn_rate, -limit), limit)
        error = wrap_angle(command.heading - self._odometry.theta)
        braking = math.sqrt(2.0 * self.body.max_angular_accel * abs(error))
        return math.copysign(min(abs(error) / self.dt, limit, braking), error)

    def _update_odometry(self, wheel: float, heading: float) -> None:
        """Advance the odometry by the wheels' distance along the mean of its heading and the
        gyro's new ``heading`` (module docstring)."""
        left, right = self._read_wheels()
        ds = ((left - self._wheel_angles[0]) + (right - self._wheel_angles[1])) * wheel / 2
        self._wheel_angles = (left, right)
        x, y, theta = self._odometry
        mid = theta + wrap_angle(heading - theta) / 2
        self._odometry = Pose(x + ds * math.cos(mid), y + ds * math.sin(mid), heading)

    def _touching(self) -> bool:
        """Whether the chassis is in contact with an obstacle (the only geoms it can touch)."""
        ncon = self.data.ncon
        if ncon == 0:
            return False
        geoms = self.data.contact.geom[:ncon]
        return bool(np.any(geoms == self._chassis))

    def pose_clearance(self, pose: Pose) -> float:
        """The exact clearance of the disc at ``pose``."""
        return self.checker.pose_clearance(pose)
