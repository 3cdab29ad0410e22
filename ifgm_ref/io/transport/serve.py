"""The program side of the JSON-lines protocol around any Python planner (``ifgm-ref serve``).

:func:`serve` reads the oracle's messages from ``stdin`` one line at a time and answers on
``stdout`` (``docs/oracle-protocol.md``): ``reset`` builds a *fresh* planner from the factory
and resets it, so that the episodes of one session are independent, exactly as separate
in-process runs are; ``observe`` steps it; ``bye`` ends the session. Every reply is flushed at
once. Whatever the planner prints goes to ``stderr``, never into the protocol.

Exit status: 0 after ``bye``; 2 on a malformed message, a message out of order, end of input
before ``bye``, or bad input the planner itself rejects (an :class:`IfgmRefError`, e.g. an
out-of-range ``params`` value); 1 when the planner crashes or returns a command JSON cannot
carry. Either failure writes one line ``ifgm-ref serve: error: ...`` on ``stderr`` (a crash
writes its traceback first).
"""

from __future__ import annotations

import contextlib
import traceback
from collections.abc import Callable
from typing import Any, TextIO

from ifgm_ref.core.errors import IfgmRefError, ProtocolError
from ifgm_ref.core.protocol import Command, Planner
from ifgm_ref.io.transport.wire import (
    MessageType,
    command_message,
    decode,
    encode,
    message_type,
    parse_bye,
    parse_observe,
    parse_reset,
    ready_message,
)

__all__ = ["EXIT_BAD_INPUT", "EXIT_OK", "EXIT_PLANNER_CRASHED", "serve"]

#: The session ended with ``bye``.
EXIT_OK = 0
#: The planner raised an unexpected exception or returned something JSON cannot carry.
EXIT_PLANNER_CRASHED = 1
#: A message was malformed or out of order, or input ended before ``bye``.
EXIT_BAD_INPUT = 2
#: Prefix of the one-line error report on stderr.
ERROR_PREFIX = "ifgm-ref serve: error: "


class _PlannerCrashed(Exception):
    """The planner under serve raised an exception that is not bad input."""


def serve(
    planner_factory: Callable[[], Planner], stdin: TextIO, stdout: TextIO, stderr: TextIO
) -> int:
    """Answer the oracle's messages with a planner from ``planner_factory``; return the status.

    Parameters
    ----------
    planner_factory : callable
        Called with no argument at every ``reset`` for a new :class:`Planner` (a class is
        such a callable; see :func:`ifgm_ref.io.transport.loading.load_factory`).
    stdin, stdout, stderr : text streams
        The oracle's messages, the replies (one JSON object a line, flushed after each), and
        the log: the planner's own output and the one-line error report.

    Returns
    -------
    int
        0 after ``bye``; 2 on bad input; 1 when the planner crashed (see the module docstring).

    Examples
    --------
    >>> import io
    >>> from ifgm_ref.planners import StraightPlanner
    >>> from ifgm_ref.core.protocol import EpisodeParams
    >>> from ifgm_ref.core.pose import Point, Pose
    >>> from ifgm_ref.io.transport.wire import bye_message, encode, reset_message
    >>> reset = reset_message(Pose(0.0, 0.0, 0.0), Point(0.0, 5.0), EpisodeParams())
    >>> stdin = io.StringIO(encode(reset) + "\\n" + encode(bye_message()) + "\\n")
    >>> stdout, stderr = io.StringIO(), io.StringIO()
    >>> serve(StraightPlanner, stdin, stdout, stderr), stdout.getvalue()
    (0, '{"type": "ready"}\\n')

    A malformed line ends the session with status 2 and one line on stderr:

    >>> serve(StraightPlanner, io.StringIO("hello\\n"), stdout, stderr), stderr.getvalue()
    (2, "ifgm-ref serve: error: line 1 is not JSON: 'hello' (Expecting value at column 1)\\n")
    """
    session = _Session(planner_factory, stdout, stderr)
    try:
        session.run(stdin)
    except IfgmRefError as err:
        _report(stderr, str(err))
        return EXIT_BAD_INPUT
    except _PlannerCrashed as crash:
        if crash.__cause__ is not None:
            traceback.print_exception(crash.__cause__, file=stderr)
        _report(stderr, f"line {session.number}: {crash}")
        return EXIT_PLANNER_CRASHED
    return EXIT_OK


class _Session:
    """One session of :func:`serve`: the planner of the current episode, the line number."""

    def __init__(
        self, planner_factory: Callable[[], Planner], stdout: TextIO, stderr: TextIO
    ) -> None:
        self.planner_factory = planner_factory
        self.stdout = stdout
        self.stderr = stderr
        self.planner: Planner | None = None
        #: The number of the line read last (1 for the first).
        self.number = 0

    def run(self, stdin: TextIO) -> None:
        """Answer every line up to ``bye``; raise at bad input or a planner crash."""
        while True:
            line = stdin.readline()
            self.number += 1
            if not line:
                raise ProtocolError(f"end of input after {self.number - 1} line(s), before bye")
            if not line.strip():
                continue  # a blank line carries nothing; the oracle never sends one
            message = decode(line, what=f"line {self.number}")
            kind = message_type(message, where=f"line {self.number}")
            try:
                if self.answer(kind, message):
                    return
            except IfgmRefError as err:
                raise type(err)(f"line {self.number} ({kind.value}): {err}") from None

    def answer(self, kind: MessageType, message: dict[str, Any]) -> bool:
        """Answer one message of type ``kind``; return whether it was ``bye``."""
        if kind is MessageType.RESET:
            reset = parse_reset(message)
            self.planner = _call(self.stderr, self.planner_factory)
            _call(self.stderr, self.planner.reset, reset.start, reset.goal, reset.params)
            _send(self.stdout, encode(ready_message()))
        elif kind is MessageType.OBSERVE:
            if self.planner is None:
                raise ProtocolError("observe before the first reset")
            command = _call(self.stderr, self.planner.step, parse_observe(message))
            _send(self.stdout, _command_line(command))
        elif kind is MessageType.BYE:
            parse_bye(message)
            return True
        else:
            raise ProtocolError(
                f"type {kind.value!r}, but should be 'reset', 'observe' or 'bye' "
                "(the program sends ready and command, the oracle does not)"
            )
        return False


def _call(stderr: TextIO, function: Callable[..., Any], *args: Any) -> Any:
    """Call planner code with its prints sent to ``stderr``; wrap a crash."""
    try:
        with contextlib.redirect_stdout(stderr):
            return function(*args)
    except IfgmRefError:
        raise
    except Exception as err:
        name = getattr(function, "__qualname__", repr(function))
        raise _PlannerCrashed(f"{name} raised {type(err).__name__}: {err}") from err


def _command_line(command: object) -> str:
    """The planner's command as one line, or :class:`_PlannerCrashed` if it has none."""
    if not isinstance(command, Command):
        raise _PlannerCrashed(
            f"step() returned {type(command).__name__}, but should return a Command"
        )
    try:
        return encode(command_message(command))
    except ProtocolError as err:
        raise _PlannerCrashed(f"step() returned {command!r}, which JSON cannot carry") from err


def _send(stdout: TextIO, line: str) -> None:
    stdout.write(line + "\n")
    stdout.flush()


def _report(stderr: TextIO, text: str) -> None:
    stderr.write(ERROR_PREFIX + " ".join(text.splitlines()) + "\n")
    stderr.flush()
