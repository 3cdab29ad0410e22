"""The simulated IR sensor (ifgm_ref.sim.sensor): scans of worlds against shapely's exact geometry.

The paper's sensor (section 4, Figure 2) sweeps 135 degrees in three 45-degree beams; here it is
a fan of exact rays reported as a ``sensor_msgs/LaserScan`` (ifgm_ref.core.laserscan).

Oracle and tolerances as in ``tests/test_raycast.py``: polygons by shapely intersection, circles
by the textbook root; distances to ``TOL = 1e-9`` ft (float64 rounding here is ~1e-14 ft), and
a ray passing within rounding of a vertex or tangent may go either way, so a range is accepted
between the exact answers of the rays ``DELTA = 1e-11`` rad either side of it.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
import shapely
from hypothesis import given, note
from hypothesis import strategies as st
from numpy.typing import NDArray

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import SensorParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.world import Circle, Obstacle, Polygon, World

#: Distance tolerance, ft (module docstring).
TOL = 1e-9
#: Ray-direction perturbation that separates ill-conditioned rays, rad (module docstring).
DELTA = 1e-11
#: Largest vertex distance from a polygon's centre, and largest circle radius, ft.
SIZE = 3.0
#: Obstacles are placed within this distance of the start, ft.
NEAR = 16.0

angles_rad = st.floats(-math.pi, math.pi)
offsets_ft = st.floats(-50.0, 50.0)


@st.composite
def obstacles(
    draw: st.DrawFn, *, around: Point, heading: float = 0.0, clearance: float
) -> Obstacle:
    """A star polygon or a circle whose every point is more than ``clearance`` from ``around``.

    Placed by distance and bearing from ``around``, the bearing usually within 1.2 rad of
    ``heading`` (in the default field of view); shrinks towards a circle straight ahead at the
    nearest allowed distance.
    """
    bearing = heading + draw(st.floats(-1.2, 1.2) | angles_rad)
    if draw(st.booleans()):
        radius = draw(st.floats(0.2, SIZE))
        distance = draw(st.floats(clearance + radius + 0.1, NEAR))
        center = (around.x + distance * math.cos(bearing), around.y + distance * math.sin(bearing))
        return Circle(center, radius)
    n = draw(st.integers(3, 6))
    distance = draw(st.floats(clearance + SIZE + 0.1, NEAR))
    cx, cy = around.x + distance * math.cos(bearing), around.y + distance * math.sin(bearing)
    # One vertex in the first 45% of each sector: star-shaped about (cx, cy), hence simple.
    offsets = draw(st.lists(st.floats(0.0, 0.45), min_size=n, max_size=n))
    lengths = draw(st.lists(st.floats(0.5, SIZE), min_size=n, max_size=n))
    vertices = []
    for i, (offset, length) in enumerate(zip(offsets, lengths, strict=True)):
        a = (i + offset) * 2.0 * math.pi / n
        vertices.append((cx + length * math.cos(a), cy + length * math.sin(a)))
    return Polygon(tuple(vertices))


@st.composite
def sensor_params(draw: st.DrawFn, *, max_rays: int = 40) -> SensorParams:
    """Noise-free sensors of any field of view below 2 pi; shrink towards the default.

    ``range_max`` is 20 ft (beyond every obstacle of :func:`worlds`) half the time.
    """
    if draw(st.booleans()):
        return SensorParams()
    return SensorParams(
        fov=draw(st.floats(0.1, 6.2)),
        rays=draw(st.integers(2, max_rays)),
        range_max=draw(st.just(20.0) | st.floats(1.0, 25.0)),
    )


@st.composite
def worlds(draw: st.DrawFn, *, max_obstacles: int = 4) -> World:
    """A valid world: 1 to ``max_obstacles`` obstacles near the start, the goal far away."""
    start = Pose(draw(offsets_ft), draw(offsets_ft), draw(angles_rad))
    clearance = 1.0  # the default robot radius: World requires start and goal clear of it
    found = draw(
        st.lists(
            obstacles(around=start.position, heading=start.theta, clearance=clearance),
            min_size=1,
            max_size=max_obstacles,
        )
    )
    goal = Point(start.x + 100.0, start.y)  # beyond every obstacle
    return World(start=start, goal=goal, obstacles=tuple(found), sensor=draw(sensor_params()))


def first_hits(
    world: World, origin: tuple[float, float], angles: NDArray[np.float64], reach: float
) -> NDArray[np.float64]:
    """Oracle: exact distance to the first obstacle on each ray, ``inf`` if none within reach."""
    o = np.asarray(origin)
    ends = o + reach * np.column_stack([np.cos(angles), np.sin(angles)])
    rays = shapely.linestrings(np.stack([np.broadcast_to(o, ends.shape), ends], axis=1))
    best = np.full(len(angles), np.inf)
    for ob in world.obstacles:
        if isinstance(ob, Polygon):
            touched = shapely.intersection(rays, shapely.Polygon(ob.vertices))
            hit = ~shapely.is_empty(touched)
            best[hit] = np.minimum(best[hit], shapely.distance(shapely.Point(o), touched[hit]))
            continue
        ux, uy = ob.center[0] - o[0], ob.center[1] - o[1]
        for i, a in enumerate(angles):
            p = ux * math.cos(a) + uy * math.sin(a)
            h2 = ux * ux + uy * uy - p * p
            if p >= 0.0 and h2 <= ob.radius**2:
                t = p - math.sqrt(ob.radius**2 - h2)
                if t <= reach:
                    best[i] = min(best[i], t)
    return best


def misfit(
    got: NDArray[np.float64],
    low: NDArray[np.float64],
    high: NDArray[np.float64],
    range_max: float,
) -> NDArray[np.intp]:
    """Indices where ``got`` disagrees with exact hits in ``[low, high]`` (searched far).

    Finite: within ``[low, high]`` +- ``TOL`` and <= ``range_max``. ``+inf``: some neighbouring
    ray has no hit up to ``range_max - TOL``.
    """
    finite = np.isfinite(got)
    with np.errstate(invalid="ignore"):
        bad = finite & ((got > range_max) | (got < low - TOL) | (got > high + TOL))
    bad |= (got == np.inf) & (high < range_max - TOL)
    bad |= np.isnan(got) | (got == -np.inf)
    return np.flatnonzero(bad)


def exact_bounds(
    world: World, pose: Pose, angles: NDArray[np.float64], range_max: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Lowest and highest exact first hit over each ray and its two ``DELTA`` neighbours."""
    absolute = angles + pose.theta
    reach = 1.5 * range_max + 1.0
    hits = np.stack(
        [first_hits(world, (pose.x, pose.y), absolute + e, reach) for e in (-DELTA, 0.0, DELTA)]
    )
    return hits.min(axis=0), hits.max(axis=0)


@given(data=st.data())
def test_scan_range_is_the_exact_distance_to_the_first_obstacle(data: st.DataObject) -> None:
    """Finite: the shapely first hit along that ray; +inf: nothing within range_max."""
    world = data.draw(worlds(), label="world")
    pose = world.start
    scan = IRSensor(world).scan(pose)
    low, high = exact_bounds(world, pose, scan.angles, scan.range_max)
    note(f"ranges={scan.ranges.tolist()!r}")
    bad = misfit(scan.ranges, low, high, scan.range_max)
    if bad.size:
        i = bad[0]
        err = AssertionError(
            f"ranges[{i}]={scan.ranges[i]!r}, but should be in [{low[i]!r}, {high[i]!r}] "
            f"(shapely, +-{TOL}; inf beyond range_max={scan.range_max!r}) [IRSensor.scan]"
        )
        err.add_note(f"reproduce: IRSensor({world!r}).scan({pose!r}).ranges[{i}]")
        raise err


@given(params=sensor_params(max_rays=400))
def test_scan_metadata_follows_the_laserscan_convention(params: SensorParams) -> None:
    world = World(start=Pose(0.0, 0.0, 0.0), goal=Point(10.0, 0.0))
    scan = IRSensor(world, params).scan(world.start)
    assert len(scan.ranges) == params.rays, f"len(ranges)={len(scan.ranges)}, but should be rays"
    assert scan.angle_min == -params.fov / 2, f"angle_min={scan.angle_min}, but should be -fov/2"
    assert scan.angle_max == params.fov / 2, f"angle_max={scan.angle_max}, but should be +fov/2"
    assert scan.angle_increment == params.fov / (params.rays - 1)
    last = scan.angle_min + scan.angle_increment * (len(scan.ranges) - 1)
    assert math.isclose(scan.angle_max, last, rel_tol=0.0, abs_tol=1e-12), (
        f"angle_max={scan.angle_max!r}, but should be angle_min + angle_increment * "
        f"(len(ranges) - 1) = {last!r} [IRSensor.scan]"
    )
    assert (scan.range_min, scan.range_max) == (params.range_min, params.range_max)


@given(
    fov=st.floats(0.1, 2.8),
    rays=st.integers(2, 200),
    distance=st.floats(2.0, 5.0),
)
def test_angle_increment_is_the_spacing_of_the_rays_cast(
    fov: float, rays: int, distance: float
) -> None:
    """A wall across the heading at ``distance`` is ``distance / cos(angle)`` along each ray.

    The angle is the one the scan *reports* (``angle_min + i * angle_increment``), so a scan
    whose metadata did not describe the rays actually cast would fail here.
    """
    half = distance * math.tan(fov / 2) + 1.0
    wall = Polygon(
        ((distance, -half), (distance + 1, -half), (distance + 1, half), (distance, half))
    )
    params = SensorParams(fov=fov, rays=rays, range_max=distance / math.cos(fov / 2) + 1.0)
    world = World(
        start=Pose(0.0, 0.0, 0.0), goal=Point(-10.0, 0.0), obstacles=(wall,), sensor=params
    )
    scan = IRSensor(world).scan(world.start)
    expected = distance / np.cos(scan.angles)
    np.testing.assert_allclose(scan.ranges, expected, rtol=1e-12, err_msg="ranges vs d/cos")


@given(data=st.data())
def test_each_range_is_read_along_its_own_angle(data: st.DataObject) -> None:
    """A thin pillar on the reported bearing of ray ``i`` is seen by ray ``i`` alone."""
    params = data.draw(sensor_params(max_rays=100), label="sensor")
    i = data.draw(st.integers(0, params.rays - 1), label="ray index")
    heading = data.draw(angles_rad, label="heading")
    distance = data.draw(st.floats(3.0, min(10.0, params.range_max + 2.0)), label="distance")
    # Narrower than half the gap to the neighbouring rays (also across the back, for a field of
    # view near 2 pi), so they pass it by.
    gap = min(params.angle_increment, 2.0 * math.pi - params.fov)
    radius = 0.25 * distance * math.sin(gap / 2)
    bearing = heading - params.fov / 2 + i * params.angle_increment
    pillar = Circle((distance * math.cos(bearing), distance * math.sin(bearing)), radius)
    world = World(
        start=Pose(0.0, 0.0, heading), goal=Point(-30.0, 0.0), obstacles=(pillar,), sensor=params
    )
    ranges = IRSensor(world).scan(world.start).ranges
    seen = np.flatnonzero(np.isfinite(ranges)).tolist()
    if distance - radius <= params.range_max:
        assert seen == [i], f"rays seeing the pillar={seen}, but should be [{i}]"
        assert math.isclose(ranges[i], distance - radius, abs_tol=TOL)
    else:
        assert seen == [], f"rays seeing the pillar={seen}, but should be none (out of range)"


@pytest.mark.paper("sensor.fov")
def test_rays_lie_on_the_paper_beam_borders() -> None:
    """Default sensor: 135 deg, rays at -67.5, -22.5, +22.5, +67.5 deg (section 4, Figure 2)."""
    world = World(start=Pose(0.0, 0.0, 0.0), goal=Point(10.0, 0.0))
    sensor = IRSensor(world)
    borders = np.degrees(sensor.angles[[0, 25, 50, 75]])
    np.testing.assert_allclose(borders, [-67.5, -22.5, 22.5, 67.5], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(sensor.angles, sensor.scan(world.start).angles)


def test_positive_angles_look_left() -> None:
    """REP-103: facing +y, an obstacle to the west (the robot's left) is at positive angles."""
    world = World(
        start=Pose(0.0, 0.0, math.pi / 2),
        goal=Point(0.0, 20.0),
        obstacles=(Circle((-5.0, 0.0), 1.0),),
        sensor=SensorParams(fov=4.0, rays=41),
    )
    scan = IRSensor(world).scan(world.start)
    seen = scan.angles[np.isfinite(scan.ranges)]
    assert seen.size and (seen > 1.0).all(), f"angles seeing the obstacle={seen}, should be > 1"


@given(data=st.data())
def test_range_min_reads_minus_inf(data: st.DataObject) -> None:
    world = data.draw(worlds(), label="world")
    fraction = data.draw(st.floats(0.01, 0.99), label="range_min / range_max")
    exact = IRSensor(world).scan(world.start).ranges
    params = replace(world.sensor, range_min=fraction * world.sensor.range_max)
    got = IRSensor(world, params).scan(world.start).ranges
    expected = np.where(exact < params.range_min, -np.inf, exact)
    np.testing.assert_array_equal(got, expected, err_msg=f"range_min={params.range_min}")


@given(data=st.data())
def test_moving_world_and_robot_together_leaves_the_scan_unchanged(data: st.DataObject) -> None:
    """Rotating and translating everything leaves every range where it was (within TOL).

    Rounding in the transform moves an obstacle by ~1e-14 ft, which turns a ray by far less
    than DELTA; the moved range must lie between the unmoved ones of the ray's neighbours.
    """
    world = data.draw(worlds(), label="world")
    turn = data.draw(angles_rad, label="rotation")
    shift = data.draw(st.tuples(offsets_ft, offsets_ft), label="translation")
    c, s = math.cos(turn), math.sin(turn)

    def move(x: float, y: float) -> tuple[float, float]:
        return (c * x - s * y + shift[0], s * x + c * y + shift[1])

    moved_obstacles = tuple(
        Circle(move(*ob.center), ob.radius)
        if isinstance(ob, Circle)
        else Polygon(tuple(move(*v) for v in ob.vertices))
        for ob in world.obstacles
    )
    start = world.start
    moved = World(
        start=Pose(*move(start.x, start.y), start.theta + turn),
        goal=Point(*move(*world.goal)),
        obstacles=moved_obstacles,
        sensor=world.sensor,
    )
    got = IRSensor(moved).scan(moved.start).ranges
    far = IRSensor(world, replace(world.sensor, range_max=1.5 * world.sensor.range_max + 1.0))
    near = np.stack(
        [far.scan(start._replace(theta=start.theta + e)).ranges for e in (-DELTA, 0, DELTA)]
    )
    bad = misfit(got, near.min(axis=0), near.max(axis=0), world.sensor.range_max)
    assert not bad.size, (
        f"ranges[{bad[0]}]={got[bad[0]]!r} after moving, but should be "
        f"{near[1, bad[0]]!r} as before (+-{TOL}) [IRSensor.scan]"
    )


@given(data=st.data())
def test_adding_an_obstacle_never_increases_a_range(data: st.DataObject) -> None:
    world = data.draw(worlds(), label="world")
    start = world.start
    extra = data.draw(
        obstacles(around=start.position, heading=start.theta, clearance=1.0), label="extra"
    )
    before = IRSensor(world).scan(world.start).ranges
    bigger = replace(world, obstacles=(*world.obstacles, extra))
    after = IRSensor(bigger).scan(world.start).ranges
    worse = np.flatnonzero(after > before + TOL)
    assert not worse.size, (
        f"ranges[{worse[0]}]={after[worse[0]]!r} with {extra!r} added, but should be <= "
        f"{before[worse[0]]!r} [IRSensor.scan]"
    )


def _walled(**sensor: float) -> World:
    """The robot at the origin facing a wall 5 ft ahead (every ray of 135 deg hits it)."""
    wall = Polygon(((5.0, -20.0), (6.0, -20.0), (6.0, 20.0), (5.0, 20.0)))
    return World(
        start=Pose(0.0, 0.0, 0.0),
        goal=Point(-10.0, 0.0),
        obstacles=(wall,),
        sensor=SensorParams(**sensor),
    )


def _scans(sensor: IRSensor, count: int = 3) -> list[LaserScan]:
    return [sensor.scan(Pose(0.0, 0.0, 0.0)) for _ in range(count)]


@given(seed=st.integers(0, 2**32 - 1), std=st.floats(0.01, 2.0))
def test_noise_is_reproducible_with_the_same_seed(seed: int, std: float) -> None:
    world = _walled(noise_std=std, seed=seed, range_max=20.0)
    assert _scans(IRSensor(world)) == _scans(IRSensor(world))


@given(seed=st.integers(0, 2**32 - 2), std=st.floats(0.01, 2.0))
def test_noise_differs_with_another_seed(seed: int, std: float) -> None:
    first = IRSensor(_walled(noise_std=std, seed=seed, range_max=20.0)).scan(Pose(0, 0, 0))
    other = IRSensor(_walled(noise_std=std, seed=seed + 1, range_max=20.0)).scan(Pose(0, 0, 0))
    assert not np.array_equal(first.ranges, other.ranges)


@given(seed=st.integers(0, 2**32 - 1))
def test_zero_noise_gives_the_exact_scan(seed: int) -> None:
    world = _walled(noise_std=0.0, seed=seed)
    scans = _scans(IRSensor(world))
    expected = 5.0 / np.cos(scans[0].angles)  # the wall, exactly (see the spacing test)
    for scan in scans:
        np.testing.assert_allclose(scan.ranges, expected, rtol=1e-12)
    assert scans == _scans(IRSensor(_walled(noise_std=0.0, seed=seed + 1)))


@given(
    seed=st.integers(0, 2**32 - 1),
    std=st.floats(0.01, 10.0),
    range_max=st.floats(5.0, 15.0),
)
def test_noise_is_gaussian_per_ray_then_clipped_at_0_and_cut_at_range_max(
    seed: int, std: float, range_max: float
) -> None:
    """Scan n adds draws n*rays .. (n+1)*rays - 1 of ``default_rng(seed).normal(0, std)``."""
    exact = IRSensor(_walled(range_max=range_max)).scan(Pose(0, 0, 0)).ranges
    sensor = IRSensor(_walled(noise_std=std, seed=seed, range_max=range_max))
    draws = np.random.default_rng(seed)
    for scan in _scans(sensor):
        noisy = np.maximum(exact + draws.normal(0.0, std, len(exact)), 0.0)
        expected = np.where(noisy > range_max, np.inf, noisy)
        np.testing.assert_array_equal(scan.ranges, expected)
        finite = scan.ranges[np.isfinite(scan.ranges)]
        assert (finite >= 0).all() and (finite <= range_max).all()
        assert (scan.ranges[np.isinf(exact)] == np.inf).all(), "noise created a return"


def test_noise_clips_at_zero_and_keeps_no_return_as_inf() -> None:
    # Wall at 5 ft, seen only by the rays within 40 deg of the heading at range_max 6.5 ft;
    # std 20 ft pushes about 40% of the readings below zero and many beyond range_max.
    sensor = IRSensor(_walled(noise_std=20.0, seed=3, range_max=6.5))
    exact = IRSensor(_walled(range_max=6.5)).scan(Pose(0, 0, 0)).ranges
    ranges = np.concatenate([s.ranges for s in _scans(sensor, 20)])
    assert (ranges == 0.0).any(), "no reading was clipped at 0"
    assert (ranges[np.isfinite(ranges)] >= 0.0).all()
    assert (ranges.reshape(20, -1)[:, np.isinf(exact)] == np.inf).all()


def test_reset_restarts_the_noise() -> None:
    sensor = IRSensor(_walled(noise_std=0.5, seed=7))
    first = _scans(sensor)
    sensor.reset()
    assert _scans(sensor) == first


def test_params_default_to_the_world_sensor_and_can_be_overridden() -> None:
    world = _walled(rays=11)
    assert IRSensor(world).params == world.sensor
    assert len(IRSensor(world).scan(world.start).ranges) == 11
    other = SensorParams(rays=5, fov=1.0)
    assert len(IRSensor(world, other).scan(world.start).ranges) == 5
    with pytest.raises(TypeError, match="`params` must be a SensorParams or None"):
        IRSensor(world, {"rays": 5})  # type: ignore[arg-type]


@pytest.mark.paper("sensor.fov")
def test_default_beams_split_the_rays_25_26_25_with_the_borders_in_front() -> None:
    """76 rays 1.8 degrees apart: rays 25 and 50 lie on the +-22.5 degree borders (front)."""
    from collections import Counter

    from ifgm_ref.core.laserscan import Beam
    from ifgm_ref.core.pose import Point, Pose
    from ifgm_ref.sim.sensor import IRSensor
    from ifgm_ref.sim.world import World

    scan = IRSensor(World(start=Pose(0.0, 0.0, 0.0), goal=Point(5.0, 0.0))).scan(
        Pose(0.0, 0.0, 0.0)
    )
    beams = scan.beams
    assert Counter(beams) == {Beam.RIGHT: 25, Beam.FRONT: 26, Beam.LEFT: 25}
    assert beams[25] is Beam.FRONT and beams[50] is Beam.FRONT
    assert beams[24] is Beam.RIGHT and beams[51] is Beam.LEFT


def test_beam_mask_agrees_with_beam_of_on_every_ray() -> None:
    from ifgm_ref.core.laserscan import Beam
    from ifgm_ref.core.pose import Point, Pose
    from ifgm_ref.sim.sensor import IRSensor
    from ifgm_ref.sim.world import World

    scan = IRSensor(World(start=Pose(0.0, 0.0, 0.0), goal=Point(5.0, 0.0))).scan(
        Pose(0.0, 0.0, 0.0)
    )
    for beam in Beam:
        assert scan.beam_mask(beam).tolist() == [b is beam for b in scan.beams]
