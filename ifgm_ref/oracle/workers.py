"""The worker processes the oracle's simulation checks run in (``--jobs N``), and how they stop.

A worker ignores Ctrl-C, which a terminal sends to the whole process group, and ends at
SIGTERM whatever handler it inherited: the parent, interrupted (Ctrl-C, or SIGTERM made an
interruption by :mod:`ifgm_ref.apps.cli.interrupt`), cancels what is queued and terminates the
workers at once, instead of waiting for their checks, and no worker prints a traceback.
"""

from __future__ import annotations

import multiprocessing
import signal
from collections.abc import Iterator
from concurrent.futures import ProcessPoolExecutor
from contextlib import contextmanager

__all__ = ["worker_pool"]


@contextmanager
def worker_pool(jobs: int) -> Iterator[ProcessPoolExecutor]:
    """A pool of ``jobs`` worker processes (the platform's default start), stopped at once
    if the block is interrupted (:class:`KeyboardInterrupt`, which is then raised again)."""
    others = set(multiprocessing.active_children())
    with ProcessPoolExecutor(max_workers=jobs, initializer=_leave_signals_to_the_parent) as pool:
        try:
            yield pool
        except KeyboardInterrupt:
            pool.shutdown(wait=False, cancel_futures=True)
            _stop(set(multiprocessing.active_children()) - others)
            raise


def _leave_signals_to_the_parent() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _stop(workers: set[multiprocessing.process.BaseProcess]) -> None:
    """Terminate ``workers`` and wait for them (none is left a zombie)."""
    for worker in workers:
        worker.terminate()
    for worker in workers:
        worker.join(timeout=10)
