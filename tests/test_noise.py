"""The simulator's noise models (``ifgm_ref/sim/noise.py``, ``docs/noise.md``): each model's
formula, that every kind draws from its own seeded stream, that noise-free runs are the runs
of before, and that a noisy run replays from its seeds."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import RobotParams, SensorParams, SimParams
from ifgm_ref.core.pose import Point, Pose, distance
from ifgm_ref.core.protocol import Command
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.noise import Actuation, NoiseLevels, Odometry
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import Circle, World

#: A ring of radius 10 round the origin: every ray of a sensor there returns at 10 - 0.5.
RING = World(
    start=Pose(0.0, 0.0, 0.0),
    goal=Point(1.0, 0.0),
    obstacles=tuple(
        Circle((10.0 * math.cos(a), 10.0 * math.sin(a)), 0.5)
        for a in np.linspace(-math.pi, math.pi, 400, endpoint=False)
    ),
)


def _ranges(scans: int, **sensor: float) -> np.ndarray:
    """``scans`` scans from the ring's centre with these sensor settings, one row each."""
    world = replace(RING, sensor=SensorParams(range_max=20.0, rays=181, **sensor))  # type: ignore[arg-type]
    ir = IRSensor(world)
    return np.array([ir.scan(RING.start).ranges for _ in range(scans)])


def _true_ranges() -> np.ndarray:
    return _ranges(1)[0]


def test_proportional_range_noise_has_the_stated_deviation() -> None:
    """``noise_rel``: returns scatter round the true range with standard deviation
    ``noise_rel * range`` (40,000 draws: within 3 %)."""
    true = _true_ranges()
    noisy = _ranges(220, noise_rel=0.05)
    relative = (noisy - true) / true
    assert abs(relative.mean()) < 0.002
    assert relative.std() == pytest.approx(0.05, rel=0.03)


def test_constant_and_proportional_noise_add_in_quadrature() -> None:
    """``noise_std`` and ``noise_rel`` together: ``sqrt(noise_std**2 + (noise_rel r)**2)``."""
    true = _true_ranges()
    noisy = _ranges(220, noise_std=0.3, noise_rel=0.04)
    expected = math.hypot(0.3, 0.04 * float(true.mean()))
    assert (noisy - true).std() == pytest.approx(expected, rel=0.03)


def test_dropouts_read_no_return_at_the_stated_rate() -> None:
    """``dropout``: a ray reads ``+inf`` with that probability; the others are exact."""
    true = _true_ranges()
    noisy = _ranges(220, dropout=0.1)
    lost = np.isposinf(noisy)
    assert lost.mean() == pytest.approx(0.1, abs=0.006)
    assert np.array_equal(noisy[~lost], np.broadcast_to(true, noisy.shape)[~lost])


def test_spurious_returns_are_nearer_than_the_truth() -> None:
    """``spurious``: a ray reads a false return nearer than what it sees, at that rate."""
    true = _true_ranges()
    noisy = _ranges(220, spurious=0.1)
    false = noisy != true
    assert false.mean() == pytest.approx(0.1, abs=0.006)
    assert (noisy[false] < np.broadcast_to(true, noisy.shape)[false]).all()
    assert (noisy >= 0.0).all()


def test_each_kind_draws_from_its_own_stream() -> None:
    """Turning dropouts on changes no Gaussian draw of the rays that still return, and the
    Gaussian stream is the one ``noise_std`` always drew from (``seed`` alone)."""
    gaussian = _ranges(20, noise_std=0.2, seed=5)
    both = _ranges(20, noise_std=0.2, seed=5, dropout=0.3)
    kept = np.isfinite(both)
    assert np.array_equal(both[kept], gaussian[kept])
    true = _true_ranges()
    legacy = np.random.default_rng(5)
    first = true + legacy.normal(0.0, 0.2, len(true))
    assert np.array_equal(gaussian[0], first)


def test_odometry_error_walks_with_distance_not_steps() -> None:
    """The believed position's error has standard deviation ``k sqrt(r D)`` per axis after a
    distance ``D``, however it is cut into steps; the heading's ``k sqrt(D / r)``."""
    k, r, length = 0.05, 2.0, 50.0
    finals = {}
    for steps in (10, 200):
        errors = []
        for seed in range(400):
            odometry = Odometry(RobotParams(radius=r, odometry_drift=k, seed=seed))
            for _ in range(steps):
                odometry.moved(length / steps)
            errors.append(odometry.error)
        finals[steps] = np.array(errors)
    for errors in finals.values():
        assert errors[:, 0].std() == pytest.approx(k * math.sqrt(r * length), rel=0.1)
        assert errors[:, 2].std() == pytest.approx(k * math.sqrt(length / r), rel=0.1)


def test_odometry_scales_with_the_robot() -> None:
    """Scaled by a power of two (robot and distances), the believed error scales exactly:
    the level is relative to the robot."""
    a = Odometry(RobotParams(radius=1.0, odometry_drift=0.01, seed=3))
    b = Odometry(RobotParams(radius=4.0, odometry_drift=0.01, seed=3))
    for d in (0.13, 0.2, 0.05):
        a.moved(d)
        b.moved(4.0 * d)
    assert (4.0 * a.error[0], 4.0 * a.error[1], a.error[2]) == b.error


def test_without_drift_the_planner_is_told_the_true_pose() -> None:
    """Odometry off: the believed pose is the true pose object itself."""
    odometry = Odometry(RobotParams())
    pose = Pose(1.0, 2.0, 0.5)
    odometry.moved(3.0)
    assert odometry.believed(pose) is pose


def test_latency_delays_commands_and_stands_still_first() -> None:
    """``latency = 2``: the first two steps execute standing still (the robot's heading,
    speed 0); from then on, the command of two steps before."""
    actuation = Actuation(RobotParams(latency=2))
    pose = Pose(0.0, 0.0, 0.3)
    commands = [Command(0.1 * k, 1.0) for k in range(5)]
    executed = [actuation.executed(c, pose)[0] for c in commands]
    assert executed[:2] == [Command(0.3, 0.0), Command(0.3, 0.0)]
    assert executed[2:] == commands[:3]


def test_actuation_noise_scales_turn_and_speed() -> None:
    """``actuation_noise = s``: the factors on turn and speed have mean 1 and deviation s,
    and speed's is never negative."""
    actuation = Actuation(RobotParams(actuation_noise=0.1, seed=1))
    factors = np.array(
        [actuation.executed(Command(0.0, 1.0), Pose(0, 0, 0))[1:] for _ in range(4000)]
    )
    assert factors.mean(axis=0) == pytest.approx([1.0, 1.0], abs=0.01)
    assert factors.std(axis=0) == pytest.approx([0.1, 0.1], rel=0.05)
    assert (factors[:, 1] >= 0.0).all()


NOISY = "range=0.02,dropout=0.05,spurious=0.01,odometry=0.02,actuation=0.05,latency=1"


def test_a_noisy_run_replays_from_its_seeds() -> None:
    """Same seeds, same trace (every field); another seed, another trace. The trace records
    the believed pose beside the true one, and they part with odometry noise."""
    world = resolve_world("post")
    runs = [
        simulate(NoiseLevels.parse(NOISY).apply(world, seed), make_planner("ifgm"))
        for seed in (4, 4, 5)
    ]
    assert runs[0].trace == runs[1].trace
    assert runs[0].trace != runs[2].trace
    last = runs[0].trace[-1]
    assert last.believed_x is not None and last.believed_y is not None
    assert 0.0 < math.dist((last.x, last.y), (last.believed_x, last.believed_y)) < 1.0


def test_the_goal_is_judged_on_the_true_pose() -> None:
    """With drift, a run ends where the *true* centre is within the goal tolerance; a robot
    whose belief is far off hovers where it believes the goal is, and stalls there."""
    world = resolve_world("free")
    small = simulate(NoiseLevels.parse("odometry=0.01").apply(world, 2), make_planner("ifgm"))
    last = small.trace[-1]
    assert small.result.reached and distance((last.x, last.y), world.goal) <= 0.5
    assert (last.believed_x, last.believed_y) != (last.x, last.y)
    large = simulate(NoiseLevels.parse("odometry=0.05").apply(world, 2), make_planner("ifgm"))
    last = large.trace[-1]
    assert large.result.stop_reason == "stalled"
    assert distance((last.x, last.y), world.goal) > 0.5


def test_noise_free_levels_change_nothing() -> None:
    """Levels of 0 and a seed change no bit of a run: the noise-free reference is the same."""
    world = resolve_world("u_trap")
    plain = simulate(world, make_planner("ifgm"))
    zero = simulate(NoiseLevels().apply(world, 9), make_planner("ifgm"))
    assert zero.trace == plain.trace


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("range", "--noise range: expected KIND=LEVEL"),
        ("gravity=1", "--noise gravity=1: expected KIND=LEVEL"),
        ("dropout=lots", "--noise dropout=lots: the level must be a number"),
        ("latency=0.5", "--noise latency=0.5: the level must be an integer >= 0"),
        ("latency=-1", "--noise latency=-1: the level must be an integer >= 0"),
        ("range=-1", "--noise range=-1: the level must be a finite number >= 0"),
        ("range=nan", "--noise range=nan: the level must be a finite number >= 0"),
        ("range_const=-0.5", "--noise range_const=-0.5: the level must be a finite number >= 0"),
        ("odometry=-1", "--noise odometry=-1: the level must be a finite number >= 0"),
        ("actuation=inf", "--noise actuation=inf: the level must be a finite number >= 0"),
        ("dropout=1.5", "--noise dropout=1.5: the level must be a probability in [0, 1]"),
        ("range=0.1,spurious=-0.1", "--noise spurious=-0.1: the level must be a probability in"),
    ],
)
def test_bad_levels_are_refused(text: str, message: str) -> None:
    """``--noise`` names the item it cannot read, as written: the kind the user typed, never
    the parameter blocks' field it sets (``range`` sets ``noise_rel``)."""
    with pytest.raises(ParameterError) as refused:
        NoiseLevels.parse(text)
    assert str(refused.value).startswith(message), refused.value
    for field in ("noise_rel", "noise_std", "odometry_drift", "actuation_noise"):
        assert field not in str(refused.value)


def test_a_level_is_named_after_the_option_that_gave_it() -> None:
    with pytest.raises(ParameterError, match=r"^--noise-sweep range=-1: the level must be a fin"):
        NoiseLevels.parse("range=-1", option="--noise-sweep")
    assert NoiseLevels.parse("latency=2.0").latency == 2


@pytest.mark.parametrize(
    ("block", "field", "value"),
    [
        (SensorParams, "dropout", 1.5),
        (SensorParams, "spurious", -0.1),
        (SensorParams, "noise_rel", math.inf),
        (RobotParams, "odometry_drift", -1.0),
        (RobotParams, "latency", 1.5),
        (RobotParams, "seed", -2),
    ],
)
def test_noise_fields_are_checked(block: type, field: str, value: float) -> None:
    """Each noise field of the world file's blocks refuses a value out of its domain."""
    with pytest.raises(ParameterError, match=f"`{field}`"):
        block(**{field: value})


class _DriveThenFace:
    """Drive along +x for 40 steps, then turn in place to face heading 1.0 (as believed)."""

    name = "drive_then_face"

    def reset(self, start: object, goal: object, params: object) -> None:
        self.steps = 0

    def step(self, observation: object) -> Command:
        self.steps += 1
        return Command(0.0, 1.0) if self.steps <= 40 else Command(1.0, 0.0)


def test_the_heading_controller_knows_only_the_believed_heading() -> None:
    """With drift, a command to face ``psi`` brings the *believed* heading to ``psi``; the
    true heading ends ``e_theta`` away from it (``docs/noise.md``)."""
    world = replace(resolve_world("free"), robot=RobotParams(odometry_drift=0.2, seed=4))
    run = simulate(world, _DriveThenFace(), SimParams(max_time=8.0, stall_time=None))
    last = run.trace[-1]
    assert last.believed_theta == pytest.approx(1.0, abs=1e-9)
    error = last.believed_theta - last.theta
    assert abs(error) > 0.01
    assert last.theta == pytest.approx(1.0 - error, abs=1e-9)
