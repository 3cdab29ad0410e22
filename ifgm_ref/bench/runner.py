"""Run the benchmark's tasks here, in a local process pool, or on a Dask cluster.

One task per world (:func:`ifgm_ref.bench.tasks.run_world`). With ``jobs=1`` the tasks run in
this process; with more, in a ``concurrent.futures.ProcessPoolExecutor``; with a scheduler
address, on a Dask cluster through the ``concurrent.futures`` executor that
``distributed.Client.get_executor()`` provides (the optional extra ``ifgm-ref[dask]``; the
workers need ``ifgm-ref`` installed). The rows come back in task order whatever order the
tasks finish in, so the table does not depend on where it ran (only the CPU-timing column
does).
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
from collections.abc import Callable, Iterator, Sequence

from tqdm import tqdm

from ifgm_ref.bench.tasks import NOISE_FREE, Condition, Row, WorldSpec, run_world
from ifgm_ref.errors import ParameterError


@contextlib.contextmanager
def _executor(jobs: int, scheduler: str | None) -> Iterator[cf.Executor | None]:
    """The executor to run on (``None``: run inline), closed on exit."""
    if scheduler is not None:
        try:
            from distributed import Client
        except ImportError:
            raise ParameterError(
                "--scheduler needs Dask's distributed package: pip install 'ifgm-ref[dask]'"
            ) from None
        with Client(scheduler) as client:
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
    conditions : the noise conditions (default: none; :class:`~ifgm_ref.bench.tasks.Condition`).
    noise_seed : the run's noise seed, from which each world's is derived
        (:func:`~ifgm_ref.bench.tasks.noise_seed`).
    progress : show a progress bar with an ETA on stderr (``None``: only on a terminal).
    on_rows : called with each world's rows as they arrive (in completion order).
    """
    if jobs < 1:
        raise ParameterError(f"jobs must be at least 1, got {jobs}")
    names, noises = tuple(planners), tuple(conditions)
    results: list[list[Row] | None] = [None] * len(specs)
    disable = None if progress is None else not progress
    with (
        tqdm(total=len(specs), unit="world", desc="bench", disable=disable) as bar,
        _executor(jobs, scheduler) as executor,
    ):
        if executor is None:
            done: Iterator[tuple[int, list[Row]]] = (
                (k, run_world(spec, names, max_time, noises, noise_seed))
                for k, spec in enumerate(specs)
            )
        else:
            futures = {
                executor.submit(run_world, spec, names, max_time, noises, noise_seed): k
                for k, spec in enumerate(specs)
            }
            done = ((futures[f], f.result()) for f in cf.as_completed(futures))
        for k, rows in done:
            results[k] = rows
            if on_rows is not None:
                on_rows(rows)
            bar.update()
    return [row for rows in results if rows is not None for row in rows]
