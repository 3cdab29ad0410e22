"""``ifgm-ref simulate --record``: a run as a ROS bag (ifgm_ref.io.bags), read back by readers
that are not ours: the ``mcap`` and ``mcap_ros2`` libraries for MCAP, rosbags' AnyReader for
the ROS 1 bag and the sqlite3 folder.

The expected topics, types and frames are written out here, not imported, so that the tests
pin the specification (docs/bags.md) rather than repeat the module.
"""

from __future__ import annotations

import json
import math
from collections import defaultdict
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import pytest
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from rosbags.highlevel import AnyReader

from ifgm_ref.apps.cli import main
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Pose
from ifgm_ref.core.protocol import Command, Observation, Planner
from ifgm_ref.core.recording import Recording, RecordingPlanner
from ifgm_ref.io.bags.write import write_bag
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.io.transport.wire import reset_message
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.sim.noise import NoiseLevels
from ifgm_ref.sim.simulator import Run, simulate
from ifgm_ref.sim.world import Circle, World

FT = 0.3048  # metres per foot: the built-in worlds are in feet
#: Every topic and its ROS 2 message type, as the issue lists them.
TOPICS = {
    "/scan": "sensor_msgs/msg/LaserScan",
    "/odom": "nav_msgs/msg/Odometry",
    "/ground_truth": "nav_msgs/msg/Odometry",
    "/cmd_vel": "geometry_msgs/msg/Twist",
    "/tf": "tf2_msgs/msg/TFMessage",
    "/tf_static": "tf2_msgs/msg/TFMessage",
    "/goal_pose": "geometry_msgs/msg/PoseStamped",
    "/obstacles": "visualization_msgs/msg/MarkerArray",
    "/ifgm_ref/branch": "std_msgs/msg/String",
    "/ifgm_ref/behaviour": "std_msgs/msg/String",
    "/ifgm_ref/episode": "std_msgs/msg/String",
}
ONCE = ("/tf_static", "/goal_pose", "/obstacles", "/ifgm_ref/episode")
#: A short run (25 s, 250 steps) up to a wall and two posts and along the wall, with odometry
#: drift: scans with and without returns, five of IFGM's branches.
SIM = SimParams(max_time=25.0)


class Recorded(NamedTuple):
    """A recorded run, and its bag read back with the mcap library."""

    world: World
    recording: Recording
    run: Run
    path: Path
    schemas: dict[str, str]  # topic -> schema name
    messages: dict[str, list[tuple[int, Any]]]  # topic -> (log time, decoded message)


def noisy_world() -> World:
    """wall_posts (one polygon, two circles) with 5 % odometry drift."""
    return NoiseLevels.parse("odometry=0.05").apply(resolve_world("wall_posts"), 3)


def read_mcap(path: Path) -> tuple[dict[str, str], dict[str, list[tuple[int, Any]]]]:
    """The schema name of every topic and every decoded message, by the mcap library."""
    messages: dict[str, list[tuple[int, Any]]] = defaultdict(list)
    with path.open("rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        assert summary is not None
        assert reader.get_header().profile == "ros2"
        schemas = {}
        for channel in summary.channels.values():
            schema = summary.schemas[channel.schema_id]
            assert (channel.message_encoding, schema.encoding) == ("cdr", "ros2msg"), channel
            schemas[channel.topic] = schema.name
        for _, channel, message, decoded in reader.iter_decoded_messages(log_time_order=True):
            assert message.publish_time == message.log_time
            messages[channel.topic].append((message.log_time, decoded))
    return schemas, dict(messages)


@pytest.fixture(scope="module")
def recorded(tmp_path_factory: pytest.TempPathFactory) -> Recorded:
    world = noisy_world()
    run, recording = record(world, IFGMPlanner())
    path = tmp_path_factory.mktemp("bag") / "run.mcap"
    write_bag(path, world, run, recording, "ft")
    return Recorded(world, recording, run, path, *read_mcap(path))


def record(world: World, planner: Planner) -> tuple[Run, Recording]:
    """Simulate ``planner`` in ``world`` (:data:`SIM`), keeping what it saw and answered."""
    recorder = RecordingPlanner(planner)
    run = simulate(world, recorder, SIM)
    return run, recorder.recording()


def stamp(message: Any) -> int:
    """A header's stamp in ns."""
    return int(message.header.stamp.sec * 10**9 + message.header.stamp.nanosec)


def yaw(orientation: Any) -> float:
    """The heading of a rotation about z."""
    assert (orientation.x, orientation.y) == (0.0, 0.0)
    return 2.0 * math.atan2(orientation.z, orientation.w)


def assert_pose(message_pose: Any, pose: Pose, scale: float) -> None:
    """A geometry_msgs/Pose is ``pose`` with its lengths times ``scale``."""
    position = message_pose.position
    assert (position.x, position.y, position.z) == pytest.approx(
        (pose.x * scale, pose.y * scale, 0.0), abs=1e-12
    )
    assert math.remainder(yaw(message_pose.orientation) - pose.theta, math.tau) == pytest.approx(
        0.0, abs=1e-12
    )


def test_every_topic_has_its_standard_message_type(recorded: Recorded) -> None:
    assert recorded.schemas == TOPICS
    assert set(recorded.messages) == set(TOPICS)


def test_message_counts_one_scan_per_observation_one_pose_per_sample(
    recorded: Recorded,
) -> None:
    steps, samples = len(recorded.recording.steps), len(recorded.run.trace)
    assert (steps, samples) == (250, 251)  # the time limit: no observation at the last sample
    counts = {topic: len(items) for topic, items in recorded.messages.items()}
    assert counts == {
        **dict.fromkeys(ONCE, 1),
        "/scan": steps,
        "/cmd_vel": steps,
        "/ifgm_ref/branch": steps,
        "/ifgm_ref/behaviour": steps,
        "/tf": samples,
        "/odom": samples,
        "/ground_truth": samples,
    }


def test_stamps_are_the_step_times_in_the_bag_and_the_headers(recorded: Recorded) -> None:
    times = [round(sample.t * 1e9) for sample in recorded.run.trace]
    assert times[0] == 0
    for topic in ("/odom", "/ground_truth", "/scan", "/cmd_vel"):
        logged = [t for t, _ in recorded.messages[topic]]
        assert logged == times[: len(logged)], topic
    for topic in ("/odom", "/ground_truth", "/scan", "/goal_pose"):
        assert all(stamp(m) == t for t, m in recorded.messages[topic]), topic
    for topic in ("/tf", "/tf_static"):
        assert all(stamp(m.transforms[0]) == t for t, m in recorded.messages[topic]), topic
    assert all(t == 0 for topic in ONCE for t, _ in recorded.messages[topic])


def test_scan_is_the_observation_in_metres_float32(recorded: Recorded) -> None:
    steps = recorded.recording.steps
    seen = [k for k, (told, _) in enumerate(steps) if np.isfinite(told.scan.ranges).any()]
    assert 0 < len(seen) < len(steps)
    for k in (0, seen[0], seen[-1]):
        observation: Observation = steps[k][0]
        _, scan = recorded.messages["/scan"][k]
        expected = (observation.scan.ranges * FT).astype(np.float32)
        assert np.array_equal(np.asarray(scan.ranges, dtype=np.float32), expected, equal_nan=True)
        assert np.isinf(expected).any()  # no return stays +inf
        assert scan.header.frame_id == "base_link"
        assert scan.range_max == pytest.approx(observation.scan.range_max * FT, rel=1e-7)
        assert scan.range_min == pytest.approx(observation.scan.range_min * FT, rel=1e-7)
        assert scan.angle_min == pytest.approx(observation.scan.angle_min, rel=1e-7)
        assert scan.angle_max == pytest.approx(observation.scan.angle_max, rel=1e-7)
        assert scan.angle_increment == pytest.approx(observation.scan.angle_increment, rel=1e-7)
        assert (scan.scan_time, scan.time_increment) == (pytest.approx(SIM.dt), 0.0)


def test_odom_is_the_believed_pose_ground_truth_the_true_one(recorded: Recorded) -> None:
    trace = recorded.run.trace
    odom, truth, tf = (recorded.messages[t] for t in ("/odom", "/ground_truth", "/tf"))
    for sample, (_, believed), (_, true), (_, transforms) in zip(
        trace, odom, truth, tf, strict=True
    ):
        assert (believed.header.frame_id, believed.child_frame_id) == ("odom", "base_link")
        assert (true.header.frame_id, true.child_frame_id) == ("map", "base_link")
        assert sample.believed_x is not None
        assert sample.believed_y is not None
        assert sample.believed_theta is not None
        told = Pose(sample.believed_x, sample.believed_y, sample.believed_theta)
        assert_pose(believed.pose.pose, told, FT)
        assert_pose(true.pose.pose, Pose(sample.x, sample.y, sample.theta), FT)
        (transform,) = transforms.transforms
        assert (transform.header.frame_id, transform.child_frame_id) == ("odom", "base_link")
        moved = transform.transform.translation
        assert (moved.x, moved.y) == (believed.pose.pose.position.x, believed.pose.pose.position.y)
    drift = max(
        math.dist(
            (b.pose.pose.position.x, b.pose.pose.position.y),
            (t.pose.pose.position.x, t.pose.pose.position.y),
        )
        for (_, b), (_, t) in zip(odom, truth, strict=True)
    )
    assert drift > 0.01  # metres: under odometry noise the two poses part


def test_map_to_odom_is_a_static_identity(recorded: Recorded) -> None:
    ((_, static),) = recorded.messages["/tf_static"]
    (transform,) = static.transforms
    assert (transform.header.frame_id, transform.child_frame_id) == ("map", "odom")
    moved, turned = transform.transform.translation, transform.transform.rotation
    assert (moved.x, moved.y, moved.z) == (0.0, 0.0, 0.0)
    assert (turned.x, turned.y, turned.z, turned.w) == (0.0, 0.0, 0.0, 1.0)


def test_cmd_vel_and_odom_twist_are_the_commands_twist(recorded: Recorded) -> None:
    params = recorded.recording.params
    odom = recorded.messages["/odom"]
    for (observation, command), (_, twist), (_, believed) in zip(
        recorded.recording.steps, recorded.messages["/cmd_vel"], odom, strict=False
    ):
        linear, angular = command.twist(observation.pose, params)
        assert (twist.linear.x, twist.linear.y, twist.linear.z) == (linear * FT, 0.0, 0.0)
        assert (twist.angular.x, twist.angular.y, twist.angular.z) == (0.0, 0.0, angular)
        assert believed.twist.twist.linear.x == twist.linear.x
        assert believed.twist.twist.angular.z == twist.angular.z
    assert any(twist.angular.z != 0.0 for _, twist in recorded.messages["/cmd_vel"])
    _, last = odom[-1]
    assert (last.twist.twist.linear.x, last.twist.twist.angular.z) == (0.0, 0.0)


def test_branch_and_behaviour_are_the_traces(recorded: Recorded) -> None:
    trace = recorded.run.trace[:-1]
    branches = [m.data for _, m in recorded.messages["/ifgm_ref/branch"]]
    behaviours = [m.data for _, m in recorded.messages["/ifgm_ref/behaviour"]]
    assert branches == [sample.branch or "" for sample in trace]
    assert behaviours == [sample.behaviour or "" for sample in trace]
    assert all(branches) and all(behaviours)  # IFGM names both at every step
    assert {"move_to_goal", "case1_gap", "follow_edge"} <= set(branches)


def test_goal_and_obstacles_are_in_map_in_metres(recorded: Recorded) -> None:
    world = recorded.world
    ((_, goal),) = recorded.messages["/goal_pose"]
    assert goal.header.frame_id == "map"
    assert_pose(goal.pose, Pose(world.goal.x, world.goal.y, 0.0), FT)
    ((_, markers),) = recorded.messages["/obstacles"]
    assert [m.id for m in markers.markers] == list(range(len(world.obstacles)))
    for marker, obstacle in zip(markers.markers, world.obstacles, strict=True):
        assert (marker.header.frame_id, marker.ns, marker.action) == ("map", "obstacles", 0)
        assert marker.color.a == 1.0
        if isinstance(obstacle, Circle):
            assert marker.type == 3  # CYLINDER
            centre = marker.pose.position
            assert (centre.x, centre.y) == pytest.approx(
                (obstacle.center[0] * FT, obstacle.center[1] * FT)
            )
            assert marker.scale.x == marker.scale.y == pytest.approx(2 * obstacle.radius * FT)
            assert marker.scale.z > 0.0
        else:
            assert marker.type == 4  # LINE_STRIP, closed
            ring = np.array([(p.x, p.y) for p in marker.points])
            expected = np.array([*obstacle.vertices, obstacle.vertices[0]]) * FT
            assert np.allclose(ring, expected, rtol=1e-12, atol=0.0)
    assert {m.type for m in markers.markers} == {3, 4}


def test_episode_topic_restores_the_reset(recorded: Recorded) -> None:
    ((_, message),) = recorded.messages["/ifgm_ref/episode"]
    episode = json.loads(message.data)
    reset = recorded.recording
    assert episode == {
        "format": "ifgm-ref episode 1",
        "planner": "ifgm",
        "world": "wall_posts",
        "length_unit": "ft",
        "metres_per_unit": FT,
        "reset": json.loads(json.dumps(reset_message(reset.start, reset.goal, reset.params))),
    }
    assert episode["reset"]["robot"]["odometry_drift"] == 0.05  # feet, as the project's


def test_recording_twice_gives_the_same_bytes(recorded: Recorded, tmp_path: Path) -> None:
    run, again = record(recorded.world, IFGMPlanner())
    write_bag(tmp_path / "run.mcap", recorded.world, run, again, "ft")  # same name
    assert (tmp_path / "run.mcap").read_bytes() == recorded.path.read_bytes()


def test_recording_leaves_the_run_unchanged(recorded: Recorded) -> None:
    plain = simulate(recorded.world, IFGMPlanner(), SIM)
    assert plain.result == recorded.run.result
    assert plain.trace == recorded.run.trace


class StopsAtStepFive(IFGMPlanner):
    """IFGM that ends the episode itself at its sixth step (``goal_unreachable``)."""

    def step(self, observation: Observation) -> Command:
        command = super().step(observation)
        if observation.t >= 0.5:
            return Command(command.heading, 0.0, stop="goal_unreachable")
        return command


def test_a_planners_stop_records_its_last_scan_but_no_command(tmp_path: Path) -> None:
    world = resolve_world("post")
    run, recording = record(world, StopsAtStepFive())
    assert (run.result.stop_reason, len(recording.steps), len(run.trace)) == (
        "goal_unreachable",
        6,
        6,
    )
    write_bag(tmp_path / "stop.mcap", world, run, recording, "ft")
    _, messages = read_mcap(tmp_path / "stop.mcap")
    counts = {topic: len(messages[topic]) for topic in ("/scan", "/odom", "/cmd_vel")}
    assert counts == {"/scan": 6, "/odom": 6, "/cmd_vel": 5}


@pytest.mark.parametrize("name", ["x.mcap", "folder"])
def test_a_recording_of_another_run_is_refused_and_nothing_written(
    recorded: Recorded, tmp_path: Path, name: str
) -> None:
    other = RecordingPlanner(IFGMPlanner())
    simulate(recorded.world, other, SimParams(max_time=1.0))
    with pytest.raises(ValueError, match="the recording holds 10 steps, but should hold 250"):
        write_bag(tmp_path / name, recorded.world, recorded.run, other.recording(), "ft")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("name", ["run.bag", "folder"])
def test_ros1_bag_and_sqlite3_folder_read_back_with_rosbags(
    recorded: Recorded, tmp_path: Path, name: str
) -> None:
    paths = [tmp_path / "one" / name, tmp_path / "two" / name]
    for path in paths:
        path.parent.mkdir()
        write_bag(path, recorded.world, recorded.run, recorded.recording, "ft")
    with AnyReader([paths[0]]) as reader:
        assert reader.is2 == (name == "folder")
        connections = {c.topic: c for c in reader.connections}
        assert {t: c.msgtype for t, c in connections.items()} == TOPICS
        assert {t: c.msgcount for t, c in connections.items()} == {
            t: len(items) for t, items in recorded.messages.items()
        }
        if not reader.is2:  # the topics published once are latched in ROS 1
            assert {t for t, c in connections.items() if c.ext.latching} == set(ONCE)  # type: ignore[union-attr]
        scans = [
            reader.deserialize(data, c.msgtype).ranges
            for c, _, data in reader.messages(connections=[connections["/scan"]])
        ]
    expected = [np.asarray(m.ranges, dtype=np.float32) for _, m in recorded.messages["/scan"]]
    assert len(scans) == len(expected)
    assert all(np.array_equal(a, b) for a, b in zip(scans, expected, strict=True))
    files = [sorted(p.rglob("*")) if p.is_dir() else [p] for p in paths]
    assert [f.read_bytes() for f in files[0]] == [f.read_bytes() for f in files[1]]


def cli(*args: str) -> list[str]:
    return ["simulate", "post", "--planner", "ifgm", "--max-time", "3", *args]


def test_cli_record_writes_the_bag_and_prints_the_same_result(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(cli()) == 0
    plain = capsys.readouterr().out
    path = tmp_path / "runs" / "post.mcap"
    assert main(cli("--record", str(path))) == 0
    assert capsys.readouterr().out == plain
    schemas, messages = read_mcap(path)
    assert schemas == TOPICS
    assert len(messages["/scan"]) == 30


@pytest.mark.parametrize(
    ("name", "message"),
    [
        ("run.txt", "cannot write .txt; use FILE.mcap (ROS 2, MCAP), FILE.bag (ROS 1) or FOLDER"),
        ("exists", "the folder exists, and a rosbag2 folder is written new"),
    ],
)
def test_cli_record_refuses_a_path_before_the_run(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str, message: str
) -> None:
    (tmp_path / "exists").mkdir()
    path = tmp_path / name
    assert main(cli("--record", str(path))) == 2
    out, err = capsys.readouterr()
    assert out == ""  # no result line: nothing ran
    assert err.count("\n") == 1
    assert err.startswith(f"ifgm-ref: error: --record {path}: {message}")
    assert not path.exists() or path.is_dir()
