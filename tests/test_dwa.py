"""BARN's DWA baseline (ifgm_ref.planners.dwa, costmap, grid_path, dwa_rollout): the costmap
of its own scans, the grid plan, the dynamic window's scores, whole episodes."""

from __future__ import annotations

import collections
import dataclasses
import itertools
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from numpy.typing import NDArray

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import SENSOR_PRESETS
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import EpisodeParams, Observation, Planner
from ifgm_ref.io import barn
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import PLANNERS, make_planner
from ifgm_ref.planners.costmap import INSCRIBED, LETHAL, Costmap, CostmapSettings
from ifgm_ref.planners.dwa import CostmapParams, DWABranch, DWAParams, DWAPlanner
from ifgm_ref.planners.dwa_rollout import Samples, legal_costs, rollout, samples
from ifgm_ref.planners.grid_path import blocked, plan_path, wavefront
from ifgm_ref.planners.tuning import episode_values
from ifgm_ref.sim.simulator import StopReason, simulate
from ifgm_ref.sim.world import World

BARN_WORLDS = Path(__file__).parent / "worlds" / "barn"
#: BARN's costmap for BARN's robot (costmap_common_params.yaml), the margin 1 m.
SETTINGS = CostmapSettings(0.05, 0.22, 0.30, 0.1, 2.5, 3.0, 1.0)
#: BARN's episode: the robot, the Jackal's LiDAR, 0.05 s steps.
BARN_EPISODE = EpisodeParams(barn.ROBOT, SENSOR_PRESETS["jackal_lidar"](), barn.SIM.dt)


def _scan(ranges: list[float], spacing: float = 0.01) -> LaserScan:
    """A scan centred on the heading, ``spacing`` rad between rays, 30 m range."""
    half = spacing * (len(ranges) - 1) / 2.0
    return LaserScan(-half, half, spacing, 0.1, 30.0, np.asarray(ranges))


def test_barns_configured_values_for_barns_robot() -> None:
    values = episode_values(PLANNERS["dwa"].tunings, BARN_EPISODE)
    expected = {
        "resolution": 0.05, "obstacle_range": 2.5, "raytrace_range": 3.0,
        "inflation_radius": 0.30, "cost_decay": 0.1, "local_size": 10.0, "max_vel_x": 0.5,
        "min_vel_x": 0.1, "max_vel_theta": 1.57, "min_in_place_vel_theta": 0.314,
        "acc_lim_x": 10.0, "acc_lim_theta": 20.0, "sim_time": 2.0, "sim_granularity": 0.02,
        "angular_sim_granularity": 0.02, "vx_samples": 6, "vtheta_samples": 20,
        "pdist_scale": 0.75, "gdist_scale": 1.0, "occdist_scale": 0.1,
        "heading_lookahead": 0.325, "planner_period": 0.05,
    }  # fmt: skip
    assert values == pytest.approx(expected, abs=1e-3)
    assert values["max_vel_theta"] == pytest.approx(math.pi / 2)  # BARN's 1.57, rounded


def test_a_return_is_marked_and_inflated_as_costmap_2d_does() -> None:
    grid = Costmap(SETTINGS, Point(0.0, 0.0), Point(3.0, 0.0))
    assert grid.origin == (-1.0, -1.0)  # cell (20, 40) has its centre at (1.025, 0.025)
    grid.update(Pose(0.0, 0.0, 0.0), _scan([math.inf, 1.01, math.inf]))  # one return
    assert grid.occupied.sum() == 1 and grid.cost_at(1.01, 0.0) == LETHAL
    # Cell centres 4, 5, 6 and 7 cells (0.05 m) in front: 0.2 m is within r = 0.22 m, then
    # floor(252 exp(-(d - 0.22) / 0.1)): 186 at 0.25 m, 113 at 0.30 m, nothing beyond 0.30 m.
    costs = [grid.cost_at(1.025 - k * 0.05, 0.025) for k in (4, 5, 6, 7)]
    assert costs == [INSCRIBED, 186, 113, 0]
    assert grid.cost_at(1.025, 0.025 + 0.25) == 186  # the same sideways
    assert grid.cost_at(1.025 - 0.15, 0.025 + 0.20) == 186  # and obliquely: 0.25 m away


def test_returns_beyond_the_obstacle_range_are_not_marked() -> None:
    grid = Costmap(SETTINGS, Point(0.0, 0.0), Point(3.0, 0.0))
    grid.update(Pose(0.0, 0.0, 0.0), _scan([2.6, 2.6, 2.6]))
    assert not grid.occupied.any()
    grid.update(Pose(0.0, 0.0, 0.0), _scan([2.4, 2.4, 2.4]))
    assert grid.cost_at(2.4, 0.0) == LETHAL


def test_a_ray_through_a_marked_cell_clears_it_up_to_the_raytrace_range() -> None:
    grid = Costmap(SETTINGS, Point(0.0, 0.0), Point(6.0, 0.0))
    grid.update(Pose(0.0, 0.0, 0.0), _scan([1.0, 1.0, 1.0]))
    grid.update(Pose(2.0, 0.0, 0.0), _scan([1.5, 1.5, 1.5]))  # marks x = 3.5
    assert grid.cost_at(1.0, 0.0) == LETHAL and grid.cost_at(3.5, 0.0) == LETHAL
    # From the start again, nothing in view: rays clear 3.0 m, so x = 1 goes, x = 3.5 stays.
    grid.update(Pose(0.0, 0.0, 0.0), _scan([math.inf] * 3))
    assert grid.cost_at(1.0, 0.0) == 0
    assert grid.cost_at(3.5, 0.0) == LETHAL
    # A return behind a marked cell clears it too, and keeps its own.
    grid.update(Pose(1.5, 0.0, 0.0), _scan([2.4, 2.4, 2.4]))
    assert grid.cost_at(3.5, 0.0) == 0 and grid.cost_at(3.9, 0.0) == LETHAL


def test_the_grid_grows_round_the_robot_and_keeps_what_it_marked() -> None:
    grid = Costmap(SETTINGS, Point(0.0, 0.0), Point(1.0, 0.0))
    grid.update(Pose(0.0, 0.0, 0.0), _scan([1.0, 1.0, 1.0]))
    shape, generation = grid.shape, grid.generation
    grid.update(Pose(0.0, 3.0, math.pi / 2), _scan([2.0, 2.0, 2.0]))  # 3 m further up
    assert grid.generation == generation + 1 and grid.shape[0] > shape[0]
    assert grid.cost_at(1.0, 0.0) == LETHAL and grid.cost_at(0.0, 5.0) == LETHAL


def test_the_plan_goes_round_a_wall() -> None:
    cost = np.zeros((40, 40), dtype=np.uint8)
    cost[20, 5:40] = LETHAL  # a wall with a way round on the left (columns 0-4)
    cost[19, 5:40] = cost[21, 5:40] = INSCRIBED
    chain = plan_path(cost, (5, 30), (35, 30))
    assert chain is not None and chain[0] == (5, 30) and chain[-1] == (35, 30)
    rows, cols = np.array(chain).T
    assert not blocked(cost[rows, cols]).any()
    assert all(abs(a - c) <= 1 and abs(b - d) <= 1 for (a, b), (c, d) in itertools.pairwise(chain))
    assert cols[rows == 20].max() < 5  # it crosses the wall's row at the gap
    cost[20, 0:5] = INSCRIBED
    assert plan_path(cost, (5, 30), (35, 30)) is None


def test_the_plan_keeps_away_from_costly_cells_when_it_costs_little() -> None:
    cost = np.zeros((11, 30), dtype=np.uint8)
    cost[5, 5:25] = 200  # a costly band on the straight line; free rows beside it
    chain = plan_path(cost, (5, 0), (5, 29))
    assert chain is not None
    assert sum(cost[r, c] > 0 for r, c in chain) == 0


def test_the_mapgrid_wavefront_goes_round_blocked_cells() -> None:
    free = np.ones((5, 5), dtype=bool)
    free[2, 0:4] = False
    source = np.zeros_like(free)
    source[0, 0] = True
    distance = wavefront(free, source)
    assert distance[4, 0] == 4 + 4 + 4  # right to column 4, down 4 rows, back left 4
    assert distance[2, 0] == free.size  # blocked: MapGrid's obstacle cost


def _breadth_first(passable: NDArray[np.bool_], sources: NDArray[np.bool_]) -> NDArray[np.int32]:
    """The 4-connected breadth-first distance from a queue, cell by cell: the definition."""
    far = np.int32(passable.size)
    distance = np.full(passable.shape, far, dtype=np.int32)
    queue = collections.deque(zip(*np.nonzero(sources & passable), strict=True))
    for cell in queue:
        distance[cell] = 0
    while queue:
        i, j = queue.popleft()
        for cell in ((i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)):
            inside = 0 <= cell[0] < passable.shape[0] and 0 <= cell[1] < passable.shape[1]
            if inside and passable[cell] and distance[cell] == far:
                distance[cell] = distance[i, j] + 1
                queue.append(cell)
    return distance


@st.composite
def _grids(
    draw: st.DrawFn,
) -> tuple[NDArray[np.bool_], NDArray[np.bool_], tuple[slice, slice] | None]:
    rows, cols = draw(st.integers(1, 12)), draw(st.integers(1, 12))
    cells = st.lists(st.booleans(), min_size=rows * cols, max_size=rows * cols)
    passable = np.array(draw(cells)).reshape(rows, cols)
    sources = np.array(draw(cells)).reshape(rows, cols) & (draw(st.integers(0, 4)) == 0)
    sources[draw(st.integers(0, rows - 1)), draw(st.integers(0, cols - 1))] = True
    if draw(st.booleans()):
        return passable, sources, None
    r0, r1 = sorted(draw(st.lists(st.integers(0, rows), min_size=2, max_size=2)))
    c0, c1 = sorted(draw(st.lists(st.integers(0, cols), min_size=2, max_size=2)))
    return passable, sources, (slice(r0, r1), slice(c0, c1))


@given(_grids())
def test_the_wavefront_is_the_breadth_first_distance(
    grid: tuple[NDArray[np.bool_], NDArray[np.bool_], tuple[slice, slice] | None],
) -> None:
    """Everywhere without a box; in the box asked about with one (beyond it a cell reads its
    distance or, reached after the wave stopped, ``passable.size``)."""
    passable, sources, box = grid
    expected, got = _breadth_first(passable, sources), wavefront(passable, sources, box)
    assert got.dtype == np.int32
    if box is None:
        assert got.tolist() == expected.tolist()
        return
    assert got[box].tolist() == expected[box].tolist()
    assert ((got == expected) | (got == passable.size)).all()


def _straight_plan_map(
    blocked_cells: tuple[tuple[int, int], ...] = (),
) -> tuple[NDArray[np.uint8], NDArray[np.int32], NDArray[np.int32]]:
    """A 60 x 60 window (0.05 m), robot at its centre heading +x, plan along the robot's
    row to the right edge, the local goal at its end."""
    cost = np.zeros((60, 60), dtype=np.uint8)
    for cell in blocked_cells:
        cost[cell] = INSCRIBED
    passable = ~blocked(cost)
    on_path = np.zeros_like(passable)
    on_path[30, 30:] = True
    at_goal = np.zeros_like(passable)
    at_goal[30, 59] = True
    return cost, wavefront(passable, on_path), wavefront(passable, at_goal)


def _score(cells_blocked: tuple[tuple[int, int], ...]) -> tuple[NDArray[np.float64], Samples]:
    """The costs of BARN's window at full speed ahead, on :func:`_straight_plan_map`."""
    tuning = DWAParams.for_episode(BARN_EPISODE)
    window = tuning.window()
    chosen = samples(window, 0.5, 0.0, 0.05)
    origin = np.array([-1.5, -1.5])  # cell (30, 30) holds the robot at (0.025, 0.025)
    roll = rollout(
        (0.025, 0.025, 0.0), (0.5, 0.0), chosen, window, sim_time=tuning.sim_time,
        granularity=tuning.sim_granularity, angular_granularity=tuning.angular_sim_granularity,
    )  # fmt: skip
    rows = np.floor((roll.y - origin[1]) / 0.05).astype(np.intp)
    cols = np.floor((roll.x - origin[0]) / 0.05).astype(np.intp)
    cost, path, goal = _straight_plan_map(cells_blocked)
    scales = (0.05 * 0.75, 0.05 * 1.0, 0.05 * 0.1)
    return legal_costs((rows, cols), roll.valid, cost, path, goal, scales), chosen


def test_the_cheapest_trajectory_is_the_fastest_along_the_plan() -> None:
    costs, chosen = _score(())
    best = int(np.nanargmin(costs))
    assert (chosen.vx[best], chosen.vth[best]) == (0.5, 0.0)


def test_a_trajectory_through_an_inscribed_cell_is_illegal() -> None:
    costs, chosen = _score(((30, 45),))  # 0.75 m straight ahead, on the plan
    straight = (chosen.vth == 0.0) & (chosen.vx >= 0.4)
    assert np.isnan(costs[straight]).all()  # 0.8 m and more straight ahead: they cross it
    assert not np.isnan(costs).all()
    best = int(np.nanargmin(costs))
    assert chosen.vth[best] != 0.0 or chosen.vx[best] < 0.4


def test_with_nothing_legal_it_turns_in_place_towards_the_path() -> None:
    planner = DWAPlanner()
    planner.reset(Pose(0.0, 0.0, 0.0), Point(0.0, 3.0), BARN_EPISODE)
    ring = LaserScan(-3.14, 3.14, 0.01, 0.1, 30.0, np.full(629, 0.15))  # walled in
    command = planner.step(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(0.0, 3.0), ring))
    assert command.branch in (DWABranch.ESCAPE, DWABranch.NO_PLAN)
    assert command.speed == 0.0 and command.turn_rate == pytest.approx(math.pi / 2)


def test_a_parameter_given_by_name_replaces_barns() -> None:
    planner = DWAPlanner()
    params = dataclasses.replace(BARN_EPISODE, params={"max_vel_x": 0.3, "resolution": 0.1})
    planner.reset(Pose(0.0, 0.0, 0.0), Point(5.0, 0.0), params)
    assert planner.tuning.max_vel_x == 0.3 and planner.costmap.settings.resolution == 0.1
    assert CostmapParams.for_episode(params).inflation_radius == pytest.approx(0.3)


@pytest.mark.parametrize("index", [1])
def test_it_reaches_the_goal_in_barn_worlds(index: int) -> None:
    world = barn.load_barn_world(BARN_WORLDS / f"world_{index}.world")
    result = simulate(world, make_planner("dwa"), barn.SIM).result
    assert result.stop_reason == StopReason.GOAL_REACHED, result
    assert not result.collided and result.min_clearance > 0.0


def _short_post() -> tuple[World, Planner]:
    """The built-in ``post``, from 8 ft before the post to 8 ft past it."""
    world = dataclasses.replace(
        resolve_world("post"), start=Pose(22.0, 0.0, 0.0), goal=Point(38.0, 0.0)
    )
    return world, make_planner("dwa")


def test_it_goes_round_the_post_deterministically() -> None:
    world, planner = _short_post()
    first = simulate(world, planner)
    again = simulate(*_short_post())
    assert first.result.reached and not first.result.collided, first.result
    assert first.result.min_clearance > 0.0
    assert first.trace == again.trace
