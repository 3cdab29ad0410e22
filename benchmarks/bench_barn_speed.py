"""BARN's bundled worlds with the robot's speed changed: does IFGM stop in time at a lower speed?

Run from the project root: ``python benchmarks/bench_barn_speed.py`` (``--help`` for options;
the mujoco engine needs the ``physics`` extra, ``pip install -e ".[physics]"``).

``ifgm-ref bench --barn`` drives BARN's robot (:data:`ifgm_ref.barn.ROBOT`) at 1.0 m/s, half
the Jackal's top speed. On the mujoco engine's Jackal every collision of IFGM there is one
while braking (``benchmarks/bench_misses.py``): the robot decides to stop about as close to a
cylinder as it needs to stop. The stopping distance ``u^2 / (2 mu g)`` falls with the square of
the speed, so this script runs the same episodes with only the robot's speed changed (each
given speed in turn; the planner's thresholds follow it, as they are derived from the robot),
among them 0.5 m/s, the top speed BARN's DWA baseline is configured with
(``max_vel_x``; :class:`ifgm_ref.planners.dwa.DWAParams`).

Each episode is the one ``ifgm-ref bench --barn DIR --engine E --sensor S`` runs (BARN's
start, goal, time step, 100 s and 1 m success radius: :data:`ifgm_ref.barn.SIM`) with the
robot's ``speed`` replaced. For each planner and speed it prints the worlds reached,
collisions, time-outs, stalls and other ends, the mean BARN score and the median time of the
arrivals; with ``--out`` one CSV row per episode. It measures, it asserts nothing.
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import importlib.util
import os
import statistics
import sys
import time
from collections import Counter
from multiprocessing import Pool
from pathlib import Path
from typing import NamedTuple

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one core, as the benchmark workers use
if importlib.util.find_spec("ifgm_ref") is None:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from tqdm import tqdm

from ifgm_ref.bench import barn
from ifgm_ref.bench.report import machine
from ifgm_ref.engine import require_physics
from ifgm_ref.errors import IfgmRefError
from ifgm_ref.params import ENGINES
from ifgm_ref.planners import make_planner
from ifgm_ref.simulator import simulate


class Task(NamedTuple):
    """One episode to run: a BARN world's files, the planner, the robot's speed (m/s)."""

    files: barn.BarnFiles
    planner: str
    speed: float
    engine: str
    sensor: str


class Outcome(NamedTuple):
    """One episode's end, as the CSV row gives it."""

    planner: str
    speed: float
    world: str
    stop_reason: str
    time_s: float
    min_clearance: float
    barn_score: float


def run(task: Task) -> Outcome:
    """The episode of ``task``: BARN's world and settings, the robot at ``task.speed``."""
    world = barn.load_barn_world(
        str(task.files.world), task.sensor, name=f"barn-{task.files.index:03d}"
    )
    world = dataclasses.replace(world, robot=dataclasses.replace(world.robot, speed=task.speed))
    sim = dataclasses.replace(barn.SIM, engine=task.engine)
    result = simulate(world, make_planner(task.planner), sim).result
    score = barn.barn_score(
        result.reached, result.time_s, barn.reference_length(str(task.files.path))
    )
    return Outcome(
        task.planner, task.speed, world.name, str(result.stop_reason), result.time_s,
        result.min_clearance, score,
    )  # fmt: skip


#: The ends counted in columns of their own; any other (IBA's ``goal_unreachable``) is "other".
_COUNTED = ("goal_reached", "collision", "time_limit", "stalled")


def summary_line(outcomes: list[Outcome]) -> str:
    """One planner and speed: the counts of each end, the mean score, the median arrival."""
    ends = Counter(o.stop_reason for o in outcomes)
    arrivals = [o.time_s for o in outcomes if o.stop_reason == "goal_reached"]
    other = len(outcomes) - sum(ends[k] for k in _COUNTED)
    score = statistics.fmean(o.barn_score for o in outcomes)
    median = statistics.median(arrivals) if arrivals else float("nan")
    first = outcomes[0]
    return (
        f"{first.planner:<7} {first.speed:>5.2f} | {ends['goal_reached']:>4}/{len(outcomes):<4}"
        f" {100 * ends['goal_reached'] / len(outcomes):>6.1f} % | {ends['collision']:>5}"
        f" {ends['time_limit']:>6} {ends['stalled']:>6} {other:>5} | {score:>6.3f} {median:>7.1f}"
    )


def _speeds(text: str) -> list[float]:
    speeds = [float(s) for s in text.split(",")]
    if any(s <= 0 for s in speeds):
        raise argparse.ArgumentTypeError(f"speeds must be positive, got {text}")
    return speeds


def main() -> None:
    """Run every planner at every speed in BARN's worlds; print the table (and the CSV)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--speeds", type=_speeds, default=[1.0, 0.5], help="m/s (1.0,0.5)")
    parser.add_argument("--planners", default="ifgm", help="planners (ifgm)")
    parser.add_argument("--engine", choices=ENGINES, default="mujoco", help="(mujoco)")
    parser.add_argument("--sensor", default=barn.DEFAULT_SENSOR, help="BARN sensor preset")
    parser.add_argument("--barn", default=None, help="BARN's folder (default: the bundled 200)")
    parser.add_argument("--barn-worlds", default=None, help="world indices, e.g. 0-49,60")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="processes")
    parser.add_argument("--out", type=Path, default=None, help="CSV of every episode")
    args = parser.parse_args()
    if args.jobs < 1:
        parser.error(f"--jobs must be at least 1, got {args.jobs}")
    planners = args.planners.split(",")
    try:  # bad input fails here, in one line, not in a worker
        barn.barn_sensor(args.sensor)
        for name in planners:
            make_planner(name)
        indices = None if args.barn_worlds is None else barn.parse_selection(args.barn_worlds)
        worlds = barn.find_barn_worlds(args.barn or barn.bundled_barn_folder(), indices)
    except IfgmRefError as error:
        parser.error(str(error))
    if args.engine == "mujoco":
        require_physics()
    print(f"machine: {machine()}")
    print(f"{len(worlds)} BARN worlds, engine {args.engine}, sensor {args.sensor}")
    print(f"{'planner':<7} {'m/s':>5} | {'reached':>16} | {'coll':>5} {'t-out':>6} "
          f"{'stall':>6} {'other':>5} | {'score':>6} {'t arr':>7}")  # fmt: skip
    rows: list[Outcome] = []
    begin = time.perf_counter()
    with Pool(args.jobs) as pool:
        for planner in planners:
            for speed in args.speeds:
                tasks = [Task(f, planner, speed, args.engine, args.sensor) for f in worlds]
                label = f"{planner} at {speed} m/s"
                found = list(tqdm(pool.imap(run, tasks), total=len(tasks), desc=label))
                print(summary_line(found), flush=True)
                rows.extend(found)
    load = " ".join(f"{v:.2f}" for v in os.getloadavg())
    print(f"total {time.perf_counter() - begin:.0f} s; load average at the end {load}")
    if args.out is not None:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        with args.out.open("w", newline="") as stream:
            writer = csv.writer(stream)
            writer.writerow(Outcome._fields)
            writer.writerows(rows)
        print(f"wrote {len(rows)} rows to {args.out}")


if __name__ == "__main__":
    main()
