"""The rospy API (ROS 1 Noetic, Python 3) over the stand-in's client, for unchanged nodes.

What a node imports as ``rospy`` (the shim package puts this module's names there):
``init_node``, ``Publisher``, ``Subscriber``, ``Rate``, ``Timer``, ``sleep``, ``spin``,
``get_time``, ``get_rostime``, ``Time``, ``Duration``, ``is_shutdown``, ``signal_shutdown``,
``on_shutdown``, ``wait_for_message``, parameters (``get_param``, ``set_param``,
``has_param``, ``delete_param``, ``search_param``, ``get_param_names``), logging
(``loginfo`` and its siblings, their ``_throttle`` and ``_once`` forms), services
(:mod:`ifgm_ref.io.ros.services`: ``Service``, ``ServiceProxy``, ``wait_for_service``), the
exceptions, ``get_name`` and ``myargv``. Time is the simulated time of the broker; every
call that waits lets the node's callbacks run (:meth:`ifgm_ref.io.ros.client.Client.wait`).
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from typing import Any

from ifgm_ref.io.ros.client import Registration, Shutdown, client
from ifgm_ref.io.ros.messages import Message, to_wire
from ifgm_ref.io.ros.names import split_argv
from ifgm_ref.io.ros.rostime import NS, Duration, Time, nanoseconds

__all__ = [
    "Duration",
    "Publisher",
    "ROSException",
    "ROSInterruptException",
    "Rate",
    "Subscriber",
    "Time",
    "Timer",
    "TimerEvent",
    "get_name",
    "get_rostime",
    "get_time",
    "init_node",
    "is_shutdown",
    "myargv",
    "on_shutdown",
    "signal_shutdown",
    "sleep",
    "spin",
    "wait_for_message",
]


class ROSException(Exception):
    """rospy's base exception (a wait that timed out raises it)."""


class ROSInterruptException(ROSException, KeyboardInterrupt):
    """Raised by a sleep that the node's shutdown interrupted."""


def init_node(
    name: str, argv: Sequence[str] | None = None, anonymous: bool = False, **_ignored: Any
) -> None:
    """Start the node ``name`` (see :mod:`ifgm_ref.io.ros.client`: it returns in an episode)."""
    client().init_node(name, anonymous, list(sys.argv if argv is None else argv))


def get_name() -> str:
    """The node's global name."""
    return client().name


def myargv(argv: Sequence[str] | None = None) -> list[str]:
    """``argv`` without the ROS arguments (``name:=value``)."""
    return split_argv(list(sys.argv if argv is None else argv))[0]


def get_time() -> float:
    """The simulated time, s."""
    return client().now / NS


def get_rostime() -> Time:
    """The simulated time."""
    return Time.from_nsec(client().now)


def is_shutdown() -> bool:
    """Whether the node was shut down."""
    return client().shutdown is not None


def signal_shutdown(reason: str) -> None:
    """Shut the node down (the stand-in counts it as ``done``)."""
    client().signal_shutdown(reason)


def on_shutdown(hook: Callable[..., Any]) -> None:
    """Call ``hook`` at shutdown."""
    client().shutdown_hooks.append(hook)


def _interruptible(wait: Callable[[], Any]) -> Any:
    try:
        return wait()
    except Shutdown as stop:
        raise ROSInterruptException(f"rospy shutdown: {stop}") from None


def sleep(duration: float | Duration) -> None:
    """Sleep ``duration`` (s or a Duration) of simulated time; callbacks run meanwhile."""
    span = duration.to_nsec() if isinstance(duration, Duration) else nanoseconds(duration)
    until = client().now + max(span, 0)
    _interruptible(lambda: client().wait(until=until))


def spin() -> None:
    """Run callbacks until the node shuts down."""
    try:
        client().wait(condition=lambda: False)
    except Shutdown:
        return


class Rate:
    """A loop rate in Hz on simulated time (rospy's ``Rate``: it keeps the loop's phase, and
    restarts it when the loop fell behind by more than a period)."""

    def __init__(self, hz: float, reset: bool = False) -> None:
        self.period = nanoseconds(1.0 / hz)
        self.last = client().now

    def remaining(self) -> Duration:
        """What is left of the current period."""
        return Duration.from_nsec(self.last + self.period - client().now)

    def sleep(self) -> None:
        """Sleep to the end of the current period."""
        now = client().now
        if now < self.last:
            self.last = now
        until = self.last + self.period
        _interruptible(lambda: client().wait(until=until))
        self.last = until
        if client().now - self.last > self.period:
            self.last = client().now


class Publisher:
    """A publisher of ``data_class`` messages on ``name``."""

    def __init__(
        self,
        name: str,
        data_class: type[Message],
        queue_size: int | None = None,
        latch: bool = False,
        **_ignored: Any,
    ) -> None:
        self.data_class = data_class
        self.type = data_class._type
        self._registration = client().register(Registration("adv", name, self.type, latch=latch))
        self.name = self._registration.resolved or name

    @property
    def resolved_name(self) -> str:
        """The topic's global name."""
        return self._registration.resolved

    def publish(self, *args: Any, **kwargs: Any) -> None:
        """Publish a message (or the fields of one, as rospy allows)."""
        if len(args) == 1 and not kwargs and isinstance(args[0], Message):
            message = args[0]
        else:
            message = self.data_class(*args, **kwargs)
        if not isinstance(message, self.data_class):
            raise ROSException(f"expected a {self.type} on {self.name}, got {message!r:.80}")
        line = {"op": "pub", "name": self._registration.resolved, "type": self.type}
        client().send({**line, "data": to_wire(message)})

    def get_num_connections(self) -> int:
        """How many subscribers listen (unknown to a node here: 1)."""
        return 1

    def unregister(self) -> None:
        """Stop publishing (nothing to undo here)."""


class Subscriber:
    """A subscriber calling ``callback(message[, callback_args])`` for each message."""

    def __init__(
        self,
        name: str,
        data_class: type[Message],
        callback: Callable[..., Any] | None = None,
        callback_args: Any = None,
        queue_size: int | None = None,
        **_ignored: Any,
    ) -> None:
        self.data_class = data_class
        self.callback = callback

        def handle(message: Message) -> None:
            if callback is None:
                return
            if callback_args is None:
                callback(message)
            else:
                callback(message, callback_args)

        registration = Registration("sub", name, data_class._type, handler=handle)
        self._registration = client().register(registration)
        self.name = self._registration.resolved or name

    def unregister(self) -> None:
        """Stop calling the callback."""
        client().unregister(self._registration)


def wait_for_message(topic: str, topic_type: type[Message], timeout: float | None = None) -> Any:
    """Wait for the next message on ``topic`` and return it.

    Raises
    ------
    ROSException
        When ``timeout`` s of simulated time pass first.
    """
    got: list[Message] = []
    subscriber = Subscriber(topic, topic_type, got.append)
    until = None if timeout is None else client().now + nanoseconds(timeout)
    try:
        arrived = _interruptible(lambda: client().wait(until=until, condition=lambda: bool(got)))
    finally:
        subscriber.unregister()
    if not arrived:
        raise ROSException(f"timeout exceeded while waiting for a message on topic {topic}")
    return got[0]


class TimerEvent:
    """What a timer's callback is given (rospy's ``TimerEvent``)."""

    def __init__(
        self,
        last_expected: Time | None,
        last_real: Time | None,
        current_expected: Time,
        current_real: Time,
        last_duration: float | None,
    ) -> None:
        self.last_expected, self.last_real = last_expected, last_real
        self.current_expected, self.current_real = current_expected, current_real
        self.last_duration = last_duration


class Timer:
    """Call ``callback(TimerEvent)`` every ``period`` of simulated time (once if ``oneshot``)."""

    def __init__(
        self,
        period: Duration,
        callback: Callable[[TimerEvent], Any],
        oneshot: bool = False,
        reset: bool = False,
    ) -> None:
        self.period = period.to_nsec() if isinstance(period, Duration) else nanoseconds(period)
        if self.period <= 0:
            raise ROSException("a timer's period must be longer than 0 s")
        self.callback, self.oneshot = callback, oneshot
        self.due: int | None = client().now + self.period
        self.last: int | None = None
        client().timers.append(self)

    def fire(self) -> None:
        """Run the callback for the period that ended (called by the client's loop)."""
        assert self.due is not None
        expected, now = self.due, client().now
        last = None if self.last is None else Time.from_nsec(self.last)
        event = TimerEvent(last, last, Time.from_nsec(expected), Time.from_nsec(now), 0.0)
        self.last = expected
        self.due = None if self.oneshot else expected + self.period
        self.callback(event)

    def shutdown(self) -> None:
        """Stop the timer."""
        self.due = None
        if self in client().timers:
            client().timers.remove(self)
