"""One benchmark task: a world, its shortest path, and every chosen planner's episode in it.

A task is described by plain, picklable data (:class:`WorldSpec`, planner names, an optional
time limit), so the same task runs in this process, in a local process pool or on a Dask
worker, and gives the same row there: the simulation is deterministic, and a generated world
is rebuilt from its own seed, ``numpy.random.SeedSequence(seed, spawn_key=(class_id, index))``
-- the ``index``-th child of the ``class_id``-th child of ``SeedSequence(seed)``, what
``SeedSequence(seed).spawn(...)`` hands out -- never from a generator shared between tasks.
World ``u-0007`` is the same world whether 10 or 500 worlds per class are asked for, and
whichever worker builds it.

A BARN world (kind ``barn``: :mod:`ifgm_ref.io.barn`) is rebuilt from its ``.world`` file
with BARN's robot, sensor preset, start and goal, and runs with BARN's time step, success
radius and time limit; its rows carry BARN's reference path length and score. Its shortest
path is not computed: extremitypathfinder takes about 20 s per BARN world (~240 cylinders,
measured), twenty times the episodes themselves, so ``optimal_length`` and
``path_ratio`` stay empty there.

Each (planner, world) pair gives one :class:`Row`, under each noise :class:`Condition` of the
task (by default one: no noise). A planner that raises is recorded as a row with stop reason
``error`` and the message in ``detail``, so one crash loses nothing else.

Noise (:mod:`ifgm_ref.sim.noise`) is seeded per world, never per task or worker: every episode in
world ``NAME`` draws from :func:`noise_seed` of the run's noise seed and ``NAME``, whatever
the planner, the noise level or the worker. So the planners meet the same draws, step for
step (common random numbers: a difference between them is theirs, not the dice's), and the
levels of one kind are coupled: the rays a 2 % dropout loses are among those a 5 % one does,
and range noise of 10 % is that of 5 %, doubled.

Every episode of a task runs on the task's engine (:mod:`ifgm_ref.sim.engine`: ``kinematic``, the
default, or ``mujoco``) with its body: they travel in the task's arguments, as plain names, so
a worker process needs no setting of its own; each row says its engine.
"""

from __future__ import annotations

import dataclasses
import math
import re
import time
import zlib
from collections.abc import Sequence
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from typing import Any

import numpy as np

from ifgm_ref.apps.bench.optimal import optimal_path
from ifgm_ref.core.errors import WorldError
from ifgm_ref.core.params import ENGINES, SimParams
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner
from ifgm_ref.core.recording import RecordingPlanner
from ifgm_ref.io import barn
from ifgm_ref.io.scenarios import BUILTIN_WORLDS
from ifgm_ref.io.transport.loading import load_factory
from ifgm_ref.io.worldfile import load_world
from ifgm_ref.sim.convergence import time_bound
from ifgm_ref.sim.noise import NoiseLevels
from ifgm_ref.sim.simulator import simulate, total_turning
from ifgm_ref.sim.world import World
from ifgm_ref.sim.worldgen.classes import GENERATORS, random_world

#: The generated world classes, in the order that fixes their seeds' ``class_id``.
CLASS_IDS: dict[str, int] = {name: k for k, name in enumerate(GENERATORS)}
#: Stop reason of a row whose planner raised an exception.
ERROR = "error"


@dataclass(frozen=True)
class WorldSpec:
    """Where a benchmark world comes from.

    ``kind`` is a generated class (``open``, ``u``, ``h``, ``symmetric``, ``mixed``: then
    ``seed`` and ``index`` rebuild it), ``builtin`` (``source`` is the name), ``file``
    (``source`` is the path) or ``barn`` (``source`` is the ``world_N.world`` file,
    ``path_file`` BARN's ``path_N.npy``, ``sensor`` the sensor preset's name).
    """

    name: str
    kind: str
    source: str | None = None
    seed: int | None = None
    index: int | None = None
    path_file: str | None = None
    sensor: str | None = None

    @classmethod
    def generated(cls, world_class: str, seed: int, index: int) -> WorldSpec:
        """The ``index``-th world of ``world_class`` for ``seed`` (named ``CLASS-NNNN``)."""
        if world_class not in CLASS_IDS:
            known = ", ".join(CLASS_IDS)
            raise WorldError(f"unknown world class {world_class!r}; known: {known}")
        return cls(f"{world_class}-{index:04d}", world_class, None, seed, index)

    @classmethod
    def from_barn(cls, files: barn.BarnFiles, sensor: str = barn.DEFAULT_SENSOR) -> WorldSpec:
        """BARN's world ``files.index`` (named ``barn-NNN``) with the sensor preset ``sensor``."""
        barn.barn_sensor(sensor)  # an unknown preset fails here, not in a worker
        return cls(
            f"barn-{files.index:03d}", "barn", str(files.world), None, files.index,
            str(files.path), sensor,
        )  # fmt: skip

    def build(self) -> World:
        """The world itself."""
        if self.kind == "barn":
            return barn.load_barn_world(str(self.source), self.sensor or barn.DEFAULT_SENSOR)
        if self.kind == "builtin":
            return BUILTIN_WORLDS[str(self.source)].build()
        if self.kind == "file":
            return load_world(str(self.source))
        assert self.seed is not None and self.index is not None
        seq = np.random.SeedSequence(self.seed, spawn_key=(CLASS_IDS[self.kind], self.index))
        return random_world(self.kind, seq)


def generated_specs(classes: list[str], per_class: int, seed: int) -> list[WorldSpec]:
    """``per_class`` generated worlds of each class in ``classes``, class by class."""
    return [WorldSpec.generated(c, seed, i) for c in classes for i in range(per_class)]


def builtin_specs() -> list[WorldSpec]:
    """Every built-in world (``ifgm-ref worlds``)."""
    return [WorldSpec(name, "builtin", name) for name in BUILTIN_WORLDS]


def barn_specs(
    folder: str | Path, sensor: str = barn.DEFAULT_SENSOR, indices: set[int] | None = None
) -> list[WorldSpec]:
    """Every BARN world in ``folder`` (flat or BARN's repository layout), by index; each is
    checked on loading."""
    specs = [WorldSpec.from_barn(files, sensor) for files in barn.find_barn_worlds(folder, indices)]
    for spec in specs:
        spec.build()
    return specs


def folder_specs(folder: str | Path) -> list[WorldSpec]:
    """Every ``*.json`` world file in ``folder``, by file name; each is checked on loading."""
    paths = sorted(Path(folder).glob("*.json"))
    if not paths:
        raise WorldError(f"no world files (*.json) in {folder}")
    for path in paths:
        load_world(path)
    return [WorldSpec(path.stem, "file", str(path)) for path in paths]


@dataclass(frozen=True)
class Row:
    """One episode of the benchmark table (one line of ``results.csv``).

    Lengths in ft, times in s, angles in rad. ``path_ratio`` is ``path_length /
    optimal_length`` for an episode that reached the goal, else empty; ``heading_change`` is
    the total absolute change of heading along the path (smoothness: less is smoother);
    ``decisions_per_cpu_s`` counts the planner's ``step`` calls per second of CPU spent in
    them (the only column that varies between runs). ``reference_length`` (BARN's path length
    L, m) and ``barn_score`` (BARN's score of the episode) are filled for BARN worlds only.

    ``noise`` is the episode's noise levels as ``--noise`` reads them (``none``: no noise);
    ``noise_kind`` and ``noise_level`` the point of a noise sweep it belongs to (``none``
    and 0 for the sweep's noise-free baseline; empty outside a sweep); ``noise_seed`` the
    seed of its noise generators (empty without noise): ``ifgm-ref simulate WORLD --noise
    NOISE --noise-seed NOISE_SEED`` replays it. ``engine`` is what moved the robot
    (:data:`~ifgm_ref.core.params.ENGINES`: ``simulate --engine ENGINE`` replays it). ``robot`` is
    what ``--robot`` changed of the world's robot (``none``: nothing; ``simulate --robot
    ROBOT`` replays it).
    """

    planner: str
    world: str
    world_class: str
    reached: bool
    collided: bool
    stop_reason: str
    time_s: float
    path_length: float
    optimal_length: float | None
    path_ratio: float | None
    min_clearance: float | None
    heading_change: float
    steps: int
    decisions_per_cpu_s: float | None
    detail: str | None = None
    reference_length: float | None = None
    barn_score: float | None = None
    noise: str = "none"
    noise_kind: str | None = None
    noise_level: float | None = None
    noise_seed: int | None = None
    engine: str = ENGINES[0]
    robot: str = "none"

    @classmethod
    def columns(cls) -> tuple[str, ...]:
        """The column names, in order."""
        return tuple(f.name for f in fields(cls))

    def as_dict(self) -> dict[str, Any]:
        """The row as a mapping of column names to values."""
        return asdict(self)


@dataclass(frozen=True)
class Condition:
    """The noise every episode of a task runs under (:mod:`ifgm_ref.sim.noise`).

    ``levels`` are applied to each world with the world's :func:`noise_seed`; with every level
    0 the world runs as it is (a world file's own noise included). ``kind`` and ``level``
    name the point of a noise sweep (``ifgm-ref bench --noise-sweep``) this is: the kind
    swept and its level, ``"none"`` and 0 for the noise-free baseline, ``None`` outside a
    sweep.
    """

    levels: NoiseLevels = dataclasses.field(default_factory=NoiseLevels)
    kind: str | None = None
    level: float | None = None

    @property
    def noisy(self) -> bool:
        """Whether any level is on."""
        return self.levels.on

    def apply(self, world: World, seed: int) -> World:
        """``world`` under these levels, its noise generators seeded with ``seed``."""
        return self.levels.apply(world, seed) if self.noisy else world

    def columns(self, seed: int) -> dict[str, Any]:
        """The noise columns of a :class:`Row` run under this condition with ``seed``."""
        return {
            "noise": self.levels.tags(),
            "noise_kind": self.kind,
            "noise_level": self.level,
            "noise_seed": seed if self.noisy else None,
        }


#: The default condition: no noise.
NOISE_FREE = Condition()


def noise_seed(seed: int, world: str) -> int:
    """The seed of the noise of every episode in the world named ``world``, for the run's
    noise seed ``seed``: an integer in [0, 2**32), the first word of
    ``numpy.random.SeedSequence([seed, crc32(world)])``.

    By name, not by position in the run, so that world ``u-0007`` meets the same noise
    however many worlds are asked for (and a built-in or file world has one too).

    >>> noise_seed(0, "u-0007") == noise_seed(0, "u-0007") != noise_seed(1, "u-0007")
    True
    """
    sequence = np.random.SeedSequence([seed, zlib.crc32(world.encode())])
    return int(sequence.generate_state(1)[0])


class _Timed:
    """A planner whose ``step`` calls are counted and timed in CPU seconds of this thread."""

    def __init__(self, planner: Planner) -> None:
        self.planner = planner
        self.name = planner.name
        self.cpu_s = 0.0
        self.decisions = 0

    def reset(self, start: Any, goal: Any, params: EpisodeParams) -> None:
        self.planner.reset(start, goal, params)

    def step(self, observation: Observation) -> Command:
        begin = time.thread_time()
        command = self.planner.step(observation)
        self.cpu_s += time.thread_time() - begin
        self.decisions += 1
        return command


def optimal_length(world: World, goal_tolerance: float) -> float:
    """The shortest collision-free path from the start to within ``goal_tolerance`` of the
    goal (where an episode ends), ft: the path to the goal less the tolerance.

    The last leg of the shortest path to the goal is straight, and the goal keeps more than
    the tolerance from every obstacle (the world classes keep 3 ft), so cutting the last
    ``goal_tolerance`` ft of it gives the shortest path to the goal disc.
    """
    return max(0.0, optimal_path(world).length - goal_tolerance)


def run_world(
    spec: WorldSpec,
    planners: tuple[str, ...],
    max_time: float | None = None,
    conditions: Sequence[Condition] = (NOISE_FREE,),
    seed: int = 0,
    record: str | None = None,
    engine: str = ENGINES[0],
    body: str | None = None,
    robot: tuple[tuple[str, float], ...] = (),
) -> list[Row]:
    """Build ``spec``'s world, find its shortest path, run each planner there under each noise
    condition: one row each, condition by condition, planner by planner; with ``record`` (a
    folder), each episode is also written there as a ROS bag (:func:`bag_path`). The robot is
    moved by ``engine`` with ``body`` (:class:`~ifgm_ref.core.params.SimParams`), the fields of
    ``robot`` changed (:func:`~ifgm_ref.core.params.changed_robot`: ``--robot``).

    The time limit is ``max_time`` s or, by default, the oracle's convergence budget for the
    world (:func:`ifgm_ref.sim.convergence.time_bound`: Bug1's path bound driven slowly); for a
    BARN world, BARN's 100 s (and its time step and success radius, :data:`barn.SIM`). The
    noise is seeded with :func:`noise_seed` of ``seed`` and the world's name.
    """
    world = spec.build()
    world = world.with_robot(dict(robot))
    rng_seed = noise_seed(seed, spec.name)
    reference: float | None = None
    if spec.kind == "barn":
        sim = dataclasses.replace(barn.SIM, max_time=max_time or barn.SIM.max_time)
        reference = barn.reference_length(str(spec.path_file))
        optimal: float | None = None
    else:
        sim = SimParams(max_time=max_time or time_bound(world))
        try:
            optimal = optimal_length(world, sim.goal_tolerance)
        except WorldError:
            optimal = None
    sim = dataclasses.replace(sim, engine=engine, body=body)
    return [
        _episode(
            spec,
            c.apply(world, rng_seed),
            name,
            optimal,
            sim,
            reference,
            {**c.columns(rng_seed), "robot": robot_tags(robot)},
            None if record is None else bag_path(record, spec, name, c),
        )
        for c in conditions
        for name in planners
    ]


def robot_tags(robot: Sequence[tuple[str, float]]) -> str:
    """``robot``'s changes as ``--robot`` reads them; ``none`` for none.

    >>> robot_tags([("speed", 2.0), ("braking", 3.72)]), robot_tags([])
    ('speed=2,braking=3.72', 'none')
    """
    return ",".join(f"{name}={value:g}" for name, value in robot) or "none"


def bag_path(folder: str, spec: WorldSpec, planner: str, condition: Condition) -> Path:
    """Where ``bench --record`` writes an episode: ``WORLD-PLANNER[-NOISE].mcap`` in
    ``folder``, every character but letters, digits and ``.-_=`` made ``_``.

    >>> from ifgm_ref.sim.noise import NoiseLevels
    >>> spec = WorldSpec("u_trap", "builtin", "u_trap")
    >>> bag_path("bags", spec, "ifgm", Condition(NoiseLevels(range=0.02))).as_posix()
    'bags/u_trap-ifgm-range=0.02.mcap'
    """
    parts = [spec.name, planner] + ([condition.levels.tags()] if condition.noisy else [])
    return Path(folder) / ("-".join(re.sub(r"[^\w.=-]", "_", p) for p in parts) + ".mcap")


def _episode(
    spec: WorldSpec,
    world: World,
    planner: str,
    optimal: float | None,
    sim: SimParams,
    reference: float | None,
    columns: dict[str, Any],
    bag: Path | None,
) -> Row:
    timed = _Timed(load_factory(planner)())
    recorder = None if bag is None else RecordingPlanner(timed)
    try:
        run = simulate(world, recorder or timed, sim)
    except Exception as err:  # a crashing planner is a result, not the end of the benchmark
        return Row(
            planner, spec.name, spec.kind, False, False, ERROR, math.nan, math.nan, optimal,
            None, None, math.nan, timed.decisions, None, f"{type(err).__name__}: {err}",
            reference, None if reference is None else 0.0, **columns, engine=sim.engine,
        )  # fmt: skip
    if recorder is not None and bag is not None:
        from ifgm_ref.io.bags.write import write_bag

        write_bag(bag, world, run, recorder.recording(), "m" if spec.kind == "barn" else "ft")
    result = run.result
    ratio = result.path_length / optimal if result.reached and optimal else None
    return Row(
        planner=planner,
        world=spec.name,
        world_class=spec.kind,
        reached=result.reached,
        collided=result.collided,
        stop_reason=result.stop_reason,
        time_s=result.time_s,
        path_length=result.path_length,
        optimal_length=optimal,
        path_ratio=ratio,
        min_clearance=result.min_clearance if math.isfinite(result.min_clearance) else None,
        heading_change=total_turning(run.trace),
        steps=result.steps,
        decisions_per_cpu_s=timed.decisions / timed.cpu_s if timed.cpu_s > 0 else None,
        detail=result.detail,
        reference_length=reference,
        barn_score=None
        if reference is None
        else barn.barn_score(result.reached, result.time_s, reference),
        **columns,
        engine=sim.engine,
    )
