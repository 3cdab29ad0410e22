"""rospy's parameter server calls and logging, for the stand-in.

Parameters live in the node (a copy of the broker's server, which the broker keeps in step:
a ``set_param`` reaches the other nodes before they next run). Names resolve as ROS 1's do
(``~private``, ``relative``, ``/global``); a name that is a namespace gives a dict of what is
under it. Logging goes to stderr, stamped with the simulated time; ``logdebug`` is dropped, as
at rospy's default level.
"""

from __future__ import annotations

import sys
from typing import Any

from ifgm_ref.io.ros.client import client

__all__ = [
    "delete_param",
    "get_param",
    "get_param_names",
    "has_param",
    "logdebug",
    "logerr",
    "logfatal",
    "loginfo",
    "logwarn",
    "search_param",
    "set_param",
]

_MISSING = object()


def get_param(name: str, default: Any = _MISSING) -> Any:
    """The parameter ``name`` (or the dict of a namespace); ``default`` if it is not set.

    Raises
    ------
    KeyError
        When it is not set and no default is given.
    """
    node = client()
    full = node.resolve(name)
    if full in node.params:
        return node.params[full]
    prefix = full.rstrip("/") + "/"
    inside = {k[len(prefix) :]: v for k, v in node.params.items() if k.startswith(prefix)}
    if inside:
        tree: dict[str, Any] = {}
        for key, value in sorted(inside.items()):
            *path, last = key.split("/")
            branch = tree
            for part in path:
                branch = branch.setdefault(part, {})
            branch[last] = value
        return tree
    if default is _MISSING:
        raise KeyError(full)
    return default


def set_param(name: str, value: Any) -> None:
    """Set the parameter ``name`` (for every node)."""
    node = client()
    full = node.resolve(name)
    node.params[full] = value
    node.send({"op": "set_param", "name": full, "value": value})


def has_param(name: str) -> bool:
    """Whether ``name`` is set."""
    return get_param(name, _MISSING) is not _MISSING


def delete_param(name: str) -> None:
    """Unset ``name`` (in this node).

    Raises
    ------
    KeyError
        When it is not set.
    """
    del client().params[client().resolve(name)]


def search_param(name: str) -> str | None:
    """The global name of ``name`` if set (the node's namespace is ``/``)."""
    for candidate in (client().resolve("~" + name), client().resolve(name)):
        if has_param(candidate):
            return candidate
    return None


def get_param_names() -> list[str]:
    """Every parameter's name."""
    return sorted(client().params)


def _log(level: str, message: Any, *args: Any) -> None:
    text = str(message) % args if args else str(message)
    print(f"[{level}] [{client().now / 1e9:.3f}] {client().name}: {text}", file=sys.stderr)


def loginfo(message: Any, *args: Any, **_ignored: Any) -> None:
    """Log at level INFO."""
    _log("INFO", message, *args)


def logwarn(message: Any, *args: Any, **_ignored: Any) -> None:
    """Log at level WARN."""
    _log("WARN", message, *args)


def logerr(message: Any, *args: Any, **_ignored: Any) -> None:
    """Log at level ERROR."""
    _log("ERROR", message, *args)


def logfatal(message: Any, *args: Any, **_ignored: Any) -> None:
    """Log at level FATAL."""
    _log("FATAL", message, *args)


def logdebug(message: Any, *args: Any, **_ignored: Any) -> None:
    """Log at level DEBUG: dropped."""


_LAST: dict[tuple[str, str], int] = {}


def _throttled(level: str, period: float, message: Any, *args: Any) -> None:
    key, now = (level, str(message)), client().now
    if key not in _LAST or now - _LAST[key] >= period * 1e9:
        _LAST[key] = now
        _log(level, message, *args)


def _once(level: str, message: Any, *args: Any) -> None:
    key = (level + "#once", str(message))
    if key not in _LAST:
        _LAST[key] = 0
        _log(level, message, *args)


def _variants() -> dict[str, Any]:
    """``loginfo_throttle(period, msg)``, ``loginfo_once(msg)`` and so on for every level."""
    found: dict[str, Any] = {}
    for level in ("debug", "info", "warn", "err", "fatal"):
        tag = {"err": "ERROR", "warn": "WARN"}.get(level, level.upper())
        if level == "debug":
            found["logdebug_throttle"] = lambda period, msg, *a, **k: None
            found["logdebug_once"] = lambda msg, *a, **k: None
            continue
        found[f"log{level}_throttle"] = lambda period, msg, *a, _t=tag, **k: _throttled(
            _t, period, msg, *a
        )
        found[f"log{level}_once"] = lambda msg, *a, _t=tag, **k: _once(_t, msg, *a)
    return found


globals().update(_variants())
__all__ += sorted(_variants())
