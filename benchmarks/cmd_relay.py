"""A relay between the oracle and a JSON-lines program that times every reply.

Run as ``python benchmarks/cmd_relay.py LOG_DIR -- PROGRAM [ARG ...]``, e.g. as the oracle's
``--cmd``. It starts ``PROGRAM``, copies each line of its own stdin to the program's stdin and
each line of the program's stdout to its own (flushed), and leaves the program's stderr to
the oracle. For every reply it appends one JSON line to ``LOG_DIR/relay-<pid>.jsonl``:

- ``{"startup": S}`` for the first reply: seconds from the relay's own process start (read
  from ``/proc/self/stat``, 10 ms resolution; elsewhere from the relay's first line of code)
  to that reply, which is what the oracle waits for its first ``ready`` (the relay's and the
  program's start-up, and the first ``reset``);
- ``{"reply": S}`` for every later one: seconds from the request's arrival at the relay to
  its reply, which is what the oracle waits per reply, less two pipe hops;
- ``{"exit": S}`` at the end: seconds from the end of the relay's input (the oracle closes
  it after ``bye``) to the program's exit, which is most of what the oracle waits for the
  exit (the relay's own exit follows).

Every record is written and flushed at once, so a relay the oracle kills has logged every
reply it relayed. The relay exits with the program's status. Standard library only: it is a
program under test's front, and must start fast. ``bench_cmd_load.py`` reads the logs.
"""

from __future__ import annotations

import time

_BEGUN = time.monotonic()  # before the other imports: the fallback start of the process

import collections  # noqa: E402 -- after the clock read, on purpose
import json  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import threading  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import IO  # noqa: E402


def process_start() -> float:
    """When this process started, on :func:`time.monotonic`'s clock, s.

    Linux: ``/proc/self/stat``'s start time (clock ticks since boot) against the boot-time
    clock, which is the monotonic clock where the machine never suspended. Elsewhere: when
    this module began.
    """
    try:
        fields = Path("/proc/self/stat").read_text().rpartition(")")[2].split()
        ticks = int(fields[19])  # field 22 of proc(5); fields[0] is field 3
        age = time.clock_gettime(time.CLOCK_BOOTTIME) - ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError, AttributeError):
        return _BEGUN
    return time.monotonic() - age


class _Log:
    """One relay's records, one JSON object a line, each flushed as it is written."""

    def __init__(self, folder: Path) -> None:
        folder.mkdir(parents=True, exist_ok=True)
        self._file = (folder / f"relay-{os.getpid()}.jsonl").open("a", buffering=1)

    def write(self, record: dict[str, float]) -> None:
        self._file.write(json.dumps(record) + "\n")


def _relay_replies(
    replies: IO[str], out: IO[str], sent: collections.deque[float], log: _Log, began: float
) -> None:
    """Copy the program's replies to ``out``, logging each one's latency (a thread)."""
    first = True
    for line in replies:
        now = time.monotonic()
        out.write(line)
        out.flush()
        asked = sent.popleft() if sent else now  # an unasked line: latency 0, the oracle sees it
        if first:
            log.write({"startup": now - began})
            first = False
        else:
            log.write({"reply": now - asked})


def main(argv: list[str]) -> int:
    """Relay between stdin/stdout and ``argv``'s program; return the program's exit status."""
    if len(argv) < 3 or argv[1] != "--":
        print("usage: cmd_relay.py LOG_DIR -- PROGRAM [ARG ...]", file=sys.stderr)
        return 2
    began = process_start()
    log = _Log(Path(argv[0]))
    program = subprocess.Popen(
        argv[2:], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, bufsize=1
    )
    assert program.stdin is not None and program.stdout is not None
    sent: collections.deque[float] = collections.deque()
    copier = threading.Thread(
        target=_relay_replies, args=(program.stdout, sys.stdout, sent, log, began), daemon=True
    )
    copier.start()
    try:
        for line in sys.stdin:
            sent.append(time.monotonic())
            program.stdin.write(line)
            program.stdin.flush()
        ended = time.monotonic()
        program.stdin.close()
    except BrokenPipeError:
        ended = math.nan  # the program ended first; its status says how
    status = program.wait()
    log.write({"exit": time.monotonic() - ended})
    copier.join()
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
