"""The range scan a planner sees, in the ROS ``sensor_msgs/LaserScan`` convention.

Angles are measured in the robot frame (REP-103: x forward, y left, counter-clockwise
positive), so a ray at a positive angle looks to the robot's *left*. ``angle_max`` is
inclusive: ``angle_max == angle_min + angle_increment * (len(ranges) - 1)``. Ranges follow
REP 117: ``+inf`` means no return within ``range_max``, ``-inf`` a return nearer than
``range_min``, ``nan`` a sensor error.

The paper (section 4, Figure 2) splits the 135-degree field of view into three 45-degree
beams. Its text gives the *left* beam as "-67.5 to -22.5 degrees" and the *right* one as
"22.5 to 67.5 degrees", i.e. with clockwise-positive angles; with REP-103 signs the left beam
is the positive one (errata row 11).

A sensor need not be the paper's. The beams keep the paper's angles on any scan: on a wider
one (a 270-degree LiDAR) the rays beyond +-67.5 degrees belong to no beam, and
:meth:`LaserScan.window` cuts out the paper's 135-degree view for the rules that speak of it;
on a narrower one each beam holds the part of it the sensor covers (errata row 30).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np
from numpy.typing import NDArray

#: Half-width of the paper's front beam, radians (section 4: front beam from -22.5 to 22.5 deg).
FRONT_HALF_WIDTH = math.radians(22.5)
#: Half of the paper's field of view, radians: the three beams span -67.5 to 67.5 degrees.
PAPER_HALF_FOV = 3.0 * FRONT_HALF_WIDTH
#: Rays computed as ``angle_min + i * angle_increment`` land on the +-22.5 degree borders only
#: to within rounding (1e-16 rad); this tolerance keeps such rays in the front beam.
BORDER_TOLERANCE = 1e-9


class Beam(StrEnum):
    """The three named 45-degree beams of the paper's sensor (section 4, Figure 2)."""

    RIGHT = "right"
    FRONT = "front"
    LEFT = "left"


def beam_of(angle: float) -> Beam | None:
    """Name the beam a robot-frame ray angle falls in (the borders +-22.5 deg are *front*,
    +-67.5 deg belong to the side beams); ``None`` beyond the paper's view.

    >>> beam_of(math.radians(40.0)), beam_of(math.radians(-22.5)), beam_of(-1.0)
    (<Beam.LEFT: 'left'>, <Beam.FRONT: 'front'>, <Beam.RIGHT: 'right'>)
    >>> beam_of(math.radians(67.5)), beam_of(math.radians(90.0))
    (<Beam.LEFT: 'left'>, None)
    """
    if abs(angle) > PAPER_HALF_FOV + BORDER_TOLERANCE:
        return None
    if angle > FRONT_HALF_WIDTH + BORDER_TOLERANCE:
        return Beam.LEFT
    if angle < -FRONT_HALF_WIDTH - BORDER_TOLERANCE:
        return Beam.RIGHT
    return Beam.FRONT


@functools.lru_cache(maxsize=32)
def _ray_angles(angle_min: float, angle_increment: float, rays: int) -> NDArray[np.float64]:
    """The ray angles of a sensor, computed once per sensor (read-only)."""
    angles = angle_min + angle_increment * np.arange(rays)
    angles.setflags(write=False)
    return angles


@functools.lru_cache(maxsize=32)
def _ray_directions(
    angle_min: float, angle_increment: float, rays: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The cosine and sine of every ray angle of a sensor, computed once per sensor."""
    angles = _ray_angles(angle_min, angle_increment, rays)
    cos, sin = np.cos(angles), np.sin(angles)
    cos.setflags(write=False)
    sin.setflags(write=False)
    return cos, sin


@functools.lru_cache(maxsize=96)
def _beam_mask(
    angle_min: float, angle_increment: float, rays: int, beam: Beam
) -> NDArray[np.bool_]:
    """Which rays of a sensor belong to ``beam``, computed once per sensor (read-only)."""
    angles = _ray_angles(angle_min, angle_increment, rays)
    border = FRONT_HALF_WIDTH + BORDER_TOLERANCE
    outer = PAPER_HALF_FOV + BORDER_TOLERANCE
    if beam is Beam.LEFT:
        mask = (angles > border) & (angles <= outer)
    elif beam is Beam.RIGHT:
        mask = (angles < -border) & (angles >= -outer)
    else:
        mask = np.abs(angles) <= border
    mask.setflags(write=False)
    return mask


@functools.lru_cache(maxsize=32)
def _window_rays(
    angle_min: float, angle_increment: float, rays: int, half_width: float
) -> tuple[int, int] | None:
    """The first and last ray of a sensor within ``half_width`` of straight ahead (``None``
    if every ray is), computed once per sensor; ``ValueError`` if fewer than two are."""
    angles = _ray_angles(angle_min, angle_increment, rays)
    inside = np.flatnonzero(np.abs(angles) <= half_width + BORDER_TOLERANCE)
    if len(inside) == rays:
        return None
    if len(inside) < 2:
        raise ValueError(
            f"{len(inside)} ray(s) within +-{half_width!r} rad, but a scan needs 2 "
            f"(angle_increment={angle_increment!r})"
        )
    return int(inside[0]), int(inside[-1])


@dataclass(frozen=True, eq=False)
class LaserScan:
    """One sweep of the range sensor (fields as in ``sensor_msgs/LaserScan``).

    ``ranges`` is a read-only float64 array, one value per ray, in ft.
    """

    angle_min: float
    angle_max: float
    angle_increment: float
    range_min: float
    range_max: float
    ranges: NDArray[np.float64]

    def __post_init__(self) -> None:
        ranges = np.asarray(self.ranges, dtype=np.float64)
        if ranges.flags.writeable:  # the caller may still hold it: keep a private copy
            ranges = ranges.copy()
            ranges.setflags(write=False)
        object.__setattr__(self, "ranges", ranges)
        expected = self.angle_min + self.angle_increment * (len(ranges) - 1)
        if len(ranges) < 2 or not math.isclose(self.angle_max, expected, abs_tol=1e-9):
            raise ValueError(
                f"angle_max={self.angle_max!r}, but should be angle_min + angle_increment * "
                f"(len(ranges) - 1) = {expected!r} for {len(ranges)} ranges"
            )

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, LaserScan):
            return NotImplemented
        return (
            self.angle_min,
            self.angle_max,
            self.angle_increment,
            self.range_min,
            self.range_max,
        ) == (
            other.angle_min,
            other.angle_max,
            other.angle_increment,
            other.range_min,
            other.range_max,
        ) and np.array_equal(self.ranges, other.ranges, equal_nan=True)

    __hash__ = None  # type: ignore[assignment]

    @property
    def angles(self) -> NDArray[np.float64]:
        """Robot-frame angle of every ray, radians (``angle_min`` to ``angle_max`` inclusive);
        read-only, shared by every scan of the same sensor."""
        return _ray_angles(self.angle_min, self.angle_increment, len(self.ranges))

    @property
    def directions(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The cosine and the sine of every ray's angle (read-only, shared like
        :attr:`angles`)."""
        return _ray_directions(self.angle_min, self.angle_increment, len(self.ranges))

    @property
    def beams(self) -> tuple[Beam | None, ...]:
        """The paper's beam name of every ray (``None`` beyond the paper's view)."""
        return tuple(beam_of(float(a)) for a in self.angles)

    def beam_mask(self, beam: Beam) -> NDArray[np.bool_]:
        """Which rays belong to ``beam`` (vectorised :func:`beam_of`).

        >>> scan = LaserScan(-1.0, 1.0, 0.5, 0.0, 10.0, [1.0] * 5)
        >>> scan.beam_mask(Beam.LEFT).tolist(), scan.beam_mask(Beam.FRONT).tolist()
        ([False, False, False, True, True], [False, False, True, False, False])
        """
        return _beam_mask(self.angle_min, self.angle_increment, len(self.ranges), beam)

    def limited(self, range_max: float) -> LaserScan:
        """The scan of a sensor that sees no farther than ``range_max``: returns beyond it
        read ``+inf`` (no return). A scan that already sees no farther is returned itself.

        >>> scan = LaserScan(-1.0, 1.0, 1.0, 0.0, 30.0, [2.0, 20.0, math.inf])
        >>> near = scan.limited(15.0)
        >>> near.range_max, near.ranges.tolist()
        (15.0, [2.0, inf, inf])
        >>> near.limited(15.0) is near
        True
        """
        if range_max >= self.range_max:
            return self
        ranges = np.where(self.ranges > range_max, np.inf, self.ranges)
        return LaserScan(
            self.angle_min,
            self.angle_max,
            self.angle_increment,
            min(self.range_min, range_max),
            range_max,
            ranges,
        )

    def window(self, half_width: float = PAPER_HALF_FOV) -> LaserScan:
        """The rays within ``half_width`` of straight ahead (borders included), as a scan.

        By default the paper's 135-degree view; a scan that lies within it is returned
        itself. Raises ``ValueError`` when fewer than two rays lie inside.

        >>> wide = LaserScan(-2.0, 2.0, 1.0, 0.0, 10.0, [1.0, 2.0, 3.0, 4.0, 5.0])
        >>> cut = wide.window()
        >>> cut.angle_min, cut.angle_max, cut.ranges.tolist()
        (-1.0, 1.0, [2.0, 3.0, 4.0])
        >>> cut.window() is cut
        True
        """
        rays = _window_rays(self.angle_min, self.angle_increment, len(self.ranges), half_width)
        if rays is None:
            return self
        first, last = rays
        angles = self.angles
        return LaserScan(
            float(angles[first]),
            float(angles[last]),
            self.angle_increment,
            self.range_min,
            self.range_max,
            self.ranges[first : last + 1],
        )

    def to_message(self) -> dict[str, Any]:
        """The scan as a JSON-ready mapping (the JSON-lines protocol's ``scan`` object).

        JSON has no infinities: ``+inf`` (no return) and ``nan`` (error) become ``None``
        (``null``); ``-inf`` (nearer than ``range_min``) becomes ``0.0``, the conservative reading.
        """
        return {
            "angle_min": self.angle_min,
            "angle_max": self.angle_max,
            "angle_increment": self.angle_increment,
            "range_min": self.range_min,
            "range_max": self.range_max,
            "ranges": _ranges_to_json(self.ranges),
        }

    @classmethod
    def from_message(cls, message: dict[str, Any]) -> LaserScan:
        """Inverse of :meth:`to_message`; ``null`` ranges read back as ``+inf`` (no return)."""
        ranges = [math.inf if r is None else float(r) for r in message["ranges"]]
        return cls(
            angle_min=float(message["angle_min"]),
            angle_max=float(message["angle_max"]),
            angle_increment=float(message["angle_increment"]),
            range_min=float(message["range_min"]),
            range_max=float(message["range_max"]),
            ranges=np.asarray(ranges),
        )


def _ranges_to_json(ranges: NDArray[np.float64]) -> list[float | None]:
    """The ranges as JSON: finite as they are, ``-inf`` as 0, ``+inf`` and ``nan`` as ``None``.

    >>> _ranges_to_json(np.array([1.5, np.inf, -np.inf, np.nan]))
    [1.5, None, 0.0, None]
    """
    values: list[float | None] = np.asarray(ranges, dtype=np.float64).tolist()
    for k in np.flatnonzero(~np.isfinite(ranges)).tolist():
        values[k] = 0.0 if values[k] == -math.inf else None
    return values
