"""Wall-clock time of the oracle's quick profile against the reference planners.

Run from the project root: ``python benchmarks/bench_oracle.py [--repeats N] [--jobs J]``.

Target (oracle issue): the quick profile of the full suite against the reference IFGM finishes
in under 2 minutes on a 2-core machine, with at least 50 examples per simulation property.
Each pass runs every check (simulation and equations) with ``check_planner(..., jobs=J)``; the
report gives the median pass and the examples and worlds one pass runs (the same on every
pass: the profile is derandomized).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import ifgm_ref.equations
from ifgm_ref.bench.report import machine
from ifgm_ref.oracle.check_types import Kind
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.runner import Status, check_planner


def main() -> None:
    """Time the quick suite and print one line per planner."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=3, help="passes per planner (default 3)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="worker processes")
    parser.add_argument("--planner", action="append", help="planner(s) (default ifgm and iba)")
    args = parser.parse_args()
    print(f"machine: {machine()}; jobs={args.jobs}")
    for planner in args.planner or ["ifgm", "iba"]:
        seconds = []
        for _ in range(args.repeats):
            started = time.perf_counter()
            report = check_planner(
                planner,
                profile="quick",
                equations=ifgm_ref.equations,
                jobs=args.jobs,
                artifacts=None,
            )
            seconds.append(time.perf_counter() - started)
        ran = [r for r in report.results if r.status is not Status.NOT_APPLICABLE]
        fewest = min(r.examples for r in ran if CHECKS[r.check].kind is Kind.SIMULATION)
        print(
            f"{planner}: median {statistics.median(seconds):.1f} s over {args.repeats} passes "
            f"(best {min(seconds):.1f} s); {len(ran)} properties, "
            f"{sum(r.examples for r in ran)} examples ({fewest} or more per simulation "
            f"property), {sum(r.worlds for r in ran)} worlds; all passed: {report.ok}"
        )


if __name__ == "__main__":
    main()
