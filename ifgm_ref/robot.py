"""Unicycle kinematics of the paper's disc robot (section 4: a "cylindrical shaped robot").

Within one time step ``dt`` the robot first turns towards the commanded heading, by at most
``max_turn_rate * dt`` along the shorter way round (or, for a velocity command, by its turn
rate times ``dt``, within the same limit), then drives straight along its new heading
at the commanded speed (clipped to the robot's speed). Between two samples the robot's centre
therefore moves on the straight segment joining them, which is exactly the segment the
simulator's swept-disc collision check tests: the discretisation and the check agree.
"""

from __future__ import annotations

import math

from ifgm_ref.params import RobotParams
from ifgm_ref.pose import Pose, wrap_angle
from ifgm_ref.protocol import Command


def advance(
    pose: Pose,
    command: Command,
    robot: RobotParams,
    dt: float,
    *,
    turn_scale: float = 1.0,
    speed_scale: float = 1.0,
) -> Pose:
    """Move ``pose`` by one time step ``dt`` under ``command`` (turn, then translate).

    ``turn_scale`` and ``speed_scale`` multiply the turn (after the turn-rate limit) and the
    speed (after the top speed): the actuation noise of :mod:`ifgm_ref.noise`.

    Examples
    --------
    A quarter turn at pi/2 rad/s needs one second; in 0.5 s the robot turns only pi/4:

    >>> robot = RobotParams(radius=1.0, speed=2.0, max_turn_rate=math.pi / 2)
    >>> advance(Pose(0.0, 0.0, 0.0), Command(heading=math.pi / 2, speed=0.0), robot, 0.5)
    Pose(x=0.0, y=0.0, theta=0.7853981633974483)

    A velocity command (:meth:`Command.from_twist`) turns at its rate, within the limit,
    whatever its heading says:

    >>> twist = Command(heading=0.0, speed=0.0, turn_rate=-0.5)
    >>> advance(Pose(0.0, 0.0, 0.0), twist, robot, 0.5)
    Pose(x=0.0, y=0.0, theta=-0.25)

    Speed above the robot's is clipped to it:

    >>> advance(Pose(0.0, 0.0, 0.0), Command(heading=0.0, speed=9.0), robot, 0.5)
    Pose(x=1.0, y=0.0, theta=0.0)
    """
    limit = robot.max_turn_rate * dt
    wanted = (
        wrap_angle(command.heading - pose.theta)
        if command.turn_rate is None
        else command.turn_rate * dt
    )
    turn = min(max(wanted, -limit), limit) * turn_scale
    theta = wrap_angle(pose.theta + turn)
    step = min(command.speed, robot.speed) * speed_scale * dt
    return Pose(pose.x + step * math.cos(theta), pose.y + step * math.sin(theta), theta)
