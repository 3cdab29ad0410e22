"""Engines: what senses and moves the robot of an episode, kinematic or physical.

The simulator (:mod:`ifgm_ref.sim.simulator`) runs the same loop whatever the engine: scan, tell
the planner the pose, execute its command for one time step, check. An engine does the three
things that depend on the robot's physics:

* :meth:`Engine.scan`: the range scan from the robot's true pose;
* :meth:`Engine.odometry`: the pose the robot's own odometry gives (before the noise models
  of :mod:`ifgm_ref.sim.noise`, which the simulator adds in either engine);
* :meth:`Engine.move`: one time step under a command; the new true pose, the clearance of the
  path swept and whether the robot collided.

Two engines (:class:`ifgm_ref.core.params.EngineName`, ``--engine`` on the command line;
:data:`ENGINE_FACTORIES` makes each):

``kinematic`` (default)
    The paper's robot as the paper simulates it: it turns, then drives, at once
    (:func:`ifgm_ref.sim.robot.advance`); its odometry is exact; a collision is a swept disc that
    meets an obstacle (:class:`ifgm_ref.sim.collision.ClearanceChecker`). Given a robot with
    finite ``braking`` or ``acceleration``, its speed moves towards the command at exactly
    those rates (:func:`ifgm_ref.sim.robot.ramp`): the dynamics a braking governor assumes,
    without physics.
``mujoco``
    A differential-drive robot with mass on the MuJoCo physics engine
    (:mod:`ifgm_ref.sim.physics`, the ``physics`` extra): wheels, velocity actuators with force
    limits, acceleration limits, wheel odometry, contacts.
"""

from __future__ import annotations

import importlib.util
import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Protocol

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import EngineName, engine_named
from ifgm_ref.core.pose import Pose
from ifgm_ref.core.protocol import Command
from ifgm_ref.sim.collision import ClearanceChecker
from ifgm_ref.sim.robot import advance, ramp
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.world import World

if TYPE_CHECKING:
    from ifgm_ref.core.params import RobotParams, SimParams

#: What to install for ``--engine mujoco`` (one line, as the command line prints it).
PHYSICS_HINT = (
    "the mujoco engine needs MuJoCo: pip install 'ifgm-ref[physics]' "
    "(from a clone: pip install -e '.[physics]')"
)


class Engine(Protocol):
    """What senses and moves the robot (see the module docstring)."""

    #: The robot the planners are told: the world's, or as the engine's body makes it (its
    #: outline's disc and its braking and acceleration, :mod:`ifgm_ref.sim.physics.bodies`).
    robot: RobotParams

    def scan(self, pose: Pose) -> LaserScan:
        """The scan from the robot at its true ``pose``."""

    def odometry(self, pose: Pose) -> Pose:
        """The pose the robot's odometry gives when its true pose is ``pose``."""

    def move(
        self, pose: Pose, command: Command, turn_scale: float, speed_scale: float
    ) -> tuple[Pose, float, bool]:
        """Execute ``command`` for one time step from the true ``pose``: the new true pose,
        the clearance of the path swept, and whether the robot collided on the way.
        ``turn_scale`` and ``speed_scale`` are the actuation noise's factors."""

    def pose_clearance(self, pose: Pose) -> float:
        """The clearance of the robot standing at ``pose``."""


class KinematicEngine:
    """The paper's robot: :func:`~ifgm_ref.sim.robot.advance`, exact odometry, the swept disc."""

    def __init__(self, world: World, dt: float) -> None:
        self.robot = world.robot
        self.dt = dt
        self.sensor = IRSensor(world)
        self.checker = ClearanceChecker(world, world.robot.radius)
        #: The robot's speed, for a robot with finite braking or acceleration.
        self.speed = 0.0
        self._instant = self.robot.stops_at_once and self.robot.acceleration == math.inf

    def scan(self, pose: Pose) -> LaserScan:
        """The exact scan from ``pose`` (:class:`~ifgm_ref.sim.sensor.IRSensor`)."""
        return self.sensor.scan(pose)

    def odometry(self, pose: Pose) -> Pose:
        """Exact: the true ``pose``."""
        return pose

    def move(
        self, pose: Pose, command: Command, turn_scale: float, speed_scale: float
    ) -> tuple[Pose, float, bool]:
        """Turn, then drive (:func:`~ifgm_ref.sim.robot.advance`, after
        :func:`~ifgm_ref.sim.robot.ramp` for a robot with finite dynamics); the straight segment's
        clearance."""
        travel = None
        if not self._instant:
            target = min(command.speed, self.robot.speed) * speed_scale
            travel, self.speed = ramp(self.speed, target, self.robot, self.dt)
        new_pose = advance(
            pose,
            command,
            self.robot,
            self.dt,
            turn_scale=turn_scale,
            speed_scale=speed_scale,
            travel=travel,
        )
        clearance = self.checker.segment_clearance(pose, new_pose)
        return new_pose, clearance, clearance < 0.0

    def pose_clearance(self, pose: Pose) -> float:
        """The exact clearance of the disc at ``pose``."""
        return self.checker.pose_clearance(pose)


def _mujoco(world: World, sim: SimParams) -> Engine:
    """The MuJoCo engine, once MuJoCo is found installed (:func:`require_physics`)."""
    require_physics()
    from ifgm_ref.sim.physics.mujoco import MujocoEngine

    return MujocoEngine(world, sim.dt, sim.body)


#: How each engine (:class:`~ifgm_ref.core.params.EngineName`) is made for a world and the
#: simulation's settings: the one registry of engines.
ENGINE_FACTORIES: dict[EngineName, Callable[[World, SimParams], Engine]] = {
    EngineName.KINEMATIC: lambda world, sim: KinematicEngine(world, sim.dt),
    EngineName.MUJOCO: _mujoco,
}


def make_engine(world: World, sim: SimParams) -> Engine:
    """The engine ``sim.engine`` for ``world``, stepped at ``sim.dt``
    (:data:`ENGINE_FACTORIES`).

    Raises
    ------
    ParameterError
        For ``mujoco`` when MuJoCo is not installed (the message says what to install).
    """
    return ENGINE_FACTORIES[engine_named(sim.engine)](world, sim)


def require_physics() -> None:
    """Raise a :class:`ParameterError` that says what to install when MuJoCo is missing."""
    if importlib.util.find_spec("mujoco") is None:
        raise ParameterError(PHYSICS_HINT)
