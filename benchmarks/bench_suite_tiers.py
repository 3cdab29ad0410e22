"""Wall-clock time of the frozen suite's quick tier beside the drawn quick profile.

Run from the project root::

    python benchmarks/bench_suite_tiers.py [--repeats 3] [--suite v1] [--c-build DIR]

Target (issue 43): the quick tier passes for the C port (``examples/c``, built with ``make
BUILD=DIR``) in at most 15 s on 2 cores, and for the Python reference in process in at most
15 s, measured side by side with today's quick profile in one run. Each repeat runs, in turn,
for the reference (``--planner ifgm``) and for the C port (``--cmd DIR/ifgm_json``): the drawn
quick profile at both levels (``ifgm-ref oracle --level reference``, every simulation check
but ``stops_in_time`` for the C port, as its test does) and the suite's quick tier at both
levels, each as a whole command (start-up included). It prints the median seconds of each,
their ratio, the verdicts and the machine's load.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.oracle.check_types import Kind
from ifgm_ref.oracle.checks import CHECKS

ROOT = Path(__file__).resolve().parent.parent


def _timed(command: list[str]) -> tuple[float, int, str]:
    """Seconds, exit status and last stderr line of ``command``."""
    started = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, check=False)
    lines = done.stderr.strip().splitlines() or [""]
    return time.perf_counter() - started, done.returncode, lines[-1]


def _commands(who: list[str], suite: str, results: Path, drawn: list[str]) -> dict[str, list[str]]:
    oracle = [sys.executable, "-m", "ifgm_ref", "oracle", *who, "--level", "reference"]
    return {
        "quick profile": [*oracle, "--artifacts", str(results / "drawn"), *drawn],
        "suite quick tier": [
            *oracle,
            "--suite",
            suite,
            "--tier",
            "quick",
            "--results",
            str(results / "run.jsonl"),
            "--artifacts",
            str(results / "suite"),
        ],
    }


def main() -> None:
    """Time both ways for both implementations and print the medians."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=3, help="runs of each (default 3)")
    parser.add_argument("--suite", default="v1", help="the suite version (default v1)")
    parser.add_argument("--c-build", type=Path, help="a build of examples/c (default: made)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench-suite-") as folder:
        results = Path(folder)
        build = args.c_build or results / "c"
        if args.c_build is None:
            subprocess.run(
                ["make", "-s", "-C", str(ROOT / "examples/c"), f"BUILD={build}"], check=True
            )
        no_stops = [f"--check={n}" for n, c in CHECKS.items() if c.kind is Kind.SIMULATION]
        no_stops.remove("--check=stops_in_time")
        who = {
            "reference (in process)": (["--planner", "ifgm"], []),
            "C port": (
                ["--cmd", f"{build / 'ifgm_json'} --planner ifgm", "--promises", "ifgm"],
                no_stops,
            ),
        }
        print(f"machine: {machine()}; load before: {os.getloadavg()[0]:.2f}")
        for name, (options, drawn) in who.items():
            commands = _commands(options, args.suite, results, drawn)
            seconds: dict[str, list[float]] = {way: [] for way in commands}
            last: dict[str, str] = {}
            for _ in range(args.repeats):
                for way, command in commands.items():
                    spent, status, line = _timed(command)
                    seconds[way].append(spent)
                    last[way] = f"exit {status}: {line}"
                    shutil.rmtree(results / "drawn", ignore_errors=True)
            medians = {way: statistics.median(found) for way, found in seconds.items()}
            for way, median in medians.items():
                spread = f"{min(seconds[way]):.1f}-{max(seconds[way]):.1f}"
                print(f"{name:<24} {way:<17} median {median:6.1f} s ({spread}); {last[way]}")
            ratio = medians["suite quick tier"] / medians["quick profile"]
            summary = json.loads((results / "run.jsonl").read_text().splitlines()[-1])
            print(f"{name:<24} suite/profile {ratio:.2f}; suite cases {summary['cases']}")
        print(f"load after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
