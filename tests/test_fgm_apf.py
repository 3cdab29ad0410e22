"""FGM and APF: the two local planners of Table 1 that the paper says fail in U and H worlds.

Unit tests check FGM's gap array, maximum gap, gap-centre angle and final heading, and APF's
forces and safety rule, on hand-made scans; episode tests run both planners in the built-in
worlds and check where they end up.

What the episodes show (default parameters, default robot and sensor, ``max_time=300``; a
trapped robot is ended by the simulator's stall rule, within ``r`` of one point for 12 s):

* ``free``: both reach the goal (196.6 ft in 148.7 s).
* ``box``: FGM passes the box (49.4 s, 64.6 ft, clearance 3.4 ft). APF does *not*: the box is
  symmetric about the start-goal line, the forces cancel in front of it and the robot turns
  to and fro 2.6 ft from its face until it stalls -- Table 1's "The algo. cannot
  avoid U, H-shaped and symmetric obstacles". A small post off the line APF does pass.
* ``u_trap`` and ``h_block``: both are trapped, without collision. FGM drives straight at the
  cavity until every ray of its 135-degree view is blocked (section 5.2: "At the centre of
  obstacle, the robot becomes unable to take any decision") and stops, facing the goal: 3 ft
  inside the U's mouth, and 1.8 ft short of the H's (from there the H's walls fill the view
  within the 15 ft range). APF drives into the cavity until the base wall's push balances the
  goal's pull and turns to and fro there, 2.9 ft from the U's base, 2.7 ft from the H's bar.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import SensorParams, SimParams
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import EpisodeParams, Observation, Planner
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import fgm
from ifgm_ref.planners.apf import (
    APFBranch,
    APFParams,
    APFPlanner,
    attractive_force,
    repulsive_force,
)
from ifgm_ref.planners.fgm import (
    FGMBranch,
    FGMParams,
    FGMPlanner,
    RayGap,
    blocked_rays,
    choose_max_gap,
    fgm_decide,
    find_gaps,
)
from ifgm_ref.sim.shapes import circle
from ifgm_ref.sim.simulator import Run, StopReason, simulate, stall_steps
from ifgm_ref.sim.world import World

SENSOR = SensorParams()
#: Robot radius plus FGM's default margin, ft.
INFLATION = 1.0 + FGMParams.paper().inflation_margin
#: Time limit of the trap episodes, s: twice the paper's longest run (Dist-Bug, 205 s) would
#: do; 300 s is the limit of McGuire et al. (2019) and five times what FGM needs in ``box``.
TRAP_TIME = 300.0


# --------------------------------------------------------------------------------------------
# Helpers
# --------------------------------------------------------------------------------------------


def scan_of(ranges: list[float] | np.ndarray, sensor: SensorParams = SENSOR) -> LaserScan:
    """A scan with the default sensor's geometry (135 degrees, 76 rays, 15 ft)."""
    half = sensor.fov / 2.0
    return LaserScan(-half, half, sensor.angle_increment, 0.0, sensor.range_max, ranges)


def scan_with_points(points: list[tuple[float, float]]) -> LaserScan:
    """A default-geometry scan whose rays nearest to each ``(angle_rad, range_ft)`` return."""
    ranges = np.full(SENSOR.rays, np.inf)
    angles = -SENSOR.fov / 2 + SENSOR.angle_increment * np.arange(SENSOR.rays)
    for angle, rng in points:
        ranges[int(np.argmin(np.abs(angles - angle)))] = rng
    return scan_of(ranges)


def wall_scan(distance: float) -> LaserScan:
    """The default scan of an infinite wall across the heading, ``distance`` ft ahead."""
    angles = -SENSOR.fov / 2 + SENSOR.angle_increment * np.arange(SENSOR.rays)
    ranges = distance / np.cos(angles)
    return scan_of(np.where(ranges <= SENSOR.range_max, ranges, np.inf))


def bounding_box(world: World) -> tuple[float, float, float, float]:
    """``(xmin, ymin, xmax, ymax)`` of the world's only (polygon) obstacle, ft."""
    (obstacle,) = world.obstacles
    xs = [v[0] for v in obstacle.vertices]  # type: ignore[union-attr]
    ys = [v[1] for v in obstacle.vertices]  # type: ignore[union-attr]
    return min(xs), min(ys), max(xs), max(ys)


def outside_by(point: tuple[float, float], box: tuple[float, float, float, float]) -> float:
    """How far ``point`` lies outside ``box`` (0 inside), ft."""
    xmin, ymin, xmax, ymax = box
    dx = max(xmin - point[0], 0.0, point[0] - xmax)
    dy = max(ymin - point[1], 0.0, point[1] - ymax)
    return math.hypot(dx, dy)


def episode(world_name: str, planner: Planner, max_time: float = TRAP_TIME) -> Run:
    return simulate(resolve_world(world_name), planner, SimParams(max_time=max_time))


def assert_trapped(run: Run) -> None:
    """No arrival, no collision, and stalled: in the last stall time (12 s) no sample farther
    than the robot's radius (1 ft) from where that time began."""
    __tracebackhide__ = True
    result = run.result
    assert not result.reached, f"reached=True, but should be trapped [{result}]"
    assert not result.collided, f"collided=True, but should stop short [{result}]"
    assert result.stop_reason == StopReason.STALLED, (
        f"stop_reason={result.stop_reason!r}, but should be 'stalled' [{result}]"
    )
    steps = stall_steps(SimParams(), EpisodeParams())
    assert steps is not None
    window = run.trace[-1 - steps :]
    spread = max(math.hypot(s.x - window[0].x, s.y - window[0].y) for s in window)
    assert spread <= 1.0, f"moved {spread:.2f} ft in the last 12 s, but should be stuck"


# --------------------------------------------------------------------------------------------
# FGM: gap array, maximum gap, gap centre, final heading
# --------------------------------------------------------------------------------------------


def test_blocked_rays_half_angle_is_asin_of_inflation_over_range() -> None:
    d = 4.0
    scan = scan_with_points([(0.0, d)])
    (ray,) = np.flatnonzero(np.isfinite(scan.ranges))  # 76 rays: the nearest is at -0.9 deg
    blocked, distance = blocked_rays(scan, INFLATION)
    expected = np.abs(scan.angles - scan.angles[ray]) <= math.asin(INFLATION / d) + 1e-12
    assert blocked.tolist() == expected.tolist()
    assert blocked.sum() == 25  # +-21.9 degrees at 1.8 degrees a ray
    assert np.all(distance[blocked] == d) and np.all(np.isinf(distance[~blocked]))


def test_blocked_rays_return_inside_inflation_blocks_a_half_plane() -> None:
    blocked, _ = blocked_rays(scan_with_points([(0.0, 0.5 * INFLATION)]), INFLATION)
    assert blocked.all()  # +-90 degrees covers the whole 135-degree view


def test_fgm_no_obstacle_heads_for_the_goal() -> None:
    empty = scan_of([math.inf] * SENSOR.rays)
    for goal_angle in (0.0, 0.4, -2.5):  # ahead, left, behind on the right
        decision = fgm_decide(empty, goal_angle, inflation=INFLATION, alpha=8.0, beta=1.0)
        assert decision.branch is FGMBranch.NO_OBSTACLE
        assert decision.heading == goal_angle
        assert decision.gap is None and decision.d_min == math.inf


@pytest.mark.paper("fgm")
def test_fgm_one_obstacle_ahead_gives_a_gap_to_the_side() -> None:
    # A short wall 4 ft ahead, -10 to +10 degrees, the goal straight behind it.
    wall = [(math.radians(a), 4.0 / math.cos(math.radians(a))) for a in range(-10, 11)]
    scan = scan_with_points(wall)
    gaps = find_gaps(scan, INFLATION)
    assert len(gaps) == 2  # one either side of the wall
    right, _ = gaps
    assert right.right_angle == pytest.approx(-SENSOR.fov / 2)  # reaches the edge of view ...
    assert right.right_distance == SENSOR.range_max  # ... so that border is at range_max
    assert right.left_distance == pytest.approx(4.0 / math.cos(math.radians(10.0)), rel=0.02)
    # Inflated by 1.5 ft, the wall's end at 4.06 ft blocks 21.7 degrees beyond it.
    assert right.left_angle < -math.radians(10.0 + 21.0)
    decision = fgm_decide(scan, 0.0, inflation=INFLATION, alpha=8.0, beta=1.0)
    assert decision.branch is FGMBranch.MAX_GAP
    assert decision.gap is not None and decision.gap in gaps
    assert abs(decision.heading) > math.radians(20.0)  # steers off to the side
    # The heading lies between the gap centre and the goal angle, weighted towards the gap.
    centre = decision.gap.centre
    assert min(centre, 0.0) <= decision.heading <= max(centre, 0.0)
    assert abs(decision.heading - centre) < abs(decision.heading)


@pytest.mark.paper("fgm")
def test_fgm_two_posts_heading_between_them() -> None:
    # Posts at -35 and +35 degrees, 5 ft away; the goal 0.3 rad to the left.
    scan = scan_with_points([(math.radians(-35.0), 5.0), (math.radians(35.0), 5.0)])
    decision = fgm_decide(scan, 0.3, inflation=INFLATION, alpha=8.0, beta=1.0)
    assert decision.branch is FGMBranch.MAX_GAP
    gap = decision.gap
    assert gap is not None
    assert gap.right_angle < 0.0 < gap.left_angle  # the gap between the posts, not beside
    assert gap.right_distance == gap.left_distance == 5.0
    assert gap.centre == pytest.approx(0.0, abs=1e-7)  # symmetric gap: straight ahead
    # (alpha / d_min) theta_gap + beta theta_goal over their sum: (1.6 * 0 + 0.3) / 2.6.
    assert decision.heading == pytest.approx(0.3 / 2.6, abs=1e-7)
    assert gap.right_angle < decision.heading < gap.left_angle


@pytest.mark.paper("fgm")
def test_fgm_gap_centre_is_the_direction_of_the_border_midpoint() -> None:
    # Unequal borders: the centre is not the angular bisector but the midpoint's direction.
    scan = scan_with_points([(math.radians(-30.0), 3.0), (math.radians(40.0), 9.0)])
    gap = fgm_decide(scan, 0.0, inflation=INFLATION, alpha=8.0, beta=1.0).gap
    assert gap is not None
    p1 = (
        gap.right_distance * math.cos(gap.right_angle),
        gap.right_distance * math.sin(gap.right_angle),
    )
    p2 = (
        gap.left_distance * math.cos(gap.left_angle),
        gap.left_distance * math.sin(gap.left_angle),
    )
    midpoint_angle = math.atan2(p1[1] + p2[1], p1[0] + p2[0])
    assert gap.centre == pytest.approx(midpoint_angle, abs=1e-7)
    assert abs(gap.centre - (gap.right_angle + gap.left_angle) / 2.0) > math.radians(5.0)


def test_fgm_no_gap_stops_facing_the_goal() -> None:
    closed = scan_of([3.0] * SENSOR.rays)  # every ray blocked
    assert find_gaps(closed, INFLATION) == ()
    planner = FGMPlanner()
    planner.reset(Pose(0.0, 0.0, 0.0), Point(10.0, 10.0), EpisodeParams())
    command = planner.step(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(10.0, 10.0), closed))
    assert command.branch == "no_gap"
    assert command.speed == 0.0
    assert command.heading == pytest.approx(math.pi / 4)


def test_choose_max_gap_prefers_most_rays_then_goal_side() -> None:
    a = RayGap(0, 9, -1.0, 5.0, -0.5, 5.0)
    b = RayGap(20, 29, 0.5, 5.0, 1.0, 5.0)
    c = RayGap(40, 40, 1.1, 5.0, 1.1, 5.0)
    assert choose_max_gap((a, b, c), goal_angle=0.9) is b  # a and b tie on 10 rays
    assert choose_max_gap((a, b, c), goal_angle=-0.9) is a


@given(
    st.lists(
        st.one_of(st.just(math.inf), st.floats(0.1, 15.0)),
        min_size=SENSOR.rays,
        max_size=SENSOR.rays,
    ).map(scan_of)
)
def test_find_gaps_are_the_maximal_runs_of_free_rays(scan: LaserScan) -> None:
    blocked, _ = blocked_rays(scan, INFLATION)
    gaps = find_gaps(scan, INFLATION)
    covered = np.zeros(len(blocked), dtype=bool)
    for gap in gaps:
        assert not blocked[gap.first : gap.last + 1].any()
        assert gap.first == 0 or blocked[gap.first - 1]
        assert gap.last == len(blocked) - 1 or blocked[gap.last + 1]
        covered[gap.first : gap.last + 1] = True
    assert covered.tolist() == (~blocked).tolist()
    chosen = choose_max_gap(gaps, 0.0)
    assert (chosen is None) == (not gaps)
    if chosen is not None:
        assert chosen.rays == max(g.rays for g in gaps)


# --------------------------------------------------------------------------------------------
# APF: forces and the safety rule
# --------------------------------------------------------------------------------------------


@pytest.mark.paper("apf")
def test_apf_attractive_force_is_k_att_times_goal_offset() -> None:
    assert attractive_force((4.0, -2.0), 0.5).tolist() == [2.0, -1.0]


@pytest.mark.paper("apf")
def test_apf_repulsive_force_is_the_firas_gradient() -> None:
    scan = scan_with_points([(0.5, 2.0)])
    (ray,) = np.flatnonzero(np.isfinite(scan.ranges))
    angle = float(scan.angles[ray])
    force, count = repulsive_force(scan, eta=10.0, d0=5.0)
    magnitude = 10.0 * (1 / 2.0 - 1 / 5.0) / 2.0**2  # eta (1/d - 1/d0) / d^2
    assert count == 1
    assert force.tolist() == pytest.approx(
        [-magnitude * math.cos(angle), -magnitude * math.sin(angle)]
    )


def test_apf_returns_beyond_d0_do_not_push() -> None:
    force, count = repulsive_force(scan_with_points([(0.3, 5.5), (-0.3, 9.0)]), eta=10.0, d0=5.0)
    assert count == 0 and force.tolist() == [0.0, 0.0]


def test_apf_symmetric_returns_cancel_sideways() -> None:
    force, _ = repulsive_force(wall_scan(3.0), eta=50.0, d0=5.0)
    assert force[0] < 0.0
    assert force[1] == pytest.approx(0.0, abs=1e-9 * abs(force[0]))


def test_apf_steers_away_from_a_return_on_the_left() -> None:
    planner = APFPlanner()
    planner.reset(Pose(0.0, 0.0, 0.0), Point(20.0, 0.0), EpisodeParams())
    scan = scan_with_points([(math.radians(30.0), 2.5)])
    command = planner.step(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(20.0, 0.0), scan))
    assert command.branch == "repel"
    assert command.heading < 0.0  # pushed to the right
    expected = math.atan2(float(planner.force[1]), float(planner.force[0]))
    assert command.heading == pytest.approx(expected)


def test_apf_safety_rule_stops_short_of_a_wall() -> None:
    planner = APFPlanner()
    planner.reset(Pose(0.0, 0.0, 0.0), Point(50.0, 0.0), EpisodeParams(params={"eta": 0.01}))
    command = planner.step(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(50.0, 0.0), wall_scan(1.6)))
    assert command.branch == str(APFBranch.BLOCKED)
    assert command.speed == 0.0


def test_apf_weak_field_is_held_off_walls_by_the_safety_rule() -> None:
    # With a field too weak to turn it, only the safety rule keeps APF from the U's base.
    run = simulate(
        resolve_world("u_trap"), APFPlanner(), SimParams(max_time=60.0), params={"eta": 0.5}
    )
    assert not run.result.collided
    assert any(s.branch == "blocked" for s in run.trace)
    assert run.result.min_clearance > 0.0


# --------------------------------------------------------------------------------------------
# Parameters and protocol
# --------------------------------------------------------------------------------------------


def test_planners_follow_the_protocol() -> None:
    assert isinstance(FGMPlanner(), Planner) and FGMPlanner.name == "fgm"
    assert isinstance(APFPlanner(), Planner) and APFPlanner.name == "apf"
    assert FGMPlanner.parameters == ("alpha", "beta", "inflation_margin")
    assert APFPlanner.parameters == ("k_att", "eta", "d0", "stop_margin")


@pytest.mark.parametrize(
    ("params", "message"),
    [
        ({"alpha": -1.0}, "`alpha` must be a finite number >= 0, got -1.0"),
        ({"beta": math.nan}, "`beta` must be a finite number >= 0, got nan"),
        ({"inflation_margin": "1"}, "`inflation_margin` must be a finite number >= 0, got '1'"),
        ({"alpha": True}, "`alpha` must be a finite number >= 0, got True"),
        ({"alpha": 0, "beta": 0.0}, "`alpha` and `beta` must not both be 0"),
    ],
)
def test_fgm_parameter_validation(params: dict[str, object], message: str) -> None:
    with pytest.raises(ParameterError) as info:
        FGMPlanner().reset(Pose(0.0, 0.0, 0.0), Point(1.0, 0.0), EpisodeParams(params=params))
    assert str(info.value) == message


@pytest.mark.parametrize(
    ("params", "message"),
    [
        ({"k_att": 0.0}, "`k_att` must be a finite number > 0, got 0.0"),
        ({"eta": -3}, "`eta` must be a finite number > 0, got -3"),
        ({"d0": math.inf}, "`d0` must be a finite number > 0, got inf"),
        ({"stop_margin": None}, "`stop_margin` must be a finite number > 0, got None"),
    ],
)
def test_apf_parameter_validation(params: dict[str, object], message: str) -> None:
    with pytest.raises(ParameterError) as info:
        APFPlanner().reset(Pose(0.0, 0.0, 0.0), Point(1.0, 0.0), EpisodeParams(params=params))
    assert str(info.value) == message


def test_parameters_are_read_by_name_and_the_rest_derived() -> None:
    fgm, apf = FGMPlanner(), APFPlanner()
    fgm.reset(Pose(0.0, 0.0, 0.0), Point(1.0, 0.0), EpisodeParams(params={"alpha": 2.0}))
    apf.reset(Pose(0.0, 0.0, 0.0), Point(1.0, 0.0), EpisodeParams(params={"eta": 7.0}))
    assert fgm.tuning == FGMParams(alpha=2.0, beta=1.0, inflation_margin=0.5)
    assert apf.tuning == APFParams(k_att=1.0, eta=7.0, d0=5.0, stop_margin=0.5)


def test_a_parameter_of_another_planner_is_rejected() -> None:
    params = EpisodeParams(params={"alpha": 2.0, "d_th": 4.0})
    with pytest.raises(ParameterError, match=r"fgm has no parameter `d_th`; it has: alpha"):
        FGMPlanner().reset(Pose(0.0, 0.0, 0.0), Point(1.0, 0.0), params)


# --------------------------------------------------------------------------------------------
# Episodes in the built-in worlds
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("planner_type", [FGMPlanner, APFPlanner])
def test_reaches_the_goal_in_free(planner_type: type[FGMPlanner | APFPlanner]) -> None:
    result = episode("free", planner_type()).result
    assert result.reached and not result.collided
    assert result.time_s == pytest.approx(148.7, abs=0.2)  # the paper's 149 s (section 5.1)


def test_fgm_reaches_the_goal_in_box() -> None:
    result = episode("box", FGMPlanner()).result
    assert result.reached and not result.collided
    assert result.min_clearance > 2.0
    assert result.path_length < 70.0  # straight line: 60 ft


@pytest.mark.paper("t1.apf_u_h_symmetric")
def test_apf_is_trapped_in_front_of_the_symmetric_box() -> None:
    # Table 1: APF "cannot avoid U, H-shaped and symmetric obstacles". The built-in box is
    # symmetric about the start-goal line; the robot halts in front of its face.
    world = resolve_world("box")
    run = simulate(world, APFPlanner(), SimParams(max_time=TRAP_TIME))
    assert_trapped(run)
    xmin, ymin, _, ymax = bounding_box(world)
    end = run.trace[-1]
    assert xmin - 4.0 < end.x < xmin and ymin < end.y < ymax


def test_apf_passes_a_post_off_the_line() -> None:
    # APF does avoid obstacles that do not cancel its attraction: a post of radius 1 ft,
    # 1 ft off the line.
    world = World(
        start=Pose(0.0, 0.0, 0.0),
        goal=Point(60.0, 0.0),
        obstacles=(circle((30.0, 1.0), 1.0),),
        name="post",
    )
    result = simulate(world, APFPlanner(), SimParams(max_time=TRAP_TIME)).result
    assert result.reached and not result.collided


@pytest.mark.paper("t1.fgm_u", "s5.fgm_trapped")
def test_fgm_is_trapped_in_the_u() -> None:
    world = resolve_world("u_trap")
    run = simulate(world, FGMPlanner(), SimParams(max_time=TRAP_TIME))
    assert_trapped(run)
    assert run.trace[-1].branch is None and run.trace[-2].branch == "no_gap"
    end = run.trace[-1]
    assert outside_by((end.x, end.y), bounding_box(world)) == 0.0  # inside the U's outline
    bearing = math.atan2(world.goal.y - end.y, world.goal.x - end.x)
    assert abs(wrap_angle(end.theta - bearing)) < 0.01  # stopped, facing the goal


@pytest.mark.paper("t1.fgm_h")
def test_fgm_is_trapped_at_the_mouth_of_the_h() -> None:
    world = resolve_world("h_block")
    run = simulate(world, FGMPlanner(), SimParams(max_time=TRAP_TIME))
    assert_trapped(run)
    assert run.trace[-2].branch == "no_gap"
    end = run.trace[-1]
    xmin, ymin, _, ymax = bounding_box(world)
    assert end.x < xmin and ymin < end.y < ymax  # facing the cavity, ...
    assert outside_by((end.x, end.y), bounding_box(world)) < 3.0  # ... within 3 ft of it


@pytest.mark.paper("t1.apf_u_h_symmetric")
@pytest.mark.parametrize("world_name", ["u_trap", "h_block"])
def test_apf_is_trapped_inside_the_cavity(world_name: str) -> None:
    world = resolve_world(world_name)
    run = simulate(world, APFPlanner(), SimParams(max_time=TRAP_TIME))
    assert_trapped(run)
    end = run.trace[-1]
    assert outside_by((end.x, end.y), bounding_box(world)) == 0.0
    assert run.result.min_clearance > 1.0


@pytest.mark.parametrize("planner_type", [FGMPlanner, APFPlanner])
def test_episodes_are_deterministic(planner_type: type[FGMPlanner | APFPlanner]) -> None:
    first = episode("box", planner_type(), max_time=60.0)
    second = episode("box", planner_type(), max_time=60.0)
    assert first.trace == second.trace
    assert first.result == second.result


@st.composite
def wide_scans(draw: st.DrawFn) -> LaserScan:
    """A LiDAR-like scan: up to 720 rays over up to 270 degrees, returns near and far (some
    inside the inflation), gaps of no return, and ``-inf`` for too near."""
    rays = draw(st.integers(2, 720))
    fov = draw(st.floats(0.1, 1.5 * math.pi))
    ranges = draw(
        st.lists(
            st.sampled_from([math.inf, -math.inf]) | st.floats(0.01, 30.0),
            min_size=rays,
            max_size=rays,
        )
    )
    return LaserScan(-fov / 2, fov / 2, fov / (rays - 1), 0.05, 30.0, np.array(ranges))


@given(scan=wide_scans(), inflation=st.floats(0.0, 3.0))
def test_wide_scans_block_the_same_rays_when_only_near_rays_are_tested(
    scan: LaserScan, inflation: float
) -> None:
    """``blocked_rays`` on a wide scan tests each return against its nearby rays only
    (``fgm.PAIRS_FROM``): the blocked rays and their distances are those of testing every
    (return, ray) pair, to the bit."""
    with pytest.MonkeyPatch.context() as monkeypatch:
        monkeypatch.setattr(fgm, "PAIRS_FROM", math.inf)
        every = blocked_rays(scan, inflation)
        monkeypatch.setattr(fgm, "PAIRS_FROM", 0)
        near = blocked_rays(scan, inflation)
    assert near[0].tolist() == every[0].tolist()
    assert near[1].tobytes() == every[1].tobytes()
