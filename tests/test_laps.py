"""The simulator's lap rule (ifgm_ref.sim.laps): it ends an endless lapper at the step its
definition says, spares a Bug1-like lap and a half and IFGM's dead-end escapes, switches off,
and fires at the same step when every length is scaled by a power of two."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.formulas import Scale
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Point, Pose, distance, wrap_angle
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.oracle.metamorphic import scale_sim, scale_world
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.sim.laps import LapLog, LapRule
from ifgm_ref.sim.shapes import circle
from ifgm_ref.sim.simulator import Run, StopReason, lap_rule, simulate
from ifgm_ref.sim.world import World

#: Both stall rules off.
NO_STALL = SimParams(stall_time=None, stall_laps=None)
#: The lap rule alone.
LAPS_ONLY = SimParams(stall_time=None)
#: A post of radius 1 ft at (10, 0), on the line from the start (0, 0) to the goal (30, 0).
POST = World(
    start=Pose(0.0, 0.0, 0.0),
    goal=Point(30.0, 0.0),
    obstacles=(circle((10.0, 0.0), 1.0),),
    name="post on the line",
)


class CirclingPlanner:
    """Drives straight at a circle of radius ``radius`` about ``centre`` (meeting it at H),
    then round it anticlockwise; after ``laps`` laps from H (``None``: never) it heads for
    the goal. Blind: it reads its pose only."""

    name = "circling"

    def __init__(self, centre: tuple[float, float], radius: float, laps: float | None) -> None:
        self.centre, self.radius, self.laps = centre, radius, laps
        self.turned = 0.0  # angle travelled round the centre since H, rad
        self.bearing: float | None = None  # the robot's bearing from the centre, once on it
        self.speed = 0.0

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.turned, self.bearing, self.speed = 0.0, None, params.robot.speed

    def step(self, observation: Observation) -> Command:
        pose, (cx, cy) = observation.pose, self.centre
        gap = distance(pose, self.centre)
        bearing = math.atan2(pose.y - cy, pose.x - cx)
        if self.bearing is None and gap > self.radius:
            return Command(heading=math.atan2(cy - pose.y, cx - pose.x), speed=self.speed)
        if self.bearing is not None:
            self.turned += wrap_angle(bearing - self.bearing)
        self.bearing = bearing
        if self.laps is not None and self.turned >= 2.0 * math.pi * self.laps:
            goal = observation.goal
            return Command(heading=math.atan2(goal.y - pose.y, goal.x - pose.x), speed=self.speed)
        inward = math.atan(2.0 * (gap - self.radius) / self.radius)  # back onto the circle
        return Command(heading=bearing + math.pi / 2 + inward, speed=self.speed)


def lapper(k: float = 1.0) -> CirclingPlanner:
    """Round the post at 3 ft from its centre for ever (lengths times ``k``)."""
    return CirclingPlanner((10.0 * k, 0.0), 3.0 * k, None)


def brute_force(
    positions: list[tuple[float, float]], goal: Point, rule: LapRule, *, same_way: bool = True
) -> list[bool]:
    """Where the lap rule with ``rule.laps == 2`` fires, step by step, by brute force over
    every pair of earlier positions (no grid, no chain of latest laps): some ``i`` and ``j``
    within ``rho`` of ``p_n``, each reached by a step at less than 90 degrees to the one that
    reached ``p_n`` (a step on the spot repeats the last step that moved; the start has
    none), with ``s_i + L <= s_j <= s_n - L`` and ``best_i - best_n <= eps``. Path lengths
    and distances are summed and taken as the simulator does. ``same_way=False`` drops the
    condition on the direction."""
    assert rule.laps == 2
    xy = np.array(positions)
    path = np.zeros(len(xy))
    steps = np.zeros_like(xy)
    for n in range(1, len(xy)):
        path[n] = path[n - 1] + distance(positions[n - 1], positions[n])
        moved = not np.array_equal(xy[n], xy[n - 1])
        steps[n] = xy[n] - xy[n - 1] if moved else steps[n - 1]
    best = np.minimum.accumulate([distance(p, goal) for p in positions])
    fires = []
    for n in range(len(xy)):
        dx, dy = xy[:n, 0] - xy[n, 0], xy[:n, 1] - xy[n, 1]
        close = dx * dx + dy * dy <= rule.radius * rule.radius
        ahead = steps[:n, 0] * steps[n, 0] + steps[:n, 1] * steps[n, 1] > 0.0
        if not same_way:
            ahead[:] = True
        near = np.flatnonzero(close & ahead & (path[:n] <= path[n] - rule.length))
        starts = near[best[near] - best[n] <= rule.progress]
        fires.append(bool(len(starts)) and path[starts].min() <= path[near].max() - rule.length)
    return fires


def first_firing(run: Run, goal: Point, rule: LapRule) -> int | None:
    """The first step of ``run`` at which :func:`brute_force` fires (``None``: none)."""
    fires = brute_force([(s.x, s.y) for s in run.trace], goal, rule)
    return fires.index(True) if True in fires else None


def default_rule(world: World) -> LapRule:
    rule = lap_rule(SimParams(), EpisodeParams(world.robot, world.sensor))
    assert rule is not None
    return rule


def test_an_endless_lapper_stalls_where_the_definition_says() -> None:
    free = simulate(POST, lapper(), replace(NO_STALL, max_time=120.0))
    assert free.result.stop_reason == StopReason.TIME_LIMIT  # it does lap for ever
    expected = first_firing(free, POST.goal, default_rule(POST))
    run = simulate(POST, lapper())
    assert run.result.stop_reason == StopReason.STALLED and not run.result.collided
    assert run.result.detail is not None and run.result.detail.startswith("lap rule")
    assert run.result.steps == expected
    assert run.trace[:-1] == free.trace[:expected]  # the same run, cut short
    # Two laps from H (7 ft from the start), then into the third until the robot comes within
    # rho of where the first lap got within eps of its best distance (near Q = (13, 0)).
    rule, end = default_rule(POST), run.trace[-1]
    laps = (run.result.path_length - 7.0) / (2.0 * math.pi * 3.0)
    assert 2.0 < laps < 3.0, f"laps={laps}"
    best = min(distance((s.x, s.y), POST.goal) for s in run.trace)
    first_lap = [s for s in run.trace if s.t < 0.4 * run.result.time_s]
    near_best = [s for s in first_lap if distance((s.x, s.y), POST.goal) <= best + rule.progress]
    assert min(distance((s.x, s.y), (end.x, end.y)) for s in near_best) <= rule.radius


def test_a_bug1_like_lap_and_a_half_does_not_stall() -> None:
    """Bug1 (section 2.1.1): once round from H, on to Q (here half a lap), then away to the
    goal. Its second pass from H to Q brings no better distance than the first, so one lap
    without progress is no stall: with ``stall_laps=1`` the rule would fire before Q."""
    bug1_like = CirclingPlanner((10.0, 0.0), 3.0, 1.5)
    run = simulate(POST, bug1_like)
    assert run.result.reached
    assert run.trace == simulate(POST, CirclingPlanner((10.0, 0.0), 3.0, 1.5), NO_STALL).trace
    one_lap = simulate(POST, CirclingPlanner((10.0, 0.0), 3.0, 1.5), SimParams(stall_laps=1))
    assert one_lap.result.stop_reason == StopReason.STALLED
    laps = (one_lap.result.path_length - 7.0) / (2.0 * math.pi * 3.0)
    assert 1.0 < laps < 1.5, f"laps={laps}"  # on the way from H back to Q, before leaving


class SlotPlanner:
    """Drives along the x axis to ``x = depth`` and back to ``x = 0``, turning on the spot at
    each end, ``passes`` times (in, out, in, ...), then heads for the goal: in and out of a
    dead-end slot, and in and out again on the way back to a leaving point."""

    name = "slot"

    def __init__(self, depth: float, passes: int) -> None:
        self.depth, self.passes = depth, passes
        self.heading, self.done, self.speed = 0.0, 0, 0.0

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.heading, self.done, self.speed = 0.0, 0, params.robot.speed

    def step(self, observation: Observation) -> Command:
        pose, goal = observation.pose, observation.goal
        if self.done >= self.passes:
            return Command(heading=math.atan2(goal.y - pose.y, goal.x - pose.x), speed=self.speed)
        end = pose.x >= self.depth if self.heading == 0.0 else pose.x <= 0.0
        if end:
            self.heading, self.done = math.pi - self.heading, self.done + 1
        facing = math.cos(pose.theta - self.heading) > 1.0 - 1e-9
        return Command(heading=self.heading, speed=self.speed if facing else 0.0)


def test_in_and_out_of_a_dead_end_twice_is_no_lap_but_going_on_is() -> None:
    """A slot 10 ft deep, the goal off to its side: in, out, in, out, then away. Each place in
    it is passed four times, no nearer the goal after the first, but only twice each way: no
    stall. Without the condition on the direction the rule would fire; a fifth pass (the
    third one way) does fire it."""
    free = World(start=Pose(0.0, 0.0, 0.0), goal=Point(5.0, 20.0), name="slot")
    rule = default_rule(free)
    run = simulate(free, SlotPlanner(10.0, 4))
    assert run.result.reached
    assert run.trace == simulate(free, SlotPlanner(10.0, 4), NO_STALL).trace
    positions = [(s.x, s.y) for s in run.trace]
    assert any(brute_force(positions, free.goal, rule, same_way=False))
    assert not any(brute_force(positions, free.goal, rule))
    once_more = simulate(free, SlotPlanner(10.0, 5)).result
    assert once_more.stop_reason == StopReason.STALLED and once_more.path_length > 40.0


@pytest.mark.parametrize("world", ["tests/worlds/small_u.json", "u_trap", "h_block"])
def test_ifgms_dead_end_escapes_run_as_without_the_rule(world: str) -> None:
    """Into the U (or the H's cavity), the dead-end turns, out and round (section 4): the
    episode is the one without any stall rule, step for step."""
    built = resolve_world(world)
    run = simulate(built, IFGMPlanner())
    assert run.result.reached
    unstalled = simulate(built, IFGMPlanner(), NO_STALL)
    assert run.trace == unstalled.trace and run.result == unstalled.result


@pytest.mark.parametrize("off", [None, 0])
def test_stall_laps_none_or_zero_turns_the_rule_off(off: int | None) -> None:
    sim = SimParams(max_time=60.0, stall_time=None, stall_laps=off)
    assert lap_rule(sim, EpisodeParams()) is None
    result = simulate(POST, lapper(), sim).result
    assert result.stop_reason == StopReason.TIME_LIMIT and result.steps == 600


def test_the_disc_rule_alone_is_blind_to_laps_and_stall_time_leaves_the_lap_rule_on() -> None:
    lapping = simulate(POST, lapper(), SimParams(stall_laps=None, max_time=60.0)).result
    assert lapping.stop_reason == StopReason.TIME_LIMIT
    caught = simulate(POST, lapper(), LAPS_ONLY).result
    assert (
        caught.stop_reason == StopReason.STALLED
        and caught.steps == simulate(POST, lapper()).result.steps
    )


@pytest.mark.parametrize("value", [-1, 1.5, True, "2"])
def test_a_bad_stall_laps_is_rejected(value: object) -> None:
    with pytest.raises(ParameterError, match="`stall_laps` must be an integer >= 0"):
        SimParams(stall_laps=value)  # type: ignore[arg-type]


@pytest.mark.parametrize("k", [0.5, 2.0, 4.0])
def test_the_lap_rule_fires_at_the_same_step_when_every_length_is_scaled(k: float) -> None:
    """The world, the robot, the sensor, the goal tolerance and the lapper's circle times a
    power of two: the same step, and every position exactly ``k`` times the original."""
    first = simulate(POST, lapper())
    scaled = simulate(scale_world(POST, k), lapper(k), scale_sim(SimParams(), k))
    assert scaled.result.stop_reason == first.result.stop_reason == StopReason.STALLED
    assert scaled.result.steps == first.result.steps
    assert [(s.x, s.y) for s in scaled.trace] == [(k * s.x, k * s.y) for s in first.trace]


def test_the_rule_is_derived_from_the_robot() -> None:
    """rho = r, L = 2 pi r, eps = v dt (:mod:`ifgm_ref.sim.laps`), for the paper's robot and a
    robot of another size, speed and time step."""
    paper = LapRule.of(Scale.paper(), 2)
    assert (paper.radius, paper.length) == (1.0, 2.0 * math.pi)
    assert paper.progress == pytest.approx(197.0 / 149.0 * 0.1)
    other = LapRule.of(Scale(0.22, 1.0, math.pi, 0.05, 30.0, 0.01, 4.7), 3)
    assert (other.radius, other.length, other.progress, other.laps) == (
        0.22,
        2.0 * math.pi * 0.22,
        0.05,
        3,
    )


def _random_walk(seed: int, steps: int) -> list[tuple[float, float]]:
    """A walk of 0.1 to 0.4 ft steps, its heading wandering, kept inside a 6 ft box (so that
    it keeps coming back), with now and then a step on the spot."""
    rng = np.random.default_rng(seed)
    x, y, heading, out = 0.0, 0.0, 0.0, [(0.0, 0.0)]
    for _ in range(steps):
        heading += rng.normal(0.0, 0.6)
        length = 0.0 if rng.random() < 0.05 else rng.uniform(0.1, 0.4)
        nx, ny = x + length * math.cos(heading), y + length * math.sin(heading)
        if abs(nx) > 3.0 or abs(ny) > 3.0:
            heading += math.pi
            nx, ny = x, y
        x, y = nx, ny
        out.append((x, y))
    return out


@pytest.mark.parametrize("seed", range(6))
def test_the_grid_hash_finds_every_firing_brute_force_finds(seed: int) -> None:
    """At every step of a random walk, the rule as the simulator runs it (the grid hash and
    the latest chain of laps) fires exactly where the brute force over all pairs does."""
    rng = np.random.default_rng(100 + seed)
    rule = LapRule(
        radius=float(rng.uniform(0.3, 1.5)),
        length=float(rng.uniform(1.0, 8.0)),
        progress=float(rng.uniform(0.0, 0.5)),
        laps=2,
    )
    walk = _random_walk(seed, 400)
    goal = Point(7.0, float(rng.uniform(-3.0, 3.0)))
    log = LapLog(rule.radius, rule.length, goal)
    path, fired = 0.0, []
    for n, here in enumerate(walk):
        if n:
            path += distance(walk[n - 1], here)
        visit = log.log(here, path)
        starts = log.laps(visit, 2)
        fired.append(len(starts) == 2 and starts[-1] - visit.best <= rule.progress)
    assert fired == brute_force(walk, goal, rule)
    assert any(fired) and not all(fired)  # the walk does close laps, not everywhere
