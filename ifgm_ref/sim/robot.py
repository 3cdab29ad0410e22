"""Unicycle kinematics of the paper's disc robot (section 4: a "cylindrical shaped robot").

Within one time step ``dt`` the robot first turns towards the commanded heading, by at most
``max_turn_rate * dt`` along the shorter way round (or, for a velocity command, by its turn
rate times ``dt``, within the same limit), then drives straight along its new heading
at the commanded speed (clipped to the robot's speed). Between two samples the robot's centre
therefore moves on the straight segment joining them, which is exactly the segment the
simulator's swept-disc collision check tests: the discretisation and the check agree.

The paper's robot reaches a commanded speed at once. A robot with finite ``braking`` ``b`` or
``acceleration`` ``A`` (:class:`~ifgm_ref.core.params.RobotParams`) moves from its speed towards
the command at exactly ``A`` when speeding up and ``b`` when slowing down, then holds it
(:func:`ramp`): the worst case the braking governor of :mod:`ifgm_ref.planners.governor`
allows for, integrated exactly.
"""

from __future__ import annotations

import math

from ifgm_ref.core.params import RobotParams
from ifgm_ref.core.pose import Pose, wrap_angle
from ifgm_ref.core.protocol import Command


def ramp(speed: float, target: float, robot: RobotParams, dt: float) -> tuple[float, float]:
    """The distance driven in ``dt`` from ``speed`` towards ``target``, and the speed at its
    end: at the robot's ``acceleration`` up or its ``braking`` down until the target is
    reached, then at the target.

    >>> robot = RobotParams(braking=2.0, acceleration=1.0)
    >>> ramp(0.0, 1.0, robot, 0.5)  # speeds up at 1: half a second of 0.5 * 1 * 0.5^2
    (0.125, 0.5)
    >>> ramp(1.0, 0.0, robot, 1.0)  # stops in 0.5 s, after 1^2 / (2 * 2)
    (0.25, 0.0)
    >>> ramp(1.0, 3.0, RobotParams(), 0.5)  # the paper's robot: at the target at once
    (1.5, 3.0)
    """
    rate = robot.acceleration if target >= speed else robot.braking
    if rate == math.inf:
        return target * dt, target
    gap = target - speed
    if abs(gap) <= rate * dt:
        t = abs(gap) / rate
        return (speed + target) / 2 * t + target * (dt - t), target
    end = speed + math.copysign(rate * dt, gap)
    return (speed + end) / 2 * dt, end


def advance(
    pose: Pose,
    command: Command,
    robot: RobotParams,
    dt: float,
    *,
    turn_scale: float = 1.0,
    speed_scale: float = 1.0,
    travel: float | None = None,
) -> Pose:
    """Move ``pose`` by one time step ``dt`` under ``command`` (turn, then translate).

    ``turn_scale`` and ``speed_scale`` multiply the turn (after the turn-rate limit) and the
    speed (after the top speed): the actuation noise of :mod:`ifgm_ref.sim.noise`. ``travel``,
    when given, is the distance driven instead (a robot with finite acceleration or braking,
    :func:`ramp`).

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
    step = min(command.speed, robot.speed) * speed_scale * dt if travel is None else travel
    return Pose(pose.x + step * math.cos(theta), pose.y + step * math.sin(theta), theta)
