"""An implementation's declared specification (issue 42, part 3): ``ifgm-ref oracle --spec``,
``pytest --ifgm-spec``, ``check_planner(spec=...)``.

The file is read and refused in one line naming the file and the key; what it declares
reaches every episode (the robot and sensor of the worlds, the ``dt`` and goal tolerance the
planner is told and judged by), decides which checks apply, and is printed as "held to".
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import SensorParams
from ifgm_ref.core.pose import Point, Pose, distance
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.profiles import Profile
from ifgm_ref.oracle.runner import Status, check_planner
from ifgm_ref.oracle.specification import (
    FEET_PER,
    Specification,
    declared,
    in_feet,
    load_specification,
    refuse_options,
)
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.world import World
from tests.test_cli import run_cli

SPECS = Path(__file__).resolve().parent.parent / "examples" / "specs"
ROS = SPECS / "ros_lidar_270.toml"
M = FEET_PER["m"]
#: A few examples: enough to run every episode kind a check has, quick on 2 busy cores.
TINY = Profile("tiny", 3)


def write(tmp_path: Path, text: str, name: str = "port.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


# -- doubles -------------------------------------------------------------------------------------


class Recording:
    """The reference IFGM, recording what each episode tells it: its parameters at ``reset``
    and the shape of every scan."""

    name = "recording"

    def __init__(self, log: list[tuple[object, ...]]) -> None:
        self.inner = make_planner("ifgm")
        self.log = log

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.log.append(("reset", params))
        self.inner.reset(start, goal, params)

    def step(self, observation: Observation) -> Command:
        scan = observation.scan
        self.log.append(("scan", len(scan.ranges), scan.angle_min, scan.angle_max))
        return self.inner.step(observation)


#: Where :class:`StopsShort` stops: 0.9 ft, 0.27 m, inside a ROS node's 0.3 m tolerance.
STOP = 0.9


class StopsShort:
    """The reference IFGM that stops :data:`STOP` from the goal and stays there, as a ROS node
    does that calls 0.3 m "arrived"."""

    name = "stops_short"

    def __init__(self) -> None:
        self.inner = make_planner("ifgm")

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.inner.reset(start, goal, params)

    def step(self, observation: Observation) -> Command:
        if distance(observation.pose, observation.goal) <= STOP:
            return Command(heading=observation.pose.theta, speed=0.0)
        return self.inner.step(observation)


# -- reading the file ----------------------------------------------------------------------------


def test_the_ros_example_is_read_in_metres_and_held_in_feet() -> None:
    spec = load_specification(ROS)
    assert spec.unit == "m" and spec.dt == 0.05
    assert spec.goal_tolerance == pytest.approx(0.3 * M)
    assert math.degrees(spec.sensor.fov) == pytest.approx(270.0) and spec.sensor.rays == 720
    assert spec.sensor.range_max == pytest.approx(30.0 * M)
    assert spec.sensor.range_min == pytest.approx(0.1 * M)
    robot = dict(spec.robot)
    assert robot["radius"] == pytest.approx(0.22 * M) and robot["speed"] == pytest.approx(0.5 * M)
    assert robot["braking"] == pytest.approx(1.0 * M)
    assert robot["acceleration"] == pytest.approx(1.5 * M)
    assert robot["max_turn_rate"] == 1.57 and robot["response"] == 0.1  # no lengths: as written
    assert spec.promises.turns_at_dead_ends and spec.promises.noise is None
    assert spec.level == "paper"


def test_the_paper_example_declares_the_defaults() -> None:
    spec = load_specification(SPECS / "paper_ir.toml")
    assert (spec.goal_tolerance, spec.dt, spec.level) == (0.5, 0.1, "reference")
    assert (round(math.degrees(spec.sensor.fov)), spec.sensor.rays) == (135, 76)
    assert (spec.sensor.range_min, spec.sensor.range_max) == (0.0, 15.0)
    assert dict(spec.robot)["braking"] == math.inf


def test_what_a_file_leaves_out_is_exactly_the_oracles_default() -> None:
    spec = Specification.parse({"unit": "m"}, "port.toml")
    assert (spec.goal_tolerance, spec.dt, spec.robot, spec.level) == (0.5, 0.1, (), "paper")
    assert spec.sensor == SensorParams()  # the paper's IR, in feet whatever the file's unit
    assert spec.promises == Implementation.from_spec("ifgm").promises


def test_a_sensor_preset_in_metres_is_converted_and_overridden_in_the_files_unit(
    tmp_path: Path,
) -> None:
    text = 'unit = "ft"\n[sensor]\npreset = "lidar_180"\nrange_max = 20.0\nrays = 361\n'
    sensor = load_specification(write(tmp_path, text)).sensor
    assert math.degrees(sensor.fov) == pytest.approx(180.0) and sensor.rays == 361
    assert sensor.range_max == 20.0  # the file's unit, ft
    assert sensor.range_min == pytest.approx(0.1 * M)  # the preset's, 0.1 m


@pytest.mark.parametrize(
    ("text", "key", "why"),
    [
        ("dt = 0.1", "unit", "missing"),
        ('unit = "yd"', "unit", "must be one of 'ft', 'm'"),
        ('unit = "m"\ngoal_tolerence = 0.3', "goal_tolerence", "unknown key"),
        ('unit = "m"\ngoal_tolerance = "0.3"', "goal_tolerance", "finite number > 0"),
        ('unit = "m"\ngoal_tolerance = 0', "goal_tolerance", "finite number > 0"),
        ('unit = "m"\ndt = -0.05', "dt", "finite number > 0"),
        ('unit = "m"\nlevel = "strict"', "level", "must be one of 'paper', 'reference'"),
        ('unit = "m"\nsensor = 3', "sensor", "must be a table"),
        ('unit = "m"\n[sensor]\nfov = 4.7', "sensor.fov", "unknown key"),
        ('unit = "m"\n[sensor]\npreset = "kinect"', "sensor.preset", "must be one of"),
        ('unit = "m"\n[sensor]\nfov_degrees = 400', "sensor.fov_degrees", "< 2 pi"),
        ('unit = "m"\n[sensor]\nrays = 1', "sensor.rays", "integer >= 2"),
        ('unit = "m"\n[sensor]\nrays = 720.5', "sensor.rays", "integer >= 2"),
        ('unit = "m"\n[sensor]\nrange_min = 40.0', "sensor.range_min", "< `range_max`"),
        ('unit = "m"\n[sensor]\nrange_max = -1', "sensor.range_max", "finite number > 0"),
        ('unit = "m"\n[robot]\nmass = 3', "robot.mass", "unknown key"),
        ('unit = "m"\n[robot]\nspeed = 0', "robot.speed", "finite number > 0"),
        ('unit = "m"\n[robot]\nradius = true', "robot.radius", "finite number"),
        ('unit = "m"\n[robot]\nbraking = 1.0', "robot.acceleration", "needed with `braking`"),
        ('unit = "m"\n[promises]\nlike = "rrt"', "promises.like", "must be one of"),
        ('unit = "m"\n[promises]\nconverges = []', "promises.converges", "unknown key"),
        ('unit = "m"\n[promises]\nconverges_in = ["z"]', "promises.converges_in", "unknown"),
        ('unit = "m"\n[promises]\nconverges_in = "u"', "promises.converges_in", "a list"),
        ('unit = "m"\n[promises]\nstops_in_time = 1', "promises.stops_in_time", "true or false"),
        ('unit = "m"\n[promises]\nnoise = 0.02', "promises.noise", "must be a string"),
        ('unit = "m"\n[promises]\nnoise = "rain=1"', "promises.noise", "expected KIND=LEVEL"),
        ('unit = "m"\n[promises]\nreference = "iba"', "promises.reference", "must be one of"),
        ('unit = "m"\n[readings]\ndead_end = "left"', "readings.dead_end", "unknown key"),
        ('unit = "m"\n[readings]\ndead_end_side = 1', "readings.dead_end_side", "a string"),
        ('unit = "m"\ndt = 0.1\ndt = 0.2', "", "not valid TOML"),
    ],
)
def test_each_mistake_is_one_line_naming_the_file_and_the_key(
    tmp_path: Path, text: str, key: str, why: str
) -> None:
    path = write(tmp_path, text)
    with pytest.raises(ParameterError) as caught:
        load_specification(path)
    message = str(caught.value)
    assert message.startswith(f"{path}: {key}"), message
    assert why in message and "\n" not in message


def test_a_missing_file_is_one_line() -> None:
    with pytest.raises(ParameterError, match=r"^nowhere\.toml: cannot read it: "):
        load_specification("nowhere.toml")


# -- options that declare what the file declares -------------------------------------------------


@pytest.mark.parametrize(
    ("option", "value", "key"),
    [
        ("--promises", "iba", "[promises]"),
        ("--level", "reference", "level"),
        ("--reading", ["dead_end_side=left"], "[readings]"),
        ("--robot", "speed=2", "[robot]"),
        ("--speed", 2.0, "[robot] speed"),
        ("--ifgm-level", "paper", "level"),
    ],
)
def test_an_option_beside_the_file_is_refused(option: str, value: object, key: str) -> None:
    pattern = rf"^port\.toml: {option} .* \({re.escape(key)}\): change the file"
    with pytest.raises(ParameterError, match=pattern):
        refuse_options("port.toml", {option: value})
    refuse_options("port.toml", {option: None})  # not given: nothing to refuse


def test_check_planner_refuses_promises_level_or_a_robot_beside_a_spec() -> None:
    spec = Specification.parse({"unit": "ft"}, "port.toml")
    with pytest.raises(ParameterError, match="promises: declared by the file"):
        check_planner("ifgm", spec=spec, promises="iba", checks=[])
    with pytest.raises(ParameterError, match="level: declared by the file"):
        check_planner("ifgm", spec=spec, level="paper", checks=[])
    robot = Profile("tiny", 1, robot=(("speed", 2.0),))
    with pytest.raises(ParameterError, match="robot: the profile already sets the robot"):
        check_planner("ifgm", spec=spec, profile=robot, checks=[])


def test_the_cli_refuses_an_option_beside_the_file_in_one_line() -> None:
    done = run_cli("oracle", "--planner", "ifgm", "--spec", str(ROS), "--robot", "speed=2")
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [
        f"ifgm-ref: error: {ROS}: --robot speed=2 given with the specification, which declares "
        "it ([robot]): change the file, or leave out the option"
    ]


# -- what the file declares reaches the episodes -------------------------------------------------


def test_the_declared_sensor_robot_dt_and_tolerance_reach_every_episode() -> None:
    log: list[tuple[object, ...]] = []
    report = check_planner(
        lambda: Recording(log), spec=ROS, profile=TINY, checks=["converges_open"], artifacts=None
    )
    assert report["converges_open"].status is Status.PASSED, report.text()
    resets = [entry[1] for entry in log if entry[0] == "reset"]
    scans = [entry[1:] for entry in log if entry[0] == "scan"]
    assert len(resets) == 3 and len(scans) > 100
    for params in resets:
        assert isinstance(params, EpisodeParams)
        assert params.dt == 0.05 and params.goal_tolerance == pytest.approx(0.3 * M)
        assert params.sensor.rays == 720 and params.robot.radius == pytest.approx(0.22 * M)
        assert params.robot.braking == pytest.approx(1.0 * M) and params.robot.response == 0.1
    for rays, low, high in scans:
        assert rays == 720 and (low, high) == pytest.approx((-0.75 * math.pi, 0.75 * math.pi))


def test_the_explicit_worlds_in_feet_get_the_declared_sensor_too(tmp_path: Path) -> None:
    spec = write(tmp_path, 'unit = "m"\n[sensor]\npreset = "lidar_180"\n')
    log: list[tuple[object, ...]] = []
    report = check_planner(
        lambda: Recording(log), spec=spec, profile=Profile("tiny", 1), checks=["dead_end_turns"]
    )
    assert report["dead_end_turns"].examples >= 3  # u_trap, h_block, then one drawn
    assert {entry[1] for entry in log if entry[0] == "scan"} == {720}
    assert in_feet(World(start=(0, 0, 0), goal=(9, 0), name="u_trap"))
    assert not in_feet(World(start=(0, 0, 0), goal=(9, 0), name="barn-001"))


def test_arrival_is_judged_at_the_declared_goal_tolerance(tmp_path: Path) -> None:
    """A node that stops 0.27 m from the goal is stalled under the oracle's 0.5 ft, arrived
    under its declared 0.3 m; under a declared 0.6 ft it fails, and the counterexample replays
    at the declared dt and tolerance."""
    open_only = dict(profile=TINY, checks=["converges_open"], artifacts=None)
    plain = check_planner(StopsShort, promises="ifgm", **open_only)  # type: ignore[arg-type]
    assert plain["converges_open"].status is Status.FAILED
    assert "stalled" in plain["converges_open"].message
    ros = write(tmp_path, 'unit = "m"\ngoal_tolerance = 0.3\n', "ros.toml")
    held = check_planner(StopsShort, spec=ros, **open_only)  # type: ignore[arg-type]
    assert held["converges_open"].status is Status.PASSED, held.text()
    tight = write(tmp_path, 'unit = "ft"\ngoal_tolerance = 0.6\ndt = 0.05\n', "tight.toml")
    found = tmp_path / "found"
    failed = check_planner(
        StopsShort, spec=tight, profile=Profile("tiny", 1, shrink=False),
        checks=["converges_open"], artifacts=found,
    )  # fmt: skip
    assert failed["converges_open"].status is Status.FAILED
    replay = (failed["converges_open"].artifacts / "report.md").read_text()  # type: ignore[operator]
    assert "--dt 0.05 --goal-tolerance 0.6 " in replay


def test_the_files_promises_decide_which_checks_apply(tmp_path: Path) -> None:
    text = (
        'unit = "ft"\nlevel = "reference"\n[promises]\nconverges_in = ["open"]\n'
        'passes_wide_gaps = false\nreference = "none"\n[readings]\ndead_end_side = "left"\n'
    )
    spec = load_specification(write(tmp_path, text))
    impl = Implementation.from_spec("ifgm")
    held, _, level, _ = declared(spec, impl, "quick")
    assert level == "reference" and held.promises.readings == {"dead_end_side": "left"}
    for name in ("converges_u", "passes_wide_gaps", "agrees_with_reference"):
        assert CHECKS[name].applies(impl) is None  # IFGM's own promises: it applies
        assert CHECKS[name].applies(held) is not None, name  # the file's: it does not
    assert CHECKS["converges_open"].applies(held) is None
    report = check_planner("ifgm", spec=spec, checks=["passes_wide_gaps"], artifacts=None)
    assert report["passes_wide_gaps"].status is Status.NOT_APPLICABLE


# -- what the report says ------------------------------------------------------------------------


def test_held_to_says_every_value_in_both_units() -> None:
    text = load_specification(ROS).held_to()
    assert text.splitlines()[0].startswith(f"held to {ROS} (lengths in m;")
    assert "goal tolerance 0.9843 ft (0.3 m), dt 0.05 s" in text
    assert "sensor 270 deg x 720 rays, range 0.3281 ft (0.1 m) to 98.43 ft (30 m)" in text
    assert "radius 0.7218 ft (0.22 m)" in text and "response 0.1 s" in text
    assert "turns_at_dead_ends" in text and "noise none" in text


def test_the_cli_holds_a_builtin_planner_to_the_ros_example_and_says_so() -> None:
    args = ["--check", "converges_open", "--profile", "brief", "--jobs", "1"]
    done = run_cli("oracle", "--planner", "ifgm", "--spec", str(ROS), *args)
    assert done.returncode == 0, done.stderr
    held = load_specification(ROS).held_to()
    assert done.stdout.startswith(held + "\nPASSED              converges_open")
    assert held in done.stderr  # said before the checks run, too


def test_the_plugin_takes_a_spec_and_says_what_it_holds_to(pytester: pytest.Pytester) -> None:
    pytester.makepyfile(stops_short=_STOPS_SHORT_MODULE)
    spec = pytester.path / "ros.toml"
    spec.write_text('unit = "m"\ngoal_tolerance = 0.3\n')
    common = ["--pyargs", "ifgm_ref.oracle", "--ifgm-impl", "stops_short:StopsShort"]
    common += ["--ifgm-profile", "brief", "-k", "converges_open", "-p", "no:cacheprovider"]
    held = pytester.runpytest_inprocess(*common, "--ifgm-spec", str(spec))
    held.stdout.fnmatch_lines([f"ifgm-ref oracle: held to {spec} (lengths in m;*"])
    held.stdout.fnmatch_lines(["ifgm-ref oracle:   goal tolerance 0.9843 ft (0.3 m), dt 0.1 s"])
    held.assert_outcomes(passed=1)
    both = pytester.runpytest_inprocess(*common, "--ifgm-spec", str(spec), "--ifgm-level", "paper")
    assert both.ret == pytest.ExitCode.USAGE_ERROR
    both.stderr.fnmatch_lines(["*--ifgm-level paper given with the specification*"])


def test_the_equations_are_checked_under_a_declared_sensor_and_robot() -> None:
    """A specification changes the worlds drawn, not the equations' inputs: with one, eq1's
    examples were put through the world's robot and sensor and the check crashed
    (``KeyError: 0`` in ``robust.with_world``)."""
    done = run_cli("oracle", "--planner", "ifgm", "--spec", str(ROS), "--check", "eq1_gap_midpoint",
                   "--profile", "brief")  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    assert re.search(r"^PASSED +eq1_gap_midpoint +10 examples", done.stdout, re.M), done.stdout


_STOPS_SHORT_MODULE = f"""
from ifgm_ref.core.params import SensorParams
from ifgm_ref.planners import make_planner
from ifgm_ref.core.pose import distance
from ifgm_ref.core.protocol import Command


class StopsShort:
    name = "stops_short"

    def __init__(self):
        self.inner = make_planner("ifgm")

    def reset(self, start, goal, params):
        self.inner.reset(start, goal, params)

    def step(self, observation):
        if distance(observation.pose, observation.goal) <= {STOP}:
            return Command(heading=observation.pose.theta, speed=0.0)
        return self.inner.step(observation)
"""
