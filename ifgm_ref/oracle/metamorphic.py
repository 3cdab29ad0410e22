"""Metamorphic relations of a whole problem: the same problem moved, or in another unit.

A planner whose every length is derived from the robot and the sensor
(:mod:`ifgm_ref.planners.tuning`) cannot tell feet from metres: scale every length of the
problem by ``k`` -- the obstacles, the bounds, the start position and the goal, the robot's
radius and speed (a length per second), the sensor's ``range_max``, ``range_min`` and
``noise_std``, the goal tolerance and any planner length parameter given by name -- keep
every time (``dt``, the time limit) and every angle (field of view, rays, headings, turn
rate), and the trajectory scales by ``k``: the same decisions, in the same branches, at the
same times. :func:`scale_world`, :func:`scale_sim` and :func:`scale_params` build the scaled
problem; the oracle's ``scale_invariant`` check (:mod:`ifgm_ref.oracle.checks`) runs both.

With ``k`` a power of two every scaled number is exact (only the exponent changes), and so is
every sum, difference, product, quotient and square root of scaled numbers: a computation
that combines lengths only with lengths (and with dimensionless numbers) gives exactly ``k``
times the unscaled result, bit for bit, as long as nothing overflows or underflows. Any
absolute length constant (a ``1.0`` margin, a ``1e-6`` ft epsilon) breaks that.

The planner's half of a relation (:func:`moved_recording`, :func:`scaled_recording`): what a
planner was handed in one run and what it answered (a
:class:`~ifgm_ref.core.recording.Recording`), transformed into what it must be handed and
answer in the moved or scaled problem. In exact arithmetic the simulator hands the planner
exactly these observations in the transformed problem (a scan is taken in the robot's frame,
so a rigid motion leaves it as it is); the oracle replays them open loop
(:mod:`ifgm_ref.oracle.invariance`).

Sources: the units of the parameters, :class:`ifgm_ref.core.formulas.Unit`; the world's
blocks, :mod:`ifgm_ref.sim.world` and :mod:`ifgm_ref.core.params`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import replace

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import RobotParams, SensorParams, SimParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.recording import Recording
from ifgm_ref.core.validate import POSITIVE, violation
from ifgm_ref.planners.tuning import ParamInfo
from ifgm_ref.sim.world import Bounds, Circle, Obstacle, Polygon, World
from ifgm_ref.sim.worldgen.classes import placed_point, placed_pose

__all__ = [
    "is_power_of_two",
    "moved_recording",
    "scale_obstacle",
    "scale_params",
    "scale_robot",
    "scale_sensor",
    "scale_sim",
    "scale_world",
    "scaled_recording",
]


def _factor(k: float) -> float:
    if why := violation(k, POSITIVE):
        raise ParameterError(f"the scale factor {why}")
    return float(k)


def is_power_of_two(k: float) -> bool:
    """Whether ``k`` is ``2 ** n`` for an integer ``n`` (scaling by it is exact).

    >>> is_power_of_two(0.25), is_power_of_two(8.0), is_power_of_two(0.3048)
    (True, True, False)
    """
    mantissa, _ = math.frexp(k)
    return k > 0 and mantissa == 0.5


def scale_obstacle(obstacle: Obstacle, k: float) -> Obstacle:
    """``obstacle`` scaled by ``k`` about the origin (centre and radius, or every vertex).

    >>> scale_obstacle(Circle((1.0, -2.0), 0.5), 4.0)
    Circle(center=(4.0, -8.0), radius=2.0)
    """
    k = _factor(k)
    if isinstance(obstacle, Circle):
        return Circle((k * obstacle.center[0], k * obstacle.center[1]), k * obstacle.radius)
    return Polygon(tuple((k * x, k * y) for x, y in obstacle.vertices))


def scale_robot(robot: RobotParams, k: float) -> RobotParams:
    """The robot ``k`` times the size: radius, speed, braking and acceleration scaled (a length,
    a length/s, lengths/s^2), turn rate and response time kept (rad/s, s)."""
    k = _factor(k)
    return replace(
        robot,
        radius=k * robot.radius,
        speed=k * robot.speed,
        braking=k * robot.braking,
        acceleration=k * robot.acceleration,
    )


def scale_sensor(sensor: SensorParams, k: float) -> SensorParams:
    """The sensor in the scaled unit: ``range_max``, ``range_min`` and ``noise_std`` scaled;
    field of view, ray count and noise seed kept.

    Gaussian noise of standard deviation ``k * s`` is ``k`` times the noise of ``s`` from the
    same seed (numpy draws ``s * z`` from the same standard normal ``z``).
    """
    k = _factor(k)
    return replace(
        sensor,
        range_max=k * sensor.range_max,
        range_min=k * sensor.range_min,
        noise_std=k * sensor.noise_std,
    )


def scale_world(world: World, k: float) -> World:
    """``world`` with every length scaled by ``k`` about the origin.

    Scaled: obstacles, bounds, the start position, the goal, the robot (radius, speed) and
    the sensor (:func:`scale_sensor`). Kept: the start heading, the robot's turn rate, the
    sensor's angles and rays, the name.

    >>> w = World(start=(1, 2, 0.5), goal=(10, 0), obstacles=[Circle((5, 3), 1.0)],
    ...           bounds=(-20, -20, 20, 20))
    >>> s = scale_world(w, 0.5)
    >>> s.start, s.goal
    (Pose(x=0.5, y=1.0, theta=0.5), Point(x=5.0, y=0.0))
    >>> s.obstacles[0], tuple(s.bounds)
    (Circle(center=(2.5, 1.5), radius=0.5), (-10.0, -10.0, 10.0, 10.0))
    >>> s.robot.radius, s.robot.max_turn_rate == w.robot.max_turn_rate, s.sensor.range_max
    (0.5, True, 7.5)
    """
    k = _factor(k)
    bounds = None if world.bounds is None else Bounds(*(k * b for b in world.bounds))
    return World(
        start=Pose(k * world.start.x, k * world.start.y, world.start.theta),
        goal=Point(k * world.goal.x, k * world.goal.y),
        obstacles=tuple(scale_obstacle(ob, k) for ob in world.obstacles),
        bounds=bounds,
        robot=scale_robot(world.robot, k),
        sensor=scale_sensor(world.sensor, k),
        name=world.name,
    )


def scale_sim(sim: SimParams, k: float) -> SimParams:
    """``sim`` with the goal tolerance scaled by ``k``; the times ``dt``, ``max_time`` and
    ``stall_time`` kept."""
    return replace(sim, goal_tolerance=_factor(k) * sim.goal_tolerance)


def scale_params(
    params: Mapping[str, object], infos: Iterable[ParamInfo], k: float
) -> dict[str, object]:
    """Planner parameters given by name, in the scaled unit: each times ``k ** p``, ``p`` the
    ``length_power`` of its declared unit (1 for a length, 4 for APF's ``eta``, 0 for a time,
    angle or number).

    A name the planner does not declare has no known unit: :class:`ParameterError`.

    >>> from ifgm_ref.core.formulas import Unit
    >>> infos = [ParamInfo("d_th", "3*r", Unit.LENGTH), ParamInfo("w_g", "9", Unit.NUMBER),
    ...          ParamInfo("eta", "50*r**4", Unit.LENGTH4)]
    >>> scale_params({"d_th": 3.0, "w_g": 9.0, "eta": 1.0}, infos, 2.0)
    {'d_th': 6.0, 'w_g': 9.0, 'eta': 16.0}
    """
    k = _factor(k)
    units = {info.name: info.unit for info in infos}
    unknown = sorted(name for name in params if name not in units)
    if unknown:
        raise ParameterError(
            f"cannot scale parameter(s) {', '.join(unknown)}: no declared unit; "
            f"declared: {', '.join(units) or 'none'}"
        )
    scaled: dict[str, object] = {}
    for name, value in params.items():
        power = units[name].length_power
        if power and (isinstance(value, bool) or not isinstance(value, int | float)):
            raise ParameterError(f"`{name}` must be a number to scale, got {value!r}")
        scaled[name] = value * k**power if power else value  # type: ignore[operator]
    return scaled


def moved_recording(recording: Recording, angle: float, shift: tuple[float, float]) -> Recording:
    """The exchange of ``recording``'s problem rotated by ``angle`` about the origin and shifted
    by ``shift`` (ft), as :func:`~ifgm_ref.sim.worldgen.classes.placed` moves a world.

    Moved: the start, the goal, and every pose and goal handed to the planner
    (:func:`~ifgm_ref.sim.worldgen.classes.placed_pose`, ``placed_point``); every heading it
    answered turned by ``angle``. Kept: times, scans (taken in the robot's frame), the episode
    parameters, and every speed, behaviour, branch and stop it answered.

    >>> from ifgm_ref.core.laserscan import LaserScan
    >>> from ifgm_ref.core.protocol import EpisodeParams
    >>> scan = LaserScan(-1.0, 1.0, 1.0, 0.0, 10.0, [3.0, 4.0, 5.0])
    >>> seen = Observation(0.0, Pose(1.0, 0.0, 0.0), Point(5.0, 0.0), scan)
    >>> was = Recording(Pose(1.0, 0.0, 0.0), Point(5.0, 0.0), EpisodeParams(),
    ...                 ((seen, Command(0.25, 1.0)),))
    >>> moved = moved_recording(was, math.pi / 2, (10.0, 0.0))
    >>> (observation, command), = moved.steps
    >>> observation.pose, observation.scan == scan, command.heading - math.pi / 2
    (Pose(x=10.0, y=1.0, theta=1.5707963267948966), True, 0.25)
    """

    def move(observation: Observation) -> Observation:
        pose = placed_pose(observation.pose, angle, shift)
        return replace(observation, pose=pose, goal=placed_point(observation.goal, angle, shift))

    return _transformed(
        recording,
        placed_pose(recording.start, angle, shift),
        placed_point(recording.goal, angle, shift),
        recording.params,
        move,
        lambda command: replace(command, heading=command.heading + angle),
    )


def scaled_recording(
    recording: Recording, k: float, params: Mapping[str, object] | None = None
) -> Recording:
    """The exchange of ``recording``'s problem with every length scaled by ``k``, as
    :func:`scale_world` and :func:`scale_sim` scale the problem.

    Scaled: the start and goal positions and every pose position and goal handed to the
    planner, every scan's ranges and range limits, the robot and the sensor
    (:func:`scale_robot`, :func:`scale_sensor`), the goal tolerance, and every speed the
    planner answered. Kept: times, headings, scan angles, ``dt``, and every heading,
    behaviour, branch and stop it answered. ``params`` are the planner parameters in the
    scaled unit (:func:`scale_params`); by default the recorded ones, kept.

    >>> from ifgm_ref.core.laserscan import LaserScan
    >>> from ifgm_ref.core.protocol import EpisodeParams
    >>> scan = LaserScan(-1.0, 1.0, 1.0, 0.0, 10.0, [3.0, 4.0, float("inf")])
    >>> seen = Observation(0.5, Pose(1.0, 2.0, 0.3), Point(5.0, 0.0), scan)
    >>> was = Recording(Pose(1.0, 2.0, 0.3), Point(5.0, 0.0), EpisodeParams(),
    ...                 ((seen, Command(0.25, 1.0)),))
    >>> (observation, command), = scaled_recording(was, 2.0).steps
    >>> observation.pose, list(observation.scan.ranges), observation.scan.range_max
    (Pose(x=2.0, y=4.0, theta=0.3), [6.0, 8.0, inf], 20.0)
    >>> command.heading, command.speed
    (0.25, 2.0)
    """
    k = _factor(k)
    episode = recording.params
    handed = replace(
        episode,
        robot=scale_robot(episode.robot, k),
        sensor=scale_sensor(episode.sensor, k),
        params=dict(episode.params if params is None else params),
        goal_tolerance=k * episode.goal_tolerance,
    )

    def scale(observation: Observation) -> Observation:
        pose, goal, scan = observation.pose, observation.goal, observation.scan
        return replace(
            observation,
            pose=Pose(k * pose.x, k * pose.y, pose.theta),
            goal=Point(k * goal.x, k * goal.y),
            scan=replace(
                scan,
                range_min=k * scan.range_min,
                range_max=k * scan.range_max,
                ranges=k * scan.ranges,
            ),
        )

    return _transformed(
        recording,
        Pose(k * recording.start.x, k * recording.start.y, recording.start.theta),
        Point(k * recording.goal.x, k * recording.goal.y),
        handed,
        scale,
        lambda command: replace(command, speed=k * command.speed),
    )


def _transformed(
    recording: Recording,
    start: Pose,
    goal: Point,
    params: EpisodeParams,
    observation: Callable[[Observation], Observation],
    command: Callable[[Command], Command],
) -> Recording:
    """``recording`` reset with ``start``, ``goal`` and ``params``, each step's observation
    mapped by ``observation`` and its command by ``command``."""
    steps = tuple((observation(seen), command(said)) for seen, said in recording.steps)
    return Recording(start, goal, params, steps)
