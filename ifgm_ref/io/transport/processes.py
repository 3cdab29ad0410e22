"""A program's process, as the oracle runs it: its stderr copied, its exit awaited without
reaping it, and its whole process group killed.

A program under test is started in a process group of its own (``start_new_session`` on
POSIX). What it starts and leaves running shares that group, and dies with it when
:func:`kill_process` kills the group, after ``bye`` too. The program's exit is awaited
unreaped (:func:`exited`): a zombie keeps its process id, which names the group, so the kill
reaches that group and no other.
"""

from __future__ import annotations

import collections
import contextlib
import os
import signal
import subprocess
import time
from typing import IO, TextIO

from ifgm_ref.io.transport.pipes import MAX_LINE

__all__ = ["STDERR_WIDTH", "copy_lines", "exited", "kill_process", "status_text"]

#: How long to wait for a killed program to be reaped, s (SIGKILL cannot be ignored).
REAP_WAIT = 5.0
#: The longest wait between two looks at whether a program has exited, s: the exit is awaited
#: without reaping the program (so that its process id, which names its process group, stays
#: its own until the group is killed), which POSIX lets one poll, not block on with a
#: timeout. 50 ms, as :meth:`subprocess.Popen.wait` polls, is nothing next to an exit.
EXIT_POLL = 0.05
#: How many characters of one stderr line an error message quotes: a traceback's lines fit;
#: one endless line does not flood the message.
STDERR_WIDTH = 1000


def copy_lines(stream: IO[str], tail: collections.deque[str], log: TextIO | None) -> None:
    """Keep the last lines of ``stream`` in ``tail``, copying each to ``log`` (a thread).

    A line is read :data:`~ifgm_ref.io.transport.pipes.MAX_LINE` characters at a time, and
    ``tail`` keeps the first :data:`STDERR_WIDTH` of each: one endless line holds no more.
    """
    whole = True  # whether the piece read last ended its line
    try:
        while piece := stream.readline(MAX_LINE):
            if whole:
                line = piece.rstrip("\r\n")
                cut = len(line) > STDERR_WIDTH or not piece.endswith("\n")
                tail.append(f"{line[:STDERR_WIDTH]} [...]" if cut else line)
            whole = piece.endswith("\n")
            if log is not None:
                log.write(piece)
                log.flush()
    except (OSError, ValueError):
        pass


def exited(process: subprocess.Popen[bytes], timeout: float) -> bool:
    """Whether ``process`` has exited, waiting up to ``timeout`` s (``<= 0``: just look).

    On POSIX the process is left unreaped: a zombie keeps its process id, which names its
    process group, so that :func:`kill_process` kills that group and no other.
    """
    if os.name != "posix":
        try:
            process.wait(timeout=max(0.0, timeout))
        except subprocess.TimeoutExpired:
            return False
        return True
    deadline, delay = time.monotonic() + timeout, 0.0005
    while True:
        if process.returncode is not None:
            return True
        try:
            if os.waitid(os.P_PID, process.pid, os.WEXITED | os.WNOHANG | os.WNOWAIT):
                return True
        except ChildProcessError:  # reaped by someone else
            return True
        left = deadline - time.monotonic()
        if left <= 0.0:
            return False
        time.sleep(min(delay, left))
        delay = min(2 * delay, EXIT_POLL)


def kill_process(process: subprocess.Popen[bytes]) -> int | None:
    """Kill ``process`` and its process group, and reap it; its ``returncode`` (``None`` if
    it could not be reaped within :data:`REAP_WAIT`).

    The group is killed even when the process has exited (after ``bye``, say): what it
    started and left running dies with it. Unless the process was already reaped: its id
    might then name another's group.
    """
    if process.returncode is None:
        try:
            if os.name == "posix":
                os.killpg(process.pid, signal.SIGKILL)
            else:
                process.kill()
        except (ProcessLookupError, PermissionError):
            pass
    with contextlib.suppress(subprocess.TimeoutExpired):
        process.wait(timeout=REAP_WAIT)
    return process.returncode


def status_text(status: int | None) -> str:
    """Say how a program ended from its ``returncode`` (``None``: it was not reaped).

    >>> status_text(3), status_text(-9), status_text(None)
    ('exited with status 3', 'was killed by signal SIGKILL', 'could not be reaped')
    """
    if status is None:
        return "could not be reaped"
    if status >= 0:
        return f"exited with status {status}"
    try:
        return f"was killed by signal {signal.Signals(-status).name}"
    except ValueError:
        return f"was killed by signal {-status}"
