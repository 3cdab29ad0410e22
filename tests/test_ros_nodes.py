"""Unchanged ROS 1 nodes under the rospy stand-in (``ifgm_ref.io.ros``, ``docs/ros-nodes.md``).

The message classes against rosbags' definitions, tf's quaternions, graph names and time in
process; then nodes in their own processes (``tests/ros_nodes/``) stepped by a
:class:`~ifgm_ref.io.ros.bridge.RosPlanner`: the ``/cmd_vel`` hold rule, ``/ifgm_ref/stop`` and a
node's end, a crash, services between two nodes, remapping, the goal's delivery; and the
reference IFGM behind a rospy node driving as the reference does, and passing the oracle.
"""

from __future__ import annotations

import dataclasses
import math
import os
import shlex
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from rosbags.typesys import Stores, get_typestore

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.io.bags import messages as bags
from ifgm_ref.io.ros import tf
from ifgm_ref.io.ros.bridge import RosFactory, RosPlanner
from ifgm_ref.io.ros.messages import from_wire, message_class, package_namespace, to_wire
from ifgm_ref.io.ros.names import parse_remap, resolve, split_argv
from ifgm_ref.io.ros.process import SHIMS
from ifgm_ref.io.ros.rostime import Duration, Time
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.oracle.check_types import Level
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.suite.run import run_cases
from ifgm_ref.oracle.suite.versions import load_suite
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.sim.simulator import simulate

NODES = Path(__file__).resolve().parent / "ros_nodes"
BUG2 = NODES / "bug2"
EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "ros" / "ifgm_node.py"
FT = 0.3048
ORIGIN, AHEAD = Pose(0.0, 0.0, 0.0), Point(10.0, 0.0)


def node(path: Path, *args: str) -> str:
    """The command line running the node at ``path`` with ``args``."""
    return shlex.join([sys.executable, str(path), *args])


def probe(mode: str, *args: str) -> str:
    return node(NODES / "probe.py", f"_mode:={mode}", *args)


def free_scan(params: EpisodeParams) -> LaserScan:
    sensor = params.sensor
    return LaserScan(
        -sensor.fov / 2,
        sensor.fov / 2,
        sensor.fov / (sensor.rays - 1),
        sensor.range_min,
        sensor.range_max,
        np.full(sensor.rays, np.inf),
    )


def drive(
    commands: list[str],
    steps: int,
    *,
    start: Pose = ORIGIN,
    goal: Point = AHEAD,
    **options: object,
) -> list[Command]:
    """Step nodes ``steps`` times from ``start`` with a free scan, the robot never moving."""
    params = EpisodeParams()
    with RosPlanner(commands, scale=FT, timeout=20.0, **options) as planner:  # type: ignore[arg-type]
        planner.reset(start, goal, params)
        return [
            planner.step(Observation(round(k * params.dt, 12), start, goal, free_scan(params)))
            for k in range(steps)
        ]


# -- in process ---------------------------------------------------------------------------------


def test_messages_are_default_constructible_and_mutable() -> None:
    Twist, Vector3 = message_class("geometry_msgs/Twist"), message_class("geometry_msgs/Vector3")
    command = Twist()
    assert [command.linear.x, command.linear.y, command.angular.z] == [0.0, 0.0, 0.0]
    command.linear.x = 0.3
    assert command.linear.x == 0.3 and Twist().linear.x == 0.0  # no shared default
    assert Twist(Vector3(1.0, 2.0, 3.0)).linear.y == 2.0
    assert Twist(angular=Vector3(z=0.5)).angular.z == 0.5
    with pytest.raises(TypeError):
        Twist(linar=Vector3())
    scan = message_class("sensor_msgs/LaserScan")()
    assert (scan.ranges, scan.header.frame_id, scan.header.stamp) == ([], "", Time(0, 0))
    assert message_class("nav_msgs/Odometry")().pose.covariance == [0.0] * 36
    assert message_class("visualization_msgs/Marker").CYLINDER == 3
    assert package_namespace("geometry_msgs", "msg")["Twist"] is Twist
    assert message_class("std_srvs/SetBoolResponse")().message == ""


@pytest.mark.parametrize(
    ("ros1", "bag_class"),
    [
        ("sensor_msgs/LaserScan", bags.LaserScanMsg),
        ("nav_msgs/Odometry", bags.Odometry),
        ("geometry_msgs/Twist", bags.Twist),
        ("geometry_msgs/PoseStamped", bags.PoseStamped),
        ("std_msgs/String", bags.String),
        ("std_msgs/Header", bags.Header),
    ],
)
def test_message_fields_are_rosbags_definitions(ros1: str, bag_class: type) -> None:
    """The classes are rosbags' ROS 1 Noetic types, field for field, and those the bags are
    written with (ROS 2 Humble) but for ROS 1's ``Header.seq``."""
    names = [name for name, _ in message_class(ros1)._spec]
    package, base = ros1.split("/")
    store = get_typestore(Stores.ROS1_NOETIC).fielddefs[f"{package}/msg/{base}"]
    assert names == [name for name, _ in store[1]]
    bag_names = [f.name for f in dataclasses.fields(bag_class) if f.name != "__msgtype__"]
    assert [n for n in names if not (ros1 == "std_msgs/Header" and n == "seq")] == bag_names


def test_messages_cross_the_wire_unchanged() -> None:
    odom = message_class("nav_msgs/Odometry")()
    odom.header.stamp = Time(3, 250_000_000)
    odom.pose.pose.position.x, odom.child_frame_id = 1.5, "base_link"
    scan = message_class("sensor_msgs/LaserScan")(ranges=[1.0, math.inf])
    assert from_wire("nav_msgs/Odometry", to_wire(odom)) == odom
    assert from_wire("sensor_msgs/LaserScan", to_wire(scan)) == scan
    with pytest.raises(ValueError, match="unknown message type"):
        message_class("geometry_msgs/Twits")


@pytest.mark.parametrize("angles", [(0.0, 0.0, 1.0), (0.3, -0.4, -2.9), (-1.0, 1.2, math.pi)])
def test_tf_euler_and_quaternion_round_trip(angles: tuple[float, float, float]) -> None:
    q = tf.quaternion_from_euler(*angles)
    assert math.isclose(float(np.dot(q, q)), 1.0)
    back = tf.euler_from_quaternion(q)
    assert all(math.isclose(math.remainder(a - b, 2 * math.pi), 0.0, abs_tol=1e-12)
               for a, b in zip(angles, back, strict=True))  # fmt: skip
    same = tf.quaternion_multiply(q, tf.quaternion_inverse(q))
    assert np.allclose(same, [0.0, 0.0, 0.0, 1.0])


def test_tf_yaw_is_the_bags_quaternion() -> None:
    q = bags.quaternion(2.5)
    assert np.allclose(tf.quaternion_from_euler(0.0, 0.0, 2.5), [q.x, q.y, q.z, q.w])
    with pytest.raises(NotImplementedError):
        tf.quaternion_from_euler(0.0, 0.0, 1.0, axes="rzyx")


def test_the_shims_import_as_a_node_imports_them() -> None:
    code = (
        "from tf import transformations; import tf.transformations, rospy\n"
        "from std_srvs.srv import SetBool, Trigger, Empty\n"
        "from sensor_msgs.msg import LaserScan; from nav_msgs.msg import Odometry\n"
        "from std_msgs.msg import String; from geometry_msgs.msg import Twist\n"
        "print(transformations.euler_from_quaternion([0, 0, 0, 1]), rospy.loginfo_throttle)"
    )
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(SHIMS), str(EXAMPLE.parents[2])])}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("(0.0, 0.0, 0.0)")


def test_graph_names_and_remaps_resolve_as_ros_1() -> None:
    assert resolve("scan", "/bug2") == "/scan"
    assert resolve("~goal_x", "/bug2") == "/bug2/goal_x"
    assert resolve("/scan", "/n", {"/scan": "/base_scan"}) == "/base_scan"
    assert parse_remap("scan:=base_scan") == ("/scan", "/base_scan")
    left, remaps, private, name = split_argv(["n.py", "_wrap:=false", "a:=b", "__name:=x", "-v"])
    assert (left, remaps, private, name) == (["n.py", "-v"], {"/a": "/b"}, {"wrap": False}, "x")


def test_time_is_exact_nanoseconds() -> None:
    t = Time.from_sec(0.1) + Duration.from_sec(0.2)
    assert t.to_nsec() == 300_000_000 and t == Time(0, 300_000_000)
    assert (t - Time(0, 100_000_000)) == Duration.from_sec(0.2)
    assert Duration(1, 500_000_000) * 2 == Duration(3)


# -- nodes in their processes -------------------------------------------------------------------


def test_a_node_s_prints_do_not_disturb_the_broker() -> None:
    """Every probe prints on stdout at its start: the broker's link is another socket."""
    assert drive([probe("silent")], 1)[0].problem() is None


def test_the_last_cmd_vel_at_or_before_the_step_is_executed() -> None:
    """The probe publishes the time at 20 Hz, twice per step: the last one wins."""
    commands = drive([probe("echo")], 5)
    assert [round(c.speed * FT, 9) for c in commands] == [0.0, 0.1, 0.2, 0.3, 0.4]
    assert all(c.turn_rate == 0.0 for c in commands)


def test_no_cmd_vel_stops_the_robot_and_a_stale_one_stops_it_too() -> None:
    assert {(c.speed, c.turn_rate) for c in drive([probe("silent")], 3)} == {(0.0, 0.0)}
    held = [round(c.speed * FT, 9) for c in drive([probe("stale")], 8)]
    assert held == [0.2] * 6 + [0.0] * 2  # published at 0 s, held 0.5 s, stale at 0.6 s


@pytest.mark.parametrize(
    ("commands", "stop"),
    [
        ([probe("stop", "_reason:=goal_unreachable")], "goal_unreachable"),
        ([probe("shutdown")], "done"),
        ([probe("exit")], "done"),
    ],
)
def test_a_node_ends_its_episode(commands: list[str], stop: str) -> None:
    command = drive(commands, 2)[0]
    assert command.stop == stop and command.problem() is None


def test_a_stop_that_is_no_planner_stop_is_an_invalid_command() -> None:
    command = drive([probe("stop", "_reason:=goal_reached")], 1)[0]
    assert command.stop == "goal_reached"
    assert "only the robot's true position decides an arrival" in (command.problem() or "")


def test_a_crash_is_reported_with_the_node_s_traceback() -> None:
    with pytest.raises(ImplementationError, match="exited with status 1") as info:
        drive([probe("crash")], 2)
    assert "the probe crashes on purpose" in str(info.value)


def test_services_between_two_node_processes() -> None:
    commands = drive([node(NODES / "switch_server.py"), node(NODES / "switch_client.py")], 3)
    assert round(commands[-1].speed * FT, 9) == 0.1


@pytest.mark.parametrize(
    ("args", "remaps"),
    [
        ((), ("/base_scan:=/scan", "/robot/cmd_vel:=/cmd_vel")),
        (("base_scan:=scan",), ("robot/cmd_vel:=cmd_vel",)),
    ],
)
def test_remapping_on_the_command_line_and_in_node_arguments(
    args: tuple[str, ...], remaps: tuple[str, ...]
) -> None:
    commands = drive([probe("remap", *args)], 2, remaps=remaps)
    assert round(commands[0].speed * FT, 9) == 0.1


@pytest.mark.parametrize(("args", "topic"), [((), None), (("_topic:=/goal",), "/goal")])
def test_the_goal_is_in_the_parameters_and_on_the_goal_topic(
    args: tuple[str, ...], topic: str | None
) -> None:
    options = {} if topic is None else {"goal_topic": topic}
    commands = drive([probe("goal", *args)], 2, goal=Point(10.0, 2.0), **options)
    assert round(commands[0].speed * FT, 9) == 0.1


def test_each_episode_starts_the_nodes_afresh_and_runs_alike() -> None:
    params, start, goal = EpisodeParams(), ORIGIN, AHEAD
    with RosPlanner([probe("echo")], scale=FT) as planner:
        runs = []
        for _ in range(2):
            planner.reset(start, goal, params)
            steps = [Observation(k / 10, start, goal, free_scan(params)) for k in range(3)]
            runs.append([planner.step(o).speed for o in steps])
    assert runs[0] == runs[1] and runs[0][0] == 0.0


def test_simulate_and_oracle_take_ros_nodes_on_the_command_line(tmp_path: Path) -> None:
    ifgm_ref = [sys.executable, "-m", "ifgm_ref"]
    simulate_nodes = [*ifgm_ref, "simulate", "free", "--ros-node", probe("echo"), "--json"]
    done = subprocess.run([*simulate_nodes, "--max-time", "2"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert '"stop_reason": "time_limit"' in done.stdout and "probe: a print" in done.stderr
    both = subprocess.run([*simulate_nodes, "--planner", "ifgm"], capture_output=True, text=True)
    assert both.returncode == 2 and "exactly one of --planner" in both.stderr
    oracle = [*ifgm_ref, "oracle", "--ros-node", probe("crash"), "--artifacts", str(tmp_path)]
    checked = [*oracle, "--check", "converges_open", "--profile", "brief"]
    crashed = subprocess.run(checked, capture_output=True, text=True)
    assert crashed.returncode == 1 and "the probe crashes on purpose" in crashed.stdout


def test_a_counterexample_of_ros_nodes_replays_them(tmp_path: Path) -> None:
    """The report's replay command runs the same nodes with the same ROS options (it said
    ``--planner ros: ...`` before, which ``simulate`` refuses), and meets the same collision."""
    straight, options = node(NODES / "straight.py"), ["--remap", "/a:=/b", "--ros-goal-topic", "/g"]
    args = ["oracle", "--ros-node", straight, *options]
    args += ["--check", "collision_free", "--profile", "brief", "--artifacts", str(tmp_path)]
    command = [sys.executable, "-m", "ifgm_ref", *args]
    failed = subprocess.run(command, capture_output=True, text=True)
    assert failed.returncode == 1 and "FAILED" in failed.stdout, failed.stdout + failed.stderr
    (report,) = tmp_path.rglob("report.md")
    (replay,) = [line.strip() for line in report.read_text().splitlines() if "simulate" in line]
    assert f"--ros-node {shlex.quote(straight)} --remap /a:=/b --ros-goal-topic /g" in replay
    command = [sys.executable, "-m", "ifgm_ref", *shlex.split(replay)[1:], "--json"]
    replayed = subprocess.run(command, capture_output=True, text=True)
    assert '"stop_reason": "collision"' in replayed.stdout, replayed.stdout + replayed.stderr


# -- ROS 2: rclpy nodes over the same broker ----------------------------------------------------


def test_ros2_messages_are_humble_s() -> None:
    header = message_class("std_msgs/Header", "ros2")()
    assert [name for name, _ in header._spec] == ["stamp", "frame_id"]
    assert (header.stamp.sec, header.stamp.nanosec) == (0, 0)
    set_bool = package_namespace("std_srvs", "srv", "ros2")["SetBool"]
    assert set_bool.Request(True).data and set_bool.Response().message == ""


def test_an_rclpy_node_drives_as_its_rospy_twin() -> None:
    world = resolve_world("free")
    runs = []
    for distro, path in (("ros1", "straight.py"), ("ros2", "ros2_straight.py")):
        with RosPlanner([node(NODES / path)], scale=FT, distro=distro) as planner:
            runs.append(simulate(world, planner, progress=None).result)
    assert [r.stop_reason for r in runs] == ["goal_reached"] * 2
    assert math.isclose(runs[0].path_length, runs[1].path_length, rel_tol=1e-9)


def test_rclpy_services_parameters_and_futures_between_two_processes() -> None:
    server, client = (
        node(NODES / "ros2_switch.py", "--ros-args", "-p", f"role:={role}")
        for role in ("server", "client")
    )
    commands = drive([server, client], 3, distro="ros2")
    assert round(commands[-1].speed * FT, 9) == 0.1


# -- real nodes: the reference IFGM behind rospy, and a course-style Bug2 -----------------------

BUG2_NODES = [node(BUG2 / "bug2.py"), node(BUG2 / "go_to_point.py"), node(BUG2 / "follow_wall.py")]
UNWRAPPED = [BUG2_NODES[0], node(BUG2 / "go_to_point.py", "_wrap_heading:=false"), BUG2_NODES[2]]


def test_ifgm_node_drives_as_the_reference_does() -> None:
    """The stand-in bends nothing: scan, pose and command timing as the in-process planner's,
    so the same path, but for the rounding of the ranges to float32, as ROS sends them, and of
    the lengths to metres (measured: 0.0009 ft apart at most, headings 0.007 rad)."""
    world = resolve_world("u_trap")
    inside = simulate(world, IFGMPlanner(), progress=None)
    with RosPlanner([node(EXAMPLE)], scale=FT) as planner:
        outside = simulate(world, planner, progress=None)
    assert outside.result.stop_reason == inside.result.stop_reason == "goal_reached"
    assert len(outside.trace) == len(inside.trace)
    for a, b in zip(outside.trace, inside.trace, strict=True):
        assert math.hypot(a.x - b.x, a.y - b.y) < 0.01


@pytest.mark.parametrize(("nodes", "sign"), [(BUG2_NODES, 1.0), (UNWRAPPED, -1.0)])
def test_bug2_turns_the_short_way_only_with_the_heading_error_wrapped(
    nodes: list[str], sign: float
) -> None:
    """Heading 3.0 rad, the goal at -3.09 rad: 0.19 rad to the left, or 6.09 to the right."""
    commands = drive(nodes, 4, start=Pose(0.0, 0.0, 3.0), goal=Point(-20.0, -1.0))
    turning = [c.turn_rate for c in commands if c.turn_rate]
    assert turning and math.copysign(1.0, turning[0]) == sign


def test_ifgm_node_passes_the_suite_quick_tier() -> None:
    """Every paper-level case of the frozen suite's quick tier (one or two of each property,
    about 6 s; the drawn quick profile: the slow test). A node that only publishes Twist
    reports no branch, so the dead-end check meets nothing to check: not exercised."""
    impl = Implementation(
        RosFactory([node(EXAMPLE)], scale=FT), "ros: ifgm_node", promises_of("ifgm")
    )
    cases = [c for c in load_suite("v1").tier("quick") if CHECKS[c.check].level is Level.PAPER]
    try:
        results = list(run_cases(cases, impl))
    finally:
        impl.close()
    others = {r.case.check: (r.verdict, r.reason) for r in results if r.verdict != "pass"}
    assert set(others) == {"reports_unreachable", "dead_end_turns"}, others
    assert {verdict for verdict, _ in others.values()} == {"skip"}
    assert others["dead_end_turns"][1].startswith("not exercised")


@pytest.mark.slow
def test_ifgm_node_passes_the_oracle_quick_profile(tmp_path: Path) -> None:
    """``ifgm-ref oracle --ros-node "python3 examples/ros/ifgm_node.py" --profile quick``:
    8 min 41 s on 2 busy cores (docs/ros-nodes.md), hence slow."""
    done = subprocess.run(
        [sys.executable, "-m", "ifgm_ref", "oracle", "--ros-node", node(EXAMPLE),
         "--profile", "quick", "--artifacts", str(tmp_path)],
        capture_output=True, text=True,
    )  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.mark.slow
@pytest.mark.parametrize(("nodes", "status"), [(BUG2_NODES, 0), (UNWRAPPED, 1)])
def test_the_oracle_tells_the_unwrapped_heading_error_apart(
    nodes: list[str], status: int, tmp_path: Path
) -> None:
    """rigid_motion_invariant on the brief profile: about 2 min 20 s each."""
    args = [arg for command in nodes for arg in ("--ros-node", command)]
    done = subprocess.run(
        [sys.executable, "-m", "ifgm_ref", "oracle", *args, "--promises", "bug2",
         "--check", "rigid_motion_invariant", "--profile", "brief", "--artifacts", str(tmp_path)],
        capture_output=True, text=True,
    )  # fmt: skip
    assert done.returncode == status, done.stdout + done.stderr
