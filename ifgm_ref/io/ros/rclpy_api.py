"""A small rclpy (ROS 2) over the same client and broker as the rospy stand-in.

What a ROS 2 node imports as ``rclpy`` under ``--ros2-node``: ``init``, ``shutdown``, ``ok``,
``spin``, ``spin_once``, ``spin_until_future_complete``, ``create_node`` and :class:`Node` with
``create_publisher``, ``create_subscription``, ``create_timer``, ``create_service``,
``create_client``, ``get_clock``, ``get_logger``, ``declare_parameter``, ``get_parameter``;
``rclpy.time.Time``, ``rclpy.duration.Duration`` and ``rclpy.qos`` (accepted, not acted on:
the broker delivers every message). The message classes are ROS 2 Humble's
(:mod:`ifgm_ref.io.ros.messages`, ``distro="ros2"``). A node's parameters are its own: those it
was given (``--ros-args -p``), the goal (``goal_x``, ``goal_y``, ``des_pos_x``, ``des_pos_y``),
and ``ifgm_ref.robot.radius`` and the rest of ``/ifgm_ref/`` with dots for slashes.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from typing import Any

from ifgm_ref.io.ros.client import Registration, Shutdown, client
from ifgm_ref.io.ros.messages import Message, ServiceType, from_wire, message_class, to_wire
from ifgm_ref.io.ros.params_log import _log
from ifgm_ref.io.ros.rospy_api import Publisher, Subscriber
from ifgm_ref.io.ros.rospy_api import Timer as _Timer
from ifgm_ref.io.ros.rostime import NS, nanoseconds

__all__ = [
    "Client",
    "Duration",
    "Future",
    "Node",
    "Parameter",
    "QoSProfile",
    "Time",
    "create_node",
    "init",
    "ok",
    "shutdown",
    "spin",
    "spin_once",
    "spin_until_future_complete",
]


def init(args: Sequence[str] | None = None, **_ignored: Any) -> None:
    """Start the process's ROS 2 context (it returns in an episode's child, as
    ``rospy.init_node`` does: :mod:`ifgm_ref.io.ros.client`)."""
    client().init_node("rclpy", False, list(sys.argv if args is None else args), "ros2")


def ok(**_ignored: Any) -> bool:
    """Whether the context was not shut down."""
    return client().shutdown is None


def shutdown(**_ignored: Any) -> None:
    """Shut the context down (the stand-in counts it as ``done``)."""
    client().signal_shutdown("rclpy.shutdown()")


try_shutdown = shutdown


def spin(node: Node | None = None, **_ignored: Any) -> None:
    """Run callbacks until shutdown."""
    try:
        client().wait(condition=lambda: False)
    except Shutdown:
        return


def spin_once(node: Node | None = None, *, timeout_sec: float | None = None, **_: Any) -> None:
    """Run the next callbacks (waiting up to ``timeout_sec`` s of simulated time)."""
    node_client = client()
    start = node_client.events
    until = None if timeout_sec is None else node_client.now + nanoseconds(timeout_sec)
    try:
        node_client.wait(until=until, condition=lambda: node_client.events > start)
    except Shutdown:
        return


def spin_until_future_complete(
    node: Node | None, future: Future, timeout_sec: float | None = None, **_ignored: Any
) -> None:
    """Run callbacks until ``future`` is done (or ``timeout_sec`` s of simulated time)."""
    node_client = client()
    until = None if timeout_sec is None else node_client.now + nanoseconds(timeout_sec)
    try:
        node_client.wait(until=until, condition=future.done)
    except Shutdown:
        return


class Duration:
    """``rclpy.duration.Duration``."""

    def __init__(self, *, seconds: float = 0.0, nanoseconds: int = 0) -> None:
        self.nanoseconds = round(seconds * NS) + int(nanoseconds)

    def to_msg(self) -> Any:
        """As a ``builtin_interfaces/Duration``."""
        sec, nanosec = divmod(self.nanoseconds, NS)
        return message_class("builtin_interfaces/Duration", "ros2")(sec=sec, nanosec=nanosec)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Duration) and other.nanoseconds == self.nanoseconds

    def __lt__(self, other: Duration) -> bool:
        return self.nanoseconds < other.nanoseconds


class Time:
    """``rclpy.time.Time`` on the simulated clock."""

    def __init__(self, *, seconds: float = 0.0, nanoseconds: int = 0, **_ignored: Any) -> None:
        self.nanoseconds = round(seconds * NS) + int(nanoseconds)

    def seconds_nanoseconds(self) -> tuple[int, int]:
        """Whole seconds and the nanoseconds beyond."""
        sec, nanosec = divmod(self.nanoseconds, NS)
        return sec, nanosec

    def to_msg(self) -> Any:
        """As a ``builtin_interfaces/Time``."""
        sec, nanosec = self.seconds_nanoseconds()
        return message_class("builtin_interfaces/Time", "ros2")(sec=sec, nanosec=nanosec)

    @classmethod
    def from_msg(cls, msg: Any, **_ignored: Any) -> Time:
        """From a ``builtin_interfaces/Time``."""
        return cls(nanoseconds=int(msg.sec) * NS + int(msg.nanosec))

    def __sub__(self, other: Any) -> Any:
        if isinstance(other, Time):
            return Duration(nanoseconds=self.nanoseconds - other.nanoseconds)
        return Time(nanoseconds=self.nanoseconds - other.nanoseconds)

    def __add__(self, other: Duration) -> Time:
        return Time(nanoseconds=self.nanoseconds + other.nanoseconds)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Time) and other.nanoseconds == self.nanoseconds

    def __lt__(self, other: Time) -> bool:
        return self.nanoseconds < other.nanoseconds


class Clock:
    """A node's clock: the simulated one."""

    def now(self) -> Time:
        """The simulated time."""
        return Time(nanoseconds=client().now)


class Logger:
    """A node's logger (to stderr, stamped with the simulated time)."""

    def debug(self, message: Any, **_ignored: Any) -> None:
        """Dropped, as at the default level."""

    def info(self, message: Any, **_ignored: Any) -> None:
        """Log at level INFO."""
        _log("INFO", message)

    def warning(self, message: Any, **_ignored: Any) -> None:
        """Log at level WARN."""
        _log("WARN", message)

    warn = warning

    def error(self, message: Any, **_ignored: Any) -> None:
        """Log at level ERROR."""
        _log("ERROR", message)

    def fatal(self, message: Any, **_ignored: Any) -> None:
        """Log at level FATAL."""
        _log("FATAL", message)


class Parameter:
    """A parameter: its ``name`` and ``value``."""

    def __init__(self, name: str, value: Any = None) -> None:
        self.name, self.value = name, value

    def get_parameter_value(self) -> Any:
        """The value (rclpy wraps it; here it is the value itself)."""
        return self.value


class QoSProfile:
    """A quality of service: accepted, not acted on."""

    def __init__(self, **settings: Any) -> None:
        self.settings = settings


class Future:
    """The answer to come of a service call."""

    def __init__(self, ident: int, response_type: type[Message]) -> None:
        self._ident, self._type = ident, response_type

    def done(self) -> bool:
        """Whether the answer came."""
        return self._ident in client().responses

    def result(self) -> Any:
        """The response, or None if the call failed or has not been answered."""
        reply = client().responses.get(self._ident)
        if reply is None or "error" in reply:
            return None
        return from_wire(self._type._type, reply["data"], "ros2")

    def exception(self) -> Exception | None:
        """Why the call failed, if it did."""
        reply = client().responses.get(self._ident)
        return None if reply is None or "error" not in reply else RuntimeError(reply["error"])


class Client:
    """A service client (``Node.create_client``)."""

    def __init__(self, srv_type: type[ServiceType], name: str) -> None:
        self.srv_type, self.srv_name = srv_type, name

    def service_is_ready(self) -> bool:
        """Whether a node offers the service (as far as this node has heard)."""
        return client().resolve(self.srv_name) in client().services_ready

    def wait_for_service(self, timeout_sec: float | None = None) -> bool:
        """Wait until the service is offered; False if ``timeout_sec`` s pass first."""
        node_client = client()
        name = node_client.resolve(self.srv_name)
        if name not in node_client.services_ready:
            node_client.send({"op": "wait_service", "name": name})
        until = None if timeout_sec is None else node_client.now + nanoseconds(timeout_sec)
        try:
            return node_client.wait(until=until, condition=self.service_is_ready)
        except Shutdown:
            return False

    def call_async(self, request: Message) -> Future:
        """Send ``request``; the future is done when the answer has come."""
        node_client = client()
        ident = node_client.new_id()
        line = {"op": "call", "name": node_client.resolve(self.srv_name), "id": ident}
        node_client.send({**line, "type": self.srv_type._type, "data": to_wire(request)})
        return Future(ident, self.srv_type.Response)

    def call(self, request: Message) -> Any:
        """Call and wait for the response (None if the call failed)."""
        future = self.call_async(request)
        client().wait(condition=future.done)
        return future.result()

    def destroy(self) -> None:
        """Nothing to release."""


class Node:
    """A ROS 2 node of the process."""

    def __init__(self, node_name: str, **_ignored: Any) -> None:
        self._name = node_name
        client().name_node(node_name)

    def get_name(self) -> str:
        """The node's name."""
        return self._name

    def get_namespace(self) -> str:
        """The node's namespace: ``/`` here."""
        return "/"

    def create_publisher(self, msg_type: type[Message], topic: str, qos: Any, **_: Any) -> Any:
        """A publisher of ``msg_type`` on ``topic`` (``publish(message)``)."""
        return Publisher(topic, msg_type)

    def create_subscription(
        self,
        msg_type: type[Message],
        topic: str,
        callback: Callable[[Any], Any],
        qos: Any,
        **_: Any,
    ) -> Any:
        """Call ``callback(message)`` for each ``msg_type`` message on ``topic``."""
        return Subscriber(topic, msg_type, callback)

    def create_timer(self, period: float, callback: Callable[[], Any], **_: Any) -> Any:
        """Call ``callback()`` every ``period`` s of simulated time."""
        return _Timer(period, lambda event: callback())  # type: ignore[arg-type]

    def create_service(
        self, srv_type: type[ServiceType], name: str, callback: Callable[[Any, Any], Any], **_: Any
    ) -> Registration:
        """Offer ``name``, answered by ``callback(request, response)``."""
        handle = Registration(
            "srv",
            name,
            srv_type._type,
            handler=lambda request: callback(request, srv_type.Response()),
        )
        return client().register(handle)

    def create_client(self, srv_type: type[ServiceType], name: str, **_: Any) -> Client:
        """A client of the service ``name``."""
        return Client(srv_type, name)

    def get_clock(self) -> Clock:
        """The simulated clock."""
        return Clock()

    def get_logger(self) -> Logger:
        """The node's logger."""
        return Logger()

    def declare_parameter(self, name: str, value: Any = None, *_: Any, **__: Any) -> Parameter:
        """Declare ``name`` with its default ``value`` (a value given to the node wins)."""
        key = self._key(name)
        if key is None:
            client().params[client().resolve("~" + name)] = value
        return self.get_parameter(name)

    def declare_parameters(self, namespace: str, parameters: Sequence[Any]) -> list[Parameter]:
        """Declare ``(name, default)`` pairs under ``namespace``."""
        prefix = f"{namespace}." if namespace else ""
        return [self.declare_parameter(prefix + p[0], *p[1:2]) for p in parameters]

    def get_parameter(self, name: str) -> Parameter:
        """The parameter ``name`` (its value None if unset)."""
        key = self._key(name)
        return Parameter(name, None if key is None else client().params[key])

    def get_parameter_or(self, name: str, alternative: Any = None) -> Parameter:
        """The parameter ``name``, or ``alternative`` if unset."""
        key = self._key(name)
        return alternative if key is None else Parameter(name, client().params[key])

    def has_parameter(self, name: str) -> bool:
        """Whether ``name`` is set."""
        return self._key(name) is not None

    def _key(self, name: str) -> str | None:
        """Where ``name`` is set: the node's own, else the global one (dots as slashes)."""
        node_client = client()
        for key in (node_client.resolve("~" + name), "/" + name.replace(".", "/")):
            if key in node_client.params:
                return key
        return None

    def destroy_node(self) -> None:
        """Nothing to release."""

    def destroy_timer(self, timer: Any) -> None:
        """Stop ``timer``."""
        timer.shutdown()

    def destroy_subscription(self, subscription: Any) -> None:
        """Stop ``subscription``."""
        subscription.unregister()

    def destroy_publisher(self, publisher: Any) -> None:
        """Nothing to release."""


def create_node(node_name: str, **options: Any) -> Node:
    """A new node."""
    return Node(node_name, **options)
