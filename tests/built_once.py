"""Build an artefact once per test run, whichever pytest-xdist worker asks for it first.

The suite runs in several worker processes (``-n auto``), each with its own temporary folder
and its own module-scoped fixtures, so a module whose tests land on two workers would build
its programs twice (the C port's sanitizer build alone takes 9 s). :func:`built_once` builds
into the temporary folder the workers share instead, and the others wait for it.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from pathlib import Path

import pytest

#: How long a worker waits for another to finish a build, s (the slowest build takes 10 s).
WAIT = 600.0


def built_once(factory: pytest.TempPathFactory, name: str, build: Callable[[Path], None]) -> Path:
    """The folder ``name`` in the run's shared temporary folder, after ``build(folder)`` ran
    into it once in this run.

    A build that raises leaves no mark: the next worker to ask builds again (and fails the
    same way, so each test that needs it reports the error).
    """
    root = factory.getbasetemp()
    if "PYTEST_XDIST_WORKER" in os.environ:
        root = root.parent  # the workers' folders (popen-gw0, ...) sit in one run folder
    folder = root / name
    done = folder / ".built"
    lock = root / f"{name}.lock"
    deadline = time.monotonic() + WAIT
    while True:
        try:
            lock.mkdir()  # atomic: one worker holds the lock
            break
        except FileExistsError:
            if time.monotonic() > deadline:
                raise TimeoutError(f"{lock} still held after {WAIT:g} s") from None
            time.sleep(0.05)
    try:
        if not done.exists():
            folder.mkdir(exist_ok=True)
            build(folder)
            done.touch()
    finally:
        lock.rmdir()
    return folder
