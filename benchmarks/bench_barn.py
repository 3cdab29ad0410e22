"""The planners on BARN's worlds: success, collisions, timeouts, BARN's score, wall time.

Run from the project root: ``python benchmarks/bench_barn.py`` (``--help`` for options). By
default it runs the 200 BARN worlds that ship with ifgm-ref (``ifgm_ref/io/barn_worlds/``,
with their README); ``--barn DIR`` takes a folder or a clone of BARN's repository (all 300)
instead. Each planner runs with the Jackal's LiDAR; IFGM runs
a second time with the paper's IR sensor scaled to the robot (``paper_ir``). Each line gives,
for one planner and sensor, the share of episodes that reached the goal, collided and timed
out (in BARN's sense: neither arrived nor collided, so a run ended by the simulator's stall
rule counts as a time-out: it would still be there at BARN's 100 s), the mean BARN score
(``ifgm_ref.io.barn.barn_score``; BARN's DWA baseline in Gazebo scores 0.159 on BARN's 50
test worlds) and the wall time. It measures, it asserts nothing.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from ifgm_ref.apps.bench.report import machine, summarize_rows
from ifgm_ref.apps.bench.runner import run_bench
from ifgm_ref.apps.bench.tasks import barn_specs
from ifgm_ref.io.barn import bundled_barn_folder

PLANNERS = ["ifgm", "iba", "distbug", "bug2", "fgm", "apf"]
#: Planners that also run with the paper's IR sensor.
IR_PLANNERS = {"ifgm"}


def _measure(folder: Path, args: argparse.Namespace) -> None:
    print(f"machine: {machine()}; jobs={args.jobs}")
    print(f"{'planner':<10} {'sensor':<13} {'worlds':>6} {'success':>8} {'collided':>9} "
          f"{'timeout':>8} {'score':>6} {'wall s':>7}")  # fmt: skip
    for planner in args.planners:
        for sensor in ("jackal_lidar", "paper_ir") if planner in IR_PLANNERS else ("jackal_lidar",):
            specs = barn_specs(folder, sensor)[: args.limit]
            begin = time.perf_counter()
            rows = run_bench(specs, [planner], jobs=args.jobs, progress=False)
            wall = time.perf_counter() - begin
            s = summarize_rows(planner, "barn", rows)
            timeout = (s.timeout_rate or 0.0) + (s.stall_rate or 0.0)
            print(
                f"{planner:<10} {sensor:<13} {s.worlds:>6} {s.success_rate:>8.1%} "
                f"{s.collision_rate or 0.0:>9.1%} {timeout:>8.1%} "
                f"{s.barn_score_mean or 0.0:>6.3f} {wall:>7.1f}",
                flush=True,
            )


def main() -> None:
    """Parse the options, find the worlds, print one line per planner and sensor."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--barn", type=Path, help="BARN folder (default: the bundled 200 worlds)")
    parser.add_argument("--jobs", type=int, default=2, help="local worker processes (2)")
    parser.add_argument(
        "--planners",
        type=lambda text: [p.strip() for p in text.split(",") if p.strip()],
        default=PLANNERS,
        help=f"comma-separated planners (default {','.join(PLANNERS)})",
    )
    parser.add_argument("--limit", type=int, help="only the first N worlds (by index)")
    args = parser.parse_args()
    _measure(args.barn or bundled_barn_folder(), args)


if __name__ == "__main__":
    main()
