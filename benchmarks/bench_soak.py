"""The soak (issue 24): many uniformly drawn worlds per class, failures named by their seeds.

Run from the project root (``--help`` for the options; ``--dask`` needs
``pip install ".[dask]"``)::

    python benchmarks/bench_soak.py                                # the issue's soak: 2,000
                                                                   # worlds per class, 4 planners
    python benchmarks/bench_soak.py --planners ifgm,iba --per-class 50 --jobs 2
    python benchmarks/bench_soak.py --replay open:5000 --planner ifgm --plot open-5000.png

Each planner runs noise-free in the worlds ``random_world(CLASS, SEED)`` of every class, for
the seeds ``--first-seed`` to ``--first-seed + --per-class - 1``, each episode to the world's
convergence bound (:mod:`ifgm_ref.apps.bench.soak`). The script prints the machine, one line per
failure as it happens (stderr), then a table of planner x class: goals reached of N, the
failures by stop reason and the upper end of the Wilson 95 % interval of the failure rate
(:mod:`ifgm_ref.apps.bench.soak_report`); then every failure with the command that replays it,
and the wall time and throughput. It asserts nothing.

Into ``--out`` (default ``soak-results``) it writes ``rows.partial.jsonl`` as rows arrive (an
interrupted soak keeps them), then ``rows.jsonl`` (every row, in class, seed, planner order:
the same whatever ``--jobs``) and ``summary.txt`` (what it printed); and ``worlds/CLASS-seedS.json``
for every world where some planner failed, which ``ifgm-ref simulate`` replays (the failure
list prints the command, with the episode's time limit).

``--replay CLASS:SEED --planner P`` runs one episode again and prints its line; ``--plot``
draws it.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time
from collections.abc import Sequence
from pathlib import Path

from tqdm import tqdm

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.apps.bench.soak import (
    SOAK_CLASSES,
    SOAK_PLANNERS,
    SoakRow,
    check_class,
    replay,
    run_soak,
    soak_world,
    write_rows,
)
from ifgm_ref.apps.bench.soak_report import describe, failure_report, summarise, summary_table
from ifgm_ref.apps.cli.common import EXIT_USAGE, Parser, names, non_negative_int
from ifgm_ref.apps.cli.simulate import PLOT_SUFFIXES
from ifgm_ref.core.errors import IfgmRefError, ParameterError
from ifgm_ref.io.transport.loading import load_planner
from ifgm_ref.io.worldfile import save_world

#: How the failure list names this script in its replay commands.
PROGRAM = "python benchmarks/bench_soak.py"
#: Worlds per class of the issue's soak: with no failure, the Wilson 95 % bound is 0.19 %.
DEFAULT_PER_CLASS = 2000
#: Exit status when the soak is interrupted (Ctrl-C): 128 + SIGINT, as ``ifgm-ref bench``.
EXIT_INTERRUPTED = 130


def build_parser() -> argparse.ArgumentParser:
    """The options of the soak and of its replay mode."""
    parser = Parser(prog="bench_soak.py", description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--planners",
        type=names,
        default=list(SOAK_PLANNERS),
        metavar="A,B,...",
        help=f"planners to soak (default {','.join(SOAK_PLANNERS)}): built-in "
        "names or module:attribute factories",
    )
    parser.add_argument(
        "--classes",
        type=names,
        default=list(SOAK_CLASSES),
        metavar="A,B,...",
        help=f"world classes (default {','.join(SOAK_CLASSES)})",
    )
    parser.add_argument(
        "--per-class",
        type=int,
        default=DEFAULT_PER_CLASS,
        metavar="N",
        help=f"worlds per class (default {DEFAULT_PER_CLASS})",
    )
    parser.add_argument(
        "--first-seed",
        type=non_negative_int,
        default=0,
        metavar="S",
        help="seed of each class's first world; the others follow (default 0)",
    )
    parser.add_argument(
        "--jobs",
        type=int,
        default=os.cpu_count() or 1,
        metavar="N",
        help="local worker processes (default: the number of CPUs)",
    )
    parser.add_argument(
        "--dask",
        "--scheduler",
        dest="dask",
        metavar="ADDRESS",
        help="run on this Dask scheduler instead, e.g. tcp://host:8786 (the "
        "workers need ifgm-ref installed)",
    )
    parser.add_argument(
        "--out", default="soak-results", metavar="DIR", help="output folder (default soak-results)"
    )
    replaying = parser.add_argument_group("replay one episode")
    replaying.add_argument(
        "--replay",
        metavar="CLASS:SEED",
        help="run one soak episode again, e.g. open:5000 (needs --planner)",
    )
    replaying.add_argument("--planner", metavar="NAME", help="the planner to replay")
    replaying.add_argument("--plot", metavar="FILE", help="with --replay: plot the episode")
    return parser


def parse_world(text: str) -> tuple[str, int]:
    """``CLASS:SEED`` as a class and a seed, checked."""
    world_class, sep, seed = text.partition(":")
    if not sep or not seed.isdigit():
        raise ParameterError(f"--replay {text!r}: expected CLASS:SEED, e.g. open:5000")
    check_class(world_class)
    return world_class, int(seed)


def run_replay(args: argparse.Namespace) -> int:
    """Replay one episode: print its line; plot it with ``--plot``."""
    if args.planner is None:
        raise ParameterError("--replay needs --planner NAME")
    world_class, seed = parse_world(args.replay)
    if args.plot and Path(args.plot).suffix.lower() not in PLOT_SUFFIXES:
        raise ParameterError(f"--plot {args.plot}: use one of {', '.join(PLOT_SUFFIXES)}")
    load_planner(args.planner)
    world, row, run = replay(args.planner, world_class, seed)
    print(describe(row))
    if args.plot and run is not None:
        from ifgm_ref.sim.plotting import plot_run, save_figure

        save_figure(plot_run(world, run.trace, run.result), args.plot)
        print(f"wrote {args.plot}")
    return 0


class Outputs:
    """The soak's files: rows as they arrive, failing worlds, then the ordered rows and the
    summary."""

    def __init__(self, folder: str) -> None:
        self.folder = Path(folder)
        self.partial = self.folder / "rows.partial.jsonl"
        self.worlds = self.folder / "worlds"
        self.worlds.mkdir(parents=True, exist_ok=True)
        self.partial.unlink(missing_ok=True)
        for stale in self.worlds.glob("*-seed*.json"):  # a former soak's failing worlds
            stale.unlink()

    def arrived(self, rows: list[SoakRow]) -> None:
        """Keep one world's rows; save the world and say so if a planner failed there."""
        write_rows(self.partial, rows, append=True)
        failed = [row for row in rows if not row.reached]
        if failed:
            world = soak_world(failed[0].world_class, failed[0].seed)
            save_world(world, self.worlds / f"{world.name}.json")
        for row in failed:
            tqdm.write(f"failure: {describe(row)}", file=sys.stderr)

    def finish(self, rows: Sequence[SoakRow], summary: str) -> None:
        """Write every row in soak order and the summary; drop the partial file."""
        write_rows(self.folder / "rows.jsonl", rows)
        (self.folder / "summary.txt").write_text(summary, encoding="utf-8")
        self.partial.unlink()


def cpu_seconds() -> float:
    """CPU time (user and system) of this process and its finished children, s: the local
    workers' time once their pool is shut down; none of a Dask cluster's."""
    own, children = (
        resource.getrusage(who) for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)
    )
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def throughput(worlds: int, episodes: int, wall: float, cpu: float | None, where: str) -> str:
    """The line on the soak's speed: per second of wall time and, when ``cpu`` (s) is known
    (a local run), per CPU second: what one core does, whatever else shares the machine."""
    line = (
        f"{episodes} episodes in {worlds} worlds, {wall:.1f} s wall on {where}: "
        f"{worlds / wall:.2f} worlds/s, {episodes / wall:.2f} episodes/s"
    )
    if cpu is None:
        return line
    return line + f"; {cpu:.1f} CPU s: {worlds / cpu:.2f} worlds per CPU s"


def run(args: argparse.Namespace) -> int:
    """Run the soak, print and write its report."""
    if args.planner is not None or args.plot is not None:
        raise ParameterError("--planner and --plot go with --replay CLASS:SEED")
    if args.per_class < 1:
        raise ParameterError(f"--per-class must be at least 1, got {args.per_class}")
    if args.jobs < 1:
        raise ParameterError(f"--jobs must be at least 1, got {args.jobs}")
    for world_class in args.classes:
        check_class(world_class)
    for planner in args.planners:
        load_planner(planner)  # a bad name is one error now, not one per episode
    seeds = range(args.first_seed, args.first_seed + args.per_class)
    where = f"Dask scheduler {args.dask}" if args.dask else f"{args.jobs} process(es)"
    header = (
        f"command: {PROGRAM} {' '.join(args.argv)}\nmachine: {machine()}\n"
        f"soak: {len(args.planners)} planners x {len(args.classes)} classes x "
        f"{args.per_class} worlds (seeds {seeds.start}-{seeds.stop - 1}) on {where}\n"
    )
    print(header, end="", flush=True)
    outputs = Outputs(args.out)
    begin, cpu_begin = time.perf_counter(), cpu_seconds()
    try:
        rows = run_soak(
            args.planners,
            args.classes,
            seeds,
            jobs=args.jobs,
            scheduler=args.dask,
            on_rows=outputs.arrived,
        )
    except KeyboardInterrupt:
        print(f"interrupted: the rows so far are in {outputs.partial}", file=sys.stderr)
        return EXIT_INTERRUPTED
    wall, cpu = time.perf_counter() - begin, cpu_seconds() - cpu_begin
    local_cpu = None if args.dask else cpu
    report = "\n\n".join(
        [
            summary_table(summarise(rows)),
            failure_report(rows, PROGRAM, outputs.worlds),
            throughput(len(args.classes) * args.per_class, len(rows), wall, local_cpu, where),
        ]
    )
    print("\n" + report)
    outputs.finish(rows, header + "\n" + report + "\n")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the soak or the replay; one line on stderr and exit status 2 on bad input."""
    args = build_parser().parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)
    try:
        return run_replay(args) if args.replay is not None else run(args)
    except (IfgmRefError, OSError) as err:
        print(f"bench_soak.py: error: {err}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
