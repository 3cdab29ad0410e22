"""Ctrl-C and SIGTERM: every command stops with one line and the shell's exit status.

SIGINT arrives as Python's :class:`KeyboardInterrupt`; while a command runs, SIGTERM is made
to arrive as :class:`Terminated`, a subclass of it, so that the same ``finally`` blocks and
``except KeyboardInterrupt`` clean-ups run for both (the output files' temporaries,
:func:`ifgm_ref.core.outputs.written`; a ``--cmd`` program, which its planner's ``close`` stops).
``main`` then prints ``ifgm-ref: interrupted by SIGINT: ...`` with what was finished and what
is missing (:data:`ifgm_ref.core.outputs.LEDGER`) and exits 130 or 143 (128 + the signal), as a
shell reports a program a signal stopped.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

__all__ = [
    "EXIT_INTERRUPTED",
    "EXIT_TERMINATED",
    "Terminated",
    "as_interruption",
    "exit_status",
    "received",
    "terminable",
]

#: Exit status after SIGINT (Ctrl-C): 128 + 2.
EXIT_INTERRUPTED = 128 + signal.SIGINT
#: Exit status after SIGTERM: 128 + 15.
EXIT_TERMINATED = 128 + signal.SIGTERM


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where the main thread was, as Ctrl-C would be."""


#: The signals received within :func:`terminable` (the last block), in order.
_RECEIVED: list[signal.Signals] = []


def _on_signal(signum: int, frame: FrameType | None) -> None:
    _RECEIVED.append(signal.Signals(signum))
    raise Terminated if signum == signal.SIGTERM else KeyboardInterrupt


@contextmanager
def terminable() -> Iterator[None]:
    """Within the block, SIGTERM raises :class:`Terminated` in the main thread, and SIGINT
    :class:`KeyboardInterrupt` unless it was ignored when the command started (``nohup``, a
    background job); both are remembered (:func:`received`). Elsewhere, and after the block,
    they keep their handlers."""
    _RECEIVED.clear()
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    ours = [signal.SIGTERM]
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        ours.append(signal.SIGINT)
    previous = {signum: signal.signal(signum, _on_signal) for signum in ours}
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


def received() -> signal.Signals | None:
    """The first signal :func:`terminable`'s last block received, if any: a library may have
    turned the interruption into an error of its own (matplotlib's SVG writer, interrupted in
    C, raises ``ValueError: Invalid affine transformation matrix``)."""
    return _RECEIVED[0] if _RECEIVED else None


def as_interruption(signum: signal.Signals) -> KeyboardInterrupt:
    """The interruption ``signum`` stands for: :class:`Terminated` or KeyboardInterrupt."""
    return Terminated() if signum == signal.SIGTERM else KeyboardInterrupt()


def exit_status(err: KeyboardInterrupt) -> tuple[str, int]:
    """The signal's name and the exit status for an interruption ``err``.

    >>> exit_status(KeyboardInterrupt()), exit_status(Terminated())
    (('SIGINT', 130), ('SIGTERM', 143))
    """
    if isinstance(err, Terminated):
        return "SIGTERM", EXIT_TERMINATED
    return "SIGINT", EXIT_INTERRUPTED
