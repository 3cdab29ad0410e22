"""The oracle's power in the paper's trap: how often the quick profile rejects what it must.

Run from the project root: ``python benchmarks/bench_oracle_power.py`` (``--help`` for
options). Table 1 says FGM and APF cannot avoid U and H shaped obstacles, and IFGM's
dead-end rule is what gets it out of them (section 4). Offered as IFGM (``promises="ifgm"``),
FGM, APF and IFGM without its dead-end rule (``mutants.NoDeadEndRule``) must fail
``converges_u`` or ``converges_h``; IFGM, IBA and the faithful variants
(:mod:`ifgm_ref.oracle.variants`) must pass both.

Target (issue "the oracle a stranger can trust"): each planner meant to be rejected is
rejected under the derandomized quick profile and under at least 9 of 10 random seeds; each
planner meant to pass passes under all of them. The quick profile's 50 examples per check
are drawn from the seed (``Profile(seed=...)``), without shrinking (the verdict is all that
is counted). It prints one line per planner: verdicts per seed, examples up to the first
failure, and whether the target is met.
"""

from __future__ import annotations

import argparse
import os
import statistics
from concurrent.futures import ProcessPoolExecutor

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.mutants import MUTANTS
from ifgm_ref.oracle.profiles import Profile
from ifgm_ref.oracle.runner import run_check
from ifgm_ref.oracle.variants import VARIANTS

#: Planners that must be rejected: built-in names or mutant names.
REJECT = ("fgm", "apf", "no_dead_end_rule")
#: Planners that must pass (with ``--accepted``): built-in names or variant names.
ACCEPT = ("ifgm", "iba", *VARIANTS)
#: The convergence checks of the paper's trap.
TRAP_CHECKS = ("converges_u", "converges_h")


def _implementation(name: str) -> Implementation:
    if name in MUTANTS:
        return Implementation(MUTANTS[name], name, promises_of("ifgm"))
    if name in VARIANTS:
        return Implementation(VARIANTS[name], name, promises_of("ifgm"))
    return Implementation.from_spec(name, promises="ifgm" if name != "iba" else "iba")


def _verdict(task: tuple[str, int | None, str]) -> tuple[str, int | None, str, bool, int]:
    """Run one check of one planner under one seed (``None``: derandomized)."""
    name, seed, check = task
    profile = Profile("quick", 50, shrink=False, seed=seed)
    result = run_check(CHECKS[check], _implementation(name), profile, artifacts=None)
    return name, seed, check, result.ok, result.examples


def main() -> None:
    """Run the trap checks per planner and seed; print the rejection counts."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=10, help="random seeds 0..N-1 (default 10)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="worker processes")
    parser.add_argument(
        "--accepted", action="store_true", help="also run the planners that must pass (slow)"
    )
    args = parser.parse_args()
    names = [*REJECT, *(ACCEPT if args.accepted else ())]
    seeds: list[int | None] = [None, *range(args.seeds)]
    tasks = [(n, s, c) for n in names for s in seeds for c in TRAP_CHECKS]
    print(f"machine: {machine()}; jobs={args.jobs}; quick profile, seeds 0..{args.seeds - 1}")
    with ProcessPoolExecutor(args.jobs) as pool:
        results = list(pool.map(_verdict, tasks))
    for name in names:
        mine = [r for r in results if r[0] == name]
        rejected = {s for _, s, _, ok, _ in mine if not ok}
        first = [n for _, _, _, ok, n in mine if not ok]
        derandomized = None in rejected
        random_rejections = len(rejected - {None})
        if name in REJECT:
            met = derandomized and random_rejections >= args.seeds - args.seeds // 10
            how = f"examples to the first failure: median {statistics.median(first):g}"
        else:
            met = not rejected
            how = f"{sum(n for *_, n in mine)} examples"
        print(
            f"{name:18} {'must fail' if name in REJECT else 'must pass'}: rejected "
            f"derandomized: {'yes' if derandomized else 'no'}; under {random_rejections} of "
            f"{args.seeds} random seeds; {how}: {'MET' if met else 'NOT MET'}"
        )


if __name__ == "__main__":
    main()
