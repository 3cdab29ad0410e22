"""The paper's range sensor: one IR ranger swept over 135 degrees, as a ``LaserScan``.

Reference: "An Improved Algorithm for Collision Avoidance in Environments Having U and H Shaped
Obstacles" (IFGM and IBA), section 4 and Figure 2. The paper's robot carries a single long-range
IR sensor on a stepper motor "restricted to rotate from -67.5 to 67.5 degrees", a field of view
of 135 degrees that the paper splits into three consecutive 45-degree beams: front from -22.5
to 22.5 degrees, left from -67.5 to -22.5 and right from 22.5 to 67.5 (the paper's signs, see
below). In simulation "the beam of IR sensor is defined by the pixels"; here it is a fan of
exact rays.

Parameters (:class:`~ifgm_ref.core.params.SensorParams`) and their meaning in the paper:

=============  ======================================================================
``fov``        the 135-degree field of view (section 4), centred on the heading
``rays``       the stepper motor's positions over the sweep (not given by the paper)
``range_max``  the "long range" of the IR sensor (not given by the paper)
``range_min``  nearer returns read ``-inf`` (REP 117; the paper has no minimum)
``noise_std``  additive Gaussian range noise (the paper's simulations are noise-free)
``seed``       seed of the noise generator
=============  ======================================================================

Conventions (see :mod:`ifgm_ref.core.laserscan`): angles in the robot frame, REP-103 (x forward,
y left, counter-clockwise positive), so a positive angle looks *left*. The paper's text names
the beam from -67.5 to -22.5 degrees "left", i.e. it counts angles clockwise; with REP-103
signs its left beam is the positive one (:func:`ifgm_ref.core.laserscan.beam_of`).

The sensor sits at the robot's centre: a range is the distance from the centre of the robot
disc, not from its rim. It sees the world's obstacles only; the world's ``bounds`` are not walls.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import SensorParams
from ifgm_ref.core.pose import Pose
from ifgm_ref.sim.noise import RangeNoise
from ifgm_ref.sim.raycast import RayCaster, RayFan
from ifgm_ref.sim.world import World

__all__ = ["IRSensor"]


class IRSensor:
    """Simulate the paper's swept IR range sensor in a world (section 4, Figure 2).

    The sensor casts ``rays`` rays from the robot's centre at the robot-frame angles
    ``angle_min + i * angle_increment``, ``i = 0 .. rays - 1``, with ``angle_min = -fov / 2``
    and ``angle_increment = fov / (rays - 1)``, so the last ray is at ``angle_max = +fov / 2``
    (inclusive, as in ``sensor_msgs/LaserScan``). Each range is the exact distance from the
    robot's centre to the first obstacle along the ray (:mod:`ifgm_ref.sim.raycast`).

    Readings follow REP 117: ``+inf`` when no obstacle lies within ``range_max``, ``-inf`` when
    the reading is below ``range_min``. A hit at exactly ``range_max`` is a reading. A robot
    centre inside a circle or on an edge reads 0 on every ray (``-inf`` if ``range_min > 0``).

    With noise on (``noise_std``, ``noise_rel``, ``dropout``, ``spurious``: the models of
    :mod:`ifgm_ref.sim.noise`, seeded with ``seed``) a noisy reading is clipped at 0 (never
    negative), one pushed beyond ``range_max`` becomes ``+inf`` (no return), one pushed below
    ``range_min`` becomes ``-inf``. Gaussian noise never creates a return where there is none:
    ``+inf`` stays ``+inf`` (only a spurious return does). Each scan draws a fixed number of
    numbers whatever it sees, so the noise of the n-th scan depends only on the seed and n.

    Parameters
    ----------
    world : World
        The obstacles to sense (its ``segments``, ``circle_centers`` and ``circle_radii``).
    params : SensorParams or None, default None
        The sensor; ``None`` takes ``world.sensor``.

    Attributes
    ----------
    angle_min, angle_max, angle_increment : float
        The scan's angles, radians: ``-fov / 2``, ``+fov / 2`` and ``fov / (rays - 1)``.

    Raises
    ------
    TypeError
        If ``params`` is neither a :class:`SensorParams` nor ``None``.

    Examples
    --------
    A pillar of radius 1 ft 5 ft ahead, seen by a 90-degree sensor with 3 rays:

    >>> import math
    >>> from ifgm_ref.core.pose import Point
    >>> from ifgm_ref.sim.world import Circle
    >>> world = World(start=Pose(0, 0, 0), goal=Point(0, 10), obstacles=(Circle((5, 0), 1),))
    >>> sensor = IRSensor(world, SensorParams(fov=math.pi / 2, rays=3))
    >>> scan = sensor.scan(world.start)
    >>> scan.ranges.tolist()
    [inf, 4.0, inf]
    >>> scan.angle_min, scan.angle_max, scan.angle_increment
    (-0.7853981633974483, 0.7853981633974483, 0.7853981633974483)

    Turned 45 degrees to the right, the pillar is seen by the left ray (positive angle):

    >>> sensor.scan(Pose(0, 0, -math.pi / 4)).ranges.tolist()
    [inf, inf, 4.0]

    The default sensor: 135 degrees, 76 rays 1.8 degrees apart:

    >>> default = IRSensor(world)
    >>> len(default.scan(world.start).ranges), round(math.degrees(default.angle_increment), 6)
    (76, 1.8)
    """

    def __init__(self, world: World, params: SensorParams | None = None) -> None:
        params = world.sensor if params is None else params
        if not isinstance(params, SensorParams):
            raise TypeError(f"`params` must be a SensorParams or None, got {params!r}")
        self._params = params
        self.angle_min = -0.5 * params.fov
        self.angle_max = 0.5 * params.fov
        self.angle_increment = params.angle_increment
        self._fan = RayFan.of(self.angle_min + self.angle_increment * np.arange(params.rays))
        self._caster = RayCaster(
            world.segments, world.circle_centers, world.circle_radii, params.range_max
        )
        self._noise = RangeNoise(params)

    @property
    def params(self) -> SensorParams:
        """The sensor's parameters."""
        return self._params

    @property
    def angles(self) -> NDArray[np.float64]:
        """Robot-frame angle of every ray, radians (read-only): the angles :meth:`scan` casts."""
        return self._fan.angles

    def reset(self) -> None:
        """Restart the noise generators from ``params.seed``, as if newly built."""
        self._noise = RangeNoise(self._params)

    def scan(self, pose: Pose) -> LaserScan:
        """Return the scan seen from ``pose``.

        Parameters
        ----------
        pose : Pose
            The robot's pose ``(x, y, theta)`` in the world frame: ft, ft, radians.

        Returns
        -------
        LaserScan
            ``rays`` ranges in ft from ``angle_min`` to ``angle_max``, REP 117 encoded.
        """
        x, y, theta = pose
        return self.reading(self._caster.cast_fan((x, y), theta, self._fan))

    def reading(self, ranges: NDArray[np.float64]) -> LaserScan:
        """The scan of the exact ``ranges`` of :attr:`angles` (``inf`` where nothing is hit,
        modified in place): noise added, REP 117 encoded, as :meth:`scan` returns it. An
        engine that casts its own rays (:mod:`ifgm_ref.sim.physics`) reads them so."""
        params = self._params
        if self._noise.active:
            self._noise.apply(ranges)
            np.maximum(ranges, 0.0, out=ranges)
            ranges[ranges > params.range_max] = np.inf
        if params.range_min > 0.0:
            ranges[ranges < params.range_min] = -np.inf
        ranges.setflags(write=False)  # a fresh array: the scan owns it, no copy needed
        return LaserScan(
            angle_min=self.angle_min,
            angle_max=self.angle_max,
            angle_increment=self.angle_increment,
            range_min=params.range_min,
            range_max=params.range_max,
            ranges=ranges,
        )
