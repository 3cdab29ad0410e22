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


def by_file(lines: list[dict[str, float | str]]) -> dict[str, list[float]]:
    """Per test file: wall, own, children, waiting (wall beyond processor time), tests."""
    files: dict[str, list[float]] = defaultdict(lambda: [0.0, 0.0, 0.0, 0.0, 0.0])
    for line in lines:
        row = files[str(line["id"]).split("::")[0]]
        wall, own, children = float(line["wall"]), float(line["own"]), float(line["children"])
        for k, value in enumerate((wall, own, children, max(0.0, wall - own - children), 1)):
            row[k] += value
    return files


def main() -> None:
    """Run the tests with the plugin, then print the table by file and the slowest tests."""
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
        lines = [json.loads(text) for f in Path(folder).glob("*.jsonl") for text in f.open()]
    files = by_file(lines)
    cpu = sum(row[1] + row[2] for row in files.values())
    waiting = sum(row[3] for row in files.values())
    print(f"\npytest exited {done.returncode} after {wall:.0f} s wall; {len(lines)} tests took "
          f"{cpu:.0f} s of processor time and waited {waiting:.0f} s")  # fmt: skip
    print(f"\n{'cpu s':>7} {'own':>6} {'child':>6} {'wait':>6} {'tests':>5}  file")
    ranked = sorted(files.items(), key=lambda kv: -(kv[1][1] + kv[1][2]))
    for name, (_, own, children, wait, count) in ranked[: args.top]:
        print(f"{own + children:7.1f} {own:6.1f} {children:6.1f} {wait:6.1f} {count:5.0f}  {name}")
    print(f"\n{'cpu s':>7} {'wait':>6}  test")
    for line in sorted(lines, key=lambda x: -(x["own"] + x["children"]))[: args.top]:
        wait = max(0.0, line["wall"] - line["own"] - line["children"])
        print(f"{line['own'] + line['children']:7.1f} {wait:6.1f}  {line['id']}")
    sys.exit(done.returncode)


if __name__ == "__main__":
    main()
