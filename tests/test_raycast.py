"""The ray-casting kernel (ifgm_ref.sim.raycast) against shapely's exact geometry.

Oracle: the first hit of a ray is the distance from its origin to ``ray & obstacle``, the
intersection of the ray (a shapely ``LineString``) with each polygon (exact in float64), and
for circles the textbook root ``p - sqrt(r^2 - h^2)`` (shapely's ``buffer`` replaces a circle
by chords, which a grazing ray can miss altogether, so it is no oracle for circle hits).

Tolerances:

* ``TOL = 1e-9`` ft on distances. Scenes span tens of feet, where float64 rounding in the kernel
  and in shapely is about 1e-14 ft; 1e-9 leaves five orders of margin and is still a
  hundred-millionth of the smallest obstacle drawn.
* ``DELTA = 1e-11`` rad of ray direction. A ray that passes a vertex or touches a circle within
  rounding (~1e-15 rad) may be counted as hitting or missing, by the kernel as by shapely:
  there the exact answer jumps. A range is therefore accepted if it lies between the exact
  answers of the rays ``DELTA`` either side (and the ray itself), widened by ``TOL``. For a ray
  meeting an edge head-on the three differ by about ``DELTA`` times the distance (< 1e-9 ft
  here), so the check stays tight; they spread only where the answer is ill-conditioned
  (glancing and grazing rays).
"""

from __future__ import annotations

import math
import re
from typing import NamedTuple

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, note
from hypothesis import strategies as st
from numpy.typing import NDArray

from ifgm_ref.sim import raycast
from ifgm_ref.sim.raycast import RayCaster, RayFan, cast_rays

#: Distance tolerance, ft (see the module docstring).
TOL = 1e-9
#: Ray-direction perturbation that separates ill-conditioned rays, rad (module docstring).
DELTA = 1e-11
#: Half-size of the square the scenes are drawn in, ft.
EXTENT = 20.0


class Scene(NamedTuple):
    """Obstacles and a ray origin: polygons as ``(v, 2)`` vertex arrays, circles as arrays."""

    polygons: tuple[NDArray[np.float64], ...]
    centers: NDArray[np.float64]
    radii: NDArray[np.float64]
    origin: tuple[float, float]

    @property
    def segments(self) -> NDArray[np.float64]:
        edges = [np.stack([p, np.roll(p, -1, axis=0)], axis=1) for p in self.polygons]
        return np.concatenate(edges) if edges else np.zeros((0, 2, 2))

    def caster(self, max_range: float) -> RayCaster:
        return RayCaster(self.segments, self.centers, self.radii, max_range)

    def moved(self, angle: float, shift: tuple[float, float]) -> Scene:
        """The scene rotated by ``angle`` about (0, 0), then translated by ``shift``."""
        c, s = math.cos(angle), math.sin(angle)
        rot = np.array([[c, -s], [s, c]])

        def move(points: NDArray[np.float64]) -> NDArray[np.float64]:
            return points @ rot.T + np.asarray(shift)

        origin = move(np.array([self.origin]))[0]
        return Scene(
            tuple(move(p) for p in self.polygons),
            move(self.centers),
            self.radii,
            (float(origin[0]), float(origin[1])),
        )


coordinates = st.floats(-EXTENT, EXTENT, allow_nan=False)
vertex_radii = st.floats(0.5, 4.0)
circle_radii = st.floats(0.2, 4.0)


@st.composite
def star_polygons(
    draw: st.DrawFn,
    *,
    centers: st.SearchStrategy[float] = coordinates,
    max_vertices: int = 6,
    radii: st.SearchStrategy[float] = vertex_radii,
) -> NDArray[np.float64]:
    """Simple polygons: one vertex per sector of ``2 pi / n`` around a centre.

    Each vertex sits in the first 45% of its sector, so consecutive vertices are less than
    ``pi`` apart as seen from the centre: the polygon is star-shaped about it, hence simple.
    Shrinks towards a regular triangle of radius 0.5 at (0, 0).
    """
    n = draw(st.integers(3, max_vertices))
    cx, cy = draw(centers), draw(centers)
    offsets = np.array(draw(st.lists(st.floats(0.0, 0.45), min_size=n, max_size=n)))
    lengths = np.array(draw(st.lists(radii, min_size=n, max_size=n)))
    angles = (np.arange(n) + offsets) * (2.0 * math.pi / n)
    return np.column_stack([cx + lengths * np.cos(angles), cy + lengths * np.sin(angles)])


@st.composite
def scenes(
    draw: st.DrawFn,
    *,
    min_polygons: int = 0,
    max_polygons: int = 3,
    max_circles: int = 2,
    origins: st.SearchStrategy[float] = coordinates,
) -> Scene:
    """A few polygons and circles (possibly overlapping), and an origin outside all of them."""
    polygons = tuple(draw(st.lists(star_polygons(), min_size=min_polygons, max_size=max_polygons)))
    circles = draw(
        st.lists(st.tuples(coordinates, coordinates, circle_radii), max_size=max_circles)
    )
    centers = np.array([(x, y) for x, y, _ in circles]).reshape(-1, 2)
    radii = np.array([r for _, _, r in circles])
    origin = (draw(origins), draw(origins))
    point = shapely.Point(origin)
    assume(not any(shapely.Polygon(p).intersects(point) for p in polygons))
    assume(all(math.dist(origin, c) > r for c, r in zip(centers, radii, strict=True)))
    return Scene(polygons, centers, radii, origin)


#: Ranges: half the time one that reaches across the whole scene (what examples shrink to).
max_ranges = st.just(60.0) | st.floats(0.5, 60.0)


@st.composite
def ray_angles(draw: st.DrawFn, *, scene: Scene, max_rays: int = 12) -> NDArray[np.float64]:
    """Ray directions, each either free or aimed near a vertex or centre of the scene.

    Aimed rays make hits common; the aim's jitter shrinks to 0, i.e. to a ray exactly at a
    vertex or through a circle's centre.
    """
    targets = [tuple(v) for p in scene.polygons for v in p] + [tuple(c) for c in scene.centers]
    free = st.floats(-math.pi, math.pi)
    if not targets:
        return np.array(draw(st.lists(free, min_size=1, max_size=max_rays)))
    aimed = st.tuples(st.sampled_from(targets), st.floats(-0.3, 0.3)).map(
        lambda aim: math.atan2(aim[0][1] - scene.origin[1], aim[0][0] - scene.origin[0]) + aim[1]
    )
    return np.array(draw(st.lists(aimed | free, min_size=1, max_size=max_rays)))


def first_hits(scene: Scene, angles: NDArray[np.float64], reach: float) -> NDArray[np.float64]:
    """Oracle: exact distance to the first obstacle on each ray, ``inf`` if none within reach."""
    origin = np.asarray(scene.origin)
    ends = origin + reach * np.column_stack([np.cos(angles), np.sin(angles)])
    rays = shapely.linestrings(np.stack([np.broadcast_to(origin, ends.shape), ends], axis=1))
    best = np.full(len(angles), np.inf)
    start = shapely.Point(origin)
    for vertices in scene.polygons:
        touched = shapely.intersection(rays, shapely.Polygon(vertices))
        hit = ~shapely.is_empty(touched)
        best[hit] = np.minimum(best[hit], shapely.distance(start, touched[hit]))
    for (cx, cy), r in zip(scene.centers, scene.radii, strict=True):
        for i, a in enumerate(angles):
            ux, uy = cx - origin[0], cy - origin[1]
            p = ux * math.cos(a) + uy * math.sin(a)  # centre's projection on the ray
            h2 = ux * ux + uy * uy - p * p  # squared distance from centre to the ray's line
            if p >= 0.0 and h2 <= r * r:
                t = p - math.sqrt(r * r - h2)
                if t <= reach:
                    best[i] = min(best[i], t)
    return best


def first_hit_bounds(
    scene: Scene, angles: NDArray[np.float64], max_range: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Lowest and highest exact first hit over each ray and its two ``DELTA`` neighbours.

    Hits are searched beyond ``max_range``, so that a hit within rounding of it is known.
    """
    reach = max_range * 1.5 + 1.0
    hits = np.stack([first_hits(scene, angles + e, reach) for e in (-DELTA, 0.0, DELTA)])
    return hits.min(axis=0), hits.max(axis=0)


def misfits(
    got: NDArray[np.float64],
    low: NDArray[np.float64],
    high: NDArray[np.float64],
    max_range: float,
) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
    """Which finite and which ``inf`` ranges of ``got`` disagree with hits in ``[low, high]``.

    A finite range must be <= ``max_range`` and within ``[low, high]`` (+- ``TOL``); ``inf``
    needs some neighbouring ray with no hit up to ``max_range`` (- ``TOL``).
    """
    finite = np.isfinite(got)
    with np.errstate(invalid="ignore"):
        bad_finite = finite & ((got > max_range) | (got < low - TOL) | (got > high + TOL))
    bad_inf = (got == np.inf) & (high < max_range - TOL)
    return bad_finite, bad_inf


def assert_first_hits(
    got: NDArray[np.float64],
    scene: Scene,
    angles: NDArray[np.float64],
    max_range: float,
    *,
    which: str,
) -> None:
    """Check the ``which`` ("finite" or "inf") ranges of ``got`` against the shapely oracle."""
    __tracebackhide__ = True
    low, high = first_hit_bounds(scene, angles, max_range)
    note(f"scene={scene!r}\nangles={angles.tolist()!r}\ngot={got.tolist()!r}")
    bad_finite, bad_inf = misfits(got, low, high, max_range)
    bad = np.flatnonzero(bad_finite if which == "finite" else bad_inf)
    if not bad.size:
        return
    i = bad[0]
    if which == "finite":
        expected = f"in [{low[i]!r}, {min(high[i], max_range)!r}] (shapely, +-{TOL})"
    else:
        expected = f"finite: shapely finds an obstacle at {high[i]!r} <= {max_range!r}"
    err = AssertionError(f"ranges[{i}]={got[i]!r}, but should be {expected} [cast]")
    err.add_note(
        "reproduce: RayCaster("
        f"{scene.segments.tolist()!r}, {scene.centers.tolist()!r}, {scene.radii.tolist()!r}, "
        f"{max_range!r}).cast({scene.origin!r}, [{float(angles[i])!r}])"
    )
    raise err


@given(data=st.data())
def test_finite_range_is_the_distance_to_the_first_obstacle(data: st.DataObject) -> None:
    scene = data.draw(scenes(), label="scene")
    angles = data.draw(ray_angles(scene=scene), label="angles")
    max_range = data.draw(max_ranges, label="max_range")
    got = scene.caster(max_range).cast(scene.origin, angles)
    assert got.shape == angles.shape
    assert_first_hits(got, scene, angles, max_range, which="finite")


@given(data=st.data())
def test_inf_range_means_no_obstacle_within_max_range(data: st.DataObject) -> None:
    scene = data.draw(scenes(), label="scene")
    angles = data.draw(ray_angles(scene=scene), label="angles")
    max_range = data.draw(max_ranges, label="max_range")
    got = scene.caster(max_range).cast(scene.origin, angles)
    assert not np.isnan(got).any()
    assert_first_hits(got, scene, angles, max_range, which="inf")


@given(data=st.data())
def test_ray_through_a_vertex_does_not_slip_between_its_edges(data: st.DataObject) -> None:
    scene = data.draw(scenes(min_polygons=1, max_circles=0), label="scene")
    # Aim at every vertex, and a few ulps to either side: the rays pass within rounding of it,
    # where a vertex side computed twice (once per edge) could disagree in sign and let the
    # ray through.
    vertices = np.concatenate(scene.polygons)
    aims = np.arctan2(vertices[:, 1] - scene.origin[1], vertices[:, 0] - scene.origin[0])
    angles = (aims[:, None] + np.arange(-8, 9) * np.spacing(aims)[:, None]).ravel()
    max_range = 100.0
    got = scene.caster(max_range).cast(scene.origin, angles)
    assert_first_hits(got, scene, angles, max_range, which="finite")
    assert_first_hits(got, scene, angles, max_range, which="inf")


@given(data=st.data())
def test_adding_an_obstacle_never_increases_a_range(data: st.DataObject) -> None:
    scene = data.draw(scenes(), label="scene")
    extra = data.draw(star_polygons(), label="extra polygon")
    extra_circle = data.draw(
        st.tuples(coordinates, coordinates, circle_radii), label="extra circle"
    )
    angles = data.draw(ray_angles(scene=scene), label="angles")
    max_range = data.draw(max_ranges, label="max_range")
    before = scene.caster(max_range).cast(scene.origin, angles)
    bigger = Scene(
        (*scene.polygons, extra),
        np.vstack([scene.centers, extra_circle[:2]]),
        np.append(scene.radii, extra_circle[2]),
        scene.origin,
    )
    after = bigger.caster(max_range).cast(scene.origin, angles)
    # TOL: the vertex set changes, so the matrix product may round a side value differently.
    worse = np.flatnonzero(after > before + TOL)
    assert not worse.size, (
        f"ranges[{worse[0]}]={after[worse[0]]!r} with the extra obstacle, but should be <= "
        f"{before[worse[0]]!r} (without it) [cast]"
    )


@given(data=st.data())
def test_moving_scene_and_rays_together_leaves_ranges_unchanged(data: st.DataObject) -> None:
    scene = data.draw(scenes(), label="scene")
    angles = data.draw(ray_angles(scene=scene), label="angles")
    max_range = data.draw(max_ranges, label="max_range")
    turn = data.draw(st.floats(-math.pi, math.pi), label="rotation")
    shift = data.draw(st.tuples(coordinates, coordinates), label="translation")
    moved = scene.moved(turn, shift)
    got = moved.caster(max_range).cast(moved.origin, angles + turn)
    # The original ranges of each ray and its DELTA neighbours, searched beyond max_range,
    # bound the moved one: rounding in the transform shifts an obstacle by ~1e-14 ft, far
    # less than DELTA turns a ray.
    caster = scene.caster(max_range * 1.5 + 1.0)
    near = np.stack([caster.cast(scene.origin, angles + e) for e in (-DELTA, 0.0, DELTA)])
    low, high = near.min(axis=0), near.max(axis=0)
    bad_finite, bad_inf = misfits(got, low, high, max_range)
    bad = np.flatnonzero(bad_finite | bad_inf)
    assert not bad.size, (
        f"ranges[{bad[0]}]={got[bad[0]]!r} after moving, but should be in "
        f"[{low[bad[0]]!r}, {high[bad[0]]!r}] (before moving, +-{TOL}; inf beyond "
        f"{max_range!r}) [cast]"
    )


@given(data=st.data())
def test_cast_fan_matches_cast_at_the_summed_angles(data: st.DataObject) -> None:
    scene = data.draw(scenes(), label="scene")
    relative = data.draw(ray_angles(scene=scene), label="fan angles")
    heading = data.draw(st.floats(-math.pi, math.pi), label="heading")
    max_range = data.draw(max_ranges, label="max_range")
    got = scene.caster(max_range).cast_fan(scene.origin, heading, RayFan.of(relative))
    # The fan turns unit vectors instead of taking cos and sin of heading + angle: the two
    # directions differ by a few ulps, far less than DELTA.
    caster = scene.caster(max_range * 1.5 + 1.0)
    angles = heading + relative
    near = np.stack([caster.cast(scene.origin, angles + e) for e in (-DELTA, 0.0, DELTA)])
    bad_finite, bad_inf = misfits(got, near.min(axis=0), near.max(axis=0), max_range)
    bad = np.flatnonzero(bad_finite | bad_inf)
    assert not bad.size, (
        f"ranges[{bad[0]}]={got[bad[0]]!r} from cast_fan, but should be {near[1, bad[0]]!r} "
        f"as from cast (+-{TOL}) [cast_fan({scene.origin!r}, {heading!r}, ...)]"
    )


@given(data=st.data())
def test_a_cast_does_not_depend_on_the_casts_before_it(data: st.DataObject) -> None:
    # The caster keeps the edges culled for a nearby origin; the ranges must be those of a
    # fresh caster bit for bit, whether the earlier origins were near (cache reused) or far.
    scene = data.draw(scenes(), label="scene")
    angles = data.draw(ray_angles(scene=scene), label="angles")
    max_range = data.draw(max_ranges, label="max_range")
    shifts = st.tuples(st.floats(-0.2, 0.2), st.floats(-0.2, 0.2)).map(
        lambda s: (s[0] * max_range, s[1] * max_range)
    )
    walk = data.draw(st.lists(shifts, min_size=1, max_size=5), label="earlier origins")
    caster = scene.caster(max_range)
    for dx, dy in walk:
        caster.cast((scene.origin[0] + dx, scene.origin[1] + dy), angles)
    got = caster.cast(scene.origin, angles)
    expected = scene.caster(max_range).cast(scene.origin, angles)
    assert got.tobytes() == expected.tobytes(), (
        f"ranges={got.tolist()!r} after casts from {walk!r}, but should be "
        f"{expected.tolist()!r} [cast({scene.origin!r}, ...)]"
    )
    # cast_fan keeps the turned rays of the last heading: a new fan at that heading, and the
    # heading -0.0 after 0.0, must not reuse them.
    fans = [RayFan.of(angles), RayFan.of(angles[::-1])]
    for heading, fan in [(0.0, fans[0]), (0.0, fans[1]), (-0.0, fans[1]), (-0.0, fans[1])]:
        got = caster.cast_fan(scene.origin, heading, fan)
        expected = scene.caster(max_range).cast_fan(scene.origin, heading, fan)
        assert got.tobytes() == expected.tobytes(), (
            f"ranges={got.tolist()!r}, but should be {expected.tolist()!r} "
            f"[cast_fan({scene.origin!r}, {heading!r}, ...) after other casts]"
        )


# Exact cases: (segments, circles, origin, angles, max_range, expected ranges).
SQUARE = [((5, -1), (5, 1)), ((5, 1), (7, 1)), ((7, 1), (7, -1)), ((7, -1), (5, -1))]
HALF_PI = math.pi / 2


@pytest.mark.parametrize(
    ("segments", "circles", "origin", "angles", "max_range", "expected"),
    [
        pytest.param(SQUARE, [], (0, 0), [0.0, math.pi], 10.0, [5.0, math.inf], id="face"),
        pytest.param(SQUARE, [], (0, 1), [0.0], 10.0, [5.0], id="through-vertex"),
        pytest.param(SQUARE, [], (0, 2), [0.0], 10.0, [math.inf], id="parallel-above"),
        pytest.param(SQUARE, [], (3, -1), [0.0], 10.0, [2.0], id="along-edge"),
        pytest.param(SQUARE, [], (9, -1), [math.pi], 10.0, [2.0], id="along-edge-reversed"),
        pytest.param(SQUARE, [], (6, 1), [HALF_PI, 0.0], 10.0, [0.0, 0.0], id="on-edge"),
        pytest.param(SQUARE, [], (5, 1), [HALF_PI, 2.0], 10.0, [0.0, 0.0], id="on-vertex"),
        pytest.param(SQUARE, [], (6, 0), [0.0, math.pi], 10.0, [1.0, 1.0], id="inside-polygon"),
        pytest.param(SQUARE, [], (0, 0), [0.0], 5.0, [5.0], id="hit-at-max-range"),
        pytest.param(SQUARE, [], (0, 0), [0.0], 4.999, [math.inf], id="beyond-max-range"),
        pytest.param([((3, 0), (3, 0))], [], (0, 0), [0.0, 0.1], 5.0, [3.0, math.inf], id="dot"),
        pytest.param([], [((5, 1), 1.0)], (0, 0), [0.0], 10.0, [5.0], id="tangent"),
        pytest.param([], [((0, 4), 1.0)], (0, 0), [HALF_PI], 10.0, [3.0], id="circle"),
        pytest.param([], [((0, 4), 1.0)], (0, 0), [-HALF_PI], 10.0, [math.inf], id="behind"),
        pytest.param([], [((0, 4), 1.0)], (0, 3.5), [0.0, 1.0], 10.0, [0.0, 0.0], id="inside"),
        pytest.param([], [((0, 4), 1.0)], (0, 3), [-HALF_PI], 10.0, [0.0], id="on-circle"),
        pytest.param(
            SQUARE, [((3, 0), 1.0)], (0, 0), [0.0], 10.0, [2.0], id="nearest-of-overlapping"
        ),
        pytest.param([], [], (0, 0), [0.0, 1.0], 10.0, [math.inf, math.inf], id="empty"),
        pytest.param(SQUARE, [], (0, 0), [], 10.0, [], id="no-rays"),
    ],
)
def test_cast_rays_exact_cases(
    segments: list,
    circles: list,
    origin: tuple[float, float],
    angles: list[float],
    max_range: float,
    expected: list[float],
) -> None:
    centers = [c for c, _ in circles]
    radii = [r for _, r in circles]
    got = cast_rays(origin, angles, segments, centers, radii, max_range)
    assert got.tolist() == pytest.approx(expected, abs=1e-12), (
        f"ranges={got.tolist()}, but should be {expected} "
        f"[cast_rays({origin}, {angles}, ..., max_range={max_range})]"
    )


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"segments": [[1.0, 2.0, 3.0]]}, "`segments` must have shape (n, 2, 2), got (1, 3)"),
        ({"segments": [((0, 0), (math.nan, 1))]}, "`segments` must be finite"),
        ({"circle_centers": [(0, 0)], "circle_radii": [1.0, 2.0]}, "len(circle_radii)=2"),
        ({"circle_centers": [(0, 0)], "circle_radii": [0.0]}, "`circle_radii` must be > 0"),
        ({"max_range": 0.0}, "`max_range` must be a finite number > 0, got 0.0"),
        ({"max_range": math.inf}, "`max_range` must be a finite number > 0, got inf"),
        ({"max_range": True}, "`max_range` must be a finite number > 0, got True"),
    ],
)
def test_ray_caster_rejects_bad_input(kwargs: dict, message: str) -> None:
    args = {"segments": [], "circle_centers": [], "circle_radii": [], "max_range": 10.0}
    args.update(kwargs)
    with pytest.raises(ValueError, match=re.escape(message)):
        RayCaster(**args)


def _both_paths(
    scene: Scene, angles: NDArray[np.float64], max_range: float, monkeypatch: pytest.MonkeyPatch
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The ranges with every (circle, ray) pair computed, and with the facing pairs only."""
    monkeypatch.setattr(raycast, "_PAIRS_FROM", math.inf)
    every = scene.caster(max_range).cast(scene.origin, angles)
    monkeypatch.setattr(raycast, "_PAIRS_FROM", 0)
    facing = scene.caster(max_range).cast(scene.origin, angles)
    return every, facing


@st.composite
def crowded_scenes(draw: st.DrawFn) -> tuple[Scene, NDArray[np.float64]]:
    """Many circles (BARN's cylinders are many and small), the origin sometimes a hair off
    one of them, and rays aimed at the circles' tangents as well as free ones."""
    count = draw(st.integers(1, 30))
    points = draw(st.lists(st.tuples(coordinates, coordinates), min_size=count, max_size=count))
    centers = np.array(points)
    radii = np.array(draw(st.lists(st.floats(0.01, 3.0), min_size=count, max_size=count)))
    if draw(st.booleans()):  # just outside circle 0, at 1e-12 to 0.1 of its radius
        bearing, gap = draw(st.floats(-math.pi, math.pi)), draw(st.floats(-12.0, -1.0))
        distance = radii[0] * (1.0 + 10.0**gap)
        origin = (
            float(centers[0, 0] + distance * math.cos(bearing)),
            float(centers[0, 1] + distance * math.sin(bearing)),
        )
    else:
        origin = (draw(coordinates), draw(coordinates))
    assume(all(math.dist(origin, c) > r for c, r in zip(centers, radii, strict=True)))
    rel = centers - origin
    bearings = np.arctan2(rel[:, 1], rel[:, 0])
    half = np.arcsin(radii / np.hypot(rel[:, 0], rel[:, 1]))
    tangents = np.concatenate([bearings - half, bearings + half])
    free = draw(st.lists(st.floats(-math.pi, math.pi), max_size=40))
    return Scene((), centers, radii, origin), np.concatenate([tangents, free])


@given(case=crowded_scenes(), max_range=max_ranges)
def test_testing_only_the_rays_facing_a_circle_changes_no_bit(
    case: tuple[Scene, NDArray[np.float64]], max_range: float
) -> None:
    """The facing pairs (``raycast._facing_pairs``) give every range of the full (circle,
    ray) computation to the bit, tangent rays and an origin a hair off a circle included."""
    scene, angles = case
    with pytest.MonkeyPatch.context() as monkeypatch:
        every, facing = _both_paths(scene, angles, max_range, monkeypatch)
    assert facing.tobytes() == every.tobytes(), (
        f"ranges={facing.tolist()!r}, but should be {every.tolist()!r} [{scene!r}]"
    )
