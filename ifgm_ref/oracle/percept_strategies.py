"""Hypothesis strategies of single percepts: scans, poses, goals, and the situations of Figure 3.

The world classes of :mod:`ifgm_ref.oracle.strategies` test a planner through whole episodes.
These strategies test its *decisions*: they draw what one step of a planner sees -- an
:class:`~ifgm_ref.core.protocol.Observation` (time, pose, goal and a
:class:`~ifgm_ref.core.laserscan.LaserScan` in the ROS convention) -- without any world behind it,
so that every branch of the reconstructed Figure 3 (section 4 of the paper: Case-1, Case-2,
Case-3, the dead-end rule; section 4.1: IBA) can be reached directly and its post-condition
checked (``tests/test_flowchart_properties.py``).

=============================  ===============================================================
strategy                       draws
=============================  ===============================================================
:func:`poses`                  a pose anywhere, heading in any direction (and the exact
                               multiples of 90 degrees, where quadrant slips show)
:func:`scans`                  one scan: runs of returns (obstacles, "clusters" of section 4)
                               separated by rays without a return, or every ray returning (a
                               U or H seen from inside)
:func:`observations`           a scan, a pose and a goal: behind a return, in the field of
                               view, exactly ahead or anywhere; far, near, or at the goal
:func:`gap_families`           one scan layout with its maximum gap widened ray by ray across
                               ``d_th`` (Case-2 to Case-1), everything else fixed
:func:`dead_end_rooms`         a ring-shaped room round the robot, closed in its field of view,
                               open in the direction of the k-th 45-degree turn (or nowhere)
:func:`preemptions`            an obstacle that makes IBA start, then the same scan with new
                               obstacles, some nearer (Case-3)
=============================  ===============================================================

Scans use the default sensor (:class:`~ifgm_ref.core.params.SensorParams`: 135 degrees, 76 rays
1.8 degrees apart, ``range_max`` 15 ft) unless another is passed. Ranges follow REP 117:
``+inf`` no return, ``-inf`` a return nearer than ``range_min`` (drawn only with
``too_near=True``). Lengths are in ft, angles in radians; bands of ranges named below (near,
middle, far) are drawn round the reference's thresholds (:data:`PARAMS`).

Every draw is labelled, so a failing example says which choice it came from; scans shrink
towards fewer obstacles, constant ranges and the low end of the middle band.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import pairwise

import numpy as np
from hypothesis import assume
from hypothesis import strategies as st
from numpy.typing import NDArray

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import SensorParams
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import EpisodeParams, Observation
from ifgm_ref.paper.flowchart import DEAD_END_STEP as STEP
from ifgm_ref.planners.boundary import BoundaryParams
from ifgm_ref.planners.ifgm.atoms import IFGMParams

#: The paper's sensor with the reference's defaults (section 4, Figure 2).
DEFAULT_SENSOR = SensorParams()
#: The reference's episode and thresholds, which the bands below are drawn round.
EPISODE = EpisodeParams()
PARAMS = IFGMParams.for_episode(EPISODE)
#: The goal counts as reached within the goal tolerance plus one step of travel, ft (0.63).
AT_GOAL = EPISODE.goal_tolerance + EPISODE.robot.speed * EPISODE.dt
#: Goal distances, ft: round the goal's reach (a tenth beyond it), near (inside the
#: encounter distance ``d_look``), and far.
NEAR_GOAL = (1e-3, 1.1 * AT_GOAL)
MID_GOAL = (NEAR_GOAL[1], PARAMS.d_look)
FAR_GOAL = (PARAMS.d_look, 100.0)
#: Bands of ranges, ft: near (round ``d_obs``, to half as far again beyond it), middle (to
#: half a radius beyond ``d_look``, so both sides of it are drawn), far (to ``range_max``).
NEAR_RANGE = (0.2, 1.5 * PARAMS.d_obs)
MID_RANGE = (NEAR_RANGE[1], PARAMS.d_look + EPISODE.robot.radius / 2)
#: Half-width of the reference's robot-wide corridor, ft: the radius plus the corridor margin
#: (:class:`~ifgm_ref.planners.boundary.BoundaryParams`). :func:`dead_end_rooms` keeps its
#: openings clear of such a corridor with :data:`ROOM_MARGIN` to spare.
HALF_WIDTH = EPISODE.robot.radius + BoundaryParams.for_episode(EPISODE).corridor_margin
#: Angular margin of the room construction, radians: every direction is either free with
#: this much room or blocked this far inside a wall, so ray sampling cannot decide it.
ROOM_MARGIN = math.radians(2.0)
#: The layouts of :func:`scans`.
LAYOUTS = ("open", "sides", "one side", "enclosed")


def scan_from_ranges(ranges: NDArray[np.float64], *, sensor: SensorParams) -> LaserScan:
    """A scan of ``sensor`` with ``ranges``, encoded as REP 117 says.

    Ranges beyond ``range_max`` read ``+inf`` (no return), below ``range_min`` ``-inf``.

    Examples
    --------
    >>> scan = scan_from_ranges(np.full(76, 20.0), sensor=DEFAULT_SENSOR)
    >>> bool(np.all(scan.ranges == np.inf)), round(math.degrees(scan.angle_max), 9)
    (True, 67.5)
    >>> near = SensorParams(range_min=0.5)
    >>> scan_from_ranges(np.array([0.2, 1.0] * 38), sensor=near).ranges[:2].tolist()
    [-inf, 1.0]
    """
    values = np.array(ranges, dtype=np.float64)
    if len(values) != sensor.rays:
        raise ValueError(f"len(ranges)={len(values)}, but should be sensor.rays={sensor.rays}")
    values[values > sensor.range_max] = np.inf
    values[values < sensor.range_min] = -np.inf
    half = 0.5 * sensor.fov
    return LaserScan(
        -half, half, sensor.angle_increment, sensor.range_min, sensor.range_max, values
    )


def ray_angles(sensor: SensorParams) -> NDArray[np.float64]:
    """Robot-frame angle of every ray of ``sensor``, radians (as in the scan).

    >>> [round(math.degrees(a), 6) for a in ray_angles(DEFAULT_SENSOR)[[0, 37, 38, -1]]]
    [-67.5, -0.9, 0.9, 67.5]
    """
    return -0.5 * sensor.fov + sensor.angle_increment * np.arange(sensor.rays)


# -- poses and goals ---------------------------------------------------------------------------


@st.composite
def poses(draw: st.DrawFn, *, extent: float = 100.0) -> Pose:
    """A pose in ``[-extent, extent]^2`` ft, heading anywhere in ``[-pi, pi]``.

    The exact multiples of 90 degrees (and +pi, which wraps to -pi) are drawn on purpose: a
    quadrant-blind arctan or a wrap slip shows there first.
    """
    x = draw(st.floats(-extent, extent), label="pose x")
    y = draw(st.floats(-extent, extent), label="pose y")
    theta = draw(
        st.one_of(
            st.sampled_from([0.0, math.pi / 2, math.pi, -math.pi, -math.pi / 2]),
            st.floats(-math.pi, math.pi),
        ),
        label="pose heading",
    )
    return Pose(x, y, theta)


def goal_at(pose: Pose, bearing: float, distance: float) -> Point:
    """The goal ``distance`` ft from ``pose`` at ``bearing`` radians from its heading.

    A direction within 1e-15 of an axis is snapped onto it, so that goals straight along an
    axis are exactly on it.

    >>> goal_at(Pose(1.0, 2.0, math.pi / 2), 0.0, 3.0)
    Point(x=1.0, y=5.0)
    """
    direction = pose.theta + bearing
    c, s = math.cos(direction), math.sin(direction)
    c, s = (0.0 if abs(c) < 1e-15 else c), (0.0 if abs(s) < 1e-15 else s)
    return Point(pose.x + distance * c, pose.y + distance * s)


# -- scans -------------------------------------------------------------------------------------


@st.composite
def ranges_bands(draw: st.DrawFn, range_max: float) -> float:
    """A range (ft) from the middle band (most draws), the far band, the near band, or
    ``range_max`` itself (a return exactly at the sensor's range counts)."""
    band = draw(st.integers(0, 9), label="range band")
    if band == 9:
        return range_max
    low, high = MID_RANGE if band < 6 else (MID_RANGE[1], range_max) if band < 8 else NEAR_RANGE
    return draw(st.floats(low, high), label="range")


@st.composite
def run_profiles(
    draw: st.DrawFn, length: int, *, ranges: st.SearchStrategy[float]
) -> NDArray[np.float64]:
    """The ranges of one obstacle over ``length`` consecutive rays: constant, a ramp (a wall
    seen obliquely) or a dip (a corner or a post, nearest inside the run), with end ranges
    from ``ranges``."""
    first = draw(ranges, label="run first range")
    shape = draw(st.sampled_from(["constant", "ramp", "dip"]), label="run shape")
    if shape == "constant" or length == 1:
        return np.full(length, first)
    last = draw(ranges, label="run last range")
    if shape == "ramp":
        return np.linspace(first, last, length)
    middle = min(first, last) * draw(st.floats(0.5, 1.0), label="run dip depth")
    at = draw(st.integers(0, length - 1), label="run dip ray")
    return np.interp(np.arange(length), [0, at, length - 1], [first, middle, last])


@st.composite
def scans(
    draw: st.DrawFn,
    *,
    sensor: SensorParams = DEFAULT_SENSOR,
    max_obstacles: int = 4,
    too_near: bool = False,
    layouts: tuple[str, ...] = LAYOUTS,
) -> LaserScan:
    """One scan of ``sensor``: up to ``max_obstacles`` runs of returns.

    Layouts: ``open`` (runs separated by rays without a return, or touching, when a jump in
    range may or may not split them into two obstacles), ``sides`` (one obstacle wholly
    right of the heading, one wholly left, perhaps one between: the gap situations of Case-1
    and Case-2), ``one side`` (one or two runs, all on one side of the heading) and
    ``enclosed`` (runs covering every ray: a U or H seen from inside, the dead end of
    section 4).

    With ``too_near`` a ``range_min`` up to 0.5 ft is drawn and near returns read ``-inf``
    (REP 117); otherwise ``range_min`` is the sensor's.
    """
    n = sensor.rays
    if too_near:
        range_min = draw(st.one_of(st.just(0.0), st.floats(0.05, 0.5)), label="range_min")
        sensor = SensorParams(
            fov=sensor.fov, rays=n, range_max=sensor.range_max, range_min=range_min
        )
    ranges = np.full(n, np.inf)
    band = ranges_bands(sensor.range_max)
    unknown = set(layouts) - set(LAYOUTS)
    if unknown or not layouts:
        raise ValueError(f"layouts={layouts!r}, but should be a non-empty subset of {LAYOUTS}")
    layout = draw(st.sampled_from(layouts), label="layout")
    if layout == "one side":
        _draw_one_side(draw, ranges, band)
    elif layout == "sides":
        _draw_sides(draw, ranges, band)
    elif layout == "enclosed":
        _draw_enclosed(draw, ranges, band, max_obstacles)
    else:
        _draw_open(draw, ranges, band, max_obstacles)
    return scan_from_ranges(ranges, sensor=sensor)


def _draw_one_side(
    draw: st.DrawFn, ranges: NDArray[np.float64], band: st.SearchStrategy[float]
) -> None:
    """Draw the ``one side`` layout of :func:`scans` into ``ranges`` (all ``inf``): one or two
    runs, all wholly on one side of the heading (Case-2's "only in one side")."""
    n = len(ranges)
    left = draw(st.booleans(), label="on the left")
    first, last = (n // 2, n - 1) if left else (0, n // 2 - 1)
    for _ in range(draw(st.integers(1, 2), label="obstacles")):
        a = draw(st.integers(first, last), label="run first ray")
        b = draw(st.integers(a, last), label="run last ray")
        ranges[a : b + 1] = draw(run_profiles(b + 1 - a, ranges=band))


def _draw_sides(
    draw: st.DrawFn, ranges: NDArray[np.float64], band: st.SearchStrategy[float]
) -> None:
    """Draw the ``sides`` layout of :func:`scans` into ``ranges`` (all ``inf``): one obstacle
    wholly right of the heading, one wholly left, maybe one between."""
    n = len(ranges)
    mid = n // 2
    a = draw(st.integers(0, mid - 2), label="right obstacle first ray")
    b = draw(st.integers(a, mid - 1), label="right obstacle last ray")
    c = draw(st.integers(mid, n - 1), label="left obstacle first ray")
    d = draw(st.integers(c, n - 1), label="left obstacle last ray")
    ranges[a : b + 1] = draw(run_profiles(b + 1 - a, ranges=band))
    ranges[c : d + 1] = draw(run_profiles(d + 1 - c, ranges=band))
    if c - b > 3 and draw(st.booleans(), label="obstacle between"):
        e = draw(st.integers(b + 2, c - 2), label="middle obstacle first ray")
        f = draw(st.integers(e, c - 2), label="middle obstacle last ray")
        ranges[e : f + 1] = draw(run_profiles(f + 1 - e, ranges=band))


def _draw_enclosed(
    draw: st.DrawFn,
    ranges: NDArray[np.float64],
    band: st.SearchStrategy[float],
    max_obstacles: int,
) -> None:
    """Draw the ``enclosed`` layout of :func:`scans` into ``ranges``: up to ``max_obstacles``
    runs covering every ray."""
    n = len(ranges)
    cuts = draw(
        st.lists(st.integers(1, n - 1), unique=True, max_size=max(0, max_obstacles - 1)),
        label="enclosed cuts",
    )
    for a, b in pairwise([0, *sorted(cuts), n]):
        ranges[a:b] = draw(run_profiles(b - a, ranges=band))


def _draw_open(
    draw: st.DrawFn,
    ranges: NDArray[np.float64],
    band: st.SearchStrategy[float],
    max_obstacles: int,
) -> None:
    """Draw the ``open`` layout of :func:`scans` into ``ranges`` (all ``inf``): up to
    ``max_obstacles`` runs from right to left, each after some rays without a return (none:
    touching runs)."""
    n = len(ranges)
    count = draw(st.integers(0, max_obstacles), label="obstacles")
    i = 0
    for _ in range(count):
        a = i + draw(st.integers(0, n // 2), label="free rays before")
        if a >= n:
            break
        b = min(n, a + draw(st.integers(1, n), label="run length"))
        ranges[a:b] = draw(run_profiles(b - a, ranges=band))
        i = b


@st.composite
def observations(
    draw: st.DrawFn,
    *,
    sensor: SensorParams = DEFAULT_SENSOR,
    scans: st.SearchStrategy[LaserScan] | None = None,
    goal_distances: st.SearchStrategy[float] | None = None,
) -> Observation:
    """One observation: a time, a pose (:func:`poses`), a scan (:func:`scans` of ``sensor``
    unless given) and a goal.

    The goal lies, in order of preference, behind a return of the scan (so the obstacle is in
    the way), anywhere in the field of view, exactly ahead, or in any direction; far (beyond
    the sensor), middle, or within the reference's goal tolerance. A goal exactly at the pose
    is not drawn (eq. (3) has no direction there, errata row 13).
    """
    scan = draw(scans_of(sensor) if scans is None else scans, label="scan")
    pose = draw(poses(), label="pose")
    half = 0.5 * scan.angle_max - 0.5 * scan.angle_min
    returns = np.flatnonzero(scan.ranges != np.inf)
    aim = draw(st.integers(0, 9), label="goal aim")
    if aim < 5 and len(returns):
        ray = int(returns[draw(st.integers(0, len(returns) - 1), label="goal behind ray")])
        nudge = draw(st.floats(-0.5, 0.5), label="goal nudge") * scan.angle_increment
        bearing = float(scan.angles[ray]) + nudge
    elif aim < 7:
        bearing = draw(st.floats(-half, half), label="goal bearing in view")
    elif aim < 8:
        bearing = 0.0
    else:
        bearing = draw(st.floats(-math.pi, math.pi), label="goal bearing")
    if goal_distances is None:
        band = draw(st.integers(0, 9), label="goal distance band")
        goal_distances = st.floats(*(FAR_GOAL if band < 6 else MID_GOAL if band < 9 else NEAR_GOAL))
    goal = goal_at(pose, bearing, draw(goal_distances, label="goal distance"))
    t = draw(st.floats(0.0, 1000.0), label="time")
    return Observation(t, pose, goal, scan)


def scans_of(sensor: SensorParams) -> st.SearchStrategy[LaserScan]:
    """:func:`scans` of ``sensor`` with the default options (for :func:`observations`, whose
    ``scans`` parameter hides the function)."""
    return scans(sensor=sensor)


# -- Case-2 to Case-1: one gap widened ---------------------------------------------------------


@dataclass(frozen=True)
class GapFamily:
    """One scene seen with its left (or right) obstacle receding ray by ray.

    ``scans[i]`` has one more free ray between the centre obstacle and the receding one than
    ``scans[i - 1]``: its gaps are no narrower, and nothing else changes -- the centre
    obstacle blocks the way to the goal within ``d_look``, the other side obstacle is fixed,
    every range exceeds the reference's ``d_obs``, obstacles lie on both sides, and some rays
    see nothing (no dead end). The first scan's gaps are all under 2.2 ft, the last one's
    widest over 3.5 ft, so any ``d_th`` in ``[2.2, 3.5]`` is crossed.
    """

    pose: Pose
    goal: Point
    scans: tuple[LaserScan, ...]
    mirrored: bool


@st.composite
def gap_families(draw: st.DrawFn, *, sensor: SensorParams = DEFAULT_SENSOR) -> GapFamily:
    """A :class:`GapFamily` of the default 76-ray sensor, placed anywhere."""
    if sensor.rays != 76:
        raise ValueError(f"gap_families builds on the 76-ray sensor, got rays={sensor.rays}")
    base = draw(st.floats(5.0, 7.5), label="base range")

    def level() -> float:
        return base + draw(st.floats(-0.3, 0.3), label="range offset")

    c0 = draw(st.integers(30, 37), label="centre first ray")
    c1 = draw(st.integers(38, 42), label="centre last ray")
    r0 = draw(st.integers(0, c0 - 3), label="right first ray")
    centre, right, left = level(), level(), level()
    goal_ray = draw(st.integers(c0, c1), label="goal ray")
    mirrored = draw(st.booleans(), label="mirrored")
    angles = ray_angles(sensor)
    family = []
    for l0 in range(c1 + 2, 75):  # the left obstacle keeps its last two rays
        ranges = np.full(sensor.rays, np.inf)
        ranges[r0 : c0 - 1] = right
        ranges[c0 : c1 + 1] = centre
        ranges[l0:] = left
        family.append(scan_from_ranges(ranges[::-1] if mirrored else ranges, sensor=sensor))
    pose = draw(poses(), label="pose")
    bearing = float(angles[goal_ray]) * (-1.0 if mirrored else 1.0)
    goal = goal_at(pose, bearing, draw(st.floats(20.0, 80.0), label="goal distance"))
    return GapFamily(pose, goal, tuple(family), mirrored)


# -- the dead end: a room open at the k-th 45-degree turn --------------------------------------


@dataclass(frozen=True)
class Room:
    """A ring-shaped wall round the robot at ``centre``, with an opening (or none).

    The wall's distance from the centre in world direction ``psi`` is
    ``radius + bump * (1 + cos(psi - bump_phase)) / 2``. Measured from ``start_heading`` the
    wall is open over ``[first_free * 45 deg + lo, first_free * 45 deg + hi]`` and over its
    mirror image, so that whichever way the robot turns, the first of its 45-degree steps
    whose robot-wide corridor is free is step ``first_free``: earlier steps face the wall
    (at least 1.5 degrees inside it) and the start's field of view sees no opening.
    ``first_free`` is ``None`` for a closed ring.
    """

    centre: Point
    start_heading: float
    radius: float
    bump: float
    bump_phase: float
    first_free: int | None
    lo: float
    hi: float

    def wall(self, psi: float) -> float:
        """Distance from the centre to the wall in world direction ``psi``, ft (``inf`` in
        the opening)."""
        if self.first_free is not None:
            u = wrap_angle(psi - self.start_heading)
            start, width = self.first_free * STEP + self.lo, self.hi - self.lo
            if any((v - start) % (2.0 * math.pi) <= width for v in (u, -u)):
                return math.inf
        return self.radius + self.bump * 0.5 * (1.0 + math.cos(psi - self.bump_phase))

    def scan(self, heading: float, *, sensor: SensorParams = DEFAULT_SENSOR) -> LaserScan:
        """The scan from the centre facing ``heading``.

        >>> room = Room(Point(0.0, 0.0), 0.0, 4.0, 0.0, 0.0, None, 0.0, 0.0)
        >>> set(room.scan(1.0).ranges.tolist())
        {4.0}
        """
        ranges = [self.wall(heading + float(a)) for a in ray_angles(sensor)]
        return scan_from_ranges(np.array(ranges), sensor=sensor)

    @property
    def steps(self) -> int:
        """How many 45-degree steps the dead-end rule takes here: the first free one, or the
        half turn when none is (section 4: "until it finds obstacle free path (on 180)")."""
        return 4 if self.first_free is None else self.first_free


def _free_half_angle(radius: float, half_width: float) -> float:
    """Half the angle an opening needs for a corridor of ``half_width`` through a wall at
    ``radius`` or farther, plus :data:`ROOM_MARGIN`."""
    return math.asin(half_width / radius) + ROOM_MARGIN


@st.composite
def dead_end_rooms(
    draw: st.DrawFn, *, sensor: SensorParams = DEFAULT_SENSOR, half_width: float = HALF_WIDTH
) -> Room:
    """A :class:`Room` seen from its centre: closed in the field of view of the start, within
    the reference's ``d_look`` (8 ft) ahead, open at the ``first_free``-th step (2, 3, 4) or
    nowhere.

    A free direction at the first step cannot arise from a standing start: the start's scan
    sees 22.5 degrees either side of it, and a corridor there would need an opening in view.
    Radii are at least 3 ft, so that a robot-wide corridor reaches 2.7 ft into the wall ahead
    before it meets it (the reference drives on when more than 2.5 ft are free).
    """
    if not math.isclose(sensor.fov, 3.0 * math.pi / 4.0):
        raise ValueError(f"dead_end_rooms is built for the 135-degree field of view, got {sensor}")
    first_free = draw(st.sampled_from([2, 3, 4, None]), label="first free step")
    low_radius = 4.2 if first_free == 2 else 3.0  # room for a free corridor out of view
    radius = draw(st.floats(low_radius, 7.5), label="radius")
    bump = draw(st.one_of(st.just(0.0), st.floats(0.05, 0.5)), label="bump")
    bump_phase = draw(st.floats(-math.pi, math.pi), label="bump phase")
    centre = draw(poses(), label="centre")
    lo = hi = 0.0
    if first_free is not None:
        k, w, margin = first_free, _free_half_angle(radius, half_width), math.radians(1.5)
        view = 0.5 * sensor.fov + margin
        lo_min = max(-STEP + margin, view - k * STEP)  # the last step blocked; none in view
        hi_max = min(2.0 * math.pi - view - k * STEP, 2.0 * math.pi - (2 * k - 1) * STEP - margin)
        assert lo_min < -w and w < hi_max, (k, radius, lo_min, w, hi_max)
        lo = draw(st.floats(lo_min, -w), label="opening lo")
        hi = draw(st.floats(w, hi_max), label="opening hi")
    return Room(centre.position, centre.theta, radius, bump, bump_phase, first_free, lo, hi)


# -- Case-3: a nearer obstacle pre-empts the followed one --------------------------------------


@dataclass(frozen=True)
class Preemption:
    """Two scans from one pose: ``first`` shows one obstacle in the way to the goal (IBA
    starts following it), ``second`` the same obstacle and ``new`` other runs of returns,
    some nearer than it."""

    pose: Pose
    goal: Point
    first: LaserScan
    second: LaserScan
    new: tuple[tuple[int, int], ...]


@st.composite
def preemptions(draw: st.DrawFn, *, sensor: SensorParams = DEFAULT_SENSOR) -> Preemption:
    """A :class:`Preemption`: the followed obstacle between 2.5 and 4.1 ft across the way to
    the goal (near enough that no leaving rule fires: DistBug's needs a free range beyond
    the encounter distance ``r + standoff + hit_margin`` = 2.17 ft of ``Step`` = 2 ft, 4.17 ft
    for the paper's robot), 1-3 new obstacles from 0.6 ft to 1 ft beyond its nearest return,
    each a run of rays one free ray or more from any other."""
    n = sensor.rays
    angles = ray_angles(sensor)
    goal_ray = draw(st.integers(n // 2 - 12, n // 2 + 11), label="goal ray")
    a0 = goal_ray - draw(st.integers(0, 6), label="followed rays right of the goal")
    a1 = goal_ray + draw(st.integers(0, 6), label="followed rays left of the goal")
    first = np.full(n, np.inf)
    profile = draw(run_profiles(a1 + 1 - a0, ranges=st.floats(2.5, 4.1)))
    first[a0 : a1 + 1] = np.clip(profile, 2.5, 4.1)
    top = float(np.min(first)) + 1.0
    second = first.copy()
    # Free rays left and right of the followed obstacle (one ray either side stays free).
    spans = [(0, a0 - 2), (a1 + 2, n - 1)]
    new: list[tuple[int, int]] = []
    for _ in range(draw(st.integers(1, 3), label="new obstacles")):
        lo_, hi_ = spans[draw(st.integers(0, len(spans) - 1), label="new obstacle side")]
        if hi_ - lo_ < 0:
            continue
        a = draw(st.integers(lo_, hi_), label="new obstacle first ray")
        b = draw(st.integers(a, min(hi_, a + 10)), label="new obstacle last ray")
        if any(not (b + 1 < c or d + 1 < a) for c, d in new):
            continue  # touching another new obstacle: keep them apart
        profile = draw(run_profiles(b + 1 - a, ranges=st.floats(0.6, top)))
        second[a : b + 1] = np.clip(profile, 0.6, top)
        new.append((a, b))
    assume(new)
    pose = draw(poses(), label="pose")
    goal = goal_at(pose, float(angles[goal_ray]), draw(st.floats(20.0, 80.0), label="goal"))
    return Preemption(
        pose,
        goal,
        scan_from_ranges(first, sensor=sensor),
        scan_from_ranges(second, sensor=sensor),
        tuple(new),
    )
