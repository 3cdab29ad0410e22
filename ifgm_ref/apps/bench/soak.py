"""The soak: many uniformly drawn worlds per class, each planner to the convergence bound.

Where the benchmark (:mod:`ifgm_ref.apps.bench.tasks`) measures path quality against the shortest
path on tens of worlds, the soak counts failures on thousands, to bound a planner's failure
rate (issue 24: 2,000 worlds per class and 0 failures bound it below 0.2 % at 95 %,
:mod:`ifgm_ref.apps.bench.soak_report`). It skips the shortest path, which would cost more than
the episodes.

Worlds. The world of class ``C`` and seed ``S`` is
:func:`ifgm_ref.sim.worldgen.classes.random_world` ``(C, S)``, named ``C-seedS``
(:func:`world_name`): the pair alone names it, on every machine and whatever else was run with it,
as the issue's own counts do ("seeds 5000-5039"). The benchmark keys its worlds by a run seed and an
index instead (``u-0007``: :meth:`~ifgm_ref.apps.bench.tasks.WorldSpec.generated`); both end in
``random_world``.

Episodes. Noise-free, with the simulator's defaults (time step, goal tolerance, stall rules)
and stopped at :func:`ifgm_ref.sim.convergence.time_bound` of the world, as the oracle's
convergence checks stop them. An episode succeeds when it reaches the goal; any other stop
reason is a failure, and a planner that raises is one too, recorded with stop reason
``error`` and the message in ``detail``. The simulation is deterministic, so a failure
replays from its class, seed and planner (:func:`replay`), and the rows of a soak do not
depend on how many processes ran it.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from ifgm_ref.apps.bench.runner import map_tasks
from ifgm_ref.apps.bench.tasks import ERROR
from ifgm_ref.core.errors import ParameterError, WorldError
from ifgm_ref.core.params import SimParams
from ifgm_ref.io.transport.loading import load_factory
from ifgm_ref.sim.convergence import time_bound
from ifgm_ref.sim.simulator import Run, simulate
from ifgm_ref.sim.world import World
from ifgm_ref.sim.worldgen.classes import GENERATORS, random_world

#: The classes a soak draws from by default: every solvable generated class.
SOAK_CLASSES: tuple[str, ...] = tuple(GENERATORS)
#: The planners of issue 24's soak: IFGM and IBA, which must not fail, and DistBug and Bug2,
#: reported whatever they score.
SOAK_PLANNERS = ("ifgm", "iba", "distbug", "bug2")


@dataclass(frozen=True)
class SoakRow:
    """One episode of a soak (one line of ``rows.jsonl``).

    Times in s, lengths in ft. ``time_bound`` is the episode's time limit
    (:func:`~ifgm_ref.sim.convergence.time_bound` of the world); ``time_s``, ``path_length`` and
    ``steps`` are ``None`` when the planner raised (``stop_reason`` ``error``, the message in
    ``detail``). Every field is deterministic: the same episode gives the same row anywhere.
    """

    planner: str
    world_class: str
    seed: int
    reached: bool
    collided: bool
    stop_reason: str
    time_s: float | None
    time_bound: float
    path_length: float | None
    steps: int | None
    detail: str | None = None

    @property
    def world(self) -> str:
        """The world's name, :func:`world_name` of its class and seed."""
        return world_name(self.world_class, self.seed)

    def to_json(self) -> str:
        """The row as one line of JSON."""
        return json.dumps(asdict(self), allow_nan=False)

    @classmethod
    def from_json(cls, line: str) -> SoakRow:
        """The row of one line of ``rows.jsonl`` (the inverse of :meth:`to_json`)."""
        data = json.loads(line)
        return cls(**{f.name: data[f.name] for f in fields(cls)})


def world_name(world_class: str, seed: int) -> str:
    """The name of the soak world of ``world_class`` and ``seed``.

    >>> world_name("open", 5000)
    'open-seed5000'
    """
    return f"{world_class}-seed{seed}"


def check_class(world_class: str) -> None:
    """Refuse a class that is not a generated, solvable one (:data:`GENERATORS`)."""
    if world_class not in GENERATORS:
        raise WorldError(f"unknown world class {world_class!r}; known: {', '.join(GENERATORS)}")


def soak_world(world_class: str, seed: int) -> World:
    """The world of ``world_class`` and ``seed``: ``random_world(world_class, seed)``, named
    :func:`world_name` (the name changes nothing else)."""
    check_class(world_class)
    if seed < 0:
        raise ParameterError(f"a world's seed must be an integer >= 0, got {seed}")
    return dataclasses.replace(random_world(world_class, seed), name=world_name(world_class, seed))


def soak_sim(world: World) -> SimParams:
    """The simulation of a soak episode in ``world``: the defaults, to its time bound."""
    return SimParams(max_time=time_bound(world))


def episode(planner: str, world_class: str, seed: int, world: World) -> tuple[SoakRow, Run | None]:
    """Run ``planner`` in ``world`` (the soak world of ``world_class`` and ``seed``): its row,
    and the run (``None`` when the planner raised)."""
    sim = soak_sim(world)
    try:
        run = simulate(world, load_factory(planner)(), sim)
    except Exception as err:  # a crashing planner is a failure, not the end of the soak
        message = f"{type(err).__name__}: {err}"
        row = SoakRow(planner, world_class, seed, False, False, ERROR, None, sim.max_time, None,
                      None, message)  # fmt: skip
        return row, None
    result = run.result
    row = SoakRow(
        planner=planner,
        world_class=world_class,
        seed=seed,
        reached=result.reached,
        collided=result.collided,
        stop_reason=result.stop_reason,
        time_s=result.time_s,
        time_bound=sim.max_time,
        path_length=result.path_length,
        steps=result.steps,
        detail=result.detail,
    )
    return row, run


def soak_task(world_class: str, seed: int, planners: tuple[str, ...]) -> list[SoakRow]:
    """One soak task: every planner in the world of ``world_class`` and ``seed``."""
    world = soak_world(world_class, seed)
    return [episode(planner, world_class, seed, world)[0] for planner in planners]


def replay(planner: str, world_class: str, seed: int) -> tuple[World, SoakRow, Run | None]:
    """One soak episode again, from its class, seed and planner: the world, the row (equal to
    the soak's) and the run with its trace."""
    world = soak_world(world_class, seed)
    row, run = episode(planner, world_class, seed, world)
    return world, row, run


def soak_tasks(
    classes: Sequence[str], seeds: Sequence[int], planners: Sequence[str]
) -> list[tuple[str, int, tuple[str, ...]]]:
    """The tasks of a soak, class by class, seed by seed; each runs every planner."""
    for world_class in classes:
        check_class(world_class)
    if not planners:
        raise ParameterError("a soak needs at least one planner")
    if any(seed < 0 for seed in seeds):
        raise ParameterError("a world's seed must be an integer >= 0")
    return [(c, seed, tuple(planners)) for c in classes for seed in seeds]


def run_soak(
    planners: Sequence[str],
    classes: Sequence[str],
    seeds: Sequence[int],
    *,
    jobs: int = 1,
    scheduler: str | None = None,
    progress: bool | None = None,
    on_rows: Callable[[list[SoakRow]], None] | None = None,
) -> list[SoakRow]:
    """Every planner in the soak world of every class and seed: the rows, class by class,
    seed by seed, planner by planner, whatever ``jobs`` or ``scheduler``.

    Parameters
    ----------
    planners : planner names or ``module:attribute`` factories (importable by the workers).
    classes : generated world classes (:data:`SOAK_CLASSES` names).
    seeds : the worlds' seeds, integers >= 0; the same for every class.
    jobs : local worker processes (1: run in this process); ignored with ``scheduler``.
    scheduler : a Dask scheduler address (``tcp://host:8786``) to run on.
    progress : show a progress bar with an ETA on stderr (``None``: only on a terminal).
    on_rows : called with each world's rows as they arrive (in completion order).
    """
    tasks = soak_tasks(classes, seeds, planners)
    results = map_tasks(
        soak_task, tasks, jobs=jobs, scheduler=scheduler, progress=progress, desc="soak",
        on_result=on_rows,
    )  # fmt: skip
    return [row for rows in results for row in rows]


def write_rows(path: Path, rows: Sequence[SoakRow], *, append: bool = False) -> None:
    """Write ``rows`` to the JSON-lines file ``path``, one line each; with ``append``, add
    them to it (created if missing)."""
    with path.open("a" if append else "w", encoding="utf-8") as out:
        out.writelines(row.to_json() + "\n" for row in rows)


def read_rows(path: str | Path) -> list[SoakRow]:
    """The rows of a JSON-lines file written by :func:`write_rows`."""
    lines = Path(path).read_text(encoding="utf-8").splitlines()
    return [SoakRow.from_json(line) for line in lines if line.strip()]
