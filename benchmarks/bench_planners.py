"""The benchmark issue's targets, measured: success, optimality, run time, identical on Dask.

Run from the project root: ``python benchmarks/bench_planners.py`` (``--help`` for options;
needs ``pip install ".[bench,dask]"``). It prints the machine, then one line per target with
the measured figure and whether it is met:

1. the default ``ifgm-ref bench`` (7 planners, classes open/u/h/symmetric, 50 worlds each,
   seed 0) on ``--jobs`` local processes finishes in under 10 minutes (wall clock; the
   median over ``--repeats`` runs);
2. IFGM and IBA reach the goal in 100 % of at least 200 worlds per class with no collision
   (the default run's first 50 worlds plus worlds 50-199, seed 0);
3. IFGM's median path length / optimal is at most 1.3 on the open and symmetric classes
   (over the same 200 worlds per class);
4. the rows of ``--dask-worlds`` worlds per class, all 7 planners, run on a 2-worker Dask
   ``LocalCluster``, equal the local rows in every column but the CPU timing.

It also prints FGM's and APF's success rates per class: the failures Table 1 predicts.
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import time
from collections.abc import Sequence

from ifgm_ref.apps.bench.report import machine, summarize
from ifgm_ref.apps.bench.runner import run_bench
from ifgm_ref.apps.bench.tasks import Row, WorldSpec, generated_specs
from ifgm_ref.apps.cli.bench import DEFAULT_BENCH_CLASSES, DEFAULT_BENCH_PLANNERS

CLASSES = list(DEFAULT_BENCH_CLASSES)
PLANNERS = list(DEFAULT_BENCH_PLANNERS)


def _verdict(ok: bool) -> str:
    return "MET" if ok else "NOT MET"


def _stable(rows: Sequence[Row]) -> list[Row]:
    return [dataclasses.replace(r, decisions_per_cpu_s=None) for r in rows]


def main() -> None:
    """Run the measurements and print one line per target."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, default=2, help="local worker processes (2)")
    parser.add_argument("--repeats", type=int, default=1, help="runs of the default bench (1)")
    parser.add_argument("--per-class", type=int, default=200, help="IFGM/IBA worlds (200)")
    parser.add_argument("--dask-worlds", type=int, default=10, help="worlds per class on Dask")
    args = parser.parse_args()
    print(f"machine: {machine()}; jobs={args.jobs}")

    seconds, rows = [], []
    for _ in range(args.repeats):
        begin = time.perf_counter()
        rows = run_bench(generated_specs(CLASSES, 50, 0), PLANNERS, jobs=args.jobs)
        seconds.append(time.perf_counter() - begin)
    wall = statistics.median(seconds)
    print(
        f"1. default bench, {len(rows)} episodes: median {wall:.1f} s over {len(seconds)} "
        f"run(s) (best {min(seconds):.1f} s); target < 600 s: {_verdict(wall < 600)}"
    )

    extra: list[WorldSpec] = [
        WorldSpec.generated(c, 0, i) for c in CLASSES for i in range(50, args.per_class)
    ]
    more = run_bench(extra, ("ifgm", "iba"), jobs=args.jobs)
    pooled = [r for r in rows if r.planner in ("ifgm", "iba")] + more
    for s in summarize(pooled):
        if s.world_class == "all":
            continue
        ok = s.success_rate == 1.0 and s.collisions == 0
        print(
            f"2. {s.planner} {s.world_class}: {s.success_rate:.1%} of {s.worlds} reached, "
            f"{s.collisions} collisions; target 100 %, 0: {_verdict(ok)}"
        )
        if s.planner == "ifgm" and s.world_class in ("open", "symmetric"):
            ratio = s.path_ratio_median
            met = _verdict(ratio is not None and ratio <= 1.3)
            print(
                f"3. ifgm {s.world_class}: median path/optimal {ratio:.3f} (p90 "
                f"{s.path_ratio_p90:.3f}); target <= 1.3: {met}"
            )
    for s in summarize(rows):
        if s.planner in ("fgm", "apf") and s.world_class != "all":
            print(f"   {s.planner} {s.world_class}: {s.success_rate:.1%} of {s.worlds} reached")

    from distributed import LocalCluster

    subset = [WorldSpec.generated(c, 0, i) for c in CLASSES for i in range(args.dask_worlds)]
    local = [r for r in rows if r.world in {s.name for s in subset}]
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster:
        begin = time.perf_counter()
        remote = run_bench(subset, PLANNERS, scheduler=cluster.scheduler_address)
        took = time.perf_counter() - begin
    same = _stable(remote) == _stable(local)
    print(
        f"4. Dask LocalCluster (2 workers), {len(remote)} episodes in {took:.1f} s: rows "
        f"{'identical' if same else 'DIFFERENT'} to the local pool's: {_verdict(same)}"
    )


if __name__ == "__main__":
    main()
