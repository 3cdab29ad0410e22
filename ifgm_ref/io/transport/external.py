"""A planner in another process: the oracle's side of the JSON-lines protocol.

:class:`ExternalPlanner` is a :class:`~ifgm_ref.core.protocol.Planner` whose decisions come from a
program in any language that speaks the protocol of ``docs/oracle-protocol.md`` on its stdin
and stdout (``ifgm-ref serve`` is such a program for Python planners). The program is started
at the first :meth:`~ExternalPlanner.reset` and kept for every episode after it;
:meth:`~ExternalPlanner.close` (or leaving a ``with`` block) sends ``bye`` and expects exit
status 0.

The adapter never hangs: each message is written and its reply awaited
(:mod:`~ifgm_ref.io.transport.pipes`) within ``timeout`` seconds, except the first of each start
of the program (its ``ready`` to the first ``reset``, start-up included), given
``startup_timeout`` seconds, as is the program's exit after ``bye``; its stderr is copied by a
background thread to ``log`` (if given), the last lines kept for error messages. Every way a
program can fail -- it cannot be started, exits, hangs, writes something that is not a
protocol message (a line that is not UTF-8, or longer than
:data:`~ifgm_ref.io.transport.pipes.MAX_LINE` bytes, included), answers out of turn, exits
non-zero at ``bye`` -- raises :class:`~ifgm_ref.core.errors.ImplementationError` saying what
happened and at which message (and which timeout expired), and kills the program. A broken
adapter stays broken: every later call raises the same error at once
(:attr:`ExternalPlanner.failure`), so that the oracle never waits twice on a dead program.

Nothing the program starts outlives it: on POSIX it runs in a session of its own (it has no
controlling terminal, so it cannot write to the oracle's, and a kill reaches its process
group), and once it has exited, after ``bye`` as after a failure, its whole process group is
killed before it is reaped, so a process it left behind cannot hold its pipes or run on. (A
process that leaves the group, with ``setsid``, escapes this.) Its output is read at most
:data:`~ifgm_ref.io.transport.pipes.MAX_LINE` at a time -- a longer line on stdout is a failure,
one on stderr is copied in pieces -- so no output, however long, fills the oracle's memory.
"""

from __future__ import annotations

import collections
import contextlib
import io
import os
import re
import shlex
import subprocess
import threading
import time
import weakref
from collections.abc import Sequence
from functools import partial
from types import TracebackType
from typing import IO, Any, NoReturn, TextIO

from ifgm_ref.core.errors import ImplementationError, ParameterError, ProtocolError
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.validate import POSITIVE, require
from ifgm_ref.io.transport.pipes import MAX_LINE, LineTooLongError, Pipes, connect
from ifgm_ref.io.transport.processes import copy_lines, exited, kill_process, status_text
from ifgm_ref.io.transport.wire import (
    bye_message,
    decode,
    encode,
    observe_message,
    parse_command,
    parse_ready,
    quote,
    reset_message,
)

__all__ = [
    "STARTUP_TIMEOUT",
    "STDERR_TAIL",
    "TIMEOUT",
    "ExternalFactory",
    "ExternalPlanner",
    "timeouts",
]

#: The default per-reply timeout, s: what a healthy program may take to answer one message.
#: With four oracles on two cores (load average up to 30), ``ifgm-ref serve --planner ifgm``
#: answered each of 9.6 million messages within 1.7 s, and the oracle, given ``timeout=2``,
#: never waited longer for any of 3.3 million (``benchmarks/bench_cmd_load.py``,
#: ``benchmarks/README.md``): a margin of 5.
TIMEOUT = 10.0
#: The default start-up timeout, s: the wait for what a program does once per start, which
#: the machine's load stretches most: its first reply (an interpreter's start, its imports,
#: the first ``reset``) and its exit after ``bye`` (the interpreter's teardown). Under the
#: same load ``ifgm-ref serve --planner ifgm``, which starts in 0.4 s on a quiet machine,
#: took up to 11.5 s to start (258 starts), past the per-reply ``TIMEOUT``, and up to 5.9 s
#: to exit (88 exits): a margin of 5 on both.
STARTUP_TIMEOUT = 60.0

#: How many of the program's last stderr lines an error message quotes: a Python traceback
#: of a few frames fits, a chatty log does not drown the message.
STDERR_TAIL = 20
#: How long to wait for the stderr copier to drain after the program ended, s: the pipe is
#: closed by then unless a grandchild still holds it, which must not stall the report.
DRAIN_WAIT = 1.0
#: What a line read holds where the program's bytes were not UTF-8 (lone surrogates, as
#: :mod:`~ifgm_ref.io.transport.pipes` decodes them: ``surrogateescape``).
_NOT_UTF8 = re.compile("[\udc80-\udcff]")

#: How a message names each timeout, with the command-line option that sets it.
PER_REPLY = "the per-reply timeout, --timeout"
STARTUP = "the start-up timeout, --startup-timeout"


def timeouts(timeout: float, startup_timeout: float | None) -> tuple[float, float]:
    """Check the per-reply and start-up timeouts; return them, the start-up one defaulted.

    Each must be a finite number > 0, in s; ``startup_timeout=None`` stands for the longer
    of :data:`STARTUP_TIMEOUT` and ``timeout`` (a program given long per reply is not given
    less to start).

    >>> timeouts(10, None), timeouts(100.0, None), timeouts(2.0, 5)
    ((10.0, 60.0), (100.0, 100.0), (2.0, 5.0))
    >>> timeouts(1.0, 0)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `startup_timeout` must be a finite number > 0, got 0
    """
    per_reply = require("timeout", timeout, POSITIVE)
    if startup_timeout is None:
        return per_reply, max(STARTUP_TIMEOUT, per_reply)
    return per_reply, require("startup_timeout", startup_timeout, POSITIVE)


class ExternalPlanner:
    """A :class:`~ifgm_ref.core.protocol.Planner` that asks a program over JSON lines.

    Parameters
    ----------
    command : str or sequence of str
        The program and its arguments; a string is split with :func:`shlex.split` (no shell).
    timeout : float, default :data:`TIMEOUT` (10 s)
        Longest wait, in s, for each reply but the first (see ``startup_timeout``).
    startup_timeout : float, optional
        Longest wait, in s, for the first reply of each start of the program (its ``ready``
        to the first ``reset``, which includes the program's start-up: an interpreter, its
        imports) and for the program's exit after ``bye``. Default: :data:`STARTUP_TIMEOUT`
        (60 s), or ``timeout`` if that is longer.
    name : str, optional
        The planner's name in results and reports; default: the command line.
    log : text stream, optional
        Where the program's stderr is copied, line by line, as it comes.
    cwd : path, optional
        The program's working directory.

    Attributes
    ----------
    name : str
        The planner's name.

    Examples
    --------
    >>> import sys
    >>> from ifgm_ref.io.scenarios import resolve_world
    >>> from ifgm_ref.sim.simulator import simulate
    >>> serve = [sys.executable, "-m", "ifgm_ref", "serve", "--planner", "straight"]
    >>> with ExternalPlanner(serve, name="straight") as planner:
    ...     simulate(resolve_world("box"), planner).result.stop_reason
    'collision'
    """

    def __init__(
        self,
        command: str | Sequence[str],
        *,
        timeout: float = TIMEOUT,
        startup_timeout: float | None = None,
        name: str | None = None,
        log: TextIO | None = None,
        cwd: str | os.PathLike[str] | None = None,
    ) -> None:
        argv = tuple(shlex.split(command) if isinstance(command, str) else command)
        if not argv or not all(isinstance(a, str) for a in argv):
            raise ParameterError(
                f"`command` must be a non-empty command line or list of strings, got {command!r}"
            )
        self._argv = argv
        self.timeout, self.startup_timeout = timeouts(timeout, startup_timeout)
        self.name = shlex.join(argv) if name is None else name
        self._log = log
        self._cwd = cwd
        self._process: subprocess.Popen[bytes] | None = None
        self._pipes: Pipes | None = None
        self._stderr_tail: collections.deque[str] = collections.deque(maxlen=STDERR_TAIL)
        self._stderr_copier: threading.Thread | None = None
        self._stderr: IO[str] | None = None
        self._failure: ImplementationError | None = None
        self._episode = EpisodeParams()  # the last reset's: velocity commands are read with it
        self._finalizer: weakref.finalize[..., ExternalPlanner] | None = None

    # --- Planner ---------------------------------------------------------------------------

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Start an episode: send ``reset`` (starting the program if needed), await ``ready``.

        The program is started here if it does not run, and its ``ready`` is then awaited
        ``startup_timeout`` s instead of ``timeout``.

        Raises
        ------
        ImplementationError
            If the program cannot be started, fails or answers anything but ``ready``.
        """
        self._raise_if_failed()
        first = self._process is None
        if first:
            self._start()
        reply = self._exchange(reset_message(start, goal, params), "reset", startup=first)
        self._parse(parse_ready, reply, "reset")
        self._episode = params

    def step(self, observation: Observation) -> Command:
        """Send ``observe`` for one step and return the program's ``command``.

        Raises
        ------
        ImplementationError
            If the program was not reset, fails, or answers anything but a valid ``command``.
        """
        self._raise_if_failed()
        what = f"observe at t={float(observation.t)!r} s"
        if self._process is None:
            raise ImplementationError(f"{what}: reset() was not called (no program running)")
        reply = self._exchange(observe_message(observation), what)
        at = (observation.pose, self._episode)
        return self._parse(partial(parse_command, at=at), reply, what)  # type: ignore[no-any-return]

    # --- lifetime --------------------------------------------------------------------------

    def close(self) -> None:
        """Send ``bye`` and wait for the program to exit with status 0.

        Does nothing if the program is not running (never started, already closed, or killed
        after a failure, which was raised then). A later :meth:`reset` starts it again.

        Raises
        ------
        ImplementationError
            If the program does not exit within ``startup_timeout`` (it is killed), exits with
            a non-zero status, or wrote something it was not asked for.
        """
        process = self._process
        if process is None or self._failure is not None:
            return
        self._check_quiet("bye")
        assert self._pipes is not None
        deadline = time.monotonic() + self.startup_timeout
        self._pipes.send(encode(bye_message()), deadline)  # one that is not read: no exit
        self._pipes.close_input()
        if not exited(process, deadline - time.monotonic()):
            self._fail(
                f"program did not exit within {self.startup_timeout!r} s after bye "
                f"({STARTUP}, which bounds the exit too; program killed)",
                tail=True,
            )
        status = kill_process(process)  # and whatever it left running in its group
        self._drain()
        if status != 0:
            self._fail(f"program {status_text(status)} after bye", tail=True)
        self._check_quiet("bye", after=True)
        self._forget()

    def __enter__(self) -> ExternalPlanner:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        if exc is None:
            self.close()
        else:  # the error in flight is the story; just make sure the program is gone
            self._kill()

    # --- introspection ---------------------------------------------------------------------

    @property
    def argv(self) -> tuple[str, ...]:
        """The program and its arguments."""
        return self._argv

    @property
    def failure(self) -> ImplementationError | None:
        """The error that broke this adapter, or ``None`` while it works."""
        return self._failure

    @property
    def pid(self) -> int | None:
        """The running program's process id, or ``None`` when none runs."""
        return None if self._process is None else self._process.pid

    def __repr__(self) -> str:
        if self._failure is not None:
            state = "failed"
        elif self._process is None:
            state = "not running"
        else:
            state = f"running as pid {self._process.pid}"
        return (
            f"ExternalPlanner({list(self._argv)!r}, timeout={self.timeout!r}, "
            f"startup_timeout={self.startup_timeout!r}, name={self.name!r}) <{state}>"
        )

    # --- the process -----------------------------------------------------------------------

    def _start(self) -> None:
        posix = os.name == "posix"
        try:
            process = subprocess.Popen(
                self._argv,
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                cwd=self._cwd,
                # its own process group, so that a kill reaches what it started, too
                start_new_session=posix,
            )
        except OSError as err:
            self._failure = ImplementationError(
                f"cannot start program {shlex.join(self._argv)!r}: {err}"
            )
            raise self._failure from None
        self._process = process
        self._pipes = connect(process)
        self._stderr_tail = collections.deque(maxlen=STDERR_TAIL)
        assert process.stderr is not None
        self._stderr = io.TextIOWrapper(process.stderr, encoding="utf-8", errors="replace")
        self._stderr_copier = threading.Thread(
            target=copy_lines,
            args=(self._stderr, self._stderr_tail, self._log),
            name=f"stderr of pid {process.pid}",
            daemon=True,
        )
        self._stderr_copier.start()
        self._finalizer = weakref.finalize(self, kill_process, process)

    def _exchange(self, message: dict[str, Any], what: str, *, startup: bool = False) -> str:
        """Send ``message`` and return the reply line, or fail saying what went wrong.

        The reply is awaited ``startup_timeout`` s if it is the program's first (``startup``),
        else ``timeout`` s; a reply that does not come is reported naming that timeout.
        """
        self._check_quiet(what)
        assert self._pipes is not None
        wait, which = (self.startup_timeout, STARTUP) if startup else (self.timeout, PER_REPLY)
        deadline = time.monotonic() + wait
        try:
            if not self._pipes.send(encode(message), deadline):
                raise TimeoutError
            line = self._pipes.receive(deadline)
        except TimeoutError:
            if self._process is not None and exited(self._process, 0.0):
                # gone, but a process it started holds its stdout open: say what it did
                self._wait_for_exit(
                    what,
                    f", but what it started held its stdout open for {wait!r} s "
                    f"({which}; its process group killed)",
                )
            self._fail(f"no reply within {wait!r} s to {what} ({which}; program killed)", tail=True)
        except LineTooLongError as err:
            self._fail(_too_long(err, f"in reply to {what}"))
        if line is None:
            self._wait_for_exit(what)
        return line

    def _parse(self, parser: Any, line: str, what: str) -> Any:
        if (byte := _NOT_UTF8.search(line)) is not None:
            self._fail(
                f"reply to {what} is not UTF-8 (byte 0x{ord(byte.group()) - 0xDC00:02x} at "
                f"column {byte.start() + 1}): {_quote(line)}"
            )
        try:
            return parser(decode(line, what=f"reply to {what}"))
        except ProtocolError as err:
            text = str(err)
            if not text.startswith("reply to "):
                text = f"reply to {what}: {text}; the reply: {quote(line)}"
            self._fail(text)

    def _check_quiet(self, what: str, *, after: bool = False) -> None:
        """Fail if the program wrote a line nobody asked for (it would desynchronise replies)."""
        assert self._pipes is not None
        when = f"after {what}" if after else f"before {what}"
        try:
            line = self._pipes.receive(deadline=0.0)  # long past: look, do not wait
        except TimeoutError:
            return
        except LineTooLongError as err:
            self._fail(_too_long(err, f"nobody asked for, {when}"))
        if line is None:
            if after:
                return
            self._wait_for_exit(what)
        self._fail(f"program wrote a line nobody asked for {when}: {_quote(line)}")

    def _wait_for_exit(self, what: str, how: str = "") -> NoReturn:
        """The program closed its stdout (or exited, ``how`` says what then): report its exit,
        killing it if it lingers, and its process group in any case."""
        process = self._process
        assert process is not None
        if not exited(process, self.timeout):
            self._fail(
                f"program closed its stdout before answering {what} (program killed)", tail=True
            )
        status = kill_process(process)
        self._drain()
        self._fail(f"program {status_text(status)} before answering {what}{how}", tail=True)

    def _drain(self) -> None:
        """Let what reads stdout and stderr finish reading what the ended program wrote."""
        if self._pipes is not None:
            self._pipes.drain(DRAIN_WAIT)
        if self._stderr_copier is not None:
            self._stderr_copier.join(timeout=DRAIN_WAIT)

    def _tail(self) -> str:
        tail = self._stderr_tail.copy()  # atomic: the copier thread may still append
        if not tail:
            return "; no stderr output"
        lines = "".join(f"\n    {line}" for line in tail)
        return f"; last stderr:{lines}"

    def _fail(self, text: str, *, tail: bool = False) -> NoReturn:
        """Kill the program, record the failure (with its last stderr lines), raise it."""
        self._kill()
        self._failure = ImplementationError(f"{self.name}: {text}{self._tail() if tail else ''}")
        raise self._failure

    def _raise_if_failed(self) -> None:
        if self._failure is not None:
            raise self._failure

    def _kill(self) -> None:
        if self._process is not None:
            kill_process(self._process)
            self._drain()
        self._forget()

    def _forget(self) -> None:
        if self._finalizer is not None:
            self._finalizer.detach()
        self._finalizer = None
        process, self._process = self._process, None
        if process is None:
            return
        if self._pipes is not None:
            self._pipes.close()
        self._pipes = None
        # stderr, if a grandchild still holds it open, is left to its copier thread: closing
        # a buffered stream under it would wait for it.
        copier, stderr = self._stderr_copier, self._stderr
        if copier is not None and stderr is not None and not copier.is_alive():
            with contextlib.suppress(OSError, ValueError):
                stderr.close()


def _too_long(err: LineTooLongError, where: str) -> str:
    """Say that the program wrote a line longer than the pipes read, and how it began."""
    return (
        f"program wrote a line longer than {MAX_LINE} bytes {where}, read no further "
        f"(program killed); it began {_quote(err.start)}..."
    )


def _quote(line: str) -> str:
    """:func:`~ifgm_ref.io.transport.wire.quote`, with the bytes that were not UTF-8 shown as
    U+FFFD.

    >>> _quote("caf\\udce9\\n")
    "'caf\ufffd'"
    """
    return quote(_NOT_UTF8.sub("\ufffd", line))


class ExternalFactory:
    """A planner factory for the oracle: one :class:`ExternalPlanner`, started once and
    handed out for every episode (its program plays them one after another).

    It holds only the command and the timeouts (checked here, as :class:`ExternalPlanner`
    checks them) until first called, so it can be copied into another process.
    """

    def __init__(
        self,
        command: str | Sequence[str],
        *,
        timeout: float = TIMEOUT,
        startup_timeout: float | None = None,
        name: str | None = None,
    ) -> None:
        self.command = command
        self.timeout, self.startup_timeout = timeouts(timeout, startup_timeout)
        self.name = name
        self._planner: ExternalPlanner | None = None

    def __call__(self) -> ExternalPlanner:
        if self._planner is None:
            self._planner = ExternalPlanner(
                self.command,
                timeout=self.timeout,
                startup_timeout=self.startup_timeout,
                name=self.name,
            )
        return self._planner

    def close(self) -> None:
        """Send ``bye`` and wait for the program to exit (if it was started)."""
        if self._planner is not None:
            planner, self._planner = self._planner, None
            planner.close()

    def __getstate__(self) -> dict[str, Any]:
        return {**self.__dict__, "_planner": None}
