"""Wall-clock time of the oracle's quick profile against the reference planners.

Run from the project root: ``python benchmarks/bench_oracle.py [--repeats N] [--jobs J]
[--level paper,reference]``.

Target (oracle issue): the quick profile of the full suite against the reference IFGM finishes
in under 2 minutes on a 2-core machine, with at least 50 examples per simulation property.
Each pass runs every check (simulation and equations) with ``check_planner(..., jobs=J)``; the
report gives the median pass and the examples and worlds one pass runs (the same on every
pass: the profile is derandomized). With several ``--level`` values the levels alternate
within each repeat, so that a change of the machine's load falls on both (issue 26's target:
the reference level's quick profile takes at most 1.5 times the paper level's).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import ifgm_ref.paper.equations
from ifgm_ref.apps.bench.report import machine
from ifgm_ref.oracle.check_types import Kind
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.runner import Report, Status, check_planner


def main() -> None:
    """Time the quick suite and print one line per planner."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=3, help="passes per planner (default 3)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="worker processes")
    parser.add_argument("--planner", action="append", help="planner(s) (default ifgm and iba)")
    parser.add_argument(
        "--level", default="paper", help="level(s), comma-separated: paper, reference (paper)"
    )
    args = parser.parse_args()
    levels = args.level.split(",")
    print(f"machine: {machine()}; jobs={args.jobs}")
    for planner in args.planner or ["ifgm", "iba"]:
        seconds: dict[str, list[float]] = {level: [] for level in levels}
        reports: dict[str, Report] = {}
        for _ in range(args.repeats):
            for level in levels:
                started = time.perf_counter()
                reports[level] = check_planner(
                    planner,
                    profile="quick",
                    equations=ifgm_ref.paper.equations,
                    jobs=args.jobs,
                    artifacts=None,
                    level=level,
                )
                seconds[level].append(time.perf_counter() - started)
        for level in levels:
            _print(f"{planner} ({level} level)", seconds[level], reports[level])


def _print(what: str, seconds: list[float], report: Report) -> None:
    ran = [r for r in report.results if r.status is not Status.NOT_APPLICABLE]
    fewest = min(r.examples for r in ran if CHECKS[r.check].kind is Kind.SIMULATION)
    print(
        f"{what}: median {statistics.median(seconds):.1f} s over {len(seconds)} passes "
        f"(best {min(seconds):.1f} s); {len(ran)} properties, "
        f"{sum(r.examples for r in ran)} examples ({fewest} or more per simulation "
        f"property), {sum(r.worlds for r in ran)} worlds; all passed: {report.ok}"
    )


if __name__ == "__main__":
    main()
