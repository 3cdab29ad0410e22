"""ROS 1 graph names: resolution, remapping, and what ``rosrun`` passes on a command line.

A node's namespace is ``/`` here (nodes are not pushed into namespaces), so a relative name
``scan`` resolves to ``/scan`` and a private name ``~goal_x`` of node ``/bug2`` to
``/bug2/goal_x``. Remappings ``from:=to`` apply to the resolved name, as ROS 1 applies them;
a command-line argument ``_name:=value`` sets the private parameter ``~name``, its value read
as YAML scalars are (:func:`scalar`), and ``__name:=NAME`` renames the node.

>>> resolve("scan", "/bug2", {"/scan": "/base_scan"})
'/base_scan'
>>> resolve("~goal_x", "/bug2")
'/bug2/goal_x'
>>> split_argv(["node.py", "_rate:=20", "cmd_vel:=/robot/cmd_vel", "--fast"])
(['node.py', '--fast'], {'/cmd_vel': '/robot/cmd_vel'}, {'rate': 20}, None)
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

__all__ = ["parse_remap", "resolve", "scalar", "split_argv", "split_ros2_argv"]


def resolve(name: str, node: str, remaps: Mapping[str, str] | None = None) -> str:
    """The global name of ``name`` used by node ``node`` (``/bug2``), remapped."""
    if not name:
        raise ValueError("a graph name cannot be empty")
    if name.startswith("~"):
        full = f"{node.rstrip('/')}/{name[1:].lstrip('/')}"
    elif name.startswith("/"):
        full = name
    else:
        full = "/" + name
    full = "/" + "/".join(part for part in full.split("/") if part)
    return (remaps or {}).get(full, full)


def parse_remap(text: str) -> tuple[str, str]:
    """A remapping ``from:=to`` (ROS's syntax) as two global names.

    >>> parse_remap("/scan:=/base_scan")
    ('/scan', '/base_scan')
    >>> parse_remap("scan")
    Traceback (most recent call last):
    ...
    ValueError: remapping 'scan': expected FROM:=TO, as ROS writes it
    """
    source, sep, target = text.partition(":=")
    if not sep or not source or not target or source.startswith(("_", "~")):
        raise ValueError(f"remapping {text!r}: expected FROM:=TO, as ROS writes it")
    return resolve(source, "/"), resolve(target, "/")


def scalar(text: str) -> Any:
    """A parameter value given as text, read as a YAML scalar: int, float, bool or string.

    >>> scalar("3"), scalar("0.5"), scalar("true"), scalar("base_link")
    (3, 0.5, True, 'base_link')
    """
    lowered = text.strip().lower()
    if lowered in ("true", "false"):
        return lowered == "true"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def split_argv(
    argv: Sequence[str],
) -> tuple[list[str], dict[str, str], dict[str, Any], str | None]:
    """Split a node's argv as rospy does: the arguments left for the node
    (``rospy.myargv()``), the remappings, the private parameters and the ``__name``."""
    left: list[str] = []
    remaps: dict[str, str] = {}
    private: dict[str, Any] = {}
    name: str | None = None
    for arg in argv:
        source, sep, target = arg.partition(":=")
        if not sep or not source:
            left.append(arg)
        elif source == "__name":
            name = target
        elif source.startswith("__"):
            continue  # __ns, __log, __ip, __master: nothing to do here
        elif source.startswith("_"):
            private[source[1:]] = scalar(target)
        else:
            remaps[resolve(source, "/")] = resolve(target, "/")
    return left, remaps, private, name


def split_ros2_argv(
    argv: Sequence[str],
) -> tuple[list[str], dict[str, str], dict[str, Any], str | None]:
    """Split a ROS 2 node's argv as rclpy does (``--ros-args -p name:=value -r from:=to``,
    ``-r __node:=name``, up to ``--``), in :func:`split_argv`'s four parts.

    >>> split_ros2_argv(["n.py", "--ros-args", "-p", "rate:=20", "-r", "scan:=/base_scan"])
    (['n.py'], {'/scan': '/base_scan'}, {'rate': 20}, None)
    """
    left: list[str] = []
    remaps: dict[str, str] = {}
    params: dict[str, Any] = {}
    name: str | None = None
    inside, expect = False, ""
    for arg in argv:
        if not inside:
            inside = arg == "--ros-args"
            if not inside:
                left.append(arg)
        elif arg == "--":
            inside = False
        elif arg in ("-p", "--param", "-r", "--remap"):
            expect = arg.lstrip("-")[0]
        elif expect:
            source, _, target = arg.partition(":=")
            if expect == "p":
                params[source] = scalar(target)
            elif source == "__node":
                name = target
            else:
                remaps[resolve(source, "/")] = resolve(target, "/")
            expect = ""
    return left, remaps, params, name
