"""The two robot bodies of the MuJoCo engine: the paper's robot and a Jackal-like one.

A body is a differential-drive robot: a chassis, a cylinder of the world's robot radius ``r``
or a box (the only part that meets obstacles), two driven wheels on the chassis' diameter
(so the robot turns about its centre, as the kinematic robot does), and a frictionless caster
in front and one behind. Velocity actuators drive the wheels within a force limit; the
heading controller's wheel speeds are limited to the body's linear and angular accelerations.
Lengths of the body are relative to ``r``, so one preset fits its robot at any size; masses
are in kg, and the length unit is the world's, so gravity is given in that unit.

The dynamics the planners' braking governor is told (:meth:`Body.told`) follow from the
parameters: ``A = min(max_accel, mu g)``, an upper bound; ``b = min(max_accel,
mu g c / (c + mu h))``, the tyres' braking with load moved onto the frictionless front caster
(``c`` the caster's distance from the axle, ``h`` the centre of mass's height), a lower
bound; the response time :data:`RESPONSE`. The source of every number, and how the response
time was chosen: ``docs/physics.md``, "The two bodies" and "Braking in time".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import RobotParams

#: The casters' distance from the centre, front and rear, in robot radii.
CASTER_OFFSET = 0.7
#: Time constant of the wheels' velocity servos, s: the motor reaches a commanded wheel speed
#: within a few hundredths of a second, faster than any acceleration limit asks.
SERVO_TIME = 0.02
#: A body's response time, s: four servo time constants, 98 % of a change of wheel speed,
#: the fewest under which every measured stop fits the governor's worst case (docs/physics.md).
RESPONSE = 4 * SERVO_TIME
#: Standard gravity, m/s^2 and ft/s^2 (9.80665 m/s^2 / 0.3048 m/ft).
GRAVITY_M = 9.80665
GRAVITY_FT = GRAVITY_M / 0.3048


@dataclass(frozen=True)
class Body:
    """A differential-drive body for a disc robot of radius ``r`` (the module docstring).

    Parameters
    ----------
    name : str
        The preset's name (``--body`` on the command line).
    chassis_mass : float
        Chassis mass, kg (wheels apart).
    chassis_izz : float or None
        Chassis moment of inertia about the vertical axis, kg length^2; ``None`` takes that of
        a uniform disc of radius ``r``.
    wheel_mass : float
        Mass of one driven wheel, kg.
    wheel_radius : float
        Wheel radius relative to ``r``.
    track : float
        Distance between the two wheels' mid-planes, relative to ``r`` (< 2).
    friction : float
        Tyre friction coefficient (the caster has none).
    max_accel : float
        Largest linear acceleration, length/s^2 (the world's length unit).
    max_angular_accel : float
        Largest angular acceleration, rad/s^2.
    gravity : float
        Gravity in the world's length unit per s^2.
    outline : tuple of float or None, default None
        The chassis as a box, its length and width relative to ``r``; ``None``: the disc of
        radius ``r``.
    circumscribe : bool, default True
        Whether the planners are told the disc that circumscribes ``outline`` (else the
        world's robot disc, which may not cover the box: for comparison only).
    """

    name: str
    chassis_mass: float
    chassis_izz: float | None
    wheel_mass: float
    wheel_radius: float
    track: float
    friction: float
    max_accel: float
    max_angular_accel: float
    gravity: float
    outline: tuple[float, float] | None = None
    circumscribe: bool = True

    def __post_init__(self) -> None:
        if not 0.0 < self.track < 2.0 - self.wheel_width_ratio:
            raise ParameterError(f"`track` must be in (0, 2 - wheel width), got {self.track!r}")

    #: Wheel width relative to ``r`` (the Jackal's 0.040 m wheels on its 0.22 m disc).
    wheel_width_ratio = 0.040 / 0.22

    def scaled_track(self, robot: RobotParams) -> float:
        """Wheel separation of this body on ``robot``, in its length unit."""
        return self.track * robot.radius

    def scaled_wheel(self, robot: RobotParams) -> float:
        """Wheel radius of this body on ``robot``, in its length unit."""
        return self.wheel_radius * robot.radius

    def outline_radius(self, robot: RobotParams) -> float:
        """The radius of the disc that circumscribes the chassis on ``robot``.

        >>> from ifgm_ref.io.barn import ROBOT
        >>> round(JACKAL.outline_radius(ROBOT), 4), PAPER.outline_radius(RobotParams())
        (0.2671, 1.0)
        """
        if self.outline is None:
            return robot.radius
        return math.hypot(*self.outline) / 2 * robot.radius

    def acceleration(self) -> float:
        """``A``: the most the robot speeds up, the controller's limit or the tyres' ``mu g``."""
        return min(self.max_accel, self.friction * self.gravity)

    def braking(self, robot: RobotParams) -> float:
        """``b``: the least the robot slows when told to, the controller's limit or what the
        tyres brake with load moved onto the front caster (module docstring).

        >>> from ifgm_ref.io.barn import ROBOT
        >>> round(JACKAL.braking(ROBOT), 2), round(JACKAL.acceleration(), 2)
        (3.72, 4.9)
        """
        caster = CASTER_OFFSET * robot.radius
        height = self.scaled_wheel(robot)
        grip = self.friction * self.gravity * caster / (caster + self.friction * height)
        return min(self.max_accel, grip)

    def told(self, robot: RobotParams) -> RobotParams:
        """The robot the planners are told on this body: ``robot`` with the outline's disc
        (when ``circumscribe``) and the body's ``b``, ``A`` and response time where
        ``robot`` leaves them at the paper's robot's (infinite, infinite, 0)."""
        radius = self.outline_radius(robot) if self.circumscribe else robot.radius
        braking = self.braking(robot) if robot.braking == math.inf else robot.braking
        accel = self.acceleration() if robot.acceleration == math.inf else robot.acceleration
        response = RESPONSE if robot.response == 0.0 else robot.response
        return replace(robot, radius=radius, braking=braking, acceleration=accel, response=response)


#: BARN's Jackal: the urdf's masses and wheels, control.yaml's limits, on BARN's 0.22 m disc
#: (sources: docs/physics.md, "The two bodies").
JACKAL = Body(
    name="jackal",
    chassis_mass=16.523,
    chassis_izz=0.4485,
    wheel_mass=2 * 0.477,
    wheel_radius=0.098 / 0.22,
    track=0.37559 / 0.22,
    friction=0.5,
    max_accel=20.0,
    max_angular_accel=25.0,
    gravity=GRAVITY_M,
    outline=(0.42 / 0.22, 0.33 / 0.22),
)

#: The paper's robot: a 9 kg Pioneer 3-DX class body on the 1 ft disc, in feet (the paper
#: gives none). Accelerations: the default robot's speed in 0.25 s and turn rate in 0.1 s.
PAPER = Body(
    name="paper",
    chassis_mass=9.0 - 2 * 0.5,
    chassis_izz=None,
    wheel_mass=0.5,
    wheel_radius=0.0975 / 0.3048,
    track=1.25,
    friction=0.8,
    max_accel=RobotParams().speed / 0.25,
    max_angular_accel=RobotParams().max_turn_rate / 0.1,
    gravity=GRAVITY_FT,
)

#: The Jackal's box, its planners told BARN's 0.22 m disc, which does not cover the box's
#: corners (``circumscribe=False``): for comparing the two outlines (docs/physics.md).
JACKAL_DISC = replace(JACKAL, name="jackal-disc", circumscribe=False)

#: BARN's robot's radius, m: half the Jackal's 0.430 m width (:data:`ifgm_ref.io.barn.ROBOT`
#: is built on it). A world's robot of this radius gets the Jackal's body.
JACKAL_RADIUS = 0.22

#: The bodies by name (``--body NAME``).
BODIES = {body.name: body for body in (PAPER, JACKAL, JACKAL_DISC)}


def body_for(robot: RobotParams) -> Body:
    """The default body of ``robot``: the Jackal for BARN's robot (metres), else the paper's.

    >>> body_for(RobotParams(radius=JACKAL_RADIUS)).name, body_for(RobotParams()).name
    ('jackal', 'paper')
    """
    return JACKAL if math.isclose(robot.radius, JACKAL_RADIUS) else PAPER


def body_named(name: str) -> Body:
    """The body called ``name``; a :class:`ParameterError` names the choices otherwise."""
    try:
        return BODIES[name]
    except KeyError:
        raise ParameterError(
            f"unknown body {name!r}; choose one of {', '.join(sorted(BODIES))}"
        ) from None
