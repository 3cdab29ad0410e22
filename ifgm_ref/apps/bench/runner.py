"""Run the benchmark's tasks here, in a local process pool, or on a Dask cluster.

:func:`map_tasks` calls one module-level function on every task of a list. With ``jobs=1``
the tasks run in this process; with more, in a ``concurrent.futures.ProcessPoolExecutor``;
with a scheduler address, on a Dask cluster through the ``concurrent.futures`` executor that
``distributed.Client.get_executor()`` provides (the optional extra ``ifgm-ref[dask]``; the
workers need ``ifgm-ref`` installed). The results come back in task order whatever order the
tasks finish in, so a table does not depend on where it ran. An interrupted run (Ctrl-C, or a
task that raises) cancels the tasks not yet started rather than waiting for them.

The benchmark (:func:`run_bench`) has one task per world
(:func:`ifgm_ref.apps.bench.tasks.run_world`; only its CPU-timing column depends on where it ran);
the soak (:func:`ifgm_ref.apps.bench.soak.run_soak`) has one per drawn world too.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
from collections.abc import Callable, Iterator, Sequence
from typing import Any, TypeVar

from ifgm_ref.apps.bench.tasks import NOISE_FREE, Condition, Row, WorldSpec, run_world
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import ENGINES, EngineName, SimParams
from ifgm_ref.core.progress import progress_bar

#: What a task's function returns.
R = TypeVar("R")


@contextlib.contextmanager
def _executor(jobs: int, scheduler: str | None) -> Iterator[cf.Executor | None]:
    """The executor to run on (``None``: run inline), closed on exit."""
    if scheduler is not None:
        try:
            from distributed import Client
        except ImportError:
            raise ParameterError(
                "running on a Dask scheduler needs Dask's distributed package: pip install "
                "'ifgm-ref[dask]'"
            ) from None
        try:
            client = Client(scheduler)
        except (ValueError, OSError) as err:  # a malformed address, or nothing answering there
            raise ParameterError(f"--scheduler {scheduler}: {err}") from None
        with client:
            executor = client.get_executor()
            try:
                yield executor
            finally:
                executor.shutdown(wait=True)
    elif jobs > 1:
        with cf.ProcessPoolExecutor(max_workers=jobs) as pool:
            yield pool
    else:
        yield None


def map_tasks(
    function: Callable[..., R],
    tasks: Sequence[tuple[Any, ...]],
    *,
    jobs: int = 1,
    scheduler: str | None = None,
    progress: bool | None = None,
    desc: str = "bench",
    unit: str = "world",
    on_result: Callable[[R], None] | None = None,
) -> list[R]:
    """``function(*task)`` for every task: the results in ``tasks`` order.

    Parameters
    ----------
    function : a module-level function (the workers import it by name).
    tasks : the arguments of each call, picklable.
    jobs : local worker processes (1: run in this process); ignored with ``scheduler``.
    scheduler : a Dask scheduler address (``tcp://host:8786``) to run the tasks on.
    progress : show a progress bar with an ETA on stderr (``None``: only on a terminal).
    desc, unit : the progress bar's label and the unit of a task.
    on_result : called with each result as it arrives (in completion order).
    """
    if jobs < 1:
        raise ParameterError(f"jobs must be at least 1, got {jobs}")
    results: dict[int, R] = {}
    with (
        progress_bar(total=len(tasks), unit=unit, desc=desc, progress=progress) as bar,
        _executor(jobs, scheduler) as executor,
    ):
        futures: dict[cf.Future[R], int] = {}
        if executor is None:
            done: Iterator[tuple[int, R]] = ((k, function(*task)) for k, task in enumerate(tasks))
        else:
            futures = {executor.submit(function, *task): k for k, task in enumerate(tasks)}
            done = ((futures[f], f.result()) for f in cf.as_completed(futures))
        try:
            for k, result in done:
                results[k] = result
                if on_result is not None:
                    on_result(result)
                bar.update()
        except BaseException:
            for future in futures:
                future.cancel()  # those not started yet: the executor then waits for the rest
            raise
    return [results[k] for k in range(len(tasks))]


def check_engine(engine: str, body: str | None) -> None:
    """Refuse an engine or body that cannot run, before any task does: one error, not an
    ``error`` row per episode (a worker would record the engine's failure as the planner's).

    >>> check_engine("kinematic", "paper")
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `body` applies to the mujoco engine only, got 'paper'
    """
    sim = SimParams(engine=engine, body=body)  # an unknown engine, a body off mujoco
    if sim.engine is EngineName.MUJOCO:
        from ifgm_ref.sim.engine import require_physics
        from ifgm_ref.sim.physics.bodies import body_named

        require_physics()
        if body is not None:
            body_named(body)


def run_bench(
    specs: Sequence[WorldSpec],
    planners: Sequence[str],
    *,
    jobs: int = 1,
    scheduler: str | None = None,
    max_time: float | None = None,
    conditions: Sequence[Condition] = (NOISE_FREE,),
    noise_seed: int = 0,
    progress: bool | None = None,
    on_rows: Callable[[list[Row]], None] | None = None,
    record: str | None = None,
    engine: str = ENGINES[0],
    body: str | None = None,
    robot: tuple[tuple[str, float], ...] = (),
) -> list[Row]:
    """Every planner in every world under every noise condition: the rows, world by world in
    ``specs`` order (then condition by condition, planner by planner).

    Parameters
    ----------
    specs : the worlds.
    planners : planner names or ``module:attribute`` factories (importable by the workers).
    jobs : local worker processes (1: run in this process); ignored with ``scheduler``.
    scheduler : a Dask scheduler address (``tcp://host:8786``) to run the tasks on.
    max_time : episode time limit, s (default: each world's convergence budget).
    conditions : the noise conditions (default: none; :class:`~.tasks.Condition`).
    noise_seed : the run's noise seed, from which each world's is derived
        (:func:`~ifgm_ref.apps.bench.tasks.noise_seed`).
    progress : show a progress bar with an ETA on stderr (``None``: only on a terminal).
    on_rows : called with each world's rows as they arrive (in completion order).
    record : a folder to write every episode to as a ROS bag
        (:func:`~ifgm_ref.apps.bench.tasks.bag_path`); the workers must reach it.
    engine, body : what moves the robot in every episode (``kinematic`` or ``mujoco``) and the
        mujoco engine's body (``None``: the world's default);
        :class:`~ifgm_ref.core.params.SimParams`.
    robot : the robot's fields changed in every world (``--robot``, ``--speed``), as pairs.
    """
    check_engine(engine, body)
    names, noises = tuple(planners), tuple(conditions)
    tasks = [
        (spec, names, max_time, noises, noise_seed, record, engine, body, robot) for spec in specs
    ]
    results = map_tasks(
        run_world, tasks, jobs=jobs, scheduler=scheduler, progress=progress, on_result=on_rows
    )
    return [row for rows in results for row in rows]
