"""BARN: the Benchmark for Autonomous Robot Navigation's static worlds, task, and score.

BARN (Perille, Truong, Xiao, Stone, "Benchmarking Metric Ground Navigation", SSRR 2020; the
repository ``Daffan/the-barn-challenge``, MIT licence) gives 300 Gazebo worlds
``world_N.world`` and reference paths ``path_N.npy``. 200 of them (indices ``N % 3 != 0``)
ship with this package (:data:`BUNDLED`, :func:`bundled_barn_folder`); their README beside
them sums up the facts used here, and each constant below gives its source or reason.

The worlds' enclosure is in the files: every one of the 200 bundled worlds holds, besides the
obstacle field, cylinders along ``x = -4.425`` and ``x = -0.075`` from ``y = 0.075`` to
``y = 9.525`` and along ``y = 0.075`` (touching cylinders of radius 0.075 m 0.15 m apart:
closed walls). The side beyond ``y = 9.6``, towards the goal, is open ground in Gazebo too,
so a BARN world here is unbounded (``bounds=None``) with those walls as obstacles, exactly
what the robot meets in BARN.

Units are metres and seconds.
"""

from __future__ import annotations

import hashlib
import io
import math
import os
import re
import shutil
import tarfile
import tempfile
from collections.abc import Collection
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ifgm_ref.core.cache import user_cache
from ifgm_ref.core.errors import ParameterError, WorldError
from ifgm_ref.core.params import SENSOR_PRESETS, RobotParams, SensorParams, SimParams, paper_ir
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.validate import POSITIVE, require
from ifgm_ref.io.gazebo import load_sdf_world
from ifgm_ref.sim.physics.bodies import JACKAL_RADIUS
from ifgm_ref.sim.world import World

#: BARN's start, ``run.py``'s ``INIT_POSITION = [-2, 3, 1.57]``: heading +y (1.57 ~ pi/2).
START = Pose(-2.0, 3.0, math.pi / 2)
#: BARN's goal: ``INIT_POSITION`` plus ``GOAL_POSITION = [0, 10]``, 10 m ahead of the start.
GOAL = Point(-2.0, 13.0)
#: The robot. A disc of radius 0.22 m: half the Jackal's 0.430 m width (its 0.508 m length
#: would need a 0.33 m disc, which BARN's narrowest gaps do not admit; BARN's reference paths
#: are planned for the width). 1.0 m/s, half the Jackal's 2 m/s top speed. pi rad/s turn
#: rate: the Jackal turns well faster, but pi rad/s makes the turning radius v / w = 0.32 m,
#: near the robot's size, so the turn rate does not make the planners' turns wide.
ROBOT = RobotParams(radius=JACKAL_RADIUS, speed=1.0, max_turn_rate=math.pi)
#: The episode. 0.05 s steps move the robot 0.05 m, about a quarter of its radius; BARN's
#: success radius is 1 m and its time limit 100 s (``barn_worlds/README.md``). BARN knows
#: no stall, only arrival within the limit: a robot the disc rule stops would still be there
#: at 100 s, but one the lap rule stops may get away on a later lap (7 of 514 arrivals of
#: Bug1, IBA and IFGM in the 200 worlds did, after 2 to 8 laps round a cluster:
#: ``benchmarks/bench_stall.py``), so BARN episodes run without the lap rule.
SIM = SimParams(dt=0.05, max_time=100.0, goal_tolerance=1.0, stall_laps=None)
#: Speed of BARN's optimal time ``t_opt = L / 2 m/s``: the Jackal's top speed.
OPTIMAL_SPEED = 2.0
#: BARN's cell: twice the obstacle cylinders' radius 0.075 m.
CELL = 0.15
#: Default sensor preset (``ifgm_ref.core.params.SENSOR_PRESETS``): the Jackal's LiDAR.
DEFAULT_SENSOR = "jackal_lidar"
#: Obstacle cylinders' radius in BARN's worlds, m.
CYLINDER_RADIUS = 0.075

_WORLD = re.compile(r"world_(\d+)\.world")

#: BARN's world indices: ``world_N.world`` for N = 0-299.
INDICES = range(300)
#: The indices of the bundled worlds (:data:`BUNDLED`): the 200 with ``N % 3 != 0``.
BUNDLED_INDICES = frozenset(n for n in INDICES if n % 3)


def barn_sensor(name: str = DEFAULT_SENSOR) -> SensorParams:
    """The sensor preset ``name``: ``jackal_lidar`` (BARN's) or ``paper_ir`` (the paper's IR
    sensor scaled to the 0.22 m robot: ``paper_ir(0.22)``, as the paper's robot is a 1 ft
    disc)."""
    if name == "paper_ir":
        return paper_ir(ROBOT.radius)
    if name in SENSOR_PRESETS:
        return SENSOR_PRESETS[name]()
    raise ParameterError(f"unknown sensor {name!r}; known: {', '.join(SENSOR_PRESETS)}")


def cell_to_world(row: float, col: float) -> tuple[float, float]:
    """BARN's grid cell ``(row, col)`` in world coordinates, as ``run.py`` converts it.

    ``x = row * 0.15 - 0.075 - 4.5``, ``y = col * 0.15 + 0.075 + 5``.

    >>> cell_to_world(0, 0)
    (-4.575, 5.075)
    """
    x = row * CELL - CELL / 2 - 30 * CELL
    y = col * CELL + CELL / 2 + 5.0
    return (round(x, 12), round(y, 12))


def reference_length(path_npy: str | os.PathLike[str]) -> float:
    """The length L of BARN's reference path for one world, m, as BARN's ``run.py`` has it.

    The cells of ``path_N.npy`` in world coordinates (:func:`cell_to_world`), with the start
    put in front and the goal behind, joined by straight segments.
    """
    try:
        cells = np.load(path_npy, allow_pickle=False)
    except (OSError, ValueError) as err:
        raise WorldError(f"{path_npy}: cannot read a BARN path: {err}") from None
    if cells.ndim != 2 or cells.shape[1] != 2 or not np.issubdtype(cells.dtype, np.number):
        raise WorldError(f"{path_npy}: expected an (n, 2) array of cells, got {cells.shape}")
    points = [START.position, *(cell_to_world(r, c) for r, c in cells.tolist()), GOAL]
    xy = np.asarray(points, dtype=np.float64)
    return float(np.hypot(*np.diff(xy, axis=0).T).sum())


def barn_score(success: bool, time_s: float, reference_length: float) -> float:
    """BARN's score of one run: ``success * t_opt / clip(t, 2 t_opt, 8 t_opt)``.

    ``t_opt = L / 2 m/s``; the best score is 0.5 (a run in at most twice the optimal time).

    >>> barn_score(True, 5.0, 10.0), barn_score(True, 10.0, 10.0), barn_score(False, 5.0, 10.0)
    (0.5, 0.5, 0.0)
    """
    if not success:
        return 0.0
    require("reference_length", reference_length, POSITIVE)
    t_opt = reference_length / OPTIMAL_SPEED
    return t_opt / float(np.clip(time_s, 2.0 * t_opt, 8.0 * t_opt))


@dataclass(frozen=True)
class BarnFiles:
    """One BARN world: its index, its ``world_N.world`` and its ``path_N.npy``."""

    index: int
    world: Path
    path: Path


#: BARN's 200 worlds with ``N % 3 != 0`` and their paths, exactly as BARN ships them (commit
#: bf5a226), in one xz-compressed tarball (296 KB) that unpacks to ``barn/``; BARN's MIT
#: licence is beside it.
BUNDLED = Path(__file__).parent / "barn_worlds" / "barn-200.tar.xz"


def bundled_barn_folder() -> Path:
    """The folder of the bundled worlds (``world_N.world``, ``path_N.npy``), unpacked from
    :data:`BUNDLED` at the first call into :func:`~ifgm_ref.core.cache.user_cache`, under the
    tarball's hash, then reused.

    Only regular files named ``barn/world_N.world`` or ``barn/path_N.npy`` are unpacked; two
    processes unpacking at once each unpack into a folder of their own and keep the first
    that lands.
    """
    data = BUNDLED.read_bytes()
    cache = user_cache()
    folder = cache / f"barn-200-{hashlib.sha256(data).hexdigest()[:12]}"
    if folder.is_dir():
        return folder
    cache.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix="barn-200-", dir=cache))
    try:
        with tarfile.open(fileobj=io.BytesIO(data), mode="r:xz") as tar:
            for member in tar.getmembers():
                name = member.name.removeprefix("barn/")
                source = tar.extractfile(member) if member.isfile() else None
                if source is not None and re.fullmatch(r"(world|path)_\d+\.(world|npy)", name):
                    (staging / name).write_bytes(source.read())
        staging.rename(folder)
    except OSError:
        if not folder.is_dir():  # not another process's folder landing first
            raise
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return folder


def _world_folder(folder: Path) -> Path:
    """Where the ``world_N.world`` files are: ``folder`` itself (the unpacked tarball, or the
    repository's ``worlds/BARN``) or the repository layout ``jackal_helper/worlds/BARN``."""
    for candidate in (folder, folder / "jackal_helper" / "worlds" / "BARN"):
        if any(_WORLD.fullmatch(p.name) for p in candidate.glob("world_*.world")):
            return candidate
    raise WorldError(
        f"no BARN worlds (world_N.world) in {folder} or {folder}/jackal_helper/worlds/BARN"
    )


class MissingWorlds(WorldError):
    """BARN worlds asked for that are not where they were looked for; ``names`` are they, as
    ``barn:N`` (the text after ``barn:`` when it is no index)."""

    def __init__(self, message: str, names: tuple[str, ...]) -> None:
        super().__init__(message)
        self.names = names


def missing_worlds(
    names: Collection[str], where: str, *, option: str = "", prefix: str = ""
) -> MissingWorlds:
    """The error for the BARN worlds ``names`` (``barn:N``) that are not in ``where`` (a
    folder, or the bundled set): one message whatever N, stating BARN's range, what ships
    with ifgm-ref and how to get the others (with ``option``, the command line's way to give
    a folder, if any), after ``prefix`` (e.g. the option that asked for them).

    >>> str(missing_worlds(["barn:300"], "the bundled set", option="--barn-dir DIR"))
    "barn:300 is not in the bundled set: BARN's worlds are barn:N for N = 0-299, of which \
ifgm-ref bundles the 200 with N % 3 != 0; for the others give a folder of all 300 (a clone of \
BARN's repository) with --barn-dir DIR"
    """
    listed = ", ".join(names)
    verb = "is" if len(names) == 1 else "are"
    lead = f"{prefix}: " if prefix else ""
    by = f" with {option}" if option else ""
    return MissingWorlds(
        f"{lead}{listed} {verb} not in {where}: BARN's worlds are barn:N for N = 0-299, of "
        "which ifgm-ref bundles the 200 with N % 3 != 0; for the others give a folder of all "
        f"300 (a clone of BARN's repository){by}",
        tuple(names),
    )


def find_barn_worlds(
    folder: str | os.PathLike[str], indices: set[int] | None = None
) -> list[BarnFiles]:
    """The BARN worlds in ``folder``, by index, each with its path file.

    ``folder`` is either a flat folder of ``world_N.world`` and ``path_N.npy`` (what
    :func:`bundled_barn_folder` gives) or a clone of BARN's repository (all 300 worlds), where
    the worlds are in ``jackal_helper/worlds/BARN/`` and the paths in
    ``jackal_helper/worlds/BARN/path_files/``.
    ``indices`` keeps only those worlds: one not there is :class:`MissingWorlds`
    (:func:`missing_worlds`, naming the folder). A world without its path file is an error.
    """
    where = _world_folder(Path(folder))
    found: dict[int, Path] = {}
    for path in where.glob("world_*.world"):
        match = _WORLD.fullmatch(path.name)
        if match:
            found[int(match.group(1))] = path
    if indices is not None:
        missing = sorted(indices - set(found))
        if missing:
            raise missing_worlds([f"barn:{n}" for n in missing], str(where))
        found = {k: v for k, v in found.items() if k in indices}
    out = []
    for index in sorted(found):
        name = f"path_{index}.npy"
        candidates = (where / name, where / "path_files" / name)
        path_file = next((p for p in candidates if p.is_file()), None)
        if path_file is None:
            raise WorldError(f"{found[index]}: no path file {name} beside it or in path_files/")
        out.append(BarnFiles(index, found[index], path_file))
    return out


def parse_selection(text: str) -> set[int]:
    """World indices from ``"0-49,60"``: comma-separated indices and inclusive ranges.

    >>> sorted(parse_selection("1-3,7"))
    [1, 2, 3, 7]
    """
    out: set[int] = set()
    for part in (p.strip() for p in text.split(",")):
        match = re.fullmatch(r"(\d+)(?:-(\d+))?", part)
        if not match:
            raise ParameterError(f"bad world selection {part!r}; e.g. 0-49,60")
        low = int(match.group(1))
        high = int(match.group(2) or low)
        if high < low:
            raise ParameterError(f"bad world range {part!r}: {high} < {low}")
        out.update(range(low, high + 1))
    return out


def load_barn_world(
    world_file: str | os.PathLike[str], sensor: str = DEFAULT_SENSOR, name: str | None = None
) -> World:
    """A BARN world with BARN's start, goal and robot and the sensor preset ``sensor``."""
    return load_sdf_world(
        world_file, start=START, goal=GOAL, name=name, robot=ROBOT, sensor=barn_sensor(sensor)
    )


#: ``simulate``'s name for BARN's world N: ``barn:N`` (any other text after ``barn:`` names
#: no world: :func:`gazebo_task` says so).
_BARN_NAME = re.compile(r"barn:(.*)")


@dataclass(frozen=True)
class GazeboTask:
    """A Gazebo world with BARN's task: the world (robot and sensor included), the simulation
    settings, and BARN's reference path length L when the world is one of BARN's with its path
    file (``None`` otherwise: no BARN score)."""

    world: World
    sim: SimParams
    reference_length: float | None


def gazebo_task(
    spec: str,
    *,
    folder: str | os.PathLike[str] | None = None,
    sensor: str = DEFAULT_SENSOR,
    start: Pose | None = None,
    goal: Point | None = None,
) -> GazeboTask | None:
    """The task ``simulate`` runs for ``spec``: ``barn:N`` (BARN's world N in ``folder``, by
    default the bundled set) or a Gazebo world file (``.world``, ``.sdf``); ``None`` for
    anything else (a JSON world file or a built-in world).

    Both get BARN's robot, the sensor preset ``sensor``, and BARN's time step, 100 s and 1 m
    success radius (:data:`SIM`), as ``bench --barn`` runs them; start and goal are BARN's
    unless given. A file named ``world_N.world`` with ``path_N.npy`` beside it (or in
    ``path_files/``) is BARN's world N and gets its reference length. A ``barn:N`` that is not
    in ``folder`` or the bundled set, whatever N (``barn:300``, ``barn:3``, ``barn:x``), is
    :class:`MissingWorlds` (:func:`missing_worlds`: ``simulate --barn-dir DIR`` gives
    ``folder``).
    """
    path = Path(spec)
    match = None if path.is_file() else _BARN_NAME.fullmatch(spec)
    if match is None and path.suffix.lower() not in (".world", ".sdf"):
        return None
    files: BarnFiles | None
    if match is not None:
        where = "the bundled set" if folder is None else str(folder)
        if not match.group(1).isdecimal():
            raise missing_worlds([spec], where, option="--barn-dir DIR")
        try:
            (files,) = find_barn_worlds(folder or bundled_barn_folder(), {int(match.group(1))})
        except MissingWorlds:
            raise missing_worlds([spec], where, option="--barn-dir DIR") from None
    elif not path.is_file():
        raise WorldError(f"{spec}: no such Gazebo world file")
    else:
        files = _barn_files_of(path)
    world = load_sdf_world(
        path if files is None else files.world,
        start=start or START, goal=goal or GOAL,
        name=path.stem if files is None else f"barn-{files.index:03d}",
        robot=ROBOT, sensor=barn_sensor(sensor),
    )  # fmt: skip
    return GazeboTask(world, SIM, None if files is None else reference_length(files.path))


def _barn_files_of(path: Path) -> BarnFiles | None:
    """BARN's files of the world file ``path`` when it is ``world_N.world`` with its
    ``path_N.npy`` beside it (or in ``path_files/``), else ``None`` (no BARN score)."""
    numbered = _WORLD.fullmatch(path.name)
    if numbered is None:
        return None
    try:
        (files,) = find_barn_worlds(path.parent, {int(numbered.group(1))})
    except WorldError:
        return None
    return files if files.world.resolve() == path.resolve() else None
