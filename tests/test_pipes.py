"""Both kinds of :class:`~ifgm_ref.io.transport.pipes.Pipes` keep the same contract.

The adapter's own failure tests (``tests/test_external.py``) run over the platform's kind;
here each contract point is checked for both, since the threaded kind serves where the
polled one cannot (Windows) and CI runs on Linux.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
import time
import tracemalloc
from collections.abc import Callable, Iterator

import pytest

from ifgm_ref.io.transport.pipes import CHUNK, MAX_LINE, LineTooLongError, Pipes, connect

#: A program's behaviour after its prelude, by name: it echoes, or misbehaves.
PROGRAMS = {
    # each line read is written back, upper-cased
    "echo": "for line in sys.stdin:\n    out(line.upper())",
    # writes a line, then a last one without a newline, and exits
    "partial": "out('one\\n'); out('two')",
    # answers one line with two, then echoes
    "chatty": "sys.stdin.readline(); out('a\\nb\\n')\nfor line in sys.stdin:\n    out(line)",
    # never reads, never writes
    "deaf": "time.sleep(30)",
    # writes bytes that are not UTF-8
    "bad_bytes": "sys.stdout.buffer.write(b'caf\\xe9\\r\\n'); sys.stdout.flush()",
    # a line of the longest length read, then one a byte longer
    "longest": f"out('x' * {MAX_LINE} + '\\n'); out('y' * {MAX_LINE + 1} + '\\n')",
    # a line of 100 MB, written a chunk at a time
    "huge": f"for _ in range({100 * 2**20 // CHUNK}):\n    out('x' * {CHUNK})\nout('\\n')",
    # a line that never ends
    "endless": f"while True:\n    out('x' * {CHUNK})",
    # lines without end
    "flood": f"while True:\n    out('x\\n' * {CHUNK // 2})",
}
PRELUDE = """
import sys, time

def out(text):
    sys.stdout.write(text)
    sys.stdout.flush()
"""
Connect = Callable[[str], Pipes]


@pytest.fixture(params=[True, False], ids=["polled", "threaded"])
def start(request: pytest.FixtureRequest) -> Iterator[Connect]:
    """Start one of :data:`PROGRAMS` and connect to it with the kind of pipes of the param."""
    started: list[tuple[subprocess.Popen[bytes], Pipes]] = []

    def make(name: str) -> Pipes:
        code = PRELUDE + textwrap.dedent(PROGRAMS[name])
        process = subprocess.Popen(
            [sys.executable, "-c", code], stdin=subprocess.PIPE, stdout=subprocess.PIPE
        )
        pipes = connect(process, polled=request.param)
        started.append((process, pipes))
        return pipes

    yield make
    for process, pipes in started:
        process.kill()
        process.wait()
        pipes.close()


def soon(seconds: float = 10.0) -> float:
    return time.monotonic() + seconds


def test_a_line_sent_is_answered(start: Connect) -> None:
    pipes = start("echo")
    for word in ["hello", "world é"]:
        assert pipes.send(word, soon())
        assert pipes.receive(soon()) == word.upper() + "\n"


def test_nothing_to_read_times_out_at_the_deadline(start: Connect) -> None:
    pipes = start("echo")
    began = time.monotonic()
    with pytest.raises(TimeoutError):
        pipes.receive(began + 0.3)
    assert 0.3 <= time.monotonic() - began < 2.0
    with pytest.raises(TimeoutError):  # a deadline past: a look, no wait
        pipes.receive(0.0)


def test_a_line_nobody_asked_for_is_seen_without_waiting(start: Connect) -> None:
    pipes = start("chatty")
    assert pipes.send("x", soon())
    assert pipes.receive(soon()) == "a\n"
    deadline = soon(5.0)
    while True:  # the second line is on its way: look until it is there
        try:
            line = pipes.receive(0.0)
            break
        except TimeoutError:
            assert time.monotonic() < deadline
            time.sleep(0.01)
    assert line == "b\n"


def test_the_end_of_output_keeps_the_last_line_and_then_reads_none(start: Connect) -> None:
    pipes = start("partial")
    assert [pipes.receive(soon()) for _ in range(4)] == ["one\n", "two", None, None]


def test_bytes_that_are_not_utf8_are_escaped_and_crlf_read_as_newline(start: Connect) -> None:
    pipes = start("bad_bytes")
    line = pipes.receive(soon())
    assert ascii(line) == ascii("caf\udce9\n")  # the byte 0xe9, told from a U+FFFD sent


def test_a_line_longer_than_max_line_is_refused(start: Connect) -> None:
    pipes = start("longest")
    assert pipes.receive(soon()) == "x" * MAX_LINE + "\n"
    for _ in range(2):  # refused, and nothing more read
        with pytest.raises(LineTooLongError) as info:
            pipes.receive(soon())
        assert info.value.start == "y" * 200


@pytest.mark.parametrize("program", ["huge", "endless"])
def test_a_line_without_end_takes_no_more_memory_than_max_line(
    start: Connect, program: str
) -> None:
    tracemalloc.start()
    try:
        pipes = start(program)
        with pytest.raises(LineTooLongError):
            pipes.receive(soon())
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 4 * MAX_LINE  # the 100 MB (or more) were neither read nor held


def test_a_flood_of_lines_is_read_only_as_asked(start: Connect) -> None:
    tracemalloc.start()
    try:
        pipes = start("flood")
        time.sleep(0.5)  # the program writes lines as fast as it can: tens of MB, unread
        assert pipes.receive(soon()) == "x\n"
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < MAX_LINE // 2  # a read's worth (tens of kB), not the flood


def test_a_program_that_never_reads_cannot_block_the_caller(start: Connect) -> None:
    pipes = start("deaf")
    line = "x" * 100_000  # more than a pipe holds
    began = time.monotonic()
    with pytest.raises(TimeoutError):
        for _ in range(10):
            if not pipes.send(line, began + 0.5):
                raise TimeoutError
            pipes.receive(began + 0.5)
    assert time.monotonic() - began < 3.0


def test_closing_the_input_ends_the_program(start: Connect) -> None:
    pipes = start("echo")
    assert pipes.send("last", soon())
    pipes.close_input()
    assert pipes.receive(soon()) == "LAST\n"
    assert pipes.receive(soon()) is None
