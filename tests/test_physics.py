"""The mujoco engine (ifgm_ref.sim.physics): the model, the sensor, motion, odometry, contacts."""

from __future__ import annotations

import dataclasses
import importlib.util
import math

import numpy as np
import pytest
import shapely

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import RobotParams, SimParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams
from ifgm_ref.io.barn import ROBOT as BARN_ROBOT
from ifgm_ref.io.barn import bundled_barn_folder, load_barn_world
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import make_planner
from ifgm_ref.planners.governor import GovernorState, Limits, stopping_distance
from ifgm_ref.sim.engine import PHYSICS_HINT, make_engine
from ifgm_ref.sim.physics.bodies import JACKAL, PAPER, body_for
from ifgm_ref.sim.physics.mjcf import substeps, triangles
from ifgm_ref.sim.physics.mujoco import MujocoEngine
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import Circle, Polygon, World

MUJOCO = SimParams(engine="mujoco")


def _barn_world() -> World:
    return load_barn_world(bundled_barn_folder() / "world_1.world")


@pytest.mark.parametrize("name", ["u_trap", "h_block"])
def test_a_polygon_becomes_triangles_that_cover_it_exactly(name: str) -> None:
    for obstacle in resolve_world(name).obstacles:
        assert isinstance(obstacle, Polygon)
        parts = [shapely.Polygon(t) for t in triangles(obstacle)]
        union = shapely.union_all(parts)
        assert union.symmetric_difference(obstacle.geometry).area < 1e-9
        assert sum(p.area for p in parts) == pytest.approx(obstacle.geometry.area, rel=1e-12)


@pytest.mark.parametrize("name", ["u_trap", "h_block", "scenario2", "barn"])
def test_the_rays_of_mujoco_read_the_exact_ranges(name: str) -> None:
    """mj_multiRay against cylinders and prism meshes gives what the exact ray caster gives."""
    world = _barn_world() if name == "barn" else _facing_its_first_obstacle(resolve_world(name))
    engine = MujocoEngine(world, 0.1)
    mujoco_scan = engine.scan(world.start).ranges
    exact = IRSensor(world).scan(engine.true_pose()).ranges
    assert np.array_equal(np.isinf(mujoco_scan), np.isinf(exact))
    seen = np.isfinite(exact)
    assert seen.any()
    # The chassis settles a hair on its tyres: the sensor is where the body is, to 1e-6 r.
    np.testing.assert_allclose(mujoco_scan[seen], exact[seen], rtol=0, atol=1e-6)


def _facing_its_first_obstacle(world: World) -> World:
    """``world`` with its robot 5 radii before its first obstacle's left side, facing it."""
    xmin, ymin, _, ymax = world.obstacles[0].geometry.bounds
    start = Pose(xmin - 5 * world.robot.radius, (ymin + ymax) / 2, 0.0)
    return dataclasses.replace(world, start=start)


def test_the_default_bodies_are_the_jackal_for_barn_and_the_papers_robot_otherwise() -> None:
    assert body_for(_barn_world().robot) is JACKAL
    assert body_for(resolve_world("u_trap").robot) is PAPER
    assert MujocoEngine(resolve_world("u_trap"), 0.1, "jackal").body is JACKAL


def test_speed_grows_no_faster_than_the_acceleration_limit() -> None:
    """In the first step, the command's speed ramps up by ``a h`` at each of its ``n``
    substeps of ``h`` s: the wheels roll at most ``a h^2 n (n + 1) / 2``."""
    world = resolve_world("free")
    engine = MujocoEngine(world, 0.1)
    pose, _, _ = engine.move(world.start, Command(0.0, 1.0), 1.0, 1.0)
    travelled = pose.x - world.start.x
    n = substeps(0.1)
    h = 0.1 / n
    assert 0.0 < travelled <= PAPER.max_accel * h * h * n * (n + 1) / 2


def test_the_odometry_keeps_the_true_heading_and_counts_the_wheels() -> None:
    world = resolve_world("free")
    engine = MujocoEngine(world, 0.1)
    pose = world.start
    for k in range(60):
        pose, _, _ = engine.move(pose, Command(0.6 * math.sin(k / 7.0), 1.0), 1.0, 1.0)
    odometry = engine.odometry(pose)
    assert odometry.theta == pose.theta
    error = math.hypot(odometry.x - pose.x, odometry.y - pose.y)
    assert 0.0 < error < 0.05 * 6.0  # tyres slip a little over 6 s at ~1 ft/s


def _drive_straight(world: World, steps: int) -> tuple[Pose, float, bool]:
    """Command heading 0 at 1.3 ft/s for up to ``steps`` steps of 0.1 s, or until a collision."""
    engine = MujocoEngine(world, 0.1)
    pose, clearance, collided = world.start, math.inf, False
    for _ in range(steps):
        pose, clearance, collided = engine.move(pose, Command(0.0, 1.3), 1.0, 1.0)
        if collided:
            break
    return pose, clearance, collided


def test_driving_into_a_wall_is_a_collision_at_contact() -> None:
    wall = Polygon(((5.0, -5.0), (6.0, -5.0), (6.0, 5.0), (5.0, 5.0)))
    world = World(start=Pose(0.0, 0.0, 0.0), goal=Point(10.0, 8.0), obstacles=(wall,))
    pose, clearance, collided = _drive_straight(world, steps=100)
    assert collided
    # The disc touches the wall's face at x = 5: its centre one radius before it.
    assert pose.x == pytest.approx(5.0 - world.robot.radius, abs=0.01)
    assert clearance == pytest.approx(0.0, abs=0.01)


def test_a_mujoco_episode_is_deterministic_and_differs_from_the_kinematic_one() -> None:
    world = resolve_world("post")
    first = simulate(world, make_planner("ifgm"), MUJOCO)
    again = simulate(world, make_planner("ifgm"), MUJOCO)
    kinematic = simulate(world, make_planner("ifgm"))
    assert first.trace_csv() == again.trace_csv()
    assert first.trace_csv() != kinematic.trace_csv()
    assert first.result.reached and not first.result.collided


def test_ifgm_leaves_the_u_trap_on_the_physical_robot() -> None:
    """The issue's command: ``simulate u_trap --planner ifgm --engine mujoco``."""
    run = simulate(resolve_world("u_trap"), make_planner("ifgm"), MUJOCO)
    assert run.result.reached, run.result
    assert not run.result.collided
    assert run.result.min_clearance > 0.0


def test_a_circle_and_a_polygon_are_both_obstacles_for_the_chassis() -> None:
    post = World(start=Pose(0, 0, 0), goal=Point(10, 0), obstacles=(Circle((3.0, 0.0), 0.5),))
    pose, _, collided = _drive_straight(post, steps=40)
    assert collided
    assert pose.x == pytest.approx(3.0 - 0.5 - post.robot.radius, abs=0.01)


def test_without_mujoco_the_engine_says_in_one_line_what_to_install(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "mujoco" else real(name, *a)
    )
    with pytest.raises(ParameterError) as raised:
        make_engine(resolve_world("post"), MUJOCO)
    assert str(raised.value) == PHYSICS_HINT
    assert "\n" not in PHYSICS_HINT and "[physics]" in PHYSICS_HINT


def test_an_unknown_engine_or_body_is_a_clear_error() -> None:
    with pytest.raises(ParameterError, match="`engine` must be one of kinematic, mujoco"):
        SimParams(engine="gazebo")
    with pytest.raises(
        ParameterError, match="unknown body 'pr2'; choose one of jackal, jackal-disc, paper"
    ):
        make_engine(resolve_world("post"), SimParams(engine="mujoco", body="pr2"))


# -- the dynamics the planners are told, and the box (issue 41) ---------------------------------


def _stop_from(body_robot: tuple[str, float], fraction: float, turn: float) -> tuple[float, float]:
    """The farthest a body driven straight at ``fraction`` of its top speed gets from where it
    is told to stop (turning by ``turn``), and the braking governor's worst case for it."""
    name, dt = body_robot
    base = BARN_ROBOT if name == "jackal" else RobotParams()
    speed = base.speed * fraction
    world = World(
        start=Pose(0, 0, 0), goal=Point(1000, 0), robot=dataclasses.replace(base, speed=speed)
    )
    engine = MujocoEngine(world, dt, name)
    pose = world.start
    for _ in range(round(2.0 / dt)):
        pose = engine.move(pose, Command(0.0, speed), 1.0, 1.0)[0]
    start, farthest = pose, 0.0
    for _ in range(round(2.0 / dt)):
        pose = engine.move(pose, Command(turn, 0.0), 1.0, 1.0)[0]
        farthest = max(farthest, math.hypot(pose.x - start.x, pose.y - start.y))
    limits = Limits.of(EpisodeParams(robot=engine.robot, dt=dt))
    return farthest, stopping_distance(GovernorState(speed, 0.0, speed), 0.0, limits)


@pytest.mark.parametrize("body", [("jackal", 0.05), ("paper", 0.1)], ids=["jackal", "paper"])
@pytest.mark.parametrize("fraction", [0.25, 0.5, 1.0, 2.0])
@pytest.mark.parametrize("turn", [0.0, math.pi / 8, math.pi], ids=["straight", "22.5", "180"])
def test_every_stop_fits_the_worst_case_the_planners_are_told(
    body: tuple[str, float], fraction: float, turn: float
) -> None:
    """The assumption of proofs/braking.py, measured: from its speed, braking (and turning as
    it brakes), each body stops within the governor's stopping distance for the ``b``, ``A``
    and response time it tells the planners."""
    farthest, worst = _stop_from(body, fraction, turn)
    assert farthest <= worst, (farthest, worst)


def test_the_bodies_tell_the_planners_their_dynamics_and_outline() -> None:
    jackal = MujocoEngine(_barn_world(), 0.05).robot
    assert (round(jackal.braking, 2), round(jackal.acceleration, 2)) == (3.72, 4.9)
    assert jackal.response == pytest.approx(0.08)
    assert jackal.radius == pytest.approx(math.hypot(0.21, 0.165))  # BARN's footprint's corner
    told = MujocoEngine(_barn_world().with_robot({"braking": 2.0, "acceleration": 1.0}), 0.05)
    assert (told.robot.braking, told.robot.acceleration) == (2.0, 1.0)  # a robot's own stand
    paper = MujocoEngine(resolve_world("post"), 0.1).robot
    assert paper.radius == 1.0 and paper.braking == pytest.approx(PAPER.max_accel)


def test_the_jackals_box_collides_where_it_touches_not_where_its_disc_would() -> None:
    """A post beside the box's side, inside the circumscribed disc but outside the box: the
    disc's clearance is negative, the box does not touch, no collision; driven into a post
    ahead, the box's front face touches 0.21 m before the centre."""
    world = _barn_world()
    x, y, _ = world.start
    side = World(start=world.start, goal=world.goal, robot=world.robot,
                 obstacles=(Circle((x + 0.26, y + 0.05), 0.02),))  # fmt: skip
    engine = MujocoEngine(side, 0.05)
    pose, clearance, collided = engine.move(side.start, Command(side.start.theta, 0.0), 1, 1)
    assert clearance < 0.0 and not collided
    ahead = World(start=world.start, goal=world.goal, robot=world.robot,
                  obstacles=(Circle((x, y + 1.0), 0.05),))  # fmt: skip
    engine, pose, collided = MujocoEngine(ahead, 0.05), ahead.start, False
    for _ in range(60):
        pose, _, collided = engine.move(pose, Command(ahead.start.theta, 0.5), 1.0, 1.0)
        if collided:
            break
    assert collided
    assert y + 1.0 - 0.05 - pose.y == pytest.approx(0.21, abs=0.01)
