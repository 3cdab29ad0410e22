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
the deadline passes, and a reply it does not write is waited for until the deadline. Neither
lets a program fill the caller's memory: a line is read up to :data:`MAX_LINE` bytes and no
further (:class:`LineTooLongError`), and lines are read only as they are asked for (polled) or
queued at most :data:`QUEUED_LINES` ahead (threaded), so a program that writes without end
blocks on its own full pipe. Bytes that are not UTF-8 reach the caller as lone surrogates
(``surrogateescape``), so that it can tell them from a program's own U+FFFD and refuse them.
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
from typing import IO, NoReturn, Protocol

__all__ = [
    "MAX_LINE",
    "POLLED",
    "LineTooLongError",
    "Pipes",
    "PolledPipes",
    "ThreadedPipes",
    "connect",
]

#: Whether :func:`connect` polls the pipes (POSIX) or hands them to threads.
POLLED = os.name == "posix"
#: The most read from the program's stdout at once, bytes.
CHUNK = 1 << 16
#: The longest line read from a program, bytes, its newline not counted. A reply is a few
#: hundred bytes (a ``command`` with every field and long labels stays under 1 kB): a line
#: a thousand times that is no reply, and reading on would let a program that writes without
#: end, or a 100 MB line, fill the oracle's memory. At most this and one :data:`CHUNK` are
#: ever held for one line.
MAX_LINE = 1 << 20
#: How many lines the threaded reader queues ahead of the caller: a program in turn has one
#: reply outstanding, and one more line shows the caller a line nobody asked for. Past that
#: the reader waits, and a program that floods its stdout blocks on the full pipe.
QUEUED_LINES = 2
#: How many characters of a line too long :class:`LineTooLongError` keeps, to be quoted.
LINE_START = 200


class LineTooLongError(Exception):
    """The program wrote a line of more than :data:`MAX_LINE` bytes; it was not read further.

    ``start`` holds its first :data:`LINE_START` characters, for the error message.
    """

    def __init__(self, start: str) -> None:
        super().__init__(f"a line longer than {MAX_LINE} bytes, beginning {start!r}")
        self.start = start


class Pipes(Protocol):
    """A program's stdin and stdout as lines of text (UTF-8; bytes that are not, as lone
    surrogates: ``surrogateescape``)."""

    def send(self, line: str, deadline: float) -> bool:
        """Write ``line`` and a newline; ``False`` if it was not all written by ``deadline``
        (:func:`time.monotonic`). A program gone is not an error here: its stdout ends."""
        ...

    def receive(self, deadline: float) -> str | None:
        """The next line from the program (with its newline; the last may lack it), or
        ``None`` once its stdout has ended; :class:`TimeoutError` if none came by
        ``deadline``. A deadline already past looks without waiting. A line of more than
        :data:`MAX_LINE` bytes raises :class:`LineTooLongError`, then and at every later
        call: the pipes read nothing more."""
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
    return line.decode("utf-8", errors="surrogateescape").replace("\r\n", "\n")


def _too_long(line: bytes | bytearray) -> LineTooLongError:
    return LineTooLongError(_text(bytes(line[: 4 * LINE_START]))[:LINE_START])


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
        self._too_long: LineTooLongError | None = None

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
        if self._too_long is not None:
            raise self._too_long
        searched = 0  # the buffer holds no newline before this
        while (end := self._buffer.find(b"\n", searched)) < 0 and not self._ended:
            searched = len(self._buffer)
            if searched > MAX_LINE:
                self._refuse()
            if not _wait(self._readable, deadline):
                raise TimeoutError
            self._read()
        if end < 0:  # the program's stdout ended: its last line may lack the newline
            end = len(self._buffer) - 1
            if end < 0:
                return None
        line = bytes(self._buffer[: end + 1])
        if len(line) - line.endswith(b"\n") > MAX_LINE:
            self._refuse()
        del self._buffer[: end + 1]
        return _text(line)

    def _refuse(self) -> NoReturn:
        """Give up on the line in the buffer, too long: raise, now and at every receive."""
        self._too_long = _too_long(self._buffer)
        self._buffer = bytearray()
        raise self._too_long

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
        self._stdout = stdout
        self._outbox: queue.Queue[str | None] = queue.Queue()
        self._replies: queue.Queue[bytes | None] = queue.Queue(maxsize=QUEUED_LINES)
        self._closed = threading.Event()
        self._ended = False
        self._too_long: LineTooLongError | None = None
        self._writer = threading.Thread(
            target=_write_lines, args=(self._stdin, self._outbox), name=f"stdin of {name}"
        )
        self._reader = threading.Thread(
            target=_read_lines,
            args=(self._stdout, self._replies, self._closed),
            name=f"stdout of {name}",
        )
        for thread in (self._writer, self._reader):
            thread.daemon = True
            thread.start()

    def send(self, line: str, deadline: float) -> bool:
        self._outbox.put(line + "\n")  # the writer may block on a full pipe; we do not
        return True

    def receive(self, deadline: float) -> str | None:
        if self._too_long is not None:
            raise self._too_long
        if self._ended:
            return None
        try:
            line = self._replies.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            raise TimeoutError from None
        if line is None:
            self._ended = True
            return None
        if len(line) - line.endswith(b"\n") > MAX_LINE:  # the reader stopped there
            self._too_long = _too_long(line)
            raise self._too_long
        return _text(line)

    def close_input(self) -> None:
        self._outbox.put(None)

    def drain(self, wait: float) -> None:
        self._reader.join(timeout=wait)

    def close(self) -> None:
        self._outbox.put(None)  # lets the writer end if it waits for a line
        self._closed.set()  # and the reader, once it has queued the line in hand:
        with contextlib.suppress(queue.Empty):
            while True:  # room for it (the reader checks _closed between two lines)
                self._replies.get_nowait()
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


def _read_lines(
    stream: IO[bytes], replies: queue.Queue[bytes | None], closed: threading.Event
) -> None:
    """Queue every line of ``stream``, then ``None``; stop after queueing the first
    :data:`MAX_LINE` + 1 bytes of a line too long, or once ``closed`` is set."""
    try:
        while not closed.is_set():
            line = stream.readline(MAX_LINE + 1)
            if not line:
                break
            replies.put(line)  # waits while QUEUED_LINES are queued
            if len(line) - line.endswith(b"\n") > MAX_LINE:
                return  # the caller refuses it: read no further
    except (OSError, ValueError):
        pass  # closed under us
    if not closed.is_set():
        replies.put(None)
