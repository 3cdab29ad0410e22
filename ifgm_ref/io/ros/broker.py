"""The broker: the one clock, the routing of messages and services, in a fixed order.

The broker runs in the simulator's process and owns simulated time. Its nodes
(:class:`~ifgm_ref.io.ros.process.NodeProcess`) run one at a time, only when it hands one
control (:mod:`ifgm_ref.io.ros.client`), so a run depends on nothing but its inputs:

- a node with messages waiting (a publication it subscribes to, a service request or
  response, a parameter another node set) runs first, lowest index first, at the current time;
- when none has, the clock moves to the earliest time a node asked to wake at, and the
  lowest-indexed node due runs;
- what a node produced while it ran (its subscriptions, publications, calls) is routed in the
  order it produced it, each message to the subscribers' nodes in the order they subscribed.

:meth:`Broker.settle` runs the nodes up to a time; :meth:`Broker.publish` is the simulator
publishing (``/odom``, ``/scan``, the goal). The broker keeps the last ``/cmd_vel`` it routed
with its time (:attr:`Broker.command`), and the end a node asked for (:attr:`Broker.stop`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.io.ros.process import NodeProcess
from ifgm_ref.io.ros.rules import CMD_VEL, LABEL_TOPICS, MAX_ACTIVATIONS, STOP_TOPIC
from ifgm_ref.io.transport.external import PER_REPLY, STARTUP

__all__ = ["Broker", "Velocity"]


@dataclass(frozen=True)
class Velocity:
    """A ``/cmd_vel`` routed at time ``t`` (ns): ``linear.x`` m/s, ``angular.z`` rad/s."""

    t: int
    linear: float
    angular: float


@dataclass
class _Node:
    """What the broker knows of one node in the current episode."""

    process: NodeProcess
    name: str = ""
    alive: bool = False
    wake: int | None = None
    inbox: list[dict[str, Any]] = field(default_factory=list)


class Broker:
    """Routes and schedules the nodes of one planner (see the module docstring).

    Parameters
    ----------
    nodes : list of NodeProcess
        The nodes, in the order their commands were given.
    timeout, startup_timeout : float
        Longest wait, s, for a node to block again after it was handed control, and for its
        start (hello) and an episode's first block.
    remaps : dict of str to str
        Remappings given to every node, global names.
    """

    def __init__(
        self,
        nodes: list[NodeProcess],
        *,
        timeout: float,
        startup_timeout: float,
        remaps: dict[str, str],
    ) -> None:
        self.nodes = [_Node(process) for process in nodes]
        self.timeout, self.startup_timeout = timeout, startup_timeout
        self.remaps = dict(remaps)
        self._new_state()

    def _new_state(self) -> None:
        self.now = 0
        self.command: Velocity | None = None
        self.stop: str | None = None
        self.labels: dict[str, str] = {}
        self.subscribers: dict[str, list[tuple[int, str]]] = {}
        self.latched: dict[str, tuple[str, Any]] = {}
        self.latching: set[tuple[int, str]] = set()
        self.services: dict[str, tuple[int, str]] = {}
        self.waiting: dict[str, list[int]] = {}
        self.params: dict[str, Any] = {}

    # --- episodes ------------------------------------------------------------------------

    def begin(self, params: dict[str, Any], private: dict[str, Any]) -> None:
        """Start an episode at time 0: each node's process forks a fresh child, which runs
        until it first blocks (nodes in order), with ``params`` (global names) and
        ``private`` (set as ``~name`` of every node) on the parameter server."""
        self._new_state()
        self.params = dict(params)
        for node in self.nodes:
            node.alive, node.wake, node.inbox = False, None, []
            if not node.process.running:
                node.process.start()
                hello = self._read(node, self.startup_timeout, "starting (rospy.init_node)")
                if hello.get("op") != "hello":
                    raise node.process.failure(f"expected hello, got {hello!r:.80}")
                node.name = str(hello.get("name"))
            order = {"op": "episode", "params": params, "private": private}
            node.process.send({**order, "remaps": self.remaps})
            node.alive = True
        for index in range(len(self.nodes)):
            self._run_lines(index, self.startup_timeout, "starting its episode")

    def end(self) -> None:
        """End the episode: every child still running exits; its process awaits the next."""
        for node in self.nodes:
            if node.process.running and node.alive:
                node.process.send({"op": "end"})
                node.alive = False
                while True:  # the parent reports the child's exit; anything else is stale
                    line = self._read(node, self.startup_timeout, "ending its episode")
                    if line.get("op") == "exited":
                        break

    def close(self) -> None:
        """Say bye to every node's process and make sure it is gone."""
        for node in self.nodes:
            if node.process.running:
                try:
                    node.process.send({"op": "bye"})
                    node.process.wait_exit(self.startup_timeout)
                except ImplementationError:
                    pass
                node.process.kill()

    def kill(self) -> None:
        """Kill every node's process group."""
        for node in self.nodes:
            node.process.kill()
            node.alive = False

    # --- the clock -----------------------------------------------------------------------

    def settle(self, limit: int, *, inclusive: bool) -> None:
        """Run the nodes until none has messages waiting and none is due before ``limit``
        (ns; or at it, if ``inclusive``); the clock then reads ``limit``."""
        activations = 0
        while True:
            index = self._next(limit, inclusive)
            if index is None:
                break
            activations += 1
            if activations > MAX_ACTIVATIONS:
                raise ImplementationError(
                    f"ROS nodes: over {MAX_ACTIVATIONS} activations without reaching "
                    f"t={limit / 1e9!r} s (nodes that keep waking each other at "
                    f"t={self.now / 1e9!r} s?)"
                )
            node = self.nodes[index]
            deliver, node.inbox = node.inbox, []
            node.process.send({"op": "run", "t": self.now, "deliver": deliver})
            self._run_lines(index, self.timeout, f"running at t={self.now / 1e9!r} s")
        self.now = max(self.now, limit)

    def _next(self, limit: int, inclusive: bool) -> int | None:
        """The node to run next, moving the clock to its wake-up if need be; None if none."""
        alive = [(i, n) for i, n in enumerate(self.nodes) if n.alive]
        for index, node in alive:
            if node.inbox:
                return index
        wakes = [n.wake for _, n in alive if n.wake is not None]
        if not wakes:
            return None
        due = max(self.now, min(wakes))
        if due > limit or (due == limit and not inclusive):
            return None
        self.now = due
        return next(i for i, n in alive if n.wake is not None and n.wake <= due)

    # --- what nodes say -------------------------------------------------------------------

    def _read(self, node: _Node, wait: float, what: str) -> dict[str, Any]:
        return node.process.receive(time.monotonic() + wait, what, self._which(wait))

    def _which(self, wait: float) -> str:
        """How an error names the timeout ``wait``, with its option."""
        option = STARTUP if wait == self.startup_timeout else PER_REPLY
        return f"{wait:g} s, {option}"

    def _run_lines(self, index: int, wait: float, what: str) -> None:
        """Handle node ``index``'s lines until it blocks (``idle``) or its child ended."""
        node = self.nodes[index]
        deadline = time.monotonic() + wait
        while True:
            line = node.process.receive(deadline, what, self._which(wait))
            op = line.get("op")
            if op == "idle":
                wake = line.get("wake")
                node.wake = None if wake is None else int(wake)
                return
            if op == "exited":
                node.alive = False
                status = line.get("status")
                if status != 0:
                    raise node.process.failure(f"it exited with status {status} while {what}")
                self.stop = self.stop or "done"
                return
            try:
                self._handle(index, op, line)
            except (KeyError, TypeError, ValueError, IndexError) as err:
                raise node.process.failure(f"bad line {line!r:.120} ({err!r})") from None

    def _handle(self, index: int, op: Any, line: dict[str, Any]) -> None:
        node = self.nodes[index]
        if op == "pub":
            self.publish(line["name"], line["type"], line["data"], sender=index)
        elif op == "sub":
            self._subscribe(index, line["name"], line["type"])
        elif op == "adv":
            if line.get("latch"):
                self.latching.add((index, line["name"]))
        elif op == "srv":
            self.services[line["name"]] = (index, line["type"])
            for waiter in self.waiting.pop(line["name"], []):
                self.nodes[waiter].inbox.append({"kind": "service_ready", "name": line["name"]})
        elif op == "wait_service":
            if line["name"] in self.services:
                node.inbox.append({"kind": "service_ready", "name": line["name"]})
            else:
                self.waiting.setdefault(line["name"], []).append(index)
        elif op == "call":
            self._call(index, line)
        elif op == "response":
            reply: dict[str, Any] = {k: line[k] for k in ("id", "data", "error") if k in line}
            self.nodes[int(line["caller"])].inbox.append({"kind": "response", **reply})
        elif op == "set_param":
            self.params[line["name"]] = line["value"]
            for other, peer in enumerate(self.nodes):
                if other != index and peer.alive:
                    values = {line["name"]: line["value"]}
                    peer.inbox.append({"kind": "params", "values": values})
        elif op == "shutdown":
            self.stop = self.stop or "done"
        else:
            raise ValueError(f"unknown op {op!r}")

    def _subscribe(self, index: int, name: str, kind: str) -> None:
        entries = self.subscribers.setdefault(name, [])
        if (index, kind) not in entries:
            entries.append((index, kind))
        if name in self.latched and self.latched[name][0] == kind:
            self.nodes[index].inbox.append(
                {"kind": "msg", "name": name, "data": self.latched[name][1]}
            )

    def _call(self, index: int, line: dict[str, Any]) -> None:
        name, ident = line["name"], line["id"]
        server = self.services.get(name)
        caller = self.nodes[index]
        if server is None or not self.nodes[server[0]].alive:
            error = f"service {name} does not exist"
            caller.inbox.append({"kind": "response", "id": ident, "error": error})
        elif server[1] != line["type"]:
            error = f"service {name} is a {server[1]}, called as a {line['type']}"
            caller.inbox.append({"kind": "response", "id": ident, "error": error})
        else:
            request = {"kind": "request", "name": name, "id": ident, "caller": index}
            self.nodes[server[0]].inbox.append({**request, "data": line["data"]})

    def publish(
        self, name: str, kind: str, data: Any, *, sender: int | None = None, latch: bool = False
    ) -> None:
        """Route a message on topic ``name`` of type ``kind`` (``data`` as
        :func:`~ifgm_ref.io.ros.messages.to_wire` gives it); ``sender`` None is the simulator."""
        if latch or (sender is not None and (sender, name) in self.latching):
            self.latched[name] = (kind, data)
        if name == CMD_VEL[0] or name == STOP_TOPIC[0]:
            self._for_the_base(name, kind, data, sender)
        elif name in LABEL_TOPICS and kind == "std_msgs/String":
            self.labels[LABEL_TOPICS[name]] = str(data[0])
        seen: set[int] = set()
        for index, wanted in self.subscribers.get(name, []):
            if wanted == kind and index not in seen and self.nodes[index].alive:
                seen.add(index)
                self.nodes[index].inbox.append({"kind": "msg", "name": name, "data": data})

    def _for_the_base(self, name: str, kind: str, data: Any, sender: int | None) -> None:
        """Keep a velocity command or a stop (``docs/ros-nodes.md``)."""
        want = CMD_VEL if name == CMD_VEL[0] else STOP_TOPIC
        if kind != want[1]:
            node = self.nodes[sender or 0].process
            raise node.failure(f"it published {name} as a {kind}, but it carries {want[1]}")
        if name == CMD_VEL[0]:
            self.command = Velocity(self.now, float(data[0][0]), float(data[1][2]))
        elif self.stop is None:
            self.stop = str(data[0])
