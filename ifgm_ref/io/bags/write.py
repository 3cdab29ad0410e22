"""Write a recorded run as a ROS bag: MCAP, a ROS 1 bag, or a rosbag2 folder (sqlite3).

The path's suffix says which (:func:`bag_format`):

* ``FILE.mcap``: one standalone MCAP file (ROS 2 profile, CDR messages, ``ros2msg``
  schemas) that Foxglove and PlotJuggler open as it is and ``ros2 bag play FILE.mcap``
  plays.
* ``FILE.bag``: a ROS 1 bag (ROS Noetic's message definitions), for ``rosbag play``, RViz 1
  and the ROS 1 tools.
* a path without suffix: a rosbag2 folder (``metadata.yaml`` and a ``.db3`` sqlite3 file),
  ROS 2's format before MCAP; the folder must not exist.

The messages are those of :func:`ifgm_ref.io.bags.messages.run_messages`, with ROS 2 Humble's
message definitions. The latched topics (published once) are offered transient-local, depth
1, so a late subscriber still gets them; the others reliable and volatile, depth 10, as
``rclcpp``'s default. The bag is written by ``rosbags`` (pure Python; no ROS install needed),
rosbag2 metadata version 8, whose QoS profiles ROS 2 Humble reads. The same run written to
the same file name gives the same bytes: nothing in a bag depends on the clock or the machine
(the MCAP header names the rosbags version that wrote it, and the rosbag2 metadata, in the
MCAP file too, the storage file's name).
"""

from __future__ import annotations

import io
import os
import tempfile
from collections.abc import Iterable
from contextlib import redirect_stdout
from enum import StrEnum
from pathlib import Path
from typing import Literal

from rosbags.convert import convert
from rosbags.interfaces import (
    Qos,
    QosDurability,
    QosHistory,
    QosLiveliness,
    QosReliability,
    QosTime,
)
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.recording import Recording
from ifgm_ref.io.bags.messages import TOPICS, Stamped, run_messages
from ifgm_ref.sim.simulator import Run
from ifgm_ref.sim.world import World


class BagFormat(StrEnum):
    """The bag formats :func:`write_bag` writes."""

    #: One MCAP file, ROS 2 (``FILE.mcap``).
    MCAP = "mcap"
    #: A ROS 1 bag (``FILE.bag``).
    ROS1 = "ros1"
    #: A rosbag2 folder with sqlite3 storage (a path without suffix).
    SQLITE3 = "sqlite3"


#: The format of each path suffix (the empty suffix: a rosbag2 folder).
BAG_SUFFIXES = {".mcap": BagFormat.MCAP, ".bag": BagFormat.ROS1, "": BagFormat.SQLITE3}
#: The path forms :func:`write_bag` takes, as its errors and ``--record``'s help name them.
BAG_FORMS = "FILE.mcap (ROS 2, MCAP), FILE.bag (ROS 1) or FOLDER without suffix (ROS 2, sqlite3)"
#: The rosbag2 metadata version written: 8, the newest whose QoS profiles Humble reads.
ROSBAG2_VERSION: Literal[8] = 8

#: A duration left to the middleware's default (infinite): deadline, lifespan, lease.
_DEFAULT_DURATION = QosTime(sec=0, nsec=0)
#: The QoS offered on a topic published every step: rclcpp's default.
STREAM_QOS = Qos(
    QosHistory.KEEP_LAST,
    10,
    QosReliability.RELIABLE,
    QosDurability.VOLATILE,
    _DEFAULT_DURATION,
    _DEFAULT_DURATION,
    QosLiveliness.AUTOMATIC,
    _DEFAULT_DURATION,
    avoid_ros_namespace_conventions=False,
)
#: The QoS offered on a topic published once (tf2's static broadcaster's, a latched topic).
LATCHED_QOS = STREAM_QOS._replace(depth=1, durability=QosDurability.TRANSIENT_LOCAL)


def bag_format(path: str | Path, option: str = "bag") -> BagFormat:
    """The format a bag at ``path`` is written in, by its suffix (in any case).

    A suffix other than ``.mcap`` and ``.bag`` is a :class:`ParameterError` naming
    ``option``, as is a folder (no suffix) that exists already: rosbag2 writes a new one.

    >>> bag_format("run.mcap"), bag_format("run.BAG"), bag_format("runs/one")
    (<BagFormat.MCAP: 'mcap'>, <BagFormat.ROS1: 'ros1'>, <BagFormat.SQLITE3: 'sqlite3'>)
    >>> bag_format("run.db3", "--record")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: --record run.db3: cannot write .db3; use FILE.mcap ...
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in BAG_SUFFIXES:
        raise ParameterError(f"{option} {path}: cannot write {suffix}; use {BAG_FORMS}")
    form = BAG_SUFFIXES[suffix]
    if form is BagFormat.SQLITE3 and path.exists():
        raise ParameterError(
            f"{option} {path}: the folder exists, and a rosbag2 folder is written new: "
            "remove it or name another"
        )
    return form


def write_bag(
    path: str | Path, world: World, run: Run, recording: Recording, unit: str
) -> BagFormat:
    """Write ``run`` as a bag at ``path``; return its format.

    Parameters
    ----------
    path : str or Path
        ``FILE.mcap``, ``FILE.bag`` or a folder without suffix (:func:`bag_format`); a file
        there is replaced, whole, when the bag is complete. Its folder must exist.
    world : World
        The world of the run.
    run : Run
        The run: its planner's name and its trace.
    recording : Recording
        What the planner was handed and answered in the run: simulate with a
        :class:`~ifgm_ref.core.recording.RecordingPlanner` and take its ``recording()``.
    unit : str
        The world's length unit, ``"ft"`` or ``"m"``: lengths are written in metres.

    Raises
    ------
    ParameterError
        For a path :func:`bag_format` refuses, or an unknown ``unit``.
    ValueError
        When ``recording`` is not that of ``run``.
    """
    path = Path(path)
    form = bag_format(path)
    messages = run_messages(run, recording, world, unit)
    if form is BagFormat.SQLITE3:
        _write_rosbag2(path, StoragePlugin.SQLITE3, messages)
        return form
    # Write beside the target, then move the complete file in place (a rename).
    with tempfile.TemporaryDirectory(dir=path.parent, prefix=".ifgm-ref-bag-") as scratch:
        folder = Path(scratch) / path.stem
        _write_rosbag2(folder, StoragePlugin.MCAP, messages)
        written = folder / f"{path.stem}.mcap"
        if form is BagFormat.ROS1:
            written = Path(scratch) / "ros1.bag"
            _convert_to_ros1(folder, written)
        os.replace(written, path)
    return form


def _write_rosbag2(folder: Path, storage: StoragePlugin, messages: Iterable[Stamped]) -> None:
    """Write ``messages`` as a new rosbag2 folder ``folder`` with ``storage``."""
    typestore = get_typestore(Stores.ROS2_HUMBLE)
    with Writer(folder, version=ROSBAG2_VERSION, storage_plugin=storage) as writer:
        connections = {
            topic.name: writer.add_connection(
                str(topic.name),
                topic.msgtype,
                typestore=typestore,
                offered_qos_profiles=[LATCHED_QOS if topic.latched else STREAM_QOS],
            )
            for topic in TOPICS
        }
        msgtypes = {topic.name: topic.msgtype for topic in TOPICS}
        for item in messages:
            data = typestore.serialize_cdr(item.message, msgtypes[item.topic])
            writer.write(connections[item.topic], item.stamp, data)


def _convert_to_ros1(folder: Path, bag: Path) -> None:
    """Convert the rosbag2 ``folder`` to the ROS 1 bag ``bag``, every message migrated to
    ROS Noetic's definition (the headers gain ``seq`` = 0, a marker loses ROS 2's fields),
    the transient-local topics latched. The converter's notes on stdout are dropped: they
    are no output of ours (``simulate --json`` prints one JSON object)."""
    with redirect_stdout(io.StringIO()):
        convert(
            srcs=[folder],
            dst=bag,
            dst_storage="",
            dst_version=0,
            compress=None,
            compress_mode="",
            default_typestore=None,
            typestore=get_typestore(Stores.ROS1_NOETIC),
            exclude_topics=[],
            include_topics=[],
            exclude_msgtypes=[],
            include_msgtypes=[],
        )
