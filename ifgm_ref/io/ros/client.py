"""The node's end of the stand-in: its link to the broker, its clock and its event loop.

A node under ``ifgm-ref simulate --ros-node`` or ``ifgm-ref oracle --ros-node`` is started
with a socket to the broker (:mod:`ifgm_ref.io.ros.broker`) open at the file descriptor named by
:data:`FD_VARIABLE`; its stdout and stderr are only its log. The link speaks JSON lines
(``docs/ros-nodes.md``, "The broker's link").

**One episode per process, imports paid once.** ``rospy.init_node`` connects and makes the
process a *zygote*: it says hello, then, for each episode, forks a child that returns from
``init_node`` and runs the rest of the node (the parent waits for the child, reports how it
ended, and waits for the next episode). Every episode so starts from the node's state just
before ``init_node``, as a fresh start would, without paying for the interpreter and its
imports again.

**Lockstep.** The node runs only when the broker hands it control (a ``run`` message: the new
time and the messages to deliver), one node at a time. It runs its callbacks, then its
program, until the program blocks in a rospy call (``sleep``, ``Rate.sleep``, ``spin``, a
service call, ``wait_for_*``), and then reports ``idle`` with the time it wants to wake at
(or none), after the lines it produced (subscriptions, publications, ...). Callbacks run in
the thread that blocked, inside the blocking call, as a single-threaded executor runs them:
a subscriber's callback runs while the program sleeps in ``Rate.sleep``, always at the same
point, so that the same inputs give the same run.
"""

from __future__ import annotations

import json
import os
import socket
import sys
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from typing import Any

from ifgm_ref.io.ros.names import resolve, split_argv, split_ros2_argv
from ifgm_ref.io.ros.rostime import set_clock

__all__ = ["FD_VARIABLE", "Client", "client", "current_time"]

#: The environment variable naming the file descriptor of the node's socket to the broker.
FD_VARIABLE = "IFGM_REF_ROS_FD"
#: The environment variable giving the node's index among the nodes (anonymous names).
INDEX_VARIABLE = "IFGM_REF_ROS_INDEX"


class Shutdown(Exception):
    """The node was shut down while it waited (rospy raises ROSInterruptException)."""


@dataclass
class Registration:
    """A publisher, subscriber or service of the node, by the name its program gave."""

    kind: str  # "adv", "sub" or "srv"
    name: str
    type: str
    handler: Callable[..., Any] | None = None
    latch: bool = False
    resolved: str = ""
    active: bool = True


@dataclass
class Client:
    """The node's link to the broker and its state (one per process: :func:`client`)."""

    name: str = "/unnamed"
    distro: str = "ros1"
    now: int = 0
    events: int = 0
    private: dict[str, Any] = field(default_factory=dict)
    started: bool = False
    shutdown: str | None = None
    remaps: dict[str, str] = field(default_factory=dict)
    params: dict[str, Any] = field(default_factory=dict)
    registrations: list[Registration] = field(default_factory=list)
    outbox: list[dict[str, Any]] = field(default_factory=list)
    responses: dict[int, dict[str, Any]] = field(default_factory=dict)
    services_ready: set[str] = field(default_factory=set)
    timers: list[Any] = field(default_factory=list)
    shutdown_hooks: list[Callable[..., Any]] = field(default_factory=list)
    next_id: int = 0
    _renamed: str | None = None
    _sock: socket.socket | None = None
    _reader: Any = None

    # --- start: init_node, the zygote --------------------------------------------------------

    def init_node(self, name: str, anonymous: bool, argv: list[str], distro: str = "ros1") -> None:
        """Connect, say hello, and become the zygote: return only in an episode's child
        (``distro`` ``ros2``: ``rclpy.init``, whose nodes are named later, :meth:`name_node`)."""
        if self._sock is not None:
            raise RuntimeError("rospy.init_node() has already been called")
        fd = os.environ.get(FD_VARIABLE)
        if fd is None:
            raise RuntimeError(
                f"this rospy is ifgm-ref's stand-in and runs only under ifgm-ref ({FD_VARIABLE} "
                "is not set): ifgm-ref simulate WORLD --ros-node 'python3 node.py'"
            )
        self.distro = distro
        split = split_ros2_argv if distro == "ros2" else split_argv
        _, argv_remaps, private, renamed = split(argv)
        self._renamed = renamed
        index = os.environ.get(INDEX_VARIABLE, "0")
        base = renamed or name
        self.name = resolve(f"{base}_{index}" if anonymous and not renamed else base, "/")
        self._sock = socket.socket(fileno=int(fd))
        self._reader = self._sock.makefile("rb")
        self._send_now({"op": "hello", "name": self.name, "pid": os.getpid()})
        while True:
            order = self._receive()
            if order.get("op") != "episode":
                os._exit(0)  # bye, or the broker gone
            pid = os.fork()
            if pid == 0:
                self._begin(order, argv_remaps, private)
                return
            _, status = os.waitpid(pid, 0)
            self._send_now({"op": "exited", "status": os.waitstatus_to_exitcode(status)})

    def _begin(
        self, order: dict[str, Any], argv_remaps: dict[str, str], private: dict[str, Any]
    ) -> None:
        """In an episode's child: take the episode's parameters and remappings."""
        self.started = True
        self.remaps = {**order.get("remaps", {}), **argv_remaps}
        self.params = dict(order.get("params", {}))
        self.private = {**private, **order.get("private", {})}
        if self.distro == "ros1":
            self.name_node(self.name)
        for registration in self.registrations:
            self._announce(registration)
        import atexit

        atexit.register(self._flush)

    def name_node(self, name: str) -> str:
        """Name the node (rclpy names it after ``init``; ``__node:=`` wins) and set its
        private parameters under that name; its global name."""
        self.name = resolve(self._renamed or name, "/") if self.distro == "ros2" else name
        for key, value in self.private.items():
            self.params[resolve("~" + key, self.name)] = value
        return self.name

    # --- registrations ------------------------------------------------------------------------

    def register(self, registration: Registration) -> Registration:
        """Add a publisher, subscriber or service; announce it if the episode runs."""
        self.registrations.append(registration)
        if self.started:
            self._announce(registration)
        return registration

    def _announce(self, registration: Registration) -> None:
        registration.resolved = self.resolve(registration.name)
        line: dict[str, Any] = {"op": registration.kind, "name": registration.resolved}
        line["type"] = registration.type
        if registration.kind == "adv":
            line["latch"] = registration.latch
        self.outbox.append(line)

    def unregister(self, registration: Registration) -> None:
        """Stop delivering to a subscriber (the broker keeps routing; the node drops)."""
        registration.active = False

    def resolve(self, name: str) -> str:
        """``name``'s global name for this node, remapped."""
        return resolve(name, self.name, self.remaps)

    # --- sending ------------------------------------------------------------------------------

    def send(self, line: dict[str, Any]) -> None:
        """Queue ``line`` for the broker (sent at the next block, in order)."""
        self.outbox.append(line)

    def new_id(self) -> int:
        """A fresh request id."""
        self.next_id += 1
        return self.next_id

    def _flush(self, idle: dict[str, Any] | None = None) -> None:
        lines = self.outbox + ([idle] if idle is not None else [])
        self.outbox = []
        if lines and self._sock is not None and self.started:
            data = "".join(json.dumps(line, separators=(",", ":")) + "\n" for line in lines)
            self._sock.sendall(data.encode())

    def _send_now(self, line: dict[str, Any]) -> None:
        assert self._sock is not None
        self._sock.sendall((json.dumps(line) + "\n").encode())

    def _receive(self) -> dict[str, Any]:
        line = self._reader.readline()
        if not line:
            os._exit(0)  # the broker is gone: nothing left to do
        result: dict[str, Any] = json.loads(line)
        return result

    # --- waiting: the event loop --------------------------------------------------------------

    def wait(self, until: int | None = None, condition: Callable[[], bool] | None = None) -> bool:
        """Block until ``condition()`` holds (return True) or the clock reaches ``until``
        (ns; return False), running callbacks meanwhile.

        Raises
        ------
        Shutdown
            When the node is shut down first.
        RuntimeError
            Before ``init_node``.
        """
        if not self.started:
            raise RuntimeError("a rospy call that waits needs rospy.init_node() first")
        while True:
            if condition is not None and condition():
                return True
            if self.shutdown is not None:
                raise Shutdown(self.shutdown)
            if until is not None and self.now >= until:
                return False
            wakes = [t for t in (until, *(timer.due for timer in self.timers)) if t is not None]
            self._flush({"op": "idle", "wake": min(wakes) if wakes else None})
            self._activation()

    def _activation(self) -> None:
        order = self._receive()
        if order.get("op") != "run":
            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(0)  # the episode is over
        self.now = max(self.now, int(order["t"]))
        for delivery in order.get("deliver", []):
            self._dispatch(delivery)
            self.events += 1
        for timer in list(self.timers):
            if timer.due is not None and timer.due <= self.now:
                _guarded(timer.fire, f"timer {timer!r}")
                self.events += 1

    def _dispatch(self, delivery: dict[str, Any]) -> None:
        kind = delivery["kind"]
        if kind == "msg":
            self._deliver_message(delivery["name"], delivery["data"])
        elif kind == "request":
            self._serve(delivery)
        elif kind == "response":
            self.responses[delivery["id"]] = delivery
        elif kind == "service_ready":
            self.services_ready.add(delivery["name"])
        elif kind == "params":
            self.params.update(delivery["values"])

    def _deliver_message(self, topic: str, data: Any) -> None:
        from ifgm_ref.io.ros.messages import from_wire

        decoded: dict[str, Any] = {}
        for reg in list(self.registrations):
            if reg.kind == "sub" and reg.active and reg.resolved == topic:
                if reg.type not in decoded:
                    decoded[reg.type] = from_wire(reg.type, data, self.distro)
                assert reg.handler is not None
                _guarded(partial(reg.handler, decoded[reg.type]), f"callback of {topic}")

    def _serve(self, delivery: dict[str, Any]) -> None:
        from ifgm_ref.io.ros.messages import from_wire, service_class, to_wire

        reply: dict[str, Any] = {"op": "response", "id": delivery["id"]}
        reply["caller"] = delivery["caller"]
        for reg in self.registrations:
            if reg.kind == "srv" and reg.resolved == delivery["name"]:
                service = service_class(reg.type, self.distro)
                try:
                    request = from_wire(service.Request._type, delivery["data"], self.distro)
                    assert reg.handler is not None
                    reply["data"] = to_wire(_response(service, reg.handler(request)))
                except Exception as err:  # rospy reports a handler's error to the caller
                    traceback.print_exc()
                    reply["error"] = f"service handler raised {type(err).__name__}: {err}"
                break
        else:
            reply["error"] = f"service {delivery['name']} is not offered by {self.name}"
        self.send(reply)

    def signal_shutdown(self, reason: str) -> None:
        """Shut the node down: run its hooks, tell the broker (it then counts as done)."""
        if self.shutdown is not None:
            return
        self.shutdown = reason or "shutdown"
        for hook in self.shutdown_hooks:
            _guarded(hook, "shutdown hook")
        self.send({"op": "shutdown", "reason": self.shutdown})
        self._flush()


def _response(service: Any, value: Any) -> Any:
    """A service handler's return value as its response message, as rospy accepts them: the
    message, ``None`` for an empty response, a tuple or list of fields, a dict, one field."""
    cls = service._response_class
    if isinstance(value, cls):
        return value
    if value is None and not cls._spec:
        return cls()
    if isinstance(value, tuple | list):
        return cls(*value)
    if isinstance(value, dict):
        return cls(**value)
    if len(cls._spec) == 1:
        return cls(value)
    raise TypeError(f"a {service._type} handler returned {value!r}, not a {cls._type}")


def _guarded(call: Callable[[], Any], what: str) -> None:
    """Run a callback; log what it raises and go on, as rospy does (the node keeps running)."""
    try:
        call()
    except Shutdown:
        raise
    except Exception:
        print(f"[ERROR] bad {what}:", file=sys.stderr)
        traceback.print_exc()


_CLIENT = Client()
set_clock(lambda: _CLIENT.now)


def client() -> Client:
    """The node's one client."""
    return _CLIENT


def current_time() -> int:
    """The node's simulated time, ns (0 before the episode's first activation)."""
    return _CLIENT.now
