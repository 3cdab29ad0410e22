"""Bug1's round, every follower's fallback (ifgm_ref.planners.circuit; errata row 34)."""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace
from itertools import pairwise

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.params import SensorParams
from ifgm_ref.core.pose import Point, Pose, distance
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import make_planner
from ifgm_ref.planners.circuit import Circuit, CircuitPhase, encloses
from ifgm_ref.planners.distbug import DistBugRule
from ifgm_ref.planners.edge_following import FollowSide
from ifgm_ref.planners.sight import BoundaryParams, Episode, Sight
from ifgm_ref.sim.simulator import simulate

EPISODE = EpisodeParams()
TUNING = BoundaryParams.for_episode(EPISODE)
NOTHING = np.empty((0, 2))


def episode(goal: Point) -> Episode:
    return Episode.of(goal, EPISODE, TUNING)


def sight(pose: Pose, goal: Point) -> Sight:
    return Sight(pose, episode(goal), NOTHING, math.atan2(goal.y - pose.y, goal.x - pose.x))


def walk(points: list[tuple[float, float]], step: float = 0.1) -> Iterator[Pose]:
    """The poses of a robot driving the polyline ``points``, one every ``step`` ft of the
    way, heading along it."""
    carried = 0.0  # how far into the segment the next pose lies
    for (x0, y0), (x1, y1) in pairwise(points):
        length = math.hypot(x1 - x0, y1 - y0)
        heading = math.atan2(y1 - y0, x1 - x0)
        while carried < length:
            f = carried / length
            yield Pose(x0 + f * (x1 - x0), y0 + f * (y1 - y0), heading)
            carried += step
        carried -= length


def first_closure(points: list[tuple[float, float]], goal: Point) -> tuple[int, Pose] | None:
    """Drive a fresh round along ``points``: the first trail point it closes on, and where."""
    circuit = Circuit().hit()
    for pose in walk(points):
        s = sight(pose, goal)
        circuit = circuit.noted(s)
        at = circuit.closing(s)
        if at is not None:
            return at, pose
    return None


def circle(radius: float, turns: float, clockwise: bool = False) -> list[tuple[float, float]]:
    n = int(64 * turns)
    sign = -1.0 if clockwise else 1.0
    return [
        (
            radius * math.cos(sign * 2 * math.pi * k / 64),
            radius * math.sin(sign * 2 * math.pi * k / 64),
        )
        for k in range(n + 1)
    ]


# -- the loop closes where the robot passes its trail again, the same way -------------------


def test_a_lap_closes_on_the_trail_after_min_loop() -> None:
    goal = Point(20.0, 0.0)
    closure = first_closure(circle(3.0, 1.5), goal)
    assert closure is not None
    at, pose = closure
    assert at == 0  # the earliest trail point, where the lap began
    lap = 2 * math.pi * 3.0
    assert distance(pose.position, Point(3.0, 0.0)) <= TUNING.return_radius
    assert lap >= TUNING.min_loop


def test_in_and_out_of_a_narrow_bay_is_not_a_lap() -> None:
    """Into a bay 0.4 ft wide and out again: the way back passes the way in, the other way."""
    bay = [(0.0, 0.0), (10.0, 0.0), (10.0, 0.4), (0.0, 0.4), (-5.0, 0.4)]
    assert first_closure(bay, Point(0.0, 30.0)) is None


def test_only_points_laid_while_following_close_a_loop() -> None:
    """IFGM lays its trail in every mode (errata row 34); driving towards the goal over a
    place and later following an edge over it the same way is no lap."""
    goal = Point(0.0, 30.0)
    circuit = Circuit().hit()
    way = circle(3.0, 2.0)
    closed = []
    for k, pose in enumerate(walk(way)):
        s = sight(pose, goal)
        circuit = circuit.noted(s, following=k > 100)  # the first 10 ft driven, not following
        closed.append(circuit.closing(s))
    # Back within return_radius of the first point laid following: a lap on from step 100,
    # less the return radius.
    lap = int((2 * math.pi * 3.0 - TUNING.return_radius) / 0.1)
    assert all(at is None for at in closed[: 100 + lap])  # over the first points: no lap
    assert any(at is not None for at in closed[100 + lap :])  # over those laid following


def test_crossing_the_own_way_square_is_not_a_lap() -> None:
    """A figure of eight between two obstacles crosses its own way at right angles."""
    eight = [(0.0, 0.0), (10.0, 0.0), (10.0, 5.0), (5.0, 5.0), (5.0, -5.0), (0.0, -5.0)]
    assert first_closure(eight, Point(0.0, 30.0)) is None


# -- whether the goal lies on the obstacle's side of the loop --------------------------------


@given(
    n=st.integers(3, 40),
    radius=st.floats(1.0, 50.0),
    centre=st.tuples(st.floats(-100, 100), st.floats(-100, 100)),
    clockwise=st.booleans(),
    side=st.sampled_from(FollowSide),
    where=st.floats(0.0, 0.95) | st.floats(1.05, 5.0),
    angle=st.floats(0.0, 2 * math.pi),
)
def test_encloses_is_the_goal_on_the_obstacles_side(
    n: int,
    radius: float,
    centre: tuple[float, float],
    clockwise: bool,
    side: FollowSide,
    where: float,
    angle: float,
) -> None:
    """A regular n-gon loop; the goal a fraction ``where`` of the inscribed radius from the
    centre (inside below 1, outside above, beyond the circumradius). Run clockwise with the
    edge on the right, or anticlockwise on the left, the loop has the obstacle inside."""
    sign = -1.0 if clockwise else 1.0
    phases = [sign * 2 * math.pi * k / n for k in range(n)]
    loop = np.array(
        [(centre[0] + radius * math.cos(a), centre[1] + radius * math.sin(a)) for a in phases]
    )
    inscribed = radius * math.cos(math.pi / n)
    reach = where * (inscribed if where < 1.0 else radius)
    goal = Point(centre[0] + reach * math.cos(angle), centre[1] + reach * math.sin(angle))
    obstacle_inside = clockwise == (side is FollowSide.RIGHT)
    assert encloses(loop, goal, side) == ((where < 1.0) == obstacle_inside)


# -- on to Q, and what the planners make of it --------------------------------------------------


def test_bug1_retraces_its_trail_to_the_point_nearest_the_goal() -> None:
    """On its way to Q the robot never strays from the way it went round (within the trail's
    spacing and the steering's lag), and it leaves from the loop's point nearest the goal."""
    run = simulate(resolve_world("box"), make_planner("bug1"))
    first = np.array([(s.x, s.y) for s in run.trace if s.branch in ("follow_edge", "loop_closed")])
    onward = [(s.x, s.y) for s in run.trace if s.branch == "follow_to_q"]
    assert onward
    gaps = [float(np.hypot(*(first - p).T).min()) for p in onward]
    assert max(gaps) <= TUNING.return_radius
    goal = resolve_world("box").goal
    (leave,) = [s for s in run.trace if s.branch == "leave_at_q"]
    nearest = min(math.dist(p, goal) for p in first)
    assert math.dist((leave.x, leave.y), goal) <= nearest + TUNING.return_radius / 2


def test_left_q_is_remembered_only_when_met_on_the_way_from_q() -> None:
    circuit = Circuit().hit()
    assert circuit.left_q == math.inf
    left = replace(circuit, q_distance=7.0).left_at_q()
    assert left.hit().left_q == 7.0 and left.hit().phase is CircuitPhase.FIRST_PASS
    assert replace(circuit, q_distance=7.0).hit().left_q == math.inf  # not left at Q


def test_a_round_is_a_value_its_changes_return_a_new_one() -> None:
    """Noting a step, closing the loop, moving on and leaving at Q return the changed round
    and leave the one they were asked of as it was (IFGM keeps the round in its state)."""
    goal = Point(-20.0, 0.0)  # Q half a lap on from where the loop closes
    circuit = Circuit().hit()
    rounds = [circuit]
    for pose in walk(circle(3.0, 1.5)):
        s = sight(pose, goal)
        rounds.append(rounds[-1].noted(s))
        if (at := rounds[-1].closing(s)) is not None:
            break
    assert at is not None and circuit.phase is CircuitPhase.FIRST_PASS
    assert len(circuit.trail) == 0 and circuit.travelled == 0.0
    laid = len(rounds[-2].trail)
    closed, way_on = rounds[-1].closed(s, at, FollowSide.LEFT)
    assert way_on and closed.returning and not rounds[-1].returning
    assert closed.q_distance < math.inf == rounds[-1].q_distance
    assert len(rounds[-2].trail) == laid  # the longer trail is a new array
    onward = closed.advanced(sight(Pose(3.0, 0.0, math.pi / 2), goal))
    assert onward.cursor > closed.cursor == at
    assert onward.left_at_q().phase is CircuitPhase.LEFT_AT_Q and onward.returning


# -- DistBug's free range: no farther than the planner remembers --------------------------------


def test_free_range_claims_the_goal_visible_only_within_view_range() -> None:
    """With a sensor that reaches beyond ``view_range`` (BARN's 30 m LiDAR), a corridor free
    of remembered points up to a goal beyond ``view_range`` is not known to be free: F is at
    most ``view_range`` less the encounter distance, not the distance to the goal."""
    long_sensor = EpisodeParams(sensor=SensorParams(range_max=100.0))
    tuning = BoundaryParams.for_episode(long_sensor)
    assert tuning.view_range < 100.0
    goal = Point(tuning.view_range + 10.0, 0.0)
    far = Sight(Pose(0.0, 0.0, 0.0), Episode.of(goal, long_sensor, tuning), NOTHING, 0.0)
    assert DistBugRule.free_range(far) == pytest.approx(tuning.view_range - far.episode.encounter)
    near_goal = Point(tuning.view_range - 1.0, 0.0)
    near = Sight(Pose(0.0, 0.0, 0.0), Episode.of(near_goal, long_sensor, tuning), NOTHING, 0.0)
    assert DistBugRule.free_range(near) == pytest.approx(near.goal_distance)
