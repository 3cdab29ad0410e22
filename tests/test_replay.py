"""``ifgm-ref replay``: a robot's log fed to the reference, open loop, compared step by step.

Logs come from two writers: this project's (``simulate --record``, :mod:`ifgm_ref.io.bags`) and
an independent one, ``mcap`` with ``mcap-ros2-support``, so that the reader is not only
checked against its own writer.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from ifgm_ref.apps.cli import main
from ifgm_ref.apps.replay import Tolerance, difference, replay_log, setting_of
from ifgm_ref.core.errors import BagError
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Point
from ifgm_ref.core.protocol import Planner
from ifgm_ref.core.recording import Recording, RecordingPlanner, replay
from ifgm_ref.io import barn
from ifgm_ref.io.bags.read import read_log
from ifgm_ref.io.bags.write import write_bag
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.oracle.mutants import MUTANTS
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.noise import NoiseLevels
from ifgm_ref.sim.simulator import Run, simulate
from ifgm_ref.sim.world import World
from tests.test_cli import run_cli

mcap_writer = pytest.importorskip("mcap_ros2.writer")


def record(
    world: World, planner: Planner, path: Path, sim: SimParams | None = None
) -> tuple[Run, Recording]:
    """Simulate ``planner`` in ``world`` and write the run as a bag at ``path``."""
    recorder = RecordingPlanner(planner)
    run = simulate(world, recorder, sim)
    write_bag(path, world, run, recorder.recording(), "ft")
    return run, recorder.recording()


# -- the reference's own runs --------------------------------------------------------------------


@pytest.mark.parametrize("suffix", [".mcap", ".bag", ""])
def test_the_reference_agrees_with_its_own_run_at_every_step(tmp_path: Path, suffix: str) -> None:
    """In every format, with odometry noise (so that /odom is the believed pose, not the true
    one): the log's float32 ranges and its metres leave every decision as it was."""
    world = NoiseLevels.parse("odometry=0.02,range=0.01").apply(resolve_world("u_trap"), 7)
    path = tmp_path / f"run{suffix}"
    run, recording = record(world, make_planner("ifgm"), path)
    log = read_log(path)
    report = replay_log(log, make_planner("ifgm"), setting_of(log))
    assert len(report.steps) == run.result.steps == len(recording.steps)
    assert report.compared == len(report.steps), "every step has its logged command"
    assert report.first_divergence is None, report.text()
    assert [s.logged_branch for s in report.steps] == [c.branch for _, c in recording.steps]
    believed = np.array([(s.believed_x, s.believed_y) for s in run.trace[:-1]])
    replayed = np.array([s.pose[:2] for s in report.steps])
    assert np.allclose(replayed, believed, rtol=0.0, atol=1e-9)


@pytest.mark.parametrize("mutant", ["no_dead_end_rule", "gap_sign_flipped"])
def test_a_broken_rule_is_found_where_it_first_acts(tmp_path: Path, mutant: str) -> None:
    """The log of a run with one broken rule: the replay names as first divergence the step
    at which the broken planner first answered the reference otherwise, found here without
    any bag, float32 or metres, by replaying its observations into the reference in process
    and comparing the commands with the same tolerances."""
    world = resolve_world("u_trap" if mutant == "no_dead_end_rule" else "fig7a")
    broken = RecordingPlanner(MUTANTS[mutant]())
    simulate(world, broken, SimParams(max_time=80.0))
    recording = broken.recording()
    params = recording.params
    acts = next(
        k
        for k, (seen, recorded, again) in enumerate(replay(recording, make_planner("ifgm")))
        if difference(
            recorded.twist(seen.pose, params),
            again.twist(seen.pose, params),
            (recorded.branch, again.branch),
            params,
            Tolerance(),
        )
    )
    path = tmp_path / "broken.mcap"
    record(world, MUTANTS[mutant](), path, SimParams(max_time=80.0))
    log = read_log(path)
    report = replay_log(log, make_planner("ifgm"), setting_of(log))
    first = report.first_divergence
    assert first is not None and first.k == acts, report.text()
    assert all(s.agrees for s in report.steps[:acts])


def test_the_replay_cli_reports_agreement_and_divergence(tmp_path: Path, capsys: Any) -> None:
    world = resolve_world("u_trap")
    record(world, make_planner("ifgm"), tmp_path / "good.mcap", SimParams(max_time=20.0))
    record(world, MUTANTS["no_dead_end_rule"](), tmp_path / "bad.mcap", SimParams(max_time=80.0))
    plot, steps = tmp_path / "out" / "replay.png", tmp_path / "out" / "steps.csv"
    good = [str(tmp_path / "good.mcap"), "--json", "--plot", str(plot), "--steps", str(steps)]
    assert main(["replay", *good]) == 0
    verdict = json.loads(capsys.readouterr().out)
    assert verdict["disagreeing"] == 0 and verdict["first_divergence"] is None
    assert verdict["steps"] == verdict["compared"] == 200 and verdict["unit"] == "ft"
    assert plot.stat().st_size > 10_000
    rows = steps.read_text().splitlines()
    assert len(rows) == 201 and rows[0].startswith("step,t,x,y,theta,logged_speed")
    assert main(["replay", str(tmp_path / "bad.mcap")]) == 1
    text = capsys.readouterr().out
    assert "first divergence at step" in text and "logged:" in text and "reference:" in text


def test_motion_and_branch_differences_are_counted_apart(tmp_path: Path, capsys: Any) -> None:
    """IFGM's run replayed into FGM (issue 45): at step 0 the two drive alike and only the
    branch labels differ, which counts in branch and not in motion; each tolerance counts the
    steps beyond it; the summary, the JSON verdict and the CSV say which rule each broke."""
    path, steps = tmp_path / "ifgm.mcap", tmp_path / "steps.csv"
    record(resolve_world("u_trap"), make_planner("ifgm"), path, SimParams(max_time=20.0))
    log = read_log(path)
    report = replay_log(log, make_planner("fgm"), setting_of(log))
    first, motion = report.first_divergence, report.first_motion_divergence
    assert first is not None and first.k == 0 and first.logged == first.reference
    assert (first.broke, first.motion_agrees, first.branch_agrees) == (("branch",), True, False)
    assert motion is not None and motion.k > 0 and {"heading", "speed"} & set(motion.broke)
    assert report.compared == report.branch_compared == report.disagreeing == 200
    dt, top = report.setting.params.dt, report.setting.params.robot.speed
    logged = [(s.logged or (math.nan, math.nan), s.reference) for s in report.steps]
    heading = sum(abs(a[1] - b[1]) * dt > 0.1 for a, b in logged)
    speed = sum(abs(min(a[0], top) - b[0]) > 0.1 * top for a, b in logged)
    assert (report.breaking("heading"), report.breaking("speed")) == (heading, speed)
    assert 0 < report.motion_disagreeing < report.branch_disagreeing == report.disagreeing

    assert main(["replay", str(path), "--planner", "fgm", "--steps", str(steps)]) == 1
    text = capsys.readouterr().out.splitlines()
    assert text[0].endswith(f"200 differ: {report.motion_disagreeing} in motion, 200 in branch"), (
        text[0]
    )
    assert text[1:4] == [
        f"  heading: {heading} steps off by more than 0.1 rad after a step (--heading-tolerance)",
        f"  speed:   {speed} steps off by more than 0.1 of the robot's speed (--speed-tolerance)",
        "  branch:  200 steps with another branch, of the 200 where both name one (the branch "
        "rule)",
    ]
    assert text[4].startswith("first divergence at step 0 ")
    assert text[4].endswith(": branch move_to_goal against no_obstacle")
    assert text[7].startswith(f"first divergence in motion at step {motion.k} ")
    rows = steps.read_text().splitlines()
    assert rows[0].endswith(",agrees,differs,motion_agrees,branch_agrees")
    assert rows[1].endswith(",False,branch move_to_goal against no_obstacle,True,False")

    assert main(["replay", str(path), "--planner", "fgm", "--json"]) == 1
    verdict = json.loads(capsys.readouterr().out)
    assert verdict["disagreeing"] == verdict["branch_disagreeing"] == 200
    assert verdict["motion_disagreeing"] == report.motion_disagreeing
    assert (verdict["heading_disagreeing"], verdict["speed_disagreeing"]) == (heading, speed)
    assert verdict["first_divergence"]["step"] == 0
    assert verdict["first_motion_divergence"]["step"] == motion.k


def test_replay_help_states_every_rule() -> None:
    """``replay --help`` names both tolerances and states the branch rule."""
    from ifgm_ref.apps.replay import BRANCH_RULE

    shown = " ".join(run_cli("replay", "--help").stdout.split())
    assert "--heading-tolerance and the speeds within --speed-tolerance" in shown
    assert f"the branch rule: {BRANCH_RULE}" in shown
    assert "1 when one differs (in motion or in branch)" in shown


# -- a log from another writer -------------------------------------------------------------------


def write_foreign(
    path: Path, steps: list[dict[str, Any]], *, goal: Point | None = None, skip: str = ""
) -> None:
    """Write ``steps`` (each: ``t``, ``pose``, ``scan`` and ``command``, metres; optionally
    a header ``stamp`` other than ``t``) as a ROS 2 MCAP file with ``mcap-ros2-support``, not
    with this project's writer. ``skip`` leaves a topic out."""
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.ROS2_HUMBLE)
    with path.open("wb") as stream:
        writer = mcap_writer.Writer(stream)
        schemas = {
            name: writer.register_msgdef(name, store.generate_msgdef(name, ros_version=2)[0])
            for name in (
                "sensor_msgs/msg/LaserScan",
                "nav_msgs/msg/Odometry",
                "geometry_msgs/msg/Twist",
                "geometry_msgs/msg/PoseStamped",
            )
        }
        if goal is not None:
            message = {"header": _header(0.0, "odom"), "pose": _pose(goal.x, goal.y, 0.0)}
            writer.write_message("/goal_pose", schemas["geometry_msgs/msg/PoseStamped"], message,
                                 log_time=0)  # fmt: skip
        for step in steps:
            ns = round(step["t"] * 1e9)
            topics: dict[str, tuple[str, dict[str, Any]]] = {
                "/scan": ("sensor_msgs/msg/LaserScan", _scan_message(step)),
                "/odom": ("nav_msgs/msg/Odometry", _odometry_message(step)),
                "/cmd_vel": ("geometry_msgs/msg/Twist", _twist_message(step)),
            }
            for topic, (kind, message) in topics.items():
                if topic != skip:
                    writer.write_message(topic, schemas[kind], message, log_time=ns,
                                         publish_time=ns)  # fmt: skip
        writer.finish()


def _header(t: float, frame: str) -> dict[str, Any]:
    ns = round(t * 1e9)
    return {"stamp": {"sec": ns // 10**9, "nanosec": ns % 10**9}, "frame_id": frame}


def _pose(x: float, y: float, theta: float) -> dict[str, Any]:
    half = 0.5 * theta
    return {
        "position": {"x": x, "y": y, "z": 0.0},
        "orientation": {"x": 0.0, "y": 0.0, "z": math.sin(half), "w": math.cos(half)},
    }


def _scan_message(step: dict[str, Any]) -> dict[str, Any]:
    scan = step["scan"]
    return {
        "header": _header(step.get("stamp", step["t"]), "base_link"),
        "angle_min": scan.angle_min,
        "angle_max": scan.angle_max,
        "angle_increment": scan.angle_increment,
        "time_increment": 0.0,
        "scan_time": 0.0,
        "range_min": scan.range_min,
        "range_max": scan.range_max,
        "ranges": [float(r) for r in scan.ranges],
        "intensities": [],
    }


def _odometry_message(step: dict[str, Any]) -> dict[str, Any]:
    zero = {"x": 0.0, "y": 0.0, "z": 0.0}
    return {
        "header": _header(step["t"], "odom"),
        "child_frame_id": "base_link",
        "pose": {"pose": _pose(*step["pose"]), "covariance": [0.0] * 36},
        "twist": {"twist": {"linear": zero, "angular": zero}, "covariance": [0.0] * 36},
    }


def _twist_message(step: dict[str, Any]) -> dict[str, Any]:
    linear, angular = step["command"]
    zero = {"x": 0.0, "y": 0.0, "z": 0.0}
    return {"linear": {**zero, "x": linear}, "angular": {**zero, "z": angular}}


def barn_steps(max_time: float = 6.0) -> tuple[World, list[dict[str, Any]]]:
    """IFGM's first seconds in BARN's world 1 (metres), as the steps of a robot's log."""
    task = barn.gazebo_task("barn:1", folder=None, sensor=barn.DEFAULT_SENSOR, start=None,
                            goal=None)  # fmt: skip
    assert task is not None
    recorder = RecordingPlanner(make_planner("ifgm"))
    simulate(task.world, recorder, replace(task.sim, max_time=max_time))
    recording = recorder.recording()
    steps = [
        {
            "t": observation.t,
            "pose": tuple(observation.pose),
            "scan": observation.scan,
            "command": command.twist(observation.pose, recording.params),
        }
        for observation, command in recording.steps
    ]
    return task.world, steps


@pytest.fixture(scope="module")
def barn_log() -> tuple[World, list[dict[str, Any]]]:
    return barn_steps()


def test_a_log_from_another_writer_replays_in_metres(
    tmp_path: Path, barn_log: tuple[World, list[dict[str, Any]]]
) -> None:
    """No episode in the log: BARN's robot, dt from the scans, the sensor from the first
    scan and the goal from /goal_pose, all in metres; the reference agrees throughout."""
    world, steps = barn_log
    path = tmp_path / "foreign.mcap"
    write_foreign(path, steps, goal=world.goal)
    log = read_log(path)
    setting = setting_of(log)
    assert (setting.unit, setting.params.dt, setting.goal) == ("m", barn.SIM.dt, world.goal)
    assert setting.params.sensor.rays == world.sensor.rays
    report = replay_log(log, make_planner("ifgm"), setting)
    assert report.compared == len(steps) == 120
    assert report.first_divergence is None, report.text()


#: Each fault of a log, and the start of the one line that reports it.
BROKEN = {
    "missing_topic": "no topic /cmd_vel; it has /goal_pose",
    "time_backwards": "/scan message 5 (t=0.100000000 s): time runs backwards",
    "ray_count": "/scan message 4 (t=0.200000000 s): 719 ranges, but the first scan has 720",
    "nan_range": "/scan message 7 (t=0.350000000 s): range 3 is NaN",
}


def broken(steps: list[dict[str, Any]], fault: str) -> tuple[list[dict[str, Any]], str]:
    """``steps`` with ``fault`` (:data:`BROKEN`), and the topic to leave out."""
    steps = [dict(step) for step in steps]
    if fault == "missing_topic":
        return steps, "/cmd_vel"
    if fault == "time_backwards":
        steps[5]["stamp"] = steps[2]["t"]  # received in order, stamped out of it
    elif fault == "ray_count":
        scan = steps[4]["scan"]
        steps[4]["scan"] = replace(
            scan, ranges=scan.ranges[:-1], angle_max=scan.angle_max - scan.angle_increment
        )
    elif fault == "nan_range":
        ranges = steps[7]["scan"].ranges.copy()
        ranges[3] = math.nan
        steps[7]["scan"] = replace(steps[7]["scan"], ranges=ranges)
    return steps, ""


@pytest.mark.parametrize("fault", BROKEN)
def test_a_broken_log_is_one_line_with_exit_2(
    tmp_path: Path, barn_log: tuple[World, list[dict[str, Any]]], fault: str, capsys: Any
) -> None:
    world, steps = barn_log
    steps, skip = broken(steps[:12], fault)
    path = tmp_path / f"{fault}.mcap"
    write_foreign(path, steps, goal=world.goal, skip=skip)
    with pytest.raises(BagError, match=re.escape(BROKEN[fault])):
        read_log(path)
    assert main(["replay", str(path)]) == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and error[0].startswith("ifgm-ref: error: ")
    assert BROKEN[fault] in error[0]


@pytest.mark.parametrize(
    ("robot", "message"),
    [
        ("0,1,1", "--robot 0,1,1: R (the radius) must be a finite number > 0, got 0.0"),
        ("0.22,1,-1.5", "--robot 0.22,1,-1.5: W (the turn rate) must be a finite number > 0"),
    ],
)
def test_a_bad_robot_is_named_as_the_option_gave_it(
    tmp_path: Path,
    barn_log: tuple[World, list[dict[str, Any]]],
    robot: str,
    message: str,
    capsys: Any,
) -> None:
    """``--robot R,V,W``: the message names the option and the number, not a field."""
    world, steps = barn_log
    path = tmp_path / "robot.mcap"
    write_foreign(path, steps[:5], goal=world.goal)
    assert main(["replay", str(path), "--robot", robot]) == 2
    error = capsys.readouterr().err
    assert error.startswith(f"ifgm-ref: error: {message}") and error.count("\n") == 1, error
    assert "`" not in error


def test_a_foreign_log_needs_a_goal(
    tmp_path: Path, barn_log: tuple[World, list[dict[str, Any]]]
) -> None:
    _, steps = barn_log
    path = tmp_path / "no_goal.mcap"
    write_foreign(path, steps[:5])
    with pytest.raises(BagError, match="no goal: the log has no /goal_pose; give --goal X,Y"):
        setting_of(read_log(path))
    assert setting_of(read_log(path), goal=Point(1.0, 2.0)).goal == Point(1.0, 2.0)


def test_bench_records_its_episodes_on_request(tmp_path: Path, capsys: Any) -> None:
    """``bench --record DIR``: one bag an episode, named after world and planner, each of
    which the reference replays in agreement; in metres, as BARN's worlds are."""
    bags = tmp_path / "bags"
    argv = ["bench", "--barn", "--barn-worlds", "1,2", "--planners", "ifgm", "--jobs", "1"]
    argv += ["--max-time", "5", "--out", str(tmp_path / "out"), "--record", str(bags)]
    assert main(argv) == 0
    assert "bench: 1 planner x 2 worlds" in capsys.readouterr().err
    assert sorted(p.name for p in bags.iterdir()) == ["barn-001-ifgm.mcap", "barn-002-ifgm.mcap"]
    log = read_log(bags / "barn-001-ifgm.mcap")
    setting = setting_of(log)
    assert (setting.unit, setting.params.dt, len(log.steps)) == ("m", barn.SIM.dt, 100)
    assert replay_log(log, make_planner("ifgm"), setting).first_divergence is None
