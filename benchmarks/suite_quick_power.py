"""How much of the full tier's power the suite's quick tier keeps, over mutants' full runs.

Run from the project root, on the run files of ``bench_mutation.py --levels suite_cases``
(each trace-changing mutant's full tier, every case run)::

    python benchmarks/suite_quick_power.py mutation-results/suite-runs/*.jsonl [--suite v1]

Target (issue 43): the quick tier kills at least 95 % of the mutants the full tier kills.
A mutant is killed by a tier when it fails (or errs on) one of the tier's cases; the quick
tier is the one installed now (``ifgm-ref suite tiers`` may have chosen it again since the
runs). Prints each mutant's verdict under both tiers, the kill counts and their ratio. Run it
on mutants drawn with another seed than those the quick tier was chosen with, to see it
generalize.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ifgm_ref.oracle.suite.tiers import kills_in_runs
from ifgm_ref.oracle.suite.versions import load_suite


def main() -> None:
    """Print the quick and full tiers' kills over the run files given."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", type=Path, help="full-tier run files, one a mutant")
    parser.add_argument("--suite", default="v1", help="the suite version (default v1)")
    args = parser.parse_args()
    quick = {case.id for case in load_suite(args.suite).tier("quick")}
    kills = kills_in_runs(args.runs)
    full = [name for name, ids in kills.items() if ids]
    by_quick = [name for name in full if set(kills[name]) & quick]
    for name, ids in sorted(kills.items()):
        caught = sorted(set(ids) & quick)
        print(f"{name:<12} full: {len(ids):>3} cases kill it; quick: {', '.join(caught) or '-'}")
    share = 100.0 * len(by_quick) / len(full) if full else 100.0
    print(
        f"{len(kills)} mutants; the full tier kills {len(full)}, the quick tier ({len(quick)} "
        f"cases) {len(by_quick)}: {share:.0f} % of the full tier's kills"
    )


if __name__ == "__main__":
    main()
