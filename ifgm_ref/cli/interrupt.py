"""Ctrl-C and SIGTERM: every command stops with one line and the shell's exit status.

SIGINT arrives as Python's :class:`KeyboardInterrupt`; while a command runs, SIGTERM is made
to arrive as :class:`Terminated`, a subclass of it, so that the same ``finally`` blocks and
``except KeyboardInterrupt`` clean-ups run for both (the output files' temporaries,
:func:`ifgm_ref.outputs.written`; a ``--cmd`` program, which its planner's ``close`` stops).
``main`` then prints ``ifgm-ref: interrupted by SIGINT: ...`` with what was finished and what
is missing (:data:`ifgm_ref.outputs.LEDGER`) and exits 130 or 143 (128 + the signal), as a
shell reports a program a signal stopped.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

__all__ = ["EXIT_INTERRUPTED", "EXIT_TERMINATED", "Terminated", "exit_status", "terminable"]

#: Exit status after SIGINT (Ctrl-C): 128 + 2.
EXIT_INTERRUPTED = 128 + signal.SIGINT
#: Exit status after SIGTERM: 128 + 15.
EXIT_TERMINATED = 128 + signal.SIGTERM


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where the main thread was, as Ctrl-C would be."""


def _raise_terminated(signum: int, frame: FrameType | None) -> None:
    raise Terminated


@contextmanager
def terminable() -> Iterator[None]:
    """Within the block, SIGTERM raises :class:`Terminated` in the main thread (elsewhere, and
    after the block, it keeps its handler)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def exit_status(err: KeyboardInterrupt) -> tuple[str, int]:
    """The signal's name and the exit status for an interruption ``err``.

    >>> exit_status(KeyboardInterrupt()), exit_status(Terminated())
    (('SIGINT', 130), ('SIGTERM', 143))
    """
    if isinstance(err, Terminated):
        return "SIGTERM", EXIT_TERMINATED
    return "SIGINT", EXIT_INTERRUPTED
