"""What the braking governor changes, episode by episode: a BARN run on the mujoco engine run
again with each planner told that the robot stops at once (so its governor lets every command
through, as the paper's planners are), everything else the same.

Run from the project root after ``ifgm-ref bench --barn --engine mujoco ... --out DIR``:
``python benchmarks/bench_ungoverned.py DIR/results.csv --planners ifgm --out DIR/ungoverned.csv``
(``--help`` for options). The planner keeps the disc the body tells it (the Jackal's
circumscribing disc), so the difference between the two runs is the governor's alone. It writes
one row per episode (``world, planner, robot, governed, ungoverned, ungoverned_min_clearance``:
the two stop reasons) and prints, per planner, the count of each pair of stop reasons. It
measures, it asserts nothing.
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import importlib.util
import sys
from collections import Counter
from multiprocessing import Pool
from pathlib import Path

if importlib.util.find_spec("ifgm_ref") is None:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from ifgm_ref.apps.bench.report import Row, read_rows
from ifgm_ref.core.params import robot_changes
from ifgm_ref.io.barn import gazebo_task
from ifgm_ref.planners import make_planner
from ifgm_ref.planners.governor import StopsAtOnce
from ifgm_ref.sim.simulator import simulate

FIELDS = ("world", "planner", "robot", "governed", "ungoverned", "ungoverned_min_clearance")


def rerun(row: Row) -> dict[str, object]:
    """The episode of ``row`` with its planner told the robot stops at once."""
    number = int(row.world.removeprefix("barn-"))
    task = gazebo_task(f"barn:{number}")
    assert task is not None
    world = task.world
    if row.robot not in (None, "none"):  # ifgm-ref bench --robot / --speed
        world = world.with_robot(robot_changes(row.robot))
    sim = dataclasses.replace(task.sim, engine=row.engine)
    run = simulate(world, StopsAtOnce(make_planner(row.planner)), sim)
    return {
        "world": row.world,
        "planner": row.planner,
        "robot": row.robot or "none",
        "governed": row.stop_reason,
        "ungoverned": run.result.stop_reason,
        "ungoverned_min_clearance": round(run.result.min_clearance, 4),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", type=Path, help="a bench run's results.csv (BARN, mujoco)")
    parser.add_argument("--planners", default="ifgm", help="comma-separated (default: ifgm)")
    parser.add_argument("--jobs", type=int, default=1, help="processes (default: 1)")
    parser.add_argument("--out", type=Path, required=True, help="the CSV to write")
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error("--jobs must be at least 1")
    wanted = set(args.planners.split(","))
    rows = [r for r in read_rows(args.results) if r.planner in wanted and r.engine == "mujoco"]
    if not rows:
        parser.error(f"{args.results} has no mujoco rows of {sorted(wanted)}")
    found = []
    with Pool(args.jobs) as pool:
        for k, out in enumerate(pool.imap(rerun, rows), 1):
            found.append(out)
            print(f"{k}/{len(rows)} {out['planner']} {out['world']}: {out['governed']} -> "
                  f"{out['ungoverned']}", file=sys.stderr, flush=True)  # fmt: skip
    with args.out.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(found)
    pairs = Counter((r["planner"], r["governed"], r["ungoverned"]) for r in found)
    for (planner, governed, ungoverned), n in sorted(pairs.items()):
        print(f"{planner:6} governed {governed:18} ungoverned {ungoverned:18} {n:4}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
