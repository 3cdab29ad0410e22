"""The JSON-lines planner protocol: planner messages as single lines of JSON, and back.

The oracle checks planners written in any language through a process boundary: it starts the
program once and talks to it over its stdin and stdout, one JSON object per line
(``docs/oracle-protocol.md`` is the full specification). This module is the codec between
those lines and the protocol's dataclasses (:mod:`ifgm_ref.core.protocol`):

===========  =================  ===========================================  =====================
message      direction          built by                                     parsed by
===========  =================  ===========================================  =====================
``reset``    oracle -> program  :func:`reset_message` (start, goal, params)  :func:`parse_reset`
``ready``    program -> oracle  :func:`ready_message`                        :func:`parse_ready`
``observe``  oracle -> program  :func:`observe_message` (Observation)        :func:`parse_observe`
``command``  program -> oracle  :func:`command_message` (Command)            :func:`parse_command`
``bye``      oracle -> program  :func:`bye_message`                          :func:`parse_bye`
===========  =================  ===========================================  =====================

:func:`encode` writes a message as one line, :func:`decode` reads one back. Floats are written
with ``repr`` and read with ``float``, which round-trip exactly: a planner stepped through the
wire sees bit-for-bit the numbers it would see in process. The exceptions are the scan's
non-finite ranges, which JSON cannot carry (REP 117 readings, :meth:`LaserScan.to_message`):
``+inf`` (no return) and ``nan`` (sensor error) travel as ``null`` and read back as ``+inf``;
``-inf`` (nearer than ``range_min``) travels as ``0.0``.

Parsing validates every field and names it in its :class:`~ifgm_ref.core.errors.ProtocolError`
(``command.heading: must be a finite number, got 'abc'``). The replies a program writes
(``ready``, ``command``) are read strictly: an unknown field is an error, so that a misspelt
optional field (``"behavior"``) is reported rather than silently dropped. The oracle's own
messages (``reset``, ``observe``, ``bye``) are read leniently: unknown fields are ignored, as
the specification asks of every program.

Units: feet, seconds, radians.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, fields
from enum import StrEnum
from typing import Any, NoReturn, TypeVar

from ifgm_ref.core.errors import ParameterError, ProtocolError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.validate import POSITIVE, REAL, Domain, violation

__all__ = [
    "PROTOCOL_VERSION",
    "QUOTE_LIMIT",
    "MessageType",
    "Reset",
    "bye_message",
    "command_message",
    "decode",
    "encode",
    "message_type",
    "observe_message",
    "parse_bye",
    "parse_command",
    "parse_observe",
    "parse_ready",
    "parse_reset",
    "quote",
    "ready_message",
    "reset_message",
]

#: The protocol's version (docs/oracle-protocol.md): raised whenever a message or a field
#: changes meaning or disappears; a suite's case files say which version they were written for.
PROTOCOL_VERSION = 1
#: Longest piece of an offending line quoted in an error message, characters: enough to see
#: the type and the first fields of a message, short enough for one terminal line or two.
QUOTE_LIMIT = 200
#: The derived scan angles sent in ``reset.sensor`` must match the sensor's fields to this,
#: radians (they are computed from them; the slack only absorbs another language's rounding).
ANGLE_TOLERANCE = 1e-9


class MessageType(StrEnum):
    """The ``type`` of every protocol message."""

    RESET = "reset"
    READY = "ready"
    OBSERVE = "observe"
    COMMAND = "command"
    BYE = "bye"


@dataclass(frozen=True)
class Reset:
    """The content of a ``reset`` message: what :meth:`Planner.reset` is called with."""

    start: Pose
    goal: Point
    params: EpisodeParams


_SENSOR_ANGLES = ("angle_min", "angle_max", "angle_increment")
_SCAN_NUMBERS = ("angle_min", "angle_max", "angle_increment", "range_min", "range_max")
_COMMAND_FIELDS = frozenset(
    {"type", "heading", "speed", "linear", "angular", "behaviour", "branch", "stop"}
)
#: The two forms of a ``command``: a heading and a speed, or a twist (linear and angular).
_COMMAND_FORMS = (("heading", "speed"), ("linear", "angular"))
_BlockT = TypeVar("_BlockT", RobotParams, SensorParams)


# --- building ---------------------------------------------------------------------------------


def reset_message(start: Pose, goal: Point, params: EpisodeParams) -> dict[str, Any]:
    """Build the ``reset`` message that starts an episode.

    ``sensor`` carries the :class:`SensorParams` fields and the angles of the scans that will
    follow (``angle_min = -fov / 2``, ``angle_max = +fov / 2``, ``angle_increment``); ``robot``
    and ``sensor`` carry the noise fields and seeds too (``docs/noise.md``).

    Examples
    --------
    >>> message = reset_message(Pose(0.0, 0.0, 0.0), Point(10.0, 0.0), EpisodeParams())
    >>> message["type"], message["start"], message["goal"], message["dt"]
    ('reset', [0.0, 0.0, 0.0], [10.0, 0.0], 0.1)
    >>> sorted(message["sensor"])  # doctest: +NORMALIZE_WHITESPACE
    ['angle_increment', 'angle_max', 'angle_min', 'dropout', 'fov', 'noise_rel', 'noise_std',
     'range_max', 'range_min', 'rays', 'seed', 'spurious']
    """
    sensor = params.sensor
    return {
        "type": MessageType.RESET.value,
        "start": [float(start[0]), float(start[1]), float(start[2])],
        "goal": [float(goal[0]), float(goal[1])],
        "robot": params.robot.to_mapping(),
        "sensor": {
            **sensor.to_mapping(),
            "angle_min": -0.5 * sensor.fov,
            "angle_max": 0.5 * sensor.fov,
            "angle_increment": sensor.angle_increment,
        },
        "dt": params.dt,
        "goal_tolerance": params.goal_tolerance,
        "params": dict(params.params),
    }


def ready_message() -> dict[str, Any]:
    """Build the ``ready`` reply to a ``reset``.

    >>> ready_message()
    {'type': 'ready'}
    """
    return {"type": MessageType.READY.value}


def observe_message(observation: Observation) -> dict[str, Any]:
    """Build the ``observe`` message of one step (scan via :meth:`LaserScan.to_message`).

    >>> scan = LaserScan(-0.5, 0.5, 0.5, 0.0, 15.0, [2.0, float("inf"), float("-inf")])
    >>> message = observe_message(Observation(0.1, Pose(1.0, 2.0, 0.5), Point(9.0, 9.0), scan))
    >>> message["t"], message["pose"], message["scan"]["ranges"]
    (0.1, [1.0, 2.0, 0.5], [2.0, None, 0.0])
    """
    pose, goal = observation.pose, observation.goal
    return {
        "type": MessageType.OBSERVE.value,
        "t": float(observation.t),
        "pose": [float(pose[0]), float(pose[1]), float(pose[2])],
        "goal": [float(goal[0]), float(goal[1])],
        "scan": observation.scan.to_message(),
    }


def command_message(command: Command) -> dict[str, Any]:
    """Build the ``command`` reply, in the command's form (heading and speed, or a velocity
    command's linear and angular velocity); the optional fields only when they are set.

    >>> command_message(Command(0.25, 1.0))
    {'type': 'command', 'heading': 0.25, 'speed': 1.0}
    >>> command_message(Command(0.0, 0.0, stop="goal_unreachable"))["stop"]
    'goal_unreachable'
    >>> command_message(Command(0.3, 1.0, turn_rate=-0.5))
    {'type': 'command', 'linear': 1.0, 'angular': -0.5}
    """
    message: dict[str, Any] = {"type": MessageType.COMMAND.value}
    if command.turn_rate is None:
        message.update(heading=float(command.heading), speed=float(command.speed))
    else:
        message.update(linear=float(command.speed), angular=float(command.turn_rate))
    for name in ("behaviour", "branch", "stop"):
        value = getattr(command, name)
        if value is not None:
            message[name] = str(value)
    return message


def bye_message() -> dict[str, Any]:
    """Build the ``bye`` message that ends the session.

    >>> bye_message()
    {'type': 'bye'}
    """
    return {"type": MessageType.BYE.value}


# --- lines --------------------------------------------------------------------------------------


def encode(message: Mapping[str, Any]) -> str:
    """Write ``message`` as one line of standard JSON (no trailing newline).

    Raises
    ------
    ProtocolError
        If the message holds NaN, an infinity or a value JSON cannot represent.

    Examples
    --------
    >>> encode({"type": "command", "heading": 0.1, "speed": 1.0})
    '{"type": "command", "heading": 0.1, "speed": 1.0}'
    >>> encode({"type": "command", "heading": float("nan"), "speed": 1.0})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: cannot encode message of type 'command' as JSON: Out of ...
    """
    try:
        return json.dumps(message, allow_nan=False)
    except (TypeError, ValueError) as err:
        raise ProtocolError(
            f"cannot encode message of type {message.get('type')!r} as JSON: {err}"
        ) from None


def decode(line: str, *, what: str = "line") -> dict[str, Any]:
    """Read one line as a JSON object; ``what`` names the line in error messages.

    Raises
    ------
    ProtocolError
        If the line is not JSON, holds the non-standard constants ``NaN``, ``Infinity`` or
        ``-Infinity``, or is not an object. The message quotes the line (shortened).

    Examples
    --------
    >>> decode('{"type": "ready"}\\n')
    {'type': 'ready'}
    >>> decode("hello", what="reply to reset")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: reply to reset is not JSON: 'hello' (Expecting value at ...
    >>> decode('{"type": "command", "heading": NaN}')
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: line contains NaN: '{"type": "command", "heading": NaN}'
    >>> decode("[1, 2]")
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: line is not a JSON object: '[1, 2]'
    """

    def reject(constant: str) -> NoReturn:
        raise ProtocolError(f"{what} contains {constant}: {quote(line)}")

    try:
        value = json.loads(line, parse_constant=reject)
    except json.JSONDecodeError as err:
        raise ProtocolError(
            f"{what} is not JSON: {quote(line)} ({err.msg} at column {err.colno})"
        ) from None
    if not isinstance(value, dict):
        raise ProtocolError(f"{what} is not a JSON object: {quote(line)}")
    return value


def quote(line: str, limit: int = QUOTE_LIMIT) -> str:
    """Quote ``line`` for an error message: ``repr``, trailing newline dropped, shortened.

    >>> quote("hello\\n")
    "'hello'"
    >>> quote("x" * 300, limit=5)
    "'xxxxx'... (300 characters)"
    """
    text = line.rstrip("\r\n")
    if len(text) <= limit:
        return repr(text)
    return f"{text[:limit]!r}... ({len(text)} characters)"


# --- parsing ------------------------------------------------------------------------------------


def message_type(message: Mapping[str, Any], *, where: str = "message") -> MessageType:
    """The ``type`` of a decoded message, or :class:`ProtocolError` if it has none we know.

    >>> message_type({"type": "observe"})
    <MessageType.OBSERVE: 'observe'>
    >>> message_type({"type": "hello"})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: message.type: 'hello', but should be one of reset, ...
    """
    value = _field(message, "type", where)
    try:
        return MessageType(value)
    except (ValueError, TypeError):
        known = ", ".join(MessageType)
        raise ProtocolError(f"{where}.type: {value!r}, but should be one of {known}") from None


def parse_reset(message: Mapping[str, Any]) -> Reset:
    """Read a ``reset`` message (unknown fields are ignored).

    >>> start, goal = Pose(0.0, 0.0, 0.0), Point(10.0, 0.0)
    >>> parse_reset(reset_message(start, goal, EpisodeParams())) == Reset(start, goal,
    ...     EpisodeParams())
    True
    >>> parse_reset({**reset_message(start, goal, EpisodeParams()), "dt": 0})
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: reset.dt: must be a finite number > 0, got 0
    """
    _expect_type(message, MessageType.RESET)
    robot = _block(RobotParams, _field(message, "robot", "reset"), "reset.robot")
    sensor_data = _field(message, "sensor", "reset")
    sensor = _block(SensorParams, sensor_data, "reset.sensor")
    expected = (-0.5 * sensor.fov, 0.5 * sensor.fov, sensor.angle_increment)
    for name, value in zip(_SENSOR_ANGLES, expected, strict=True):
        got = _number(_field(sensor_data, name, "reset.sensor"), f"reset.sensor.{name}")
        if not math.isclose(got, value, rel_tol=0.0, abs_tol=ANGLE_TOLERANCE):
            raise ProtocolError(
                f"reset.sensor.{name}: {got!r}, but should be {value!r} "
                f"(fov={sensor.fov!r}, rays={sensor.rays!r})"
            )
    params = _field(message, "params", "reset")
    if not isinstance(params, dict):
        raise ProtocolError(f"reset.params: must be an object, got {params!r}")
    episode = EpisodeParams(
        robot=robot,
        sensor=sensor,
        dt=_positive(_field(message, "dt", "reset"), "reset.dt"),
        params=params,
        goal_tolerance=_positive(
            _field(message, "goal_tolerance", "reset"), "reset.goal_tolerance"
        ),
    )
    return Reset(
        start=Pose(*_numbers(_field(message, "start", "reset"), 3, "reset.start")),
        goal=Point(*_numbers(_field(message, "goal", "reset"), 2, "reset.goal")),
        params=episode,
    )


def parse_ready(message: Mapping[str, Any]) -> None:
    """Check a ``ready`` reply (no field but ``type``).

    >>> parse_ready({"type": "ready"})
    >>> parse_ready({"type": "command", "heading": 0.0, "speed": 1.0})
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: type 'command', but should be 'ready'
    """
    _expect_type(message, MessageType.READY)
    _no_unknown(message, frozenset({"type"}), "ready")


def parse_observe(message: Mapping[str, Any]) -> Observation:
    """Read an ``observe`` message (unknown fields are ignored); ``null`` ranges are ``+inf``.

    >>> message = {"type": "observe", "t": 0.5, "pose": [1, 2, 0], "goal": [9, 9],
    ...     "scan": {"angle_min": -0.5, "angle_max": 0.5, "angle_increment": 0.5,
    ...              "range_min": 0, "range_max": 15, "ranges": [2.5, None, 3]}}
    >>> parse_observe(message).scan.ranges.tolist()
    [2.5, inf, 3.0]
    >>> bad = {**message, "scan": {**message["scan"], "ranges": [1, "far"]}}
    >>> parse_observe(bad)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: observe.scan.ranges[1]: must be a finite number or ...
    """
    _expect_type(message, MessageType.OBSERVE)
    scan = _field(message, "scan", "observe")
    if not isinstance(scan, dict):
        raise ProtocolError(f"observe.scan: must be an object, got {scan!r}")
    for name in _SCAN_NUMBERS:
        _number(_field(scan, name, "observe.scan"), f"observe.scan.{name}")
    ranges = _field(scan, "ranges", "observe.scan")
    if not isinstance(ranges, list):
        raise ProtocolError(f"observe.scan.ranges: must be an array, got {ranges!r}")
    for i, value in enumerate(ranges):
        if value is not None and violation(value):
            raise ProtocolError(
                f"observe.scan.ranges[{i}]: must be a finite number or null, got {value!r}"
            )
    try:
        laser_scan = LaserScan.from_message(scan)
    except ValueError as err:
        raise ProtocolError(f"observe.scan: {err}") from None
    return Observation(
        t=_number(_field(message, "t", "observe"), "observe.t"),
        pose=Pose(*_numbers(_field(message, "pose", "observe"), 3, "observe.pose")),
        goal=Point(*_numbers(_field(message, "goal", "observe"), 2, "observe.goal")),
        scan=laser_scan,
    )


def parse_command(
    message: Mapping[str, Any], *, at: tuple[Pose, EpisodeParams] | None = None
) -> Command:
    """Read a ``command`` reply strictly (an unknown field is an error).

    A reply holds ``heading`` and ``speed``, or ``linear`` and ``angular`` (a velocity
    command, ROS's ``geometry_msgs/Twist``), never a mix. A velocity command is read with
    :meth:`Command.from_twist` at ``at``: the pose the program was told and the episode's
    parameters; without them it is an error.

    Only types are checked here: a negative speed is a valid message, and the simulator's
    ``invalid_command`` (:meth:`Command.problem`) to report.

    >>> parse_command({"type": "command", "heading": 0.5, "speed": 1, "branch": "case1_gap"})
    Command(heading=0.5, speed=1.0, behaviour=None, branch='case1_gap', stop=None, turn_rate=None)
    >>> parse_command({"type": "command", "heading": "abc", "speed": 1.0})
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: command.heading: must be a finite number, got 'abc'
    >>> parse_command({"type": "command", "heading": 0.0})
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: command.speed: missing
    >>> misspelt = {"type": "command", "heading": 0, "speed": 1, "behavior": "x"}
    >>> parse_command(misspelt)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: command: unknown field(s) 'behavior'; allowed: angular, ...
    >>> twist = {"type": "command", "linear": 1.0, "angular": 0.5}
    >>> parse_command(twist, at=(Pose(0.0, 0.0, 0.0), EpisodeParams())).turn_rate
    0.5
    >>> parse_command({**twist, "speed": 1.0}, at=(Pose(0.0, 0.0, 0.0), EpisodeParams()))
    ... # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ProtocolError: command: has speed, linear, angular; give heading and ...
    """
    _expect_type(message, MessageType.COMMAND)
    _no_unknown(message, _COMMAND_FIELDS, "command")
    behaviour, branch, stop = (
        _optional_text(message.get(name), f"command.{name}")
        for name in ("behaviour", "branch", "stop")
    )
    heading_form, twist_form = _COMMAND_FORMS
    if not any(name in message for name in twist_form):
        heading = _number(_field(message, "heading", "command"), "command.heading")
        speed = _number(_field(message, "speed", "command"), "command.speed")
        return Command(heading, speed, behaviour=behaviour, branch=branch, stop=stop)
    if any(name in message for name in heading_form):
        given = [name for name in (*heading_form, *twist_form) if name in message]
        raise ProtocolError(
            f"command: has {', '.join(given)}; give heading and speed, or linear and angular"
        )
    linear = _number(_field(message, "linear", "command"), "command.linear")
    angular = _number(_field(message, "angular", "command"), "command.angular")
    if at is None:
        raise ProtocolError("command: a velocity command needs the pose it answers")
    return Command.from_twist(linear, angular, *at, behaviour=behaviour, branch=branch, stop=stop)


def parse_bye(message: Mapping[str, Any]) -> None:
    """Check a ``bye`` message (unknown fields are ignored).

    >>> parse_bye({"type": "bye"})
    """
    _expect_type(message, MessageType.BYE)


# --- field checks -------------------------------------------------------------------------------


def _expect_type(message: Mapping[str, Any], expected: MessageType) -> None:
    value = message.get("type")
    if value != expected.value:
        raise ProtocolError(f"type {value!r}, but should be {expected.value!r}")


def _field(container: Mapping[str, Any], name: str, where: str) -> Any:
    try:
        return container[name]
    except KeyError:
        raise ProtocolError(f"{where}.{name}: missing") from None


def _no_unknown(message: Mapping[str, Any], allowed: frozenset[str], where: str) -> None:
    unknown = sorted(set(message) - allowed)
    if unknown:
        raise ProtocolError(
            f"{where}: unknown field(s) {', '.join(map(repr, unknown))}; "
            f"allowed: {', '.join(sorted(allowed))}"
        )


def _number(value: object, where: str, domain: Domain = REAL) -> float:
    """``value`` as a float if it is a finite number in ``domain`` (``true`` is no number;
    1e400 parses to inf), else a :class:`ProtocolError` saying ``where``."""
    if why := violation(value, domain):
        raise ProtocolError(f"{where}: {why}")
    return float(value)  # type: ignore[arg-type]


def _positive(value: object, where: str) -> float:
    return _number(value, where, POSITIVE)


def _numbers(value: object, count: int, where: str) -> tuple[float, ...]:
    if not isinstance(value, list) or len(value) != count:
        raise ProtocolError(f"{where}: must be an array of {count} numbers, got {value!r}")
    return tuple(_number(v, f"{where}[{i}]") for i, v in enumerate(value))


def _optional_text(value: object, where: str) -> str | None:
    if value is not None and not isinstance(value, str):
        raise ProtocolError(f"{where}: must be a string or null, got {value!r}")
    return value


def _block(cls: type[_BlockT], data: object, where: str) -> _BlockT:
    """Build a parameter block from its fields in ``data`` (others ignored): every one, but
    those marked optional (the noise models), which default to off."""
    if not isinstance(data, dict):
        raise ProtocolError(f"{where}: must be an object, got {data!r}")
    values = {
        f.name: _field(data, f.name, where)
        for f in fields(cls)
        if f.name in data or not f.metadata.get("optional")
    }
    try:
        return cls(**values)
    except ParameterError as err:
        raise ProtocolError(f"{where}: {err}") from None
