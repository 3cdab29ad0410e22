"""Lines to a program's stdin and from its stdout, every wait bounded by a deadline.

:func:`connect` wraps a started :class:`subprocess.Popen` (binary pipes) in one of two
:class:`Pipes` with the same contract:

* :class:`PolledPipes`, on POSIX: the caller's own thread writes and reads the pipes, both
  non-blocking, waiting in ``select`` for at most the time left. An exchange costs one round
  trip of the pipes.
* :class:`ThreadedPipes`, elsewhere (Windows cannot ``select`` on a pipe): a thread writes
  each line, a thread queues each line read. Each exchange then also waits for two threads to
  be woken, which costs more than the round trip itself (``benchmarks/README.md``).

Neither lets a program block its caller: a line it does not read is still being written when
the deadline passes, and a reply it does not write is waited for until the deadline.
"""

from __future__ import annotations

import contextlib
import io
import os
import queue
import selectors
import subprocess
import threading
import time
from typing import IO, Protocol

__all__ = ["POLLED", "Pipes", "PolledPipes", "ThreadedPipes", "connect"]

#: Whether :func:`connect` polls the pipes (POSIX) or hands them to threads.
POLLED = os.name == "posix"
#: The most read from the program's stdout at once, bytes.
CHUNK = 1 << 16


class Pipes(Protocol):
    """A program's stdin and stdout as lines of text (UTF-8; bytes that are not, replaced)."""

    def send(self, line: str, deadline: float) -> bool:
        """Write ``line`` and a newline; ``False`` if it was not all written by ``deadline``
        (:func:`time.monotonic`). A program gone is not an error here: its stdout ends."""
        ...

    def receive(self, deadline: float) -> str | None:
        """The next line from the program (with its newline; the last may lack it), or
        ``None`` once its stdout has ended; :class:`TimeoutError` if none came by
        ``deadline``. A deadline already past looks without waiting."""
        ...

    def close_input(self) -> None:
        """Close the program's stdin (after the lines already sent)."""
        ...

    def drain(self, wait: float) -> None:
        """Give what reads the program's stdout up to ``wait`` s to finish, once it ended."""
        ...

    def close(self) -> None:
        """Release both pipes (a pipe still used by a thread is left to that thread)."""
        ...


def connect(process: subprocess.Popen[bytes], *, polled: bool | None = None) -> Pipes:
    """The pipes of ``process`` (started with binary stdin and stdout pipes): polled if
    ``polled`` (default :data:`POLLED`), else threaded."""
    assert process.stdin is not None and process.stdout is not None
    if POLLED if polled is None else polled:
        return PolledPipes(process.stdin, process.stdout)
    return ThreadedPipes(process.stdin, process.stdout, name=f"pid {process.pid}")


def _text(line: bytes) -> str:
    return line.decode("utf-8", errors="replace").replace("\r\n", "\n")


class PolledPipes:
    """:class:`Pipes` written and read by the caller, non-blocking (POSIX)."""

    def __init__(self, stdin: IO[bytes], stdout: IO[bytes]) -> None:
        self._stdin, self._stdout = stdin, stdout
        self._in, self._out = stdin.fileno(), stdout.fileno()
        os.set_blocking(self._in, False)
        os.set_blocking(self._out, False)
        self._writable = selectors.DefaultSelector()
        self._writable.register(self._in, selectors.EVENT_WRITE)
        self._readable = selectors.DefaultSelector()
        self._readable.register(self._out, selectors.EVENT_READ)
        self._buffer = bytearray()
        self._ended = False

    def send(self, line: str, deadline: float) -> bool:
        data = memoryview((line + "\n").encode("utf-8"))
        while data:
            try:
                data = data[os.write(self._in, data) :]
            except BlockingIOError:
                if not _wait(self._writable, deadline):
                    return False
            except OSError:  # the program closed its stdin or is gone
                return True
        return True

    def receive(self, deadline: float) -> str | None:
        while (end := self._buffer.find(b"\n")) < 0 and not self._ended:
            if not _wait(self._readable, deadline):
                raise TimeoutError
            self._read()
        if end < 0:  # the program's stdout ended: its last line may lack the newline
            end = len(self._buffer) - 1
            if end < 0:
                return None
        line = bytes(self._buffer[: end + 1])
        del self._buffer[: end + 1]
        return _text(line)

    def _read(self) -> None:
        try:
            data = os.read(self._out, CHUNK)
        except BlockingIOError:  # woken, but nothing there after all
            return
        except OSError:
            data = b""
        if data:
            self._buffer += data
        else:
            self._ended = True

    def close_input(self) -> None:
        with contextlib.suppress(OSError):
            self._stdin.close()

    def drain(self, wait: float) -> None:
        """Nothing to wait for: the stdout is read when a line is asked for."""

    def close(self) -> None:
        self._writable.close()
        self._readable.close()
        for pipe in (self._stdin, self._stdout):
            with contextlib.suppress(OSError):
                pipe.close()


def _wait(selector: selectors.BaseSelector, deadline: float) -> bool:
    """Whether ``selector``'s pipe became ready before ``deadline``."""
    return bool(selector.select(max(0.0, deadline - time.monotonic())))


class ThreadedPipes:
    """:class:`Pipes` written by one thread and read by another (any platform)."""

    def __init__(self, stdin: IO[bytes], stdout: IO[bytes], *, name: str) -> None:
        self._stdin = io.TextIOWrapper(stdin, encoding="utf-8")
        self._stdout = io.TextIOWrapper(stdout, encoding="utf-8", errors="replace")
        self._outbox: queue.Queue[str | None] = queue.Queue()
        self._replies: queue.Queue[str | None] = queue.Queue()
        self._ended = False
        self._writer = threading.Thread(
            target=_write_lines, args=(self._stdin, self._outbox), name=f"stdin of {name}"
        )
        self._reader = threading.Thread(
            target=_read_lines, args=(self._stdout, self._replies), name=f"stdout of {name}"
        )
        for thread in (self._writer, self._reader):
            thread.daemon = True
            thread.start()

    def send(self, line: str, deadline: float) -> bool:
        self._outbox.put(line + "\n")  # the writer may block on a full pipe; we do not
        return True

    def receive(self, deadline: float) -> str | None:
        if self._ended:
            return None
        try:
            line = self._replies.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            raise TimeoutError from None
        self._ended = line is None
        return line

    def close_input(self) -> None:
        self._outbox.put(None)

    def drain(self, wait: float) -> None:
        self._reader.join(timeout=wait)

    def close(self) -> None:
        self._outbox.put(None)  # lets the writer end if it waits for a line
        # A pipe its thread still uses (blocked on a full pipe, or a grandchild holds it
        # open) is left to that thread: closing a buffered stream under it would wait for it.
        for pipe, thread in ((self._stdin, self._writer), (self._stdout, self._reader)):
            if not thread.is_alive():
                with contextlib.suppress(OSError, ValueError):
                    pipe.close()


def _write_lines(stream: IO[str], outbox: queue.Queue[str | None]) -> None:
    """Write every line put in ``outbox`` to ``stream``, flushed; close it at ``None``."""
    try:
        while (line := outbox.get()) is not None:
            stream.write(line)
            stream.flush()
        stream.close()
    except (OSError, ValueError):
        pass  # the program is gone (broken pipe) or the pipe was closed: the reader sees it


def _read_lines(stream: IO[str], replies: queue.Queue[str | None]) -> None:
    """Queue every line of ``stream``, then ``None``."""
    try:
        for line in stream:
            replies.put(line)
    except (OSError, ValueError):
        pass  # closed under us
    replies.put(None)
