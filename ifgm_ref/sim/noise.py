"""Less perfect worlds: the simulator's range, odometry and actuation noise.

Every model is off by default, seeded, and relative to the robot and the sensor, so that a
level means the same for the paper's 1 ft robot and BARN's 0.22 m one (errata row 29).
Symbols: ``r`` the robot radius, ``R`` the sensor's ``range_max``, ``d`` the distance the
robot's centre moved in one step, ``N(0, s)`` a Gaussian draw, ``U(a, b)`` a uniform one.

* **Range** (:class:`~ifgm_ref.core.params.SensorParams`): a ray of true range ``rho`` reads
  no return with probability ``dropout``, else a false return ``U(range_min, min(rho, R))``
  with probability ``spurious``, else ``rho + N(0, sqrt(noise_std**2 + (noise_rel *
  rho)**2))``; each kind draws a fixed count of numbers per scan from its own generator.
* **Odometry** (:class:`~ifgm_ref.core.params.RobotParams`, ``odometry_drift = k``): the
  believed pose is the true pose plus a random walk, at every step
  ``e_x, e_y += N(0, k sqrt(r d))``, ``e_theta += N(0, k sqrt(d / r))``; the heading
  controller turns the *believed* heading to the command. Collisions, the goal and the stall
  rules are judged on the true pose.
* **Actuation** (``actuation_noise = s``, ``latency = k``): the command decided at step
  ``n - k`` runs at step ``n``, its turn and speed each times ``1 + N(0, s)``, never backwards.

The robot block's ``seed`` seeds odometry and actuation, the sensor block's the range noise:
same seeds, same trace. The models in full, and the reasons: ``docs/noise.md``.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.core.pose import Pose, wrap_angle
from ifgm_ref.core.protocol import Command
from ifgm_ref.core.validate import NON_NEGATIVE, violation
from ifgm_ref.sim.world import World

#: Salts of the independent generators drawn from one seed.
_GAUSS, _DROPOUT, _SPURIOUS, _ODOMETRY, _ACTUATION = range(5)


def _generator(seed: int, salt: int) -> np.random.Generator:
    """The generator of one noise kind: the seed alone for range noise (as before the other
    kinds existed), the seed and a salt otherwise."""
    return np.random.default_rng(seed if salt == _GAUSS else [seed, salt])


class RangeNoise:
    """The sensor's noise: Gaussian (constant and proportional), dropouts, spurious returns."""

    def __init__(self, params: SensorParams) -> None:
        self.params = params
        self._gauss = _generator(params.seed, _GAUSS)
        self._dropout = _generator(params.seed, _DROPOUT)
        self._spurious = _generator(params.seed, _SPURIOUS)

    @property
    def active(self) -> bool:
        """Whether any range noise is on."""
        p = self.params
        return bool(p.noise_std or p.noise_rel or p.dropout or p.spurious)

    def apply(self, ranges: NDArray[np.float64]) -> None:
        """Make the exact ``ranges`` of one scan noisy, in place (before REP 117's clipping:
        the caller reads below 0 as 0, beyond ``range_max`` as no return)."""
        p, n = self.params, len(ranges)
        true = ranges.copy() if p.spurious else ranges
        if p.noise_std or p.noise_rel:
            z = self._gauss.standard_normal(n)
            sigma = p.noise_std if not p.noise_rel else np.hypot(p.noise_std, p.noise_rel * ranges)
            returns = np.isfinite(ranges)
            ranges[returns] += (sigma * z)[returns] if p.noise_rel else sigma * z[returns]
        if p.spurious:
            hit = self._spurious.random(n) < p.spurious
            depth = self._spurious.random(n)
            far = np.minimum(true, p.range_max)
            false = p.range_min + depth * np.maximum(far - p.range_min, 0.0)
            ranges[hit] = false[hit]
        if p.dropout:
            lost = self._dropout.random(n) < p.dropout
            ranges[lost] = np.inf


class Odometry:
    """The pose the planner is told: the true pose plus a random walk per distance travelled."""

    def __init__(self, robot: RobotParams) -> None:
        self.drift = robot.odometry_drift
        self.radius = robot.radius
        self._rng = _generator(robot.seed, _ODOMETRY)
        self.error = (0.0, 0.0, 0.0)

    def believed(self, pose: Pose) -> Pose:
        """What odometry says of the true ``pose``."""
        if not self.drift:
            return pose
        ex, ey, et = self.error
        return Pose(pose.x + ex, pose.y + ey, wrap_angle(pose.theta + et))

    def true_heading(self, heading: float) -> float:
        """The true heading a command to face ``heading`` turns the robot towards: its heading
        controller knows only the believed heading, so it is ``e_theta`` off."""
        return heading - self.error[2]

    def moved(self, distance: float) -> None:
        """The robot's centre moved ``distance``: the error walks on."""
        if not self.drift:
            return
        k, r = self.drift, self.radius
        step = k * math.sqrt(r * distance)
        dx, dy, dt = self._rng.standard_normal(3)
        ex, ey, et = self.error
        self.error = (ex + step * dx, ey + step * dy, et + k * math.sqrt(distance / r) * dt)


class Actuation:
    """The command the robot executes: ``latency`` steps late, turn and speed scaled by
    ``1 + N(0, actuation_noise)``."""

    def __init__(self, robot: RobotParams) -> None:
        self.noise = robot.actuation_noise
        self._rng = _generator(robot.seed, _ACTUATION)
        self._queue: deque[Command | None] = deque([None] * robot.latency)

    def executed(self, command: Command, pose: Pose) -> tuple[Command, float, float]:
        """The command executed now, given the one just decided, and the factors on its turn
        and speed."""
        self._queue.append(command)
        late = self._queue.popleft()
        if late is None:  # nothing decided yet: stand still
            late = Command(pose.theta, 0.0)
        if not self.noise:
            return late, 1.0, 1.0
        turn, speed = 1.0 + self.noise * self._rng.standard_normal(2)
        return late, float(turn), max(0.0, float(speed))


#: The noise kinds of :class:`NoiseLevels`, as ``--noise KIND=LEVEL`` names them.
KINDS = ("range", "range_const", "dropout", "spurious", "odometry", "actuation", "latency")
#: The kinds whose level is a probability.
PROBABILITIES = ("dropout", "spurious")


def _level(kind: str, text: str) -> float | int:
    """The level ``text`` of ``kind``; :class:`ValueError` saying what it must be if it is
    none: a number, and then an integer >= 0 (``latency``), a probability in [0, 1]
    (:data:`PROBABILITIES`) or a finite number >= 0 (the others)."""
    try:
        level = float(text)
    except ValueError:
        raise ValueError("a number") from None
    if kind == "latency":
        if not level.is_integer() or level < 0:
            raise ValueError("an integer >= 0")
        return int(level)
    if kind in PROBABILITIES and not 0 <= level <= 1:
        raise ValueError("a probability in [0, 1]")
    if violation(level, NON_NEGATIVE):
        raise ValueError(f"a finite number {NON_NEGATIVE}")
    return level


@dataclass(frozen=True)
class NoiseLevels:
    """Noise levels, each relative to the robot or the sensor (0: off).

    Parameters
    ----------
    range : float
        Gaussian range noise proportional to the range: its standard deviation as a fraction
        of the true range (``noise_rel``).
    range_const : float
        Constant Gaussian range noise as a fraction of the sensor's ``range_max``
        (``noise_std = range_const * range_max``).
    dropout, spurious : float
        Probabilities of a ray reading no return, or a false short return.
    odometry : float
        ``odometry_drift`` ``k``: the position error gains ``k r`` over each stretch of length
        ``r`` (a random walk; the module docstring).
    actuation : float
        ``actuation_noise``: the standard deviation of the executed turn and speed, relative.
    latency : int
        Steps between a decision and its execution.
    """

    range: float = 0.0
    range_const: float = 0.0
    dropout: float = 0.0
    spurious: float = 0.0
    odometry: float = 0.0
    actuation: float = 0.0
    latency: int = 0

    @classmethod
    def parse(cls, text: str, option: str = "--noise") -> NoiseLevels:
        """Levels from ``"KIND=LEVEL,..."`` (``KINDS``); ``""`` or ``"none"`` is no noise. A
        level out of its kind's domain is refused here, naming the item as written after
        ``option`` (the command line's option that gave ``text``), not the parameter blocks'
        fields it sets (``range`` sets ``noise_rel``).

        >>> NoiseLevels.parse("range=0.02,dropout=0.05,odometry=0.01").tags()
        'range=0.02,dropout=0.05,odometry=0.01'
        >>> NoiseLevels.parse("range=x")
        Traceback (most recent call last):
        ...
        ifgm_ref.core.errors.ParameterError: --noise range=x: the level must be a number
        >>> NoiseLevels.parse("range=-1")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        ifgm_ref.core.errors.ParameterError: --noise range=-1: the level must be a finite ...
        """
        levels: dict[str, float | int] = {}
        for item in filter(None, (part.strip() for part in text.split(","))):
            if item == "none":
                continue
            kind, sep, value = item.partition("=")
            if not sep or kind not in KINDS:
                raise ParameterError(
                    f"{option} {item}: expected KIND=LEVEL with KIND one of {', '.join(KINDS)}"
                )
            try:
                levels[kind] = _level(kind, value)
            except ValueError as why:
                raise ParameterError(f"{option} {item}: the level must be {why}") from None
        return cls(**levels)  # type: ignore[arg-type]

    @property
    def on(self) -> bool:
        """Whether any level is on.

        >>> NoiseLevels().on, NoiseLevels(latency=1).on
        (False, True)
        """
        return self != NoiseLevels()

    def tags(self) -> str:
        """The levels that are on, as ``parse`` reads them (``"none"`` if none is)."""
        on = [f"{k}={getattr(self, k)}" for k in KINDS if getattr(self, k)]
        return ",".join(on) or "none"

    def apply(self, world: World, seed: int | None = None) -> World:
        """``world`` with these levels in its sensor and robot blocks (and both seeds set to
        ``seed``, if given); a level of 0 leaves the block's own setting."""
        sensor, robot = world.sensor, world.robot
        sensor_changes: dict[str, float | int] = {
            name: value
            for name, value in (
                ("noise_rel", self.range),
                ("noise_std", self.range_const * sensor.range_max),
                ("dropout", self.dropout),
                ("spurious", self.spurious),
            )
            if value
        }
        robot_changes: dict[str, float | int] = {
            name: value
            for name, value in (
                ("odometry_drift", self.odometry),
                ("actuation_noise", self.actuation),
                ("latency", self.latency),
            )
            if value
        }
        if seed is not None:
            sensor_changes["seed"] = robot_changes["seed"] = seed
        return replace(
            world,
            sensor=replace(sensor, **sensor_changes),  # type: ignore[arg-type]
            robot=replace(robot, **robot_changes),  # type: ignore[arg-type]
        )
