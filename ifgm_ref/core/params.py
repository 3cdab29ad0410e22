"""Robot, sensor and simulation parameters, with every default in one place.

The paper (section 5.1) reports an obstacle-free run of 197 ft covered in 149 s; that fixes the
default forward speed. It gives no robot size, turn rate, sensor range or resolution: the
values below are our choices, each with its reason, and each can be overridden in a world
file's ``robot`` and ``sensor`` blocks or on the command line.

Units: any consistent length unit (feet for the paper's worlds, metres for BARN's), seconds,
radians. Nothing here or in the planners assumes feet: every planner length is derived from
the robot and the sensor (:mod:`ifgm_ref.planners.tuning`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from enum import StrEnum
from typing import Any, Final, Literal, Self

from ifgm_ref.core.elements import traces
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.validate import NON_NEGATIVE, POSITIVE, require

#: Straight-line source-to-destination distance of the paper's Scenario 1, ft (section 5.1).
PAPER_FREE_DISTANCE_FT = 197.0
#: Time of the paper's obstacle-free run over that distance, s (section 5.1).
PAPER_FREE_TIME_S = 149.0


#: Metadata of a field a protocol message may leave out (the noise models came later: a
#: ``reset`` written before them still reads, with the noise off).
OPTIONAL = {"optional": True}


def _noise(default: float | int = 0) -> Any:
    """A noise field: off (0) by default, optional in a protocol message."""
    return field(default=default, metadata=OPTIONAL)


#: Metadata of a field of the robot's dynamics (its braking, acceleration and response). The
#: paper's robot stops and speeds up at once: infinite limits, no response time, which JSON
#: cannot all hold. Such a field is left out of a message or file while it has its default,
#: and reads as the default when absent, so that the paper's robot is written as before.
DYNAMICS = {"optional": True, "dynamics": True}


def _dynamics(default: float = math.inf) -> Any:
    """A dynamics field: the paper's instant robot by default."""
    return field(default=default, metadata=DYNAMICS)


def _limit(name: str, value: float) -> None:
    if value != math.inf:
        require(name, value, POSITIVE)


def _probability(name: str, value: float) -> None:
    require(name, value, NON_NEGATIVE)
    if value > 1:
        raise ParameterError(f"`{name}` must be a probability in [0, 1], got {value!r}")


def _count(name: str, value: object) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise ParameterError(f"`{name}` must be an integer >= 0, got {value!r}")


class _Block:
    """Mixin: build a parameter block from a JSON mapping and write it back."""

    @classmethod
    def from_mapping(cls, data: dict[str, Any], *, where: str) -> Self:
        """Build the block from ``data``, overriding defaults; unknown keys are an error."""
        if not isinstance(data, dict):
            raise ParameterError(f"{where}: must be an object, got {type(data).__name__}")
        names = {f.name for f in fields(cls)}  # type: ignore[arg-type]
        unknown = sorted(set(data) - names)
        if unknown:
            raise ParameterError(
                f"{where}: unknown field(s) {', '.join(unknown)}; "
                f"allowed: {', '.join(sorted(names))}"
            )
        try:
            return cls(**data)
        except ParameterError as err:
            raise ParameterError(f"{where}: {err}") from None

    def to_mapping(self) -> dict[str, Any]:
        """The block as a JSON-ready mapping (every field, defaults included, but for the
        dynamics fields left at the paper's robot's, :data:`DYNAMICS`)."""
        return {
            f.name: getattr(self, f.name)
            for f in fields(self)  # type: ignore[arg-type]
            if not (f.metadata.get("dynamics") and getattr(self, f.name) == f.default)
        }


@dataclass(frozen=True)
class RobotParams(_Block):
    """A disc robot with unicycle kinematics (section 4: "cylindrical shaped robot").

    Parameters
    ----------
    radius : float, default 1.0
        Disc radius r in ft. The paper gives none; 1 ft is a small indoor platform, well below
        the gaps of its figures, and makes ``d_th`` > 2 r easy to read.
    speed : float, default 197/149
        Constant forward speed v in ft/s: the paper's 197 ft obstacle-free run in 149 s.
    max_turn_rate : float, default pi/2
        Largest heading change per second, rad/s. The paper's stepper-motor platform turns in
        45-degree steps (section 4, Case-3); 90 deg/s lets one such step take half a second.
    odometry_drift : float, default 0
        Odometry noise ``k``: the pose the planner is told walks away from the true one, its
        position error gaining ``k r`` over each stretch of ``r`` travelled
        (:mod:`ifgm_ref.sim.noise`).
    actuation_noise : float, default 0
        Standard deviation of the executed turn and speed, relative to the commanded ones.
    latency : int, default 0
        Steps between a decision and its execution.
    seed : int, default 0
        Seed of the odometry and actuation noise.
    braking : float, default inf
        The deceleration ``b`` the robot is guaranteed when commanded slower than it moves,
        turning or not, length/s^2. The paper's robot stops at once (``inf``); a robot with
        mass has a finite ``b``, and every planner then brakes in time
        (:mod:`ifgm_ref.planners.governor`, errata row 36).
    acceleration : float, default inf
        The largest acceleration ``A`` of the robot, length/s^2 (``inf``: it reaches any
        commanded speed at once).
    response : float, default 0
        How long after a command the robot may still move as under the one before, s (its
        motors' and controller's lag; 0: at once). The braking governor allows for it.
    """

    radius: float = 1.0
    speed: float = PAPER_FREE_DISTANCE_FT / PAPER_FREE_TIME_S
    max_turn_rate: float = math.pi / 2
    odometry_drift: float = _noise(0.0)
    actuation_noise: float = _noise(0.0)
    latency: int = _noise()
    seed: int = _noise()
    braking: float = _dynamics()
    acceleration: float = _dynamics()
    response: float = _dynamics(0.0)

    def __post_init__(self) -> None:
        require("radius", self.radius, POSITIVE)
        require("speed", self.speed, POSITIVE)
        require("max_turn_rate", self.max_turn_rate, POSITIVE)
        require("odometry_drift", self.odometry_drift, NON_NEGATIVE)
        require("actuation_noise", self.actuation_noise, NON_NEGATIVE)
        _count("latency", self.latency)
        _count("seed", self.seed)
        _limit("braking", self.braking)
        _limit("acceleration", self.acceleration)
        require("response", self.response, NON_NEGATIVE)
        if self.braking != math.inf and self.acceleration == math.inf:
            raise ParameterError(
                "`acceleration` is needed with `braking`: a robot that may reach any speed "
                f"within a step cannot be kept able to stop (braking={self.braking!r})"
            )

    @property
    def stops_at_once(self) -> bool:
        """Whether the robot stops at once (infinite ``braking``): the paper's robot."""
        return self.braking == math.inf


@traces("sensor.fov")
@dataclass(frozen=True)
class SensorParams(_Block):
    """The paper's IR range sensor on a stepper motor (section 4, Figure 2).

    Parameters
    ----------
    fov : float, default 3 pi / 4
        Field of view in radians, centred on the heading: 135 degrees, from -67.5 to +67.5
        degrees (section 4).
    rays : int, default 76
        Number of rays over the field of view, both ends included, so the angular resolution
        is ``fov / (rays - 1)``: 1.8 degrees by default, one full step of a common 200-step
        stepper motor. 76 rays put rays exactly on the beam borders at +-22.5 degrees.
    range_max : float, default 15.0
        Maximum range in ft. The paper's "single long range IR" is not specified; long-range IR
        rangers reach about 5 m (16 ft).
    range_min : float, default 0.0
        Minimum range in ft; nearer returns read ``-inf`` (REP 117).
    noise_std : float, default 0.0
        Standard deviation of additive Gaussian range noise in ft (off by default).
    seed : int, default 0
        Seed of the noise generator, so noisy runs are reproducible.
    noise_rel : float, default 0.0
        Standard deviation of Gaussian range noise proportional to the range, a fraction of it.
    dropout : float, default 0.0
        Probability that a ray reads no return.
    spurious : float, default 0.0
        Probability that a ray reads a false return nearer than what it sees
        (:mod:`ifgm_ref.sim.noise` gives every model's formula).
    """

    fov: float = 3.0 * math.pi / 4.0
    rays: int = 76
    range_max: float = 15.0
    range_min: float = 0.0
    noise_std: float = 0.0
    seed: int = 0
    noise_rel: float = _noise(0.0)
    dropout: float = _noise(0.0)
    spurious: float = _noise(0.0)

    def __post_init__(self) -> None:
        require("fov", self.fov, POSITIVE)
        if self.fov >= 2.0 * math.pi:
            raise ParameterError(f"`fov` must be < 2 pi, got {self.fov!r}")
        if isinstance(self.rays, bool) or not isinstance(self.rays, int) or self.rays < 2:
            raise ParameterError(f"`rays` must be an integer >= 2, got {self.rays!r}")
        require("range_max", self.range_max, POSITIVE)
        require("range_min", self.range_min, NON_NEGATIVE)
        if self.range_min >= self.range_max:
            raise ParameterError(
                f"`range_min` must be < `range_max`, got {self.range_min!r} >= {self.range_max!r}"
            )
        require("noise_std", self.noise_std, NON_NEGATIVE)
        _count("seed", self.seed)
        require("noise_rel", self.noise_rel, NON_NEGATIVE)
        _probability("dropout", self.dropout)
        _probability("spurious", self.spurious)

    @property
    def angle_increment(self) -> float:
        """Angle between consecutive rays, radians."""
        return self.fov / (self.rays - 1)


#: :attr:`SimParams.stall_time`'s default: the stall time derived from the robot and the time
#: step (:data:`ifgm_ref.sim.simulator.STALL_TIME`).
AUTO: Final = "auto"
#: The default time step, s (:class:`SimParams`, and the planner's
#: :class:`~ifgm_ref.core.protocol.EpisodeParams`).
DT: Final = 0.1
#: The default goal tolerance, ft (the same two).
GOAL_TOLERANCE: Final = 0.5


class EngineName(StrEnum):
    """The engines that move the robot (:mod:`ifgm_ref.sim.engine`, ``--engine``), each made
    by :data:`ifgm_ref.sim.engine.ENGINE_FACTORIES`.

    >>> EngineName("mujoco") is EngineName.MUJOCO, f"{EngineName.KINEMATIC}"
    (True, 'kinematic')
    """

    #: The paper's instant robot (the default).
    KINEMATIC = "kinematic"
    #: A robot with mass on the MuJoCo physics engine; the only one with a ``body``.
    MUJOCO = "mujoco"


#: The engines' names; the first is the default.
ENGINES: Final = tuple(EngineName)


def engine_named(name: str) -> EngineName:
    """The engine ``name``, or a :class:`ParameterError` naming the known ones.

    >>> engine_named("physx")
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `engine` must be one of kinematic, mujoco, got 'physx'
    """
    try:
        return EngineName(name)
    except ValueError:
        known = ", ".join(ENGINES)
        raise ParameterError(f"`engine` must be one of {known}, got {name!r}") from None


@dataclass(frozen=True)
class SimParams:
    """How a simulation is run.

    Parameters
    ----------
    dt : float, default 0.1
        Fixed time step in s: the robot moves 0.13 ft per step at the default speed, far below
        the robot radius, so the decision rate does not limit safety.
    max_time : float, default 600.0
        Time limit in s: four times the paper's longest reported run (205 s for Dist-Bug).
    goal_tolerance : float, default 0.5
        The goal counts as reached when the robot's centre is this close, in ft.
    stall_time : float, "auto" or None, default "auto"
        End the episode as ``stalled`` once the robot's centre has stayed within one robot
        radius of where it was this many seconds before, for all of them (the stall rule of
        :mod:`ifgm_ref.sim.simulator`). ``"auto"`` derives it from the robot and ``dt``
        (:data:`ifgm_ref.sim.simulator.STALL_TIME`: 12 s for the paper's robot); ``None`` or 0
        turns this rule off (the lap rule is switched by ``stall_laps``).
    stall_laps : int or None, default 2
        End the episode as ``stalled`` once the robot has come back to one place after this
        many laps in a row with no better distance to the goal (the lap rule of
        :mod:`ifgm_ref.sim.simulator`, thresholds in :mod:`ifgm_ref.sim.laps`); ``None`` or 0 turns
        this rule off. With both rules off a robot that makes no progress runs to
        ``max_time``.
    engine : EngineName or str, default "kinematic"
        What senses and moves the robot (:mod:`ifgm_ref.sim.engine`): ``kinematic``, the paper's
        instant robot, or ``mujoco``, a robot with mass on the MuJoCo physics engine
        (:mod:`ifgm_ref.sim.physics`).
    body : str or None, default None
        The ``mujoco`` engine's robot body (:data:`ifgm_ref.sim.physics.bodies.BODIES`:
        ``paper`` or ``jackal``); ``None`` takes the Jackal for BARN's robot and the
        paper's otherwise. The kinematic engine has no body: a body with it is a
        :class:`ParameterError` here, the one place this rule is checked.
    """

    dt: float = DT
    max_time: float = 600.0
    goal_tolerance: float = GOAL_TOLERANCE
    stall_time: float | Literal["auto"] | None = AUTO
    stall_laps: int | None = 2
    engine: EngineName | str = EngineName.KINEMATIC  # made an EngineName on construction
    body: str | None = None

    def __post_init__(self) -> None:
        require("dt", self.dt, POSITIVE)
        require("max_time", self.max_time, POSITIVE)
        object.__setattr__(self, "engine", engine_named(self.engine))
        if self.body is not None and not isinstance(self.body, str):
            raise ParameterError(f"`body` must be a body's name or None, got {self.body!r}")
        if self.body is not None and self.engine is not EngineName.MUJOCO:  # the one place
            raise ParameterError(f"`body` applies to the mujoco engine only, got {self.body!r}")
        require("goal_tolerance", self.goal_tolerance, POSITIVE)
        if self.stall_time is not None and self.stall_time != AUTO:
            if isinstance(self.stall_time, str):
                raise ParameterError(
                    f"`stall_time` must be a number, {AUTO!r} or None, got {self.stall_time!r}"
                )
            require("stall_time", self.stall_time, NON_NEGATIVE)
        if self.stall_laps is not None:
            _count("stall_laps", self.stall_laps)


def paper_ir(length_scale: float = 1.0) -> SensorParams:
    """The paper's IR sensor (section 4, Figure 2): 135 degrees in 76 rays, 15 ft of range.

    ``length_scale`` converts the ranges to another robot or unit: the sensor of a robot
    ``length_scale`` times the size of the paper's 1 ft robot (``paper_ir(0.22)`` for a 0.22 m
    disc in metres: 3.3 m of range). Angles and the ray count do not change.

    >>> paper_ir().range_max, paper_ir(0.22).rays, round(paper_ir(0.22).range_max, 6)
    (15.0, 76, 3.3)
    """
    require("length_scale", length_scale, POSITIVE)
    base = SensorParams()
    return SensorParams(
        fov=base.fov,
        rays=base.rays,
        range_max=base.range_max * length_scale,
        range_min=base.range_min * length_scale,
    )


def jackal_lidar() -> SensorParams:
    """The 2D LiDAR of BARN's Clearpath Jackal: 270 degrees in 720 rays, 0.1 to 30 m.

    Units are metres. The field of view and ray count are BARN's
    (``ifgm_ref/io/barn_worlds/README.md``); the range is that of the Jackal's simulated
    laser (30 m, more than any BARN world needs).

    >>> s = jackal_lidar()
    >>> round(math.degrees(s.fov)), s.rays, s.range_max
    (270, 720, 30.0)
    """
    return SensorParams(fov=1.5 * math.pi, rays=720, range_max=30.0, range_min=0.1)


def lidar_180() -> SensorParams:
    """A common 2D LiDAR looking ahead only: 180 degrees in 720 rays, 0.1 to 30 m.

    Units are metres (as :func:`jackal_lidar`, the 270-degree one).

    >>> s = lidar_180()
    >>> round(math.degrees(s.fov)), s.rays, s.range_min, s.range_max
    (180, 720, 0.1, 30.0)
    """
    return SensorParams(fov=math.pi, rays=720, range_max=30.0, range_min=0.1)


#: Sensor presets by name (``--sensor NAME`` on the command line).
SENSOR_PRESETS = {"paper_ir": paper_ir, "jackal_lidar": jackal_lidar, "lidar_180": lidar_180}
#: The length unit each preset of :data:`SENSOR_PRESETS` is written in.
SENSOR_PRESET_UNITS = {"paper_ir": "ft", "jackal_lidar": "m", "lidar_180": "m"}


#: The robot's fields ``--robot NAME=VALUE`` sets (its noise has ``--noise``).
ROBOT_OPTIONS = ("radius", "speed", "max_turn_rate", "braking", "acceleration", "response")


def robot_changes(text: str, *, option: str = "--robot") -> dict[str, float]:
    """The robot's fields ``"NAME=VALUE,..."`` sets (:data:`ROBOT_OPTIONS`), checked as a
    robot of the defaults would check them; errors name ``option`` and the item.

    >>> robot_changes("speed=2,braking=4.9,acceleration=4.9")
    {'speed': 2.0, 'braking': 4.9, 'acceleration': 4.9}
    >>> robot_changes("mass=3")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: --robot mass=3: expected NAME=VALUE with NAME one of ...
    >>> robot_changes("speed=-1")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: --robot speed=-1: `speed` must be a finite number > 0, ...
    """
    changes: dict[str, float] = {}
    for item in filter(None, (part.strip() for part in text.split(","))):
        name, sep, value = item.partition("=")
        if not sep or name not in ROBOT_OPTIONS:
            raise ParameterError(
                f"{option} {item}: expected NAME=VALUE with NAME one of {', '.join(ROBOT_OPTIONS)}"
            )
        try:
            changes[name] = float(value)
        except ValueError:
            raise ParameterError(f"{option} {item}: the value must be a number") from None
        try:
            replace(RobotParams(), **{name: changes[name], "acceleration": 1.0})  # type: ignore[arg-type]
        except ParameterError as err:
            raise ParameterError(f"{option} {item}: {err}") from None
    return changes


def changed_robot(
    robot: RobotParams, changes: Mapping[str, float], *, option: str = "--robot"
) -> RobotParams:
    """``robot`` with ``changes`` (:func:`robot_changes`); a robot they leave inconsistent (a
    finite braking with no acceleration) is refused naming ``option``.

    >>> changed_robot(RobotParams(), {"speed": 2.0}).speed
    2.0
    >>> changed_robot(RobotParams(), {"braking": 3.0})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: --robot: `acceleration` is needed with `braking`: ...
    """
    try:
        return replace(robot, **changes)  # type: ignore[arg-type]
    except ParameterError as err:
        raise ParameterError(f"{option}: {err}") from None
