"""ROS 1's ``Time`` and ``Duration`` (rospy's ``genpy`` classes), on integer nanoseconds.

A node under the stand-in reads only simulated time: :func:`ifgm_ref.io.ros.rospy.get_time` and
``Time.now()`` give the clock the broker set (:mod:`ifgm_ref.io.ros.client`), never the wall
clock. Both classes keep ``secs`` and ``nsecs`` as rospy's do, normalised so that
``0 <= nsecs < 1e9``, and compute on whole nanoseconds, so that time arithmetic is exact and
the same on every run.

>>> t = Time(1, 500_000_000) + Duration.from_sec(0.25)
>>> t.secs, t.nsecs, t.to_sec()
(1, 750000000, 1.75)
>>> (Time.from_sec(2.0) - t).to_sec()
0.25
"""

from __future__ import annotations

from collections.abc import Callable
from functools import total_ordering
from typing import Any, Self

from ifgm_ref.core.validate import violation

__all__ = ["Duration", "Time", "nanoseconds", "set_clock"]

#: Nanoseconds per second.
NS = 1_000_000_000


def nanoseconds(seconds: float) -> int:
    """``seconds`` as a whole number of nanoseconds (rounded to the nearest).

    >>> nanoseconds(0.1), nanoseconds(1 / 3)
    (100000000, 333333333)
    """
    if why := violation(seconds):
        raise ValueError(f"a time in s {why}")
    return round(seconds * NS)


#: What reads the node's clock, ns (:func:`set_clock`; 0 until a node's client sets it).
_CLOCK: list[Callable[[], int]] = [lambda: 0]


def set_clock(read: Callable[[], int]) -> None:
    """Make ``Time.now()`` read ``read()`` (the client's simulated clock, ns)."""
    _CLOCK[0] = read


@total_ordering
class _Span:
    """What :class:`Time` and :class:`Duration` share: ``secs``, ``nsecs``, conversions."""

    __slots__ = ("nsecs", "secs")

    def __init__(self, secs: float = 0, nsecs: int = 0) -> None:
        if isinstance(secs, float):  # rospy accepts Time(1.5) for 1.5 s
            total = nanoseconds(secs) + int(nsecs)
        else:
            total = int(secs) * NS + int(nsecs)
        self.secs, self.nsecs = divmod(total, NS)

    @classmethod
    def from_sec(cls, seconds: float) -> Self:
        """The span of ``seconds`` s (rounded to the nanosecond)."""
        return cls(0, nanoseconds(seconds))

    @classmethod
    def from_nsec(cls, ns: int) -> Self:
        """The span of ``ns`` nanoseconds."""
        return cls(0, int(ns))

    def to_nsec(self) -> int:
        """The span in nanoseconds."""
        return self.secs * NS + self.nsecs

    def to_sec(self) -> float:
        """The span in seconds."""
        return self.to_nsec() / NS

    def is_zero(self) -> bool:
        """Whether the span is zero."""
        return self.to_nsec() == 0

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, _Span):
            return NotImplemented
        return self.to_nsec() == other.to_nsec()

    def __lt__(self, other: object) -> bool:
        if not isinstance(other, _Span):
            return NotImplemented
        return self.to_nsec() < other.to_nsec()

    def __hash__(self) -> int:
        return hash(self.to_nsec())

    def __bool__(self) -> bool:
        return not self.is_zero()

    def __repr__(self) -> str:
        return f"{type(self).__name__}[{self.to_nsec()}]"

    def __str__(self) -> str:
        return str(self.to_nsec())


class Duration(_Span):
    """A signed span of time (rospy's ``rospy.Duration``)."""

    __slots__ = ()

    def __add__(self, other: Any) -> Any:
        if isinstance(other, Time):
            return Time.from_nsec(self.to_nsec() + other.to_nsec())
        if isinstance(other, Duration):
            return Duration.from_nsec(self.to_nsec() + other.to_nsec())
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: Any) -> Any:
        if isinstance(other, Duration):
            return Duration.from_nsec(self.to_nsec() - other.to_nsec())
        return NotImplemented

    def __neg__(self) -> Duration:
        return Duration.from_nsec(-self.to_nsec())

    def __abs__(self) -> Duration:
        return Duration.from_nsec(abs(self.to_nsec()))

    def __mul__(self, factor: float) -> Duration:
        return Duration.from_nsec(round(self.to_nsec() * factor))

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> Any:
        if isinstance(other, Duration):
            return self.to_nsec() / other.to_nsec()
        return Duration.from_nsec(round(self.to_nsec() / other))


class Time(_Span):
    """A point in (simulated) time since the episode's start (rospy's ``rospy.Time``)."""

    __slots__ = ()

    @staticmethod
    def now() -> Time:
        """The node's current simulated time (``rospy.Time.now()``)."""
        return Time.from_nsec(_CLOCK[0]())

    def __add__(self, other: Any) -> Any:
        if isinstance(other, Duration):
            return Time.from_nsec(self.to_nsec() + other.to_nsec())
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: Any) -> Any:
        if isinstance(other, Time):
            return Duration.from_nsec(self.to_nsec() - other.to_nsec())
        if isinstance(other, Duration):
            return Time.from_nsec(self.to_nsec() - other.to_nsec())
        return NotImplemented
