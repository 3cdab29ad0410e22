"""The world classes, solvable by construction and checked: one generator per class.

Every class is one generator, a function of a :class:`~ifgm_ref.sim.worldgen.draws.Draw` (the
source of its random choices), used twice: as a Hypothesis strategy
(:mod:`ifgm_ref.oracle.strategies`, ``*_worlds()``, for the property checks; failing worlds
shrink) and as plain seeded sampling (:func:`random_world`, for the benchmark; the same seed
gives the same world). Each draws one navigation problem of a class the paper talks about
(section 5: "obstacles of simple but different shapes", "critical shaped" U and H obstacles,
Figure 7's symmetric obstacles) and returns a :class:`~ifgm_ref.sim.world.World`:

=======================  ==========================================================================
generator                class
=======================  ==========================================================================
:func:`open_world`       1-4 simple convex obstacles (discs, rectangles, regular polygons) near the
                         start-goal line, every passage between them wider than the robot
:func:`u_world`          a U across the line, opening towards the start (Figure 8); half of them
                         the paper's trap, met head-on (section 5.2, Table 1)
:func:`h_world`          an H across the line, one cavity facing the start (Figure 8); half of
                         them the paper's trap
:func:`symmetric_world`  three equal discs or squares across the line, symmetric about it
                         (Figure 7), their gaps either wider than the IFGM gap threshold or
                         narrower than the robot
:func:`mixed_world`      two or three of the above in a row, 30 ft apart
:func:`enclosed_world`   the goal inside a closed box: unsolvable, for planners that report it
:func:`gap_wall`         a wall across the line pierced by one gap, and the gap
=======================  ==========================================================================

Solvability. The plane is unbounded (``bounds=None``), obstacles of one feature keep at least
:data:`PASSAGE` ft from those of another (so the robot disc fits between any two), U and H
cavities are wider than the robot, and start and goal keep :data:`START_GOAL_CLEARANCE` ft
from every obstacle. Then the obstacles inflated by the robot radius are disjoint, simply
connected sets, whose complement is connected: a path exists. :func:`solvable` checks it
independently with shapely (free space = a box minus the inflated obstacles; start and goal in
one connected part), and every generator asserts it.

Shrinking. A candidate obstacle that would come too close to another or to the start or goal
is dropped, not rejected, so draws are never wasted; lists shrink to fewer obstacles, kinds
to discs (the first choice), numbers to the low end of their ranges, the placement rotation
to 0: a failing world shrinks towards one simple obstacle straight on the line.

Placement. The class is drawn in a canonical frame (start at the origin facing +x, goal on
+x) and then moved by a drawn rigid motion (:func:`placed`), so that goals lie in every
direction: a quadrant-blind arctan or a frame mix-up cannot hide.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence

import numpy as np
import shapely

from ifgm_ref.core.errors import WorldError
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.sim.shapes import circle, h_shape, rectangle, regular_polygon, u_shape
from ifgm_ref.sim.world import Circle, Obstacle, Polygon, World
from ifgm_ref.sim.worldgen.draws import Draw, RandomDraw

#: Robot radius of every generated world, ft (the default :class:`RobotParams`).
ROBOT_RADIUS = 1.0
#: Minimum distance between obstacles of different features, ft: the robot's diameter plus
#: one foot, so the disc passes between any two with half a foot either side.
PASSAGE = 2.0 * ROBOT_RADIUS + 1.0
#: Minimum distance from the start and the goal to any obstacle, ft: the robot's radius plus
#: two feet, so the robot starts free and the goal can be reached from every side.
START_GOAL_CLEARANCE = ROBOT_RADIUS + 2.0
#: Symmetric triples (Figure 7): a narrow gap is below the robot's diameter minus this margin,
#: a wide one above IFGM's default gap threshold ``2 r + 1`` plus it, ft. Gaps in between
#: (the robot fits, barely) are not drawn: from afar they look wider than they are (Figure 7
#: notes in :mod:`ifgm_ref.io.scenarios`), which no planner of the paper is built to judge.
SYMMETRIC_GAP_MARGIN = 0.5


def _clear_of(candidate: Obstacle, others: Sequence[Obstacle], gap: float) -> bool:
    geometry = candidate.geometry
    return all(shapely.distance(geometry, other.geometry) >= gap for other in others)


def _clear_of_points(candidate: Obstacle, points: Sequence[tuple[float, float]]) -> bool:
    return all(candidate.distance(p) >= START_GOAL_CLEARANCE for p in points)


def _keep(
    candidates: Sequence[Obstacle],
    kept: list[Obstacle],
    points: Sequence[tuple[float, float]],
) -> list[Obstacle]:
    """Add the candidates that keep :data:`PASSAGE` from ``kept`` and clear of ``points``."""
    for candidate in candidates:
        if _clear_of_points(candidate, points) and _clear_of(candidate, kept, PASSAGE):
            kept.append(candidate)
    return kept


def convex_obstacle(
    d: Draw,
    *,
    x: tuple[float, float],
    y: tuple[float, float] = (-8.0, 8.0),
    size: tuple[float, float] = (1.0, 6.0),
) -> Obstacle:
    """One simple convex obstacle (disc, rectangle or regular polygon) centred in ``x`` x ``y``.

    ``size`` bounds the diameter (discs, polygons) or the side lengths (rectangles), ft.
    """
    kind = d.choice(("disc", "rectangle", "polygon"), "kind")
    cx = d.floats(*x, "centre x")
    cy = d.floats(*y, "centre y")
    extent = d.floats(*size, "size")
    if kind == "disc":
        return circle((cx, cy), extent / 2.0)
    if kind == "rectangle":
        other = d.floats(*size, "other side")
        return rectangle((cx, cy), extent, other, d.floats(0.0, math.pi, "angle"))
    sides = d.integers(3, 8, "sides")
    return regular_polygon((cx, cy), extent / 2.0, sides, d.floats(0.0, math.pi, "angle"))


def _clutter(d: Draw, length: float, max_size: int) -> list[Obstacle]:
    return d.repeat(
        lambda d: convex_obstacle(d, x=(0.2 * length, 0.8 * length)),
        max_size=max_size,
        label="clutter",
    )


def solvable(world: World) -> bool:
    """Whether the robot disc can get from start to goal (shapely, obstacles inflated by r).

    Circles are inflated with 64 chords per quarter: chords make an inflated disc slightly
    *smaller* than the true one, by under ``r * 1.2e-4`` ft, far below the strategies'
    margins.

    >>> solvable(World(start=(0, 0, 0), goal=(20, 0), obstacles=[circle((10, 0), 2)]))
    True
    """
    r = world.robot.radius
    start, goal = shapely.Point(world.start.position), shapely.Point(world.goal)
    if not world.obstacles:
        return True
    inflated = shapely.union_all(
        [shapely.buffer(ob.geometry, r, quad_segs=64) for ob in world.obstacles]
    )
    if inflated.intersects(start) or inflated.intersects(goal):
        return False
    box = shapely.box(*inflated.union(start).union(goal).bounds).buffer(10.0)
    free = box.difference(inflated)
    parts = getattr(free, "geoms", [free])
    return any(part.contains(start) and part.contains(goal) for part in parts)


def _mover(angle: float, shift: tuple[float, float]) -> Callable[[Sequence[float]], Point]:
    c, s = math.cos(angle), math.sin(angle)
    return lambda p: Point(c * p[0] - s * p[1] + shift[0], s * p[0] + c * p[1] + shift[1])


def placed_obstacle(obstacle: Obstacle, angle: float, shift: tuple[float, float]) -> Obstacle:
    """``obstacle`` rotated by ``angle`` about the origin, then shifted by ``shift`` (ft)."""
    move = _mover(angle, shift)
    if isinstance(obstacle, Circle):
        return Circle(move(obstacle.center), obstacle.radius)
    return Polygon(tuple(move(v) for v in obstacle.vertices))


def placed_point(point: Sequence[float], angle: float, shift: tuple[float, float]) -> Point:
    """``point`` rotated by ``angle`` about the origin, then shifted by ``shift`` (ft)."""
    return _mover(angle, shift)(point)


def placed_pose(pose: Pose, angle: float, shift: tuple[float, float]) -> Pose:
    """``pose`` rotated by ``angle`` about the origin, then shifted by ``shift`` (ft): its
    position moved as :func:`placed_point` moves it, its heading turned by ``angle``.

    >>> placed_pose(Pose(1.0, 0.0, 3.0), math.pi / 2, (0.0, 0.0)).theta  # wrapped
    -1.7123889803846897
    """
    return Pose(*placed_point(pose.position, angle, shift), wrap_angle(pose.theta + angle))


def placed(world: World, angle: float, shift: tuple[float, float]) -> World:
    """``world`` rotated by ``angle`` about the origin, then shifted by ``shift`` (ft).

    The whole problem moves: obstacles, start pose (heading included) and goal.

    >>> moved = placed(World(start=(0, 0, 0), goal=(10, 0)), math.pi / 2, (1.0, 2.0))
    >>> [round(v, 12) for v in (*moved.start, *moved.goal)]
    [1.0, 2.0, 1.570796326795, 1.0, 12.0]
    """
    return World(
        start=placed_pose(world.start, angle, shift),
        goal=placed_point(world.goal, angle, shift),
        obstacles=tuple(placed_obstacle(ob, angle, shift) for ob in world.obstacles),
        bounds=None,
        robot=world.robot,
        sensor=world.sensor,
        name=world.name,
    )


def placement(d: Draw) -> tuple[float, tuple[float, float]]:
    """A rigid motion: a rotation in ``[-pi, pi]`` and a shift of up to 50 ft per axis."""
    angle = d.floats(-math.pi, math.pi, "placement angle")
    shift = (d.floats(-50.0, 50.0, "placement dx"), d.floats(-50.0, 50.0, "placement dy"))
    return angle, shift


def _canonical(
    d: Draw,
    name: str,
    length: float,
    features: Sequence[Obstacle],
    clutter: Sequence[Obstacle],
) -> World:
    """A world from the origin to ``(length, 0)``, dropping conflicting clutter."""
    heading = d.floats(-math.pi / 4, math.pi / 4, "start heading")
    obstacles = _keep(clutter, list(features), ((0.0, 0.0), (length, 0.0)))
    return World(
        start=Pose(0.0, 0.0, heading),
        goal=Point(length, 0.0),
        obstacles=tuple(obstacles),
        name=name,
    )


def _world(
    d: Draw,
    name: str,
    length: float,
    features: Sequence[Obstacle],
    clutter: Sequence[Obstacle],
) -> World:
    """Assemble a canonical-frame world, place it, check it."""
    angle, shift = placement(d)
    world = placed(_canonical(d, name, length, features, clutter), angle, shift)
    assert solvable(world) == (name != "enclosed"), f"world class {name} built {world}"
    return world


def open_world(d: Draw, *, max_obstacles: int = 4) -> World:
    """Open worlds: 1 to ``max_obstacles`` simple convex obstacles near the start-goal line.

    The start is at the origin facing within 45 degrees of the goal, 20-40 ft away along +x
    (before placement); obstacle centres lie in the middle 60 % of the way, within 8 ft of the
    line. Every two obstacles keep :data:`PASSAGE` apart.
    """
    length = d.floats(20.0, 40.0, "start-goal distance")
    first = convex_obstacle(d, x=(0.3 * length, 0.7 * length), y=(-2.0, 2.0))
    clutter = _clutter(d, length, max_obstacles - 1)
    features = _keep([first], [], ((0.0, 0.0), (length, 0.0)))
    return _world(d, "open", length, features, clutter)


def u_feature(d: Draw, *, at: float) -> Obstacle:
    """A U centred near ``(at, 0)``, its mouth towards the start (within 30 degrees).

    Outer size 8-20 ft across the mouth, 5-14 ft deep, walls 0.5-2 ft thick: the cavity is
    at least 4 ft wide, twice the robot.
    """
    return u_shape(
        (at, d.floats(-3.0, 3.0, "U offset")),
        width=d.floats(8.0, 20.0, "U width"),
        depth=d.floats(5.0, 14.0, "U depth"),
        thickness=d.floats(0.5, 2.0, "U wall"),
        opening=math.pi + d.floats(-math.pi / 6, math.pi / 6, "U tilt"),
    )


def h_feature(d: Draw, *, at: float) -> Obstacle:
    """An H centred near ``(at, 0)``, a cavity towards the start (within 30 degrees).

    Walls 8-16 ft long and 8-20 ft apart (outer), 0.5-2 ft thick; the crossbar 0.5-2 ft.
    """
    return h_shape(
        (at, d.floats(-3.0, 3.0, "H offset")),
        width=d.floats(8.0, 20.0, "H width"),
        height=d.floats(8.0, 16.0, "H length"),
        thickness=d.floats(0.5, 2.0, "H wall"),
        bar_thickness=d.floats(0.5, 2.0, "H bar"),
        orientation=math.pi / 2 + d.floats(-math.pi / 6, math.pi / 6, "H tilt"),
    )


def symmetric_triple(d: Draw, *, at: float) -> list[Obstacle]:
    """Three equal discs or squares across the line at ``x = at``, the middle one on it."""
    size = d.floats(3.0, 8.0, "triple size")
    narrow = (0.3, 2.0 * ROBOT_RADIUS - SYMMETRIC_GAP_MARGIN)
    wide = (2.0 * ROBOT_RADIUS + 1.0 + SYMMETRIC_GAP_MARGIN, 7.0)
    gap = d.floats(*d.choice((narrow, wide), "triple gap kind"), "triple gap")
    pitch = size + gap
    if d.boolean("squares"):
        return [rectangle((at, k * pitch), size, size) for k in (-1, 0, 1)]
    return [circle((at, k * pitch), size / 2.0) for k in (-1, 0, 1)]


#: The paper's trap (section 5.2, Figure 8a; Table 1: FGM and APF "cannot avoid U shaped
#: obstacles", H-shaped ones are "dead-end scenarios"): a U or H met head-on, its cavity
#: opening towards the start within this angle of the start-goal line, rad (10 degrees).
TRAP_TILT = math.pi / 18
#: The trap's centre lies within this distance of the start-goal line, ft: the line runs deep
#: into the cavity, so a planner that steers into the cavity's gap meets its base.
TRAP_OFFSET = 2.0


def u_trap_feature(d: Draw, *, at: float) -> Obstacle:
    """The paper's U trap centred near ``(at, 0)``: met head-on, filling the view from inside.

    Outer size 16-28 ft across the mouth and 12-20 ft deep (Figure 8's U, ``u_trap`` in
    :mod:`ifgm_ref.io.scenarios`, is 24 x 16), walls 0.5-2 ft thick, the mouth towards the
    start within :data:`TRAP_TILT`, the centre within :data:`TRAP_OFFSET` of the line. The
    cavity, 12 ft wide or more, is a gap far wider than any gap threshold, so a gap follower
    steers in; at its base the side walls and the base fill the 135-degree view within the
    sensor's 15 ft, and there is no gap left (the local minimum of section 5.2).
    """
    return u_shape(
        (at, d.floats(-TRAP_OFFSET, TRAP_OFFSET, "U offset")),
        width=d.floats(16.0, 28.0, "U width"),
        depth=d.floats(12.0, 20.0, "U depth"),
        thickness=d.floats(0.5, 2.0, "U wall"),
        opening=math.pi + d.floats(-TRAP_TILT, TRAP_TILT, "U tilt"),
    )


def h_trap_feature(d: Draw, *, at: float) -> Obstacle:
    """The paper's H trap centred near ``(at, 0)``: a cavity met head-on, as for the U.

    Walls 20-30 ft long and 16-26 ft apart (outer; Figure 8's H, ``h_block``, is 24 x 20),
    0.5-2 ft thick, the crossbar 0.5-2 ft; the cavity towards the start within
    :data:`TRAP_TILT`, the centre within :data:`TRAP_OFFSET` of the line.
    """
    return h_shape(
        (at, d.floats(-TRAP_OFFSET, TRAP_OFFSET, "H offset")),
        width=d.floats(16.0, 26.0, "H width"),
        height=d.floats(20.0, 30.0, "H length"),
        thickness=d.floats(0.5, 2.0, "H wall"),
        bar_thickness=d.floats(0.5, 2.0, "H bar"),
        orientation=math.pi / 2 + d.floats(-TRAP_TILT, TRAP_TILT, "H tilt"),
    )


def _cavity_world(
    d: Draw,
    name: str,
    feature: Callable[..., Obstacle],
    trap: Callable[..., Obstacle],
    max_clutter: int,
) -> World:
    """A U or H world: half the draws the paper's trap (40-60 ft from start to goal), half
    the general feature (35-50 ft), plus up to ``max_clutter`` convex obstacles."""
    if d.boolean(f"paper's {name.upper()} trap"):
        length = d.floats(40.0, 60.0, "start-goal distance")
        obstacle = trap(d, at=length / 2.0)
    else:
        length = d.floats(35.0, 50.0, "start-goal distance")
        obstacle = feature(d, at=length / 2.0)
    return _world(d, name, length, [obstacle], _clutter(d, length, max_clutter))


def u_world(d: Draw, *, max_clutter: int = 0) -> World:
    """A U in the way, opening towards the start, plus up to ``max_clutter`` convex obstacles.

    Half the draws are the paper's trap (:func:`u_trap_feature`: head-on, 40-60 ft from start
    to goal), half the general U (:func:`u_feature`: tilted up to 30 degrees and off the line,
    35-50 ft). No clutter by default: the reference IFGM livelocks between a post and an H
    cavity (``tests/worlds/ifgm_h_post_livelock.json``, errata row 25).
    """
    return _cavity_world(d, "u", u_feature, u_trap_feature, max_clutter)


def h_world(d: Draw, *, max_clutter: int = 0) -> World:
    """An H in the way, a cavity facing the start, plus up to ``max_clutter`` convex obstacles.

    Half the draws are the paper's trap (:func:`h_trap_feature`), half the general H
    (:func:`h_feature`), as for :func:`u_world`. No clutter by default, as for
    :func:`u_world`.
    """
    return _cavity_world(d, "h", h_feature, h_trap_feature, max_clutter)


def symmetric_world(d: Draw) -> World:
    """Figure 7's class: three equal obstacles across the line, symmetric about it.

    Start-goal distance 30-50 ft (before placement); the triple halfway.
    """
    length = d.floats(30.0, 50.0, "start-goal distance")
    return _world(d, "symmetric", length, symmetric_triple(d, at=length / 2.0), [])


#: The features a mixed world strings together, by name.
_FEATURES = ("convex", "u", "h", "symmetric")


def mixed_world(d: Draw) -> World:
    """Two or three features (convex clusters, U, H, symmetric triple) in a row, 30 ft apart.

    The start-goal distance is 30 ft per feature plus 10 (a tilted H reaches 12 ft either
    side of its centre, so neighbours keep over 6 ft apart).
    """
    kinds = d.repeat(
        lambda d: d.choice(_FEATURES, "feature"), min_size=2, max_size=3, label="features"
    )
    length = 30.0 * len(kinds) + 10.0
    features: list[Obstacle] = []
    clutter: list[Obstacle] = []
    for k, kind in enumerate(kinds):
        at = 20.0 + 30.0 * k
        if kind == "convex":
            cluster = functools.partial(convex_obstacle, x=(at - 5.0, at + 5.0))
            clutter += d.repeat(cluster, max_size=3, label="cluster")
        elif kind == "u":
            features.append(u_feature(d, at=at))
        elif kind == "h":
            features.append(h_feature(d, at=at))
        else:
            features += symmetric_triple(d, at=at)
    return _world(d, "mixed", length, features, clutter)


def enclosed_world(d: Draw) -> World:
    """The unsolvable case: the goal inside a closed box of four overlapping walls.

    The box's inner half-size is 4-8 ft, its walls 0.5-2 ft thick; the goal is at its centre,
    20-40 ft from the start (before placement).
    """
    length = d.floats(20.0, 40.0, "start-goal distance")
    half = d.floats(4.0, 8.0, "box half-size")
    wall = d.floats(0.5, 2.0, "box wall")
    outer = 2.0 * (half + wall)
    mid = half + wall / 2.0
    box = [
        rectangle((length - mid, 0.0), wall, outer),
        rectangle((length + mid, 0.0), wall, outer),
        rectangle((length, -mid), outer, wall),
        rectangle((length, mid), outer, wall),
    ]
    return _world(d, "enclosed", length, box, [])


def gap_wall(d: Draw) -> tuple[World, Polygon]:
    """A wall across the line pierced by one gap of 3-4.5 robot diameters, off the line;
    returns the world and the gap (the box between the wall's ends).

    The wall is two rectangles 1-2 ft thick, each reaching 25 ft beyond the gap, halfway
    along a 30-45 ft start-goal line (before placement); the gap's centre is 1.5-4 ft to
    either side of the line, so a mirrored (sign-flipped) gap angle points at the wall. Why
    not narrower, down to ``d_th``: eq. (4) steers between the gap and the goal, not at the
    gap's middle, and the robot meets a gap of 2 diameters (4 ft) off-centre, too close to
    its edge, and goes round (``tests/worlds/gap_4ft_off_line.json``).
    """
    length = d.floats(30.0, 45.0, "start-goal distance")
    width = d.floats(6.0 * ROBOT_RADIUS, 9.0 * ROBOT_RADIUS, "gap width")
    offset = d.floats(1.5, 4.0, "gap offset") * d.choice((1, -1), "gap side")
    thick = d.floats(1.0, 2.0, "wall thickness")
    x, low, high = length / 2.0, offset - width / 2.0, offset + width / 2.0
    wall = [rectangle((x, low - 12.5), thick, 25.0), rectangle((x, high + 12.5), thick, 25.0)]
    gap = rectangle((x, offset), thick, width)
    angle, shift = placement(d)
    world = placed(_canonical(d, "gap_wall", length, wall, []), angle, shift)
    assert solvable(world), f"world class gap_wall built {world}"
    moved = placed_obstacle(gap, angle, shift)
    assert isinstance(moved, Polygon)  # a polygon moves as a polygon
    return world, moved


#: The solvable classes' generators by the names checks, reports and the benchmark use.
GENERATORS: dict[str, Callable[[Draw], World]] = {
    "open": open_world,
    "u": u_world,
    "h": h_world,
    "symmetric": symmetric_world,
    "mixed": mixed_world,
}


def random_world(world_class: str, seed: int | np.random.SeedSequence) -> World:
    """One world of ``world_class`` (a :data:`GENERATORS` name), sampled uniformly from a seed.

    The same seed gives the same world on every machine (numpy's PCG64).

    >>> random_world("u", 3) == random_world("u", np.random.SeedSequence(3))
    True
    """
    try:
        generate = GENERATORS[world_class]
    except KeyError:
        known = ", ".join(GENERATORS)
        raise WorldError(f"unknown world class {world_class!r}; known: {known}") from None
    return generate(RandomDraw(np.random.default_rng(seed)))
