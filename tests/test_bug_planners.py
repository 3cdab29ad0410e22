"""The classic Bug planners (ifgm_ref.planners.bug1, bug2, distbug), paper section 2.1.

Each planner is run in the simulator on built-in and hand-made worlds; the checks are the
properties the Bug literature proves or the paper's figures show: the goal is reached without
collision where it can be, Lumelsky and Stepanov's path-length bounds hold, an enclosed goal
is reported unreachable, DistBug leaves earlier than Bug1, and runs are deterministic.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from itertools import pairwise

import numpy as np
import pytest
import shapely

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import RobotParams, SensorParams, SimParams
from ifgm_ref.core.pose import Point, Pose, distance
from ifgm_ref.core.protocol import EpisodeParams, Planner
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners.boundary import GOAL_UNREACHABLE, BoundaryParams, BoundaryPlanner
from ifgm_ref.planners.bug1 import Bug1Planner
from ifgm_ref.planners.bug2 import Bug2Planner, signed_distance
from ifgm_ref.planners.distbug import DistBugPlanner, DistBugRule
from ifgm_ref.planners.sight import Episode, Sight
from ifgm_ref.sim.shapes import rectangle, regular_polygon, u_shape
from ifgm_ref.sim.simulator import Run, StopReason, simulate
from ifgm_ref.sim.world import Bounds, World

PLANNERS: dict[str, type[BoundaryPlanner]] = {
    "bug1": Bug1Planner,
    "bug2": Bug2Planner,
    "distbug": DistBugPlanner,
}
#: Distance the followers keep from an edge to the robot's centre with default tuning, ft:
#: the default robot's radius plus ``standoff_margin``.
STANDOFF = RobotParams().radius + BoundaryParams.paper().standoff_margin
#: Arena, start and goal of the hand-made worlds: those of the built-in demonstration worlds.
ARENA = Bounds(-15.0, -35.0, 85.0, 35.0)
START = Pose(0.0, 0.0, 0.0)
GOAL = Point(60.0, 0.0)


def _enclosure() -> World:
    """The goal inside a square ring of four 1 ft walls overlapping at the corners.

    A ring is not a simple polygon, so the walls are four rectangles; the cavity is 16 ft
    square, centred on the goal; the start is 50 ft outside it.
    """
    half, t = 9.0, 1.0
    gx, gy = GOAL
    walls = (
        rectangle((gx - half + t / 2, gy), t, 2 * half),
        rectangle((gx + half - t / 2, gy), t, 2 * half),
        rectangle((gx, gy + half - t / 2), 2 * half, t),
        rectangle((gx, gy - half + t / 2), 2 * half, t),
    )
    return World(start=START, goal=GOAL, obstacles=walls, bounds=ARENA, name="enclosure")


HANDMADE = {
    "two_boxes": lambda: World(
        start=START,
        goal=GOAL,
        obstacles=(rectangle((18.0, 1.0), 4.0, 10.0), rectangle((40.0, -2.0), 6.0, 8.0)),
        bounds=ARENA,
        name="two_boxes",
    ),
    "hexagon": lambda: World(
        start=START,
        goal=GOAL,
        obstacles=(regular_polygon((30.0, 0.5), 7.0, 6, angle=0.2),),
        bounds=ARENA,
        name="hexagon",
    ),
    "enclosure": _enclosure,
    # The start inside a U opening towards -y, 1.5 ft from its left wall: following from the
    # hit on the right wall (up, left, down), the robot crosses the m-line inside the U on
    # the left wall, farther from the goal than the hit point, with the goal direction free
    # for 20 ft; Bug2 must not leave there.
    "pocket": lambda: World(
        start=Pose(20.5, 0.0, 0.0),
        goal=GOAL,
        obstacles=(
            u_shape((30.0, 0.0), width=24.0, depth=16.0, thickness=1.0, opening=-math.pi / 2),
        ),
        bounds=ARENA,
        name="pocket",
    ),
}


@cache
def world(name: str) -> World:
    """A built-in world or one of :data:`HANDMADE`, by name."""
    return HANDMADE[name]() if name in HANDMADE else resolve_world(name)


@cache
def run(planner: str, world_name: str) -> Run:
    """One episode of ``planner`` in ``world_name`` (cached: episodes are deterministic)."""
    return simulate(world(world_name), PLANNERS[planner]())


def describe(planner: str, world_name: str) -> str:
    """What to paste to reproduce an episode, for failure messages."""
    return f"simulate(world({world_name!r}), {PLANNERS[planner].__name__}())"


@dataclass(frozen=True)
class FollowedObstacle:
    """An obstacle as the robot can follow it: grown by the stand-off.

    ``perimeter`` is p_i of Lumelsky and Stepanov's bounds; ``crossings`` is n_i, the number
    of times the m-line (start-goal segment) crosses its boundary; ``detour`` is what going
    round it adds to the m-line: the shorter boundary arc between the first and the last
    crossing, less the part of the m-line inside (0 when the m-line misses it).
    """

    perimeter: float
    crossings: int
    detour: float


def followed_obstacles(w: World) -> list[FollowedObstacle]:
    """Every obstacle of ``w`` buffered by :data:`STANDOFF` (shapely ``buffer(standoff)``).

    The robot's centre cannot follow the obstacle's own boundary: it follows the curve at the
    stand-off, so its perimeter is the one the bounds are about. ``quad_segs=64`` makes the
    chords of the rounded corners a negligible under-estimate (< 0.01 %).
    """
    m_line = shapely.LineString([w.start.position, w.goal])
    out = []
    for obstacle in w.obstacles:
        grown = obstacle.geometry.buffer(STANDOFF, quad_segs=64)
        ring = grown.exterior
        crossings = shapely.get_parts(m_line.intersection(ring))
        detour = 0.0
        if len(crossings):
            at = sorted(ring.line_locate_point(c) for c in crossings)
            arc = at[-1] - at[0]
            detour = min(arc, ring.length - arc) - m_line.intersection(grown).length
        out.append(FollowedObstacle(ring.length, len(crossings), detour))
    return out


def assert_reached_safely(planner: str, world_name: str) -> None:
    """The episode reached the goal and never touched an obstacle."""
    __tracebackhide__ = True
    result = run(planner, world_name).result
    if result.stop_reason != StopReason.GOAL_REACHED or result.collided:
        err = AssertionError(
            f"stop_reason={result.stop_reason!r}, collided={result.collided}, but should be "
            f"'goal_reached' without collision [{describe(planner, world_name)}]"
        )
        err.add_note(repr(result))
        raise err
    assert result.min_clearance > 0.0, f"min_clearance={result.min_clearance}"


def leave_points(r: Run, branch: str) -> list[Pose]:
    """The poses where the trace took ``branch`` (the leaving decisions)."""
    return [Pose(s.x, s.y, s.theta) for s in r.trace if s.branch == branch]


def hit_points(r: Run) -> list[Point]:
    """The positions where the robot started following an edge (the hit points H)."""
    return [
        Point(s.x, s.y)
        for before, s in pairwise(r.trace)
        if s.branch == "follow_edge" and before.branch != "follow_edge"
    ]


# -- registration data ------------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_bug_planner_follows_the_protocol(name: str) -> None:
    planner = PLANNERS[name]()
    assert isinstance(planner, Planner)
    assert planner.name == name
    assert PLANNERS[name].parameters[: len(BoundaryPlanner.parameters)] == (
        BoundaryPlanner.parameters
    )


def test_distbug_exposes_step_length_and_bug2_its_m_line_tolerance() -> None:
    assert "step_length" in DistBugPlanner.parameters
    assert "m_line_tolerance" in Bug2Planner.parameters
    assert Bug1Planner.parameters == BoundaryPlanner.parameters


@pytest.mark.parametrize("bad", [0, -2.0, math.inf, math.nan, "2", True])
def test_step_length_is_validated(bad: object) -> None:
    with pytest.raises(ParameterError, match=r"^`step_length` must be a finite number > 0"):
        simulate(world("box"), DistBugPlanner(), params={"step_length": bad})


@pytest.mark.parametrize("bad", [0, -0.1, math.inf, None])
def test_m_line_tolerance_is_validated(bad: object) -> None:
    with pytest.raises(ParameterError, match=r"^`m_line_tolerance` must be a finite number > 0"):
        simulate(world("box"), Bug2Planner(), params={"m_line_tolerance": bad})


def test_signed_distance_is_positive_left_of_the_m_line() -> None:
    start, goal = Point(0.0, 0.0), Point(0.0, 10.0)  # m-line along +y: left is -x
    assert signed_distance((-3.0, 4.0), start, goal) == 3.0
    assert signed_distance((3.0, 4.0), start, goal) == -3.0


# -- reaching the goal ------------------------------------------------------------------------
REACHABLE = ["free", "box", "u_trap", "h_block", "two_boxes", "hexagon", "pocket"]


@pytest.mark.parametrize("world_name", REACHABLE)
@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_bug_planner_reaches_the_goal_without_collision(name: str, world_name: str) -> None:
    assert_reached_safely(name, world_name)


@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_free_world_is_the_straight_run(name: str) -> None:
    """No obstacle: every Bug planner is the *move to goal* behaviour alone (Figure 4a)."""
    r = run(name, "free")
    assert {s.branch for s in r.trace[:-1]} == {"move_to_goal"}
    d = distance(world("free").start.position, world("free").goal)
    assert d - 0.5 <= r.result.path_length <= d


# -- Lumelsky and Stepanov's bounds -----------------------------------------------------------
BOUND_WORLDS = ["box", "u_trap", "h_block", "two_boxes", "hexagon"]


@pytest.mark.parametrize("world_name", BOUND_WORLDS)
def test_bug1_path_is_within_d_plus_one_and_a_half_perimeters(world_name: str) -> None:
    """Bug1: ``L <= D + 1.5 * sum(p_i)``, p_i the perimeter of each obstacle buffered by the
    stand-off (the curve the robot can follow); and ``L >= D + 0.9 * sum(p_i)``: it went round
    each obstacle once completely (the 10 % covers the leg cut short at Q and the hit made
    ``hit_margin`` before the stand-off)."""
    w = world(world_name)
    d = distance(w.start.position, w.goal)
    perimeters = sum(o.perimeter for o in followed_obstacles(w))
    assert_reached_safely("bug1", world_name)
    length = run("bug1", world_name).result.path_length
    upper = d + 1.5 * perimeters
    lower = d + 0.9 * perimeters
    assert lower <= length <= upper, (
        f"path_length={length:.2f}, but should be in [{lower:.2f}, {upper:.2f}] "
        f"(D={d:.2f}, sum p_i={perimeters:.2f}) [{describe('bug1', world_name)}]"
    )


@pytest.mark.parametrize("world_name", BOUND_WORLDS)
def test_bug2_path_is_within_d_plus_half_the_crossed_perimeters(world_name: str) -> None:
    """Bug2: ``L <= D + sum(n_i * p_i) / 2``, p_i the perimeter of each obstacle buffered by
    the stand-off (the curve the robot can follow), n_i the number of crossings of the m-line
    with that buffered boundary; and ``L >= 0.98 * (D + sum(detour_i))``: it went round each
    obstacle from where the m-line enters it to where it leaves it, at least the shorter way
    (2 % for the hit made ``hit_margin`` before the stand-off and the corners cut)."""
    w = world(world_name)
    d = distance(w.start.position, w.goal)
    crossed = [o for o in followed_obstacles(w) if o.crossings > 0]
    assert crossed, "the m-line should cross an obstacle"
    assert_reached_safely("bug2", world_name)
    length = run("bug2", world_name).result.path_length
    upper = d + sum(o.crossings * o.perimeter for o in crossed) / 2.0
    lower = 0.98 * (d + sum(o.detour for o in crossed))
    assert lower <= length <= upper, (
        f"path_length={length:.2f}, but should be in [{lower:.2f}, {upper:.2f}] "
        f"(D={d:.2f}, n_i p_i={[(o.crossings, round(o.perimeter, 2)) for o in crossed]}) "
        f"[{describe('bug2', world_name)}]"
    )


# -- leaving points ---------------------------------------------------------------------------
@pytest.mark.paper("bug1")
@pytest.mark.parametrize("world_name", [*BOUND_WORLDS, "pocket"])
def test_bug1_leaves_each_obstacle_at_its_point_nearest_the_goal(world_name: str) -> None:
    """Q is the point of the followed curve (the obstacle buffered by the stand-off) nearest
    the goal; on ``box`` it is (32 + standoff, 0). Bug1 leaves within 0.5 ft of that
    distance, once per obstacle on the m-line."""
    w = world(world_name)
    leaves = leave_points(run("bug1", world_name), "leave_at_q")
    crossed = [o for o in followed_obstacles(w) if o.crossings > 0]
    assert len(leaves) == len(crossed), f"{len(leaves)=}, but should be {len(crossed)}"
    goal = shapely.Point(w.goal)
    for leave in leaves:
        here = shapely.Point(leave.position)
        nearest = min(w.obstacles, key=lambda o: shapely.distance(o.geometry, here))
        ring = nearest.geometry.buffer(STANDOFF, quad_segs=64).exterior
        q = shapely.shortest_line(ring, goal).coords[0]
        assert abs(distance(leave.position, w.goal) - distance(q, w.goal)) <= 0.5, (
            f"leave={leave}, {distance(leave.position, w.goal)=:.2f}, but Q={q} is at "
            f"{distance(q, w.goal):.2f} [{describe('bug1', world_name)}]"
        )


@pytest.mark.paper("bug1")
def test_bug1_goes_round_once_then_follows_to_q() -> None:
    branches = [s.branch for s in run("bug1", "box").trace]
    first = {b: branches.index(b) for b in set(branches) - {None}}
    assert branches.count("loop_closed") == 1
    assert branches.count("leave_at_q") == 1
    assert first["follow_edge"] < first["loop_closed"] < first["follow_to_q"]
    assert first["follow_to_q"] < first["leave_at_q"]


@pytest.mark.paper("bug2")
@pytest.mark.parametrize("world_name", REACHABLE[1:])
def test_bug2_leaves_on_the_m_line_nearer_the_goal(world_name: str) -> None:
    w = world(world_name)
    r = run("bug2", world_name)
    leaves = leave_points(r, "leave_on_m_line")
    assert leaves, "Bug2 should leave at least once"
    tolerance = w.robot.speed * 0.1  # the default m_line_tolerance: one step
    for leave in leaves:
        offset = signed_distance(leave.position, w.start.position, w.goal)
        assert abs(offset) <= tolerance, f"leave={leave}: {offset=} off the m-line"
    # Each obstacle is left once, nearer the goal than where it was met.
    hits = hit_points(r)
    assert len(hits) == len(leaves), f"{hits=}, {leaves=}"
    for hit, leave in zip(hits, leaves, strict=True):
        assert distance(leave.position, w.goal) < distance(hit, w.goal), (hit, leave)


@pytest.mark.paper("distbug")
def test_distbug_leaves_earlier_than_bug1_on_box() -> None:
    """The ordering of the paper's Figures 4b and 5a: DistBug leaves the box as soon as the
    free range promises progress, Bug1 only after going round it once and on to Q."""
    distbug = run("distbug", "box").result
    bug1 = run("bug1", "box").result
    assert distbug.path_length < 0.7 * bug1.path_length, (distbug, bug1)
    assert distbug.time_s < bug1.time_s


@pytest.mark.paper("distbug")
@pytest.mark.parametrize("world_name", REACHABLE[1:])
def test_distbug_leaves_no_farther_from_the_goal_than_d_min_minus_step(world_name: str) -> None:
    """Kamon and Rivlin: each hit point is at least Step nearer the goal than the previous
    obstacle's best, so the robot never re-meets an obstacle where it has just left it (with
    our F, which counts only the distance the robot can travel)."""
    w = world(world_name)
    r = run("distbug", world_name)
    hits = hit_points(r)
    d_hits = [distance(h, w.goal) for h in hits]
    step = 2.0 * w.robot.radius  # the default step_length
    assert all(a - b >= step for a, b in pairwise(d_hits)), f"{d_hits=}, {step=}"
    assert len(leave_points(r, "leave_distbug")) == len(hits)


def test_distbug_free_range_counts_only_what_the_robot_can_travel() -> None:
    """F = 0 with the goal out of view; d(x, T) with the way to a goal within range clear;
    otherwise the free length (at most ``range_max``) less the encounter distance."""
    params = EpisodeParams()
    tuning = BoundaryParams.for_episode(params)
    here = Pose(0.0, 0.0, 0.0)

    def free_range(goal: Point, pose: Pose, points: tuple[tuple[float, float], ...] = ()) -> float:
        episode = Episode.of(goal, params, tuning)
        seen = np.array(points, dtype=float).reshape(-1, 2)
        bearing = math.atan2(goal.y - pose.y, goal.x - pose.x)
        return DistBugRule.free_range(Sight(pose, episode, seen, bearing))

    goal = Point(10.0, 0.0)
    assert free_range(goal, here) == 10.0  # nothing seen: the goal, 10 ft away, is visible
    assert free_range(goal, Pose(0.0, 0.0, math.pi)) == 0.0  # the goal behind the robot
    encounter = STANDOFF + BoundaryParams.paper().hit_margin
    far = Point(100.0, 0.0)
    assert free_range(far, here) == params.sensor.range_max - encounter
    wall = ((6.0, 0.0),)  # an obstacle 6 ft dead ahead
    assert free_range(far, here, wall) == pytest.approx(6.0 - encounter)


def test_step_length_beyond_the_sensor_reach_leaves_only_in_sight_of_the_goal() -> None:
    """F is at most ``range_max - encounter`` = 12.5 ft unless the goal is visible, so with
    Step above that the second leaving condition can never hold: on ``box``, whose edge is
    never within ``range_max`` of the goal, DistBug's own rule never leaves, and the robot
    gets round only by Bug1's round, leaving at Q (errata row 34)."""
    reach = SensorParams().range_max - STANDOFF - BoundaryParams.paper().hit_margin
    for step, leave in [(reach - 0.5, "leave_distbug"), (reach + 0.5, "leave_at_q")]:
        run = simulate(world("box"), DistBugPlanner(), params={"step_length": step})
        assert run.result.stop_reason == StopReason.GOAL_REACHED, (step, run.result)
        leaves = {s.branch for s in run.trace} & {"leave_distbug", "leave_at_q"}
        assert leaves == {leave}, step


# -- an enclosed goal -------------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_enclosed_goal_is_reported_unreachable(name: str) -> None:
    """Goal inside a ring of four walls: each planner goes round it once and gives up with
    ``goal_unreachable``, well within the time limit and without collision."""
    w = world("enclosure")
    result = run(name, "enclosure").result
    assert result.stop_reason == GOAL_UNREACHABLE, (result, describe(name, "enclosure"))
    assert not result.collided and result.min_clearance > 0.0
    assert result.time_s < SimParams().max_time / 2
    # One loop round the ring as the robot follows it: the walls' union grown by the stand-off.
    ring = shapely.union_all([o.geometry for o in w.obstacles]).buffer(STANDOFF, quad_segs=64)
    loop = ring.exterior.length
    approach = shapely.distance(ring, shapely.Point(w.start.position))
    lower, upper = approach + 0.9 * loop, approach + 1.2 * loop
    assert lower <= result.path_length <= upper, (
        f"path_length={result.path_length:.2f}, but should be in [{lower:.2f}, {upper:.2f}] "
        f"(one loop of {loop:.2f} ft after {approach:.2f} ft) [{describe(name, 'enclosure')}]"
    )


# -- determinism ------------------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_same_world_gives_the_same_trace(name: str) -> None:
    first = simulate(world("u_trap"), PLANNERS[name]())
    planner = PLANNERS[name]()
    second = simulate(world("u_trap"), planner)
    again = simulate(world("u_trap"), planner)  # a reset planner forgets its last episode
    assert first.trace == second.trace == again.trace
    assert first.result == second.result == again.result
