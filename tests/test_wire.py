"""The JSON-lines codec (``ifgm_ref.io.transport.wire``): exact round trips and clear rejections."""

from __future__ import annotations

import json
import math
import struct
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import ProtocolError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Behaviour, Command, EpisodeParams, Observation
from ifgm_ref.io.transport.wire import (
    QUOTE_LIMIT,
    MessageType,
    Reset,
    bye_message,
    command_message,
    decode,
    encode,
    message_type,
    observe_message,
    parse_bye,
    parse_command,
    parse_observe,
    parse_ready,
    parse_reset,
    ready_message,
    reset_message,
)

# --- strategies ---------------------------------------------------------------------------------

finite = st.floats(allow_nan=False, allow_infinity=False)
positive = st.floats(min_value=1e-6, max_value=1e6, allow_nan=False, allow_infinity=False)
texts = st.text(max_size=12)
json_values = st.recursive(
    st.none() | st.booleans() | st.integers(-(10**6), 10**6) | finite | texts,
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(texts, inner, max_size=3),
    max_leaves=8,
)
poses = st.builds(Pose, finite, finite, finite)
points = st.builds(Point, finite, finite)


@st.composite
def sensors(draw: st.DrawFn) -> SensorParams:
    range_min = draw(st.floats(min_value=0.0, max_value=10.0))
    return SensorParams(
        fov=draw(st.floats(min_value=1e-3, max_value=6.28)),
        rays=draw(st.integers(2, 400)),
        range_min=range_min,
        range_max=draw(st.floats(min_value=range_min + 1e-3, max_value=1e4)),
        noise_std=draw(st.floats(min_value=0.0, max_value=10.0)),
        seed=draw(st.integers(0, 2**32)),
    )


episodes = st.builds(
    EpisodeParams,
    robot=st.builds(RobotParams, radius=positive, speed=positive, max_turn_rate=positive),
    sensor=sensors(),
    dt=positive,
    params=st.dictionaries(texts, json_values, max_size=4),
    goal_tolerance=positive,
)


@st.composite
def scans(draw: st.DrawFn, *, ranges: st.SearchStrategy[float] | None = None) -> LaserScan:
    count = draw(st.integers(2, 80))
    angle_min = draw(st.floats(-4.0, 0.0))
    increment = draw(st.floats(1e-4, 0.2))
    values = ranges if ranges is not None else st.floats(0.0, 1e3) | st.just(math.inf)
    return LaserScan(
        angle_min=angle_min,
        angle_max=angle_min + increment * (count - 1),
        angle_increment=increment,
        range_min=draw(st.floats(0.0, 1.0)),
        range_max=draw(st.floats(1.0, 1e3)),
        ranges=np.array(draw(st.lists(values, min_size=count, max_size=count))),
    )


observations = st.builds(Observation, t=finite, pose=poses, goal=points, scan=scans())
optional_texts = st.none() | texts | st.sampled_from(Behaviour)
commands = st.builds(
    Command,
    heading=finite,
    speed=finite,
    behaviour=optional_texts,
    branch=optional_texts,
    stop=optional_texts,
)


def through_the_wire(message: dict[str, Any]) -> dict[str, Any]:
    """What the other side reads: one line, decoded."""
    line = encode(message)
    assert "\n" not in line
    return decode(line + "\n")


def bits(values: tuple[float, ...]) -> bytes:
    """The exact IEEE 754 representation, so that 0.0 and -0.0 differ."""
    return struct.pack(f"<{len(values)}d", *values)


# --- round trips --------------------------------------------------------------------------------


@given(start=poses, goal=points, params=episodes)
def test_reset_round_trips_exactly(start: Pose, goal: Point, params: EpisodeParams) -> None:
    reset = parse_reset(through_the_wire(reset_message(start, goal, params)))
    assert reset == Reset(start, goal, params)
    assert bits(reset.start) == bits(start) and bits(reset.goal) == bits(goal)
    assert bits((reset.params.dt, reset.params.robot.speed)) == bits(
        (params.dt, params.robot.speed)
    )


@given(params=episodes)
def test_reset_sends_the_scan_angles(params: EpisodeParams) -> None:
    sensor = reset_message(Pose(0.0, 0.0, 0.0), Point(1.0, 1.0), params)["sensor"]
    assert sensor["angle_min"] == -params.sensor.fov / 2
    assert sensor["angle_max"] == params.sensor.fov / 2
    assert sensor["angle_increment"] == params.sensor.fov / (params.sensor.rays - 1)
    assert sensor["rays"] == params.sensor.rays and isinstance(sensor["rays"], int)


@given(observation=observations)
def test_observe_round_trips_exactly(observation: Observation) -> None:
    back = parse_observe(through_the_wire(observe_message(observation)))
    assert back == observation
    assert bits((back.t, *back.pose, *back.goal)) == bits(
        (observation.t, *observation.pose, *observation.goal)
    )
    assert back.scan.ranges.tobytes() == observation.scan.ranges.tobytes()


@given(command=commands)
def test_command_round_trips_exactly(command: Command) -> None:
    back = parse_command(through_the_wire(command_message(command)))
    assert back == command
    assert bits((back.heading, back.speed)) == bits((command.heading, command.speed))
    assert all(type(v) is str for v in (back.behaviour, back.branch, back.stop) if v is not None)


def test_ready_and_bye_round_trip() -> None:
    parse_ready(through_the_wire(ready_message()))
    parse_bye(through_the_wire(bye_message()))
    assert message_type(through_the_wire(bye_message())) is MessageType.BYE


def test_ranges_json_cannot_carry_become_null_or_zero() -> None:
    """REP 117 readings: +inf (no return) and nan travel as null, -inf as 0.0."""
    scan = LaserScan(-0.5, 0.5, 0.5, 0.1, 15.0, [math.inf, math.nan, -math.inf])
    message = observe_message(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(1.0, 0.0), scan))
    line = encode(message)
    assert '"ranges": [null, null, 0.0]' in line
    assert parse_observe(decode(line)).scan.ranges.tolist() == [math.inf, math.inf, 0.0]


# --- rejections ---------------------------------------------------------------------------------


@pytest.mark.parametrize("constant", ["NaN", "Infinity", "-Infinity"])
def test_decode_rejects_non_standard_constants(constant: str) -> None:
    line = f'{{"type": "command", "heading": {constant}, "speed": 1.0}}'
    with pytest.raises(ProtocolError, match=f"line contains {constant}: ") as info:
        decode(line)
    assert repr(line) in str(info.value)


@pytest.mark.parametrize(
    ("line", "message"),
    [
        ("hello", "reply is not JSON: 'hello' (Expecting value at column 1)"),
        ('{"type": "ready"', 'reply is not JSON: \'{"type": "ready"\''),
        ("", "reply is not JSON: ''"),
        ("[1, 2]", "reply is not a JSON object: '[1, 2]'"),
        ('"ready"', "reply is not a JSON object: '\"ready\"'"),
    ],
)
def test_decode_rejects_what_is_not_one_object(line: str, message: str) -> None:
    with pytest.raises(ProtocolError) as info:
        decode(line, what="reply")
    assert message in str(info.value)


def test_decode_quotes_a_long_line_shortened() -> None:
    line = '{"type": "command", "heading": 1.0, "speed": NaN, "pad": "' + "x" * 1000 + '"}'
    with pytest.raises(ProtocolError) as info:
        decode(line)
    text = str(info.value)
    assert text.startswith('line contains NaN: \'{"type": "command"')
    assert len(text) < QUOTE_LIMIT + 100 and "(1060 characters)" in text


def test_encode_rejects_nan_and_non_json_values() -> None:
    with pytest.raises(ProtocolError, match="cannot encode message of type 'command' as JSON"):
        encode(command_message(Command(math.nan, 1.0)))
    with pytest.raises(ProtocolError, match="cannot encode message of type 'reset' as JSON"):
        encode(reset_message(Pose(0, 0, 0), Point(1, 1), EpisodeParams(params={"x": object()})))


COMMAND = {"type": "command", "heading": 0.5, "speed": 1.0}
#: A field value that means "leave the field out".
DROP = object()


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"heading": "abc"}, "command.heading: must be a finite number, got 'abc'"),
        ({"heading": True}, "command.heading: must be a finite number, got True"),
        ({"heading": None}, "command.heading: must be a finite number, got None"),
        ({"speed": 1e400}, "command.speed: must be a finite number, got inf"),
        ({"speed": [1.0]}, "command.speed: must be a finite number, got [1.0]"),
        ({"speed": DROP}, "command.speed: missing"),
        ({"behaviour": 3}, "command.behaviour: must be a string or null, got 3"),
        ({"stop": False}, "command.stop: must be a string or null, got False"),
        ({"behavior": "x"}, "command: unknown field(s) 'behavior'; allowed: angular, behaviour"),
        ({"angular": 0.5}, "command: has heading, speed, angular; give heading and speed"),
        ({"heading": DROP, "speed": DROP, "linear": 1.0}, "command.angular: missing"),
        ({"heading": DROP, "speed": DROP, "linear": 1.0, "angular": "x"}, "command.angular: must"),
        ({"type": "ready"}, "type 'ready', but should be 'command'"),
        ({"type": DROP}, "type None, but should be 'command'"),
    ],
)
def test_malformed_command_is_named_field_by_field(change: dict[str, Any], message: str) -> None:
    command = {k: v for k, v in {**COMMAND, **change}.items() if v is not DROP}
    with pytest.raises(ProtocolError) as info:
        parse_command(command, at=(Pose(0.0, 0.0, 0.0), EpisodeParams()))
    assert message in str(info.value)


@given(pose=poses, linear=finite, angular=finite, params=episodes)
def test_a_velocity_command_round_trips_exactly(
    pose: Pose, linear: float, angular: float, params: EpisodeParams
) -> None:
    command = Command.from_twist(linear, angular, pose, params, branch="case1_gap")
    back = parse_command(through_the_wire(command_message(command)), at=(pose, params))
    assert back == command
    assert bits((back.heading, back.speed, back.turn_rate)) == bits(
        (command.heading, command.speed, command.turn_rate)
    )


def test_a_velocity_command_needs_the_pose_it_answers() -> None:
    with pytest.raises(ProtocolError, match="needs the pose it answers"):
        parse_command({"type": "command", "linear": 1.0, "angular": 0.0})


def test_command_optional_fields_may_be_null() -> None:
    assert parse_command({**COMMAND, "behaviour": None, "stop": None}) == Command(0.5, 1.0)


def test_ready_is_strict() -> None:
    with pytest.raises(ProtocolError, match="ready: unknown field"):
        parse_ready({"type": "ready", "name": "mine"})
    with pytest.raises(ProtocolError, match="type 'command', but should be 'ready'"):
        parse_ready(COMMAND)


def _observe() -> dict[str, Any]:
    scan = LaserScan(-0.5, 0.5, 0.5, 0.0, 15.0, [1.0, 2.0, 3.0])
    return observe_message(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(5.0, 0.0), scan))


@pytest.mark.parametrize(
    ("path", "value", "message"),
    [
        (("t",), "0", "observe.t: must be a finite number, got '0'"),
        (("pose",), [0.0, 0.0], "observe.pose: must be an array of 3 numbers, got [0.0, 0.0]"),
        (("goal",), {"x": 1}, "observe.goal: must be an array of 2 numbers"),
        (("pose",), [0.0, "a", 0.0], "observe.pose[1]: must be a finite number, got 'a'"),
        (("scan",), [], "observe.scan: must be an object, got []"),
        (("scan", "ranges"), "1 2 3", "observe.scan.ranges: must be an array, got '1 2 3'"),
        (("scan", "ranges"), [1.0, -1e400, 2.0], "observe.scan.ranges[1]: must be a finite"),
        (("scan", "range_max"), None, "observe.scan.range_max: must be a finite number, got None"),
        (("scan", "angle_max"), 2.0, "observe.scan: angle_max=2.0, but should be angle_min"),
        (("scan", "ranges"), [1.0], "observe.scan: angle_max=0.5, but should be"),
    ],
)
def test_malformed_observe_is_named_field_by_field(
    path: tuple[str, ...], value: object, message: str
) -> None:
    observe = _observe()
    container = observe
    for key in path[:-1]:
        container = container[key]
    container[path[-1]] = value
    with pytest.raises(ProtocolError) as info:
        parse_observe(observe)
    assert message in str(info.value)


def test_observe_ignores_unknown_fields() -> None:
    assert parse_observe({**_observe(), "future": 1}) == parse_observe(_observe())


def _reset() -> dict[str, Any]:
    return reset_message(Pose(0.0, 0.0, 0.0), Point(5.0, 0.0), EpisodeParams())


@pytest.mark.parametrize(
    ("path", "value", "message"),
    [
        (("dt",), 0, "reset.dt: must be a finite number > 0, got 0"),
        (("goal_tolerance",), "x", "reset.goal_tolerance: must be a finite number > 0, got 'x'"),
        (("params",), [], "reset.params: must be an object, got []"),
        (("start",), [0, 0], "reset.start: must be an array of 3 numbers"),
        (("robot",), None, "reset.robot: must be an object, got None"),
        (("robot", "radius"), -1.0, "reset.robot: `radius` must be a finite number > 0, got -1.0"),
        (("sensor", "rays"), 76.0, "reset.sensor: `rays` must be an integer >= 2, got 76.0"),
        (("sensor", "angle_min"), 0.0, "reset.sensor.angle_min: 0.0, but should be -1.178"),
        (("sensor", "angle_increment"), "x", "reset.sensor.angle_increment: must be a finite"),
    ],
)
def test_malformed_reset_is_named_field_by_field(
    path: tuple[str, ...], value: object, message: str
) -> None:
    reset = _reset()
    container = reset
    for key in path[:-1]:
        container = container[key]
    container[path[-1]] = value
    with pytest.raises(ProtocolError) as info:
        parse_reset(reset)
    assert message in str(info.value)


@pytest.mark.parametrize("name", ["robot", "sensor", "dt", "params", "goal_tolerance", "goal"])
def test_reset_without_a_field_says_it_is_missing(name: str) -> None:
    reset = _reset()
    del reset[name]
    with pytest.raises(ProtocolError, match=rf"^reset\.{name}: missing$"):
        parse_reset(reset)


def test_reset_sensor_without_a_field_says_it_is_missing() -> None:
    reset = _reset()
    del reset["sensor"]["seed"]
    with pytest.raises(ProtocolError, match=r"^reset\.sensor\.seed: missing$"):
        parse_reset(reset)


def test_message_type_names_the_known_types() -> None:
    with pytest.raises(ProtocolError, match=r"^message\.type: missing$"):
        message_type({})
    with pytest.raises(ProtocolError, match="should be one of reset, ready, observe, command, bye"):
        message_type({"type": 7})


def test_the_encoded_line_is_plain_json_any_reader_accepts() -> None:
    line = encode(_reset())
    assert json.loads(line) == _reset()
    assert line.isascii()
