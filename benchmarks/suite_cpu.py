"""Where the test run's time goes: processor time per test file, and time spent waiting.

Runs the README's test command (``python3 -m pytest``, with any arguments given after
``--``) with this module as a plugin in every worker, which records for each test its wall
time, its own processor time and that of the processes it waited for (a notebook's kernel,
the site's Sphinx, an ``ifgm-ref`` command). A test's waiting is its wall time beyond the
processor time: with as many workers as processors that is the test's own waiting (a timeout,
a sleeping program); with more workers (``-n auto`` starts one more, tests/conftest.py) it
also holds the time the worker waited for a processor. The run is bound by processor time
when the waiting is small: two workers on two cores then take about half the processor time,
whatever the order of the tests (docs/testing.md)::

    python benchmarks/suite_cpu.py -- -n 2
    python benchmarks/suite_cpu.py --top 15 -- tests/test_oracle.py

A test's children are counted when it waits for them; a process pool's workers count for the
test that closes the pool. Collection and each worker's start are not in any test.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from collections.abc import Generator
from pathlib import Path
from typing import NamedTuple

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: The folder each worker writes its lines into (set by :func:`main` for the run).
OUT = "IFGM_SUITE_CPU_OUT"


def _cpu() -> tuple[float, float]:
    """Processor time (user and system) of this process, and of its children waited for, s."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime, children.ru_utime + children.ru_stime


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item: pytest.Item) -> Generator[None, None, None]:
    """Record the test's wall, own and children's processor time, set-up and tear-down
    included, as one JSON line in this process's file."""
    began, (own, children) = time.perf_counter(), _cpu()
    yield
    wall, (own_after, children_after) = time.perf_counter() - began, _cpu()
    line = {"id": item.nodeid, "wall": wall, "own": own_after - own}
    line["children"] = children_after - children
    with (Path(os.environ[OUT]) / f"{os.getpid()}.jsonl").open("a") as out:
        out.write(json.dumps(line) + "\n")


class Timed(NamedTuple):
    """One test's times, s: wall, its own processor time, its children's."""

    id: str
    wall: float
    own: float
    children: float

    @property
    def cpu(self) -> float:
        """Processor time, the test's and its children's."""
        return self.own + self.children

    @property
    def waiting(self) -> float:
        """Wall time beyond the processor time."""
        return max(0.0, self.wall - self.cpu)


def by_file(tests: list[Timed]) -> dict[str, list[Timed]]:
    """The tests of each test file (or module, for the doctests)."""
    files: dict[str, list[Timed]] = defaultdict(list)
    for test in tests:
        files[test.id.split("::")[0]].append(test)
    return files


def main() -> None:
    """Run the tests with the plugin, then print the table by file and the costliest tests."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--top", type=int, default=25, help="rows of each table (25)")
    parser.add_argument("pytest_args", nargs="*", help="after --: arguments for pytest")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        env = dict(os.environ, **{OUT: folder})
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
        command = [sys.executable, "-m", "pytest", "-p", "benchmarks.suite_cpu", "-q"]
        began = time.perf_counter()
        done = subprocess.run([*command, *args.pytest_args], cwd=ROOT, env=env, check=False)
        wall = time.perf_counter() - began
        tests = [
            Timed(**json.loads(text)) for f in Path(folder).glob("*.jsonl") for text in f.open()
        ]
    print(f"\npytest exited {done.returncode} after {wall:.0f} s wall; {len(tests)} tests took "
          f"{sum(t.cpu for t in tests):.0f} s of processor time and waited "
          f"{sum(t.waiting for t in tests):.0f} s")  # fmt: skip
    print(f"\n{'cpu s':>7} {'own':>6} {'child':>6} {'wait':>6} {'tests':>5}  file")
    files = sorted(by_file(tests).items(), key=lambda kv: -sum(t.cpu for t in kv[1]))
    for name, mine in files[: args.top]:
        own, children = sum(t.own for t in mine), sum(t.children for t in mine)
        wait = sum(t.waiting for t in mine)
        print(
            f"{own + children:7.1f} {own:6.1f} {children:6.1f} {wait:6.1f} {len(mine):5d}  {name}"
        )
    print(f"\n{'cpu s':>7} {'wait':>6}  test")
    for test in sorted(tests, key=lambda t: -t.cpu)[: args.top]:
        print(f"{test.cpu:7.1f} {test.waiting:6.1f}  {test.id}")
    sys.exit(done.returncode)


if __name__ == "__main__":
    main()
