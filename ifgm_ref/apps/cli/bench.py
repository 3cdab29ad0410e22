"""``ifgm-ref bench``: run planners on many worlds against the shortest path."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ifgm_ref.apps.cli.common import (
    add_engine_options,
    add_robot_options,
    names,
    non_negative_int,
    output_folder,
    positive_float,
    robot_of,
    with_engine,
)
from ifgm_ref.apps.cli.interrupt import exit_status
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import EngineName, SimParams

if TYPE_CHECKING:
    from ifgm_ref.apps.bench.tasks import Condition, WorldSpec
    from ifgm_ref.apps.cli.common import Subcommands


#: What ``ifgm-ref bench`` runs by default: the paper's seven planners on four classes.
DEFAULT_BENCH_PLANNERS = ("bug1", "bug2", "distbug", "iba", "fgm", "ifgm", "apf")
DEFAULT_BENCH_CLASSES = ("open", "u", "h", "symmetric")
#: Worlds per class of ``ifgm-ref bench`` (a sweep's default is ``bench.noise.SWEEP_PER_CLASS``).
DEFAULT_PER_CLASS = 50


def add_bench(sub: Subcommands) -> None:
    """Add ``bench`` to the subcommands."""
    bench = sub.add_parser(
        "bench",
        help="run planners on many worlds against the shortest path (docs/benchmark.md)",
        description="Run planners on generated worlds (default), the built-in worlds or a "
        "folder of world files; write one row per (planner, world) to OUT/results.csv, "
        "summaries per planner and class (OUT/summary.csv, OUT/summary.md) and plots. Path "
        "lengths are divided by the shortest collision-free path of the robot disc.",
    )
    bench.add_argument(
        "--planners",
        type=names,
        default=list(DEFAULT_BENCH_PLANNERS),
        metavar="A,B,...",
        help=f"planners to run (default {','.join(DEFAULT_BENCH_PLANNERS)}); built-in names "
        "or module:attribute factories",
    )
    source = bench.add_mutually_exclusive_group()
    source.add_argument(
        "--classes",
        type=names,
        default=list(DEFAULT_BENCH_CLASSES),
        metavar="A,B,...",
        help=f"generated world classes (default {','.join(DEFAULT_BENCH_CLASSES)}; also: mixed)",
    )
    source.add_argument("--builtin", action="store_true", help="use the built-in worlds instead")
    source.add_argument("--world-dir", metavar="DIR", help="use the world files DIR/*.json instead")
    source.add_argument(
        "--barn",
        nargs="?",
        const="",
        metavar="DIR",
        help="use BARN's worlds instead: the 200 that ship with ifgm-ref, or DIR's, which holds "
        "world_N.world and path_N.npy or is a clone of BARN's repository (all 300, in "
        "jackal_helper/worlds/BARN); adds BARN's reference_length and barn_score to the "
        "results (docs/benchmark.md)",
    )
    _add_run_options(bench)
    add_engine_options(bench)
    add_robot_options(bench)
    _add_noise_options(bench)
    bench.set_defaults(func=run_bench)


def _add_run_options(bench: argparse.ArgumentParser) -> None:
    """BARN's options, the generated worlds' number and seed, where to run, where to write."""
    bench.add_argument(
        "--barn-worlds",
        metavar="SEL",
        help="with --barn: only these world indices, e.g. 0-49,60 (default: every world found)",
    )
    bench.add_argument(
        "--sensor",
        choices=("jackal_lidar", "paper_ir"),
        help="with --barn: the sensor preset (default jackal_lidar: BARN's 270-degree LiDAR; "
        "paper_ir: the paper's IR sensor scaled to the 0.22 m robot)",
    )
    bench.add_argument(
        "--per-class",
        type=int,
        metavar="N",
        help=f"worlds per class (default {DEFAULT_PER_CLASS}; 13 with --noise-sweep)",
    )
    bench.add_argument(
        "--seed", type=non_negative_int, default=0, help="seed of the generated worlds (0)"
    )
    bench.add_argument(
        "--jobs",
        type=int,
        default=os.cpu_count() or 1,
        metavar="N",
        help="local worker processes (default: the number of CPUs; 1 runs in this process)",
    )
    bench.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="run on a Dask cluster instead, e.g. tcp://host:8786 (pip install "
        "'ifgm-ref[dask]'; the workers need ifgm-ref installed)",
    )
    bench.add_argument(
        "--max-time",
        type=positive_float,
        help="episode time limit, s (default: each world's convergence budget, docs/oracle.md; "
        "BARN's 100 s for BARN worlds)",
    )
    bench.add_argument(
        "--out", default="bench-results", metavar="DIR", help="output folder (bench-results)"
    )


def _add_noise_options(bench: argparse.ArgumentParser) -> None:
    """The noise of every episode, the noise sweep, the noise seed."""
    bench.add_argument(
        "--noise",
        metavar="KIND=LEVEL,...",
        help="run every episode with this noise, e.g. range=0.02,dropout=0.05,odometry=0.01 "
        "(the kinds and levels of ifgm-ref simulate --noise; docs/benchmark.md#under-noise); "
        "with --noise-sweep, the noise under every point of the sweep",
    )
    bench.add_argument(
        "--noise-sweep",
        nargs="?",
        const="",
        metavar="KIND=L1:L2:...,...",
        help="sweep noise levels, one kind at a time, from a noise-free baseline; alone, the "
        "default sweep range=0.01:0.02:0.05:0.1,dropout=0.05:0.1:0.2:0.5,"
        "odometry=0.005:0.01:0.02:0.05 (13 worlds per class unless --per-class); writes "
        "sweep.csv, sweep.md and a plot per kind",
    )
    bench.add_argument(
        "--record",
        metavar="DIR",
        help="also write every episode as a ROS 2 bag, DIR/WORLD-PLANNER[-NOISE].mcap "
        "(docs/bags.md); with --scheduler, DIR must be reachable by the workers",
    )
    bench.add_argument(
        "--noise-seed",
        type=non_negative_int,
        metavar="N",
        help="seed of the noise, each world's derived from it and the world's name "
        "(default: --seed)",
    )


def run_bench(args: argparse.Namespace) -> int:
    """Run the benchmark and write its report; return the exit status."""
    import time

    from ifgm_ref.apps.bench.noise_sweep import write_sweep_report
    from ifgm_ref.apps.bench.report import PARTIAL, write_csv, write_report
    from ifgm_ref.apps.bench.runner import run_bench as run_tasks
    from ifgm_ref.apps.bench.tasks import Row

    sim = _check_args(args)
    conditions = _conditions(args)
    specs, source = _specs(args)
    where = f"Dask scheduler {args.scheduler}" if args.scheduler else _processes(args.jobs)
    points = f" x {_count(len(conditions), 'noise level')}" if args.noise_sweep is not None else ""
    planners, worlds = _count(len(args.planners), "planner"), _count(len(specs), "world")
    engine = f", {sim.engine} engine" if sim.engine is not EngineName.KINEMATIC else ""
    print(f"bench: {planners} x {worlds}{points} ({source}) on {where}{engine}", file=sys.stderr)
    if args.record is not None:
        output_folder("--record", args.record, is_folder=True)
    partial = Path(args.out) / PARTIAL
    partial.parent.mkdir(parents=True, exist_ok=True)
    partial.unlink(missing_ok=True)
    begin = time.perf_counter()
    try:
        rows = run_tasks(
            specs,
            args.planners,
            jobs=args.jobs,
            scheduler=args.scheduler,
            max_time=args.max_time,
            conditions=conditions,
            noise_seed=_noise_seed(args),
            progress=None,
            on_rows=lambda done: write_csv(partial, Row.columns(), done, append=True),
            record=args.record,
            engine=sim.engine,
            body=sim.body,
            robot=tuple(robot_of(args).items()),
        )
    except KeyboardInterrupt as err:
        name, status = exit_status(err)
        print(f"ifgm-ref: interrupted by {name}: the rows so far are in {partial}", file=sys.stderr)
        return status
    wall = time.perf_counter() - begin
    header = _header(args, source, where, wall, len(rows), conditions)
    write = write_report if args.noise_sweep is None else write_sweep_report
    written = write(rows, specs, args.out, header)
    partial.unlink()
    print(
        f"wrote {', '.join(p.name for p in written)} to {args.out} ({wall:.1f} s)",
        file=sys.stderr,
    )
    return 0


def _count(n: int, thing: str) -> str:
    """``n`` and ``thing``, plural unless ``n`` is 1.

    >>> _count(1, "BARN world"), _count(2, "BARN world"), _count(0, "planner")
    ('1 BARN world', '2 BARN worlds', '0 planners')
    """
    return f"{n} {thing}{'' if n == 1 else 's'}"


def _processes(jobs: int) -> str:
    """Where ``--jobs`` runs the episodes.

    >>> _processes(1), _processes(4)
    ('1 process', '4 processes')
    """
    return f"{jobs} process{'' if jobs == 1 else 'es'}"


def _check_args(args: argparse.Namespace) -> SimParams:
    """Refuse what cannot run, before anything runs: one error, not one per episode. The
    simulation parameters of ``--engine`` and ``--body``, the rest of them the defaults."""
    from ifgm_ref.apps.bench.optimal import require_pathfinder
    from ifgm_ref.io.transport.loading import load_planner

    if args.jobs < 1:
        raise ParameterError(f"--jobs {args.jobs}: must be at least 1")
    if args.barn is None:
        require_pathfinder()  # BARN worlds skip the shortest path (ifgm_ref/apps/bench/tasks.py)
        for option in ("barn_worlds", "sensor"):
            if getattr(args, option) is not None:
                flag = "--" + option.replace("_", "-")
                raise ParameterError(f"{flag} applies to BARN worlds only: give --barn [DIR]")
    engine = with_engine(SimParams(), args)  # MuJoCo missing is one error now, too
    robot_of(args)  # a bad --robot is one error now, too
    for planner in args.planners:
        load_planner(planner)  # a bad name or factory is one error now, not one per episode
    return engine


def _specs(args: argparse.Namespace) -> tuple[list[WorldSpec], str]:
    """The worlds to run, and a phrase saying where they come from."""
    from ifgm_ref.apps.bench.tasks import barn_specs, builtin_specs, folder_specs, generated_specs

    if args.barn is not None:
        from ifgm_ref.io.barn import (
            DEFAULT_SENSOR,
            MissingWorlds,
            bundled_barn_folder,
            missing_worlds,
            parse_selection,
        )

        sensor = args.sensor or DEFAULT_SENSOR
        prefix = f"--barn-worlds {args.barn_worlds}"
        try:
            chosen = None if args.barn_worlds is None else parse_selection(args.barn_worlds)
        except ParameterError as err:
            raise ParameterError(f"{prefix}: {err}") from None
        try:
            specs = barn_specs(args.barn or bundled_barn_folder(), sensor, chosen)
        except MissingWorlds as err:
            where = args.barn or "the bundled set"
            raise missing_worlds(err.names, where, option="--barn DIR", prefix=prefix) from None
        where = args.barn or "ifgm-ref's bundled set"
        return specs, f"{_count(len(specs), 'BARN world')} from {where}, sensor {sensor}"
    if args.builtin:
        return builtin_specs(), "the built-in worlds"
    if args.world_dir is not None:
        return folder_specs(args.world_dir), f"the world files in {args.world_dir}"
    per_class = _per_class(args)
    if per_class < 1:
        raise ParameterError(f"--per-class must be at least 1, got {per_class}")
    specs = generated_specs(args.classes, per_class, args.seed)
    return specs, (
        f"{per_class} generated worlds per class ({', '.join(args.classes)}), seed {args.seed}"
    )


def _per_class(args: argparse.Namespace) -> int:
    """Generated worlds per class: ``--per-class``, else the default of a run or a sweep."""
    from ifgm_ref.apps.bench.noise_sweep import SWEEP_PER_CLASS

    if args.per_class is not None:
        return int(args.per_class)
    return DEFAULT_PER_CLASS if args.noise_sweep is None else SWEEP_PER_CLASS


def _noise_seed(args: argparse.Namespace) -> int:
    """The run's noise seed: ``--noise-seed``, else ``--seed``."""
    return int(args.seed if args.noise_seed is None else args.noise_seed)


def _conditions(args: argparse.Namespace) -> list[Condition]:
    """The noise conditions of ``--noise`` and ``--noise-sweep`` (none: one, noise-free),
    checked before anything runs."""
    from ifgm_ref.apps.bench.noise_sweep import check_levels, parse_sweep, sweep_conditions
    from ifgm_ref.apps.bench.tasks import Condition
    from ifgm_ref.sim.noise import NoiseLevels

    background = NoiseLevels.parse(args.noise or "")
    if args.noise_sweep is not None:
        return sweep_conditions(parse_sweep(args.noise_sweep), background)
    return [Condition(check_levels(background))]


def _header(
    args: argparse.Namespace,
    source: str,
    where: str,
    wall: float,
    episodes: int,
    conditions: list[Condition],
) -> str:
    """The report's header: the command, the worlds, the planners, the noise, the limit, the
    machine."""
    import shlex

    from ifgm_ref.apps.bench.report import machine

    limit = f"{args.max_time:g} s" if args.max_time else "each world's convergence budget"
    if args.barn is not None and not args.max_time:
        limit = "BARN's 100 s"
    title = "Benchmark against the shortest collision-free path"
    if args.barn is not None:
        title = "Benchmark on BARN's worlds, with BARN's score"
    if args.noise_sweep is not None:
        title = "Benchmark under noise: a sweep of noise levels"
    return "\n".join(
        [
            f"# {title}",
            "",
            f"Generated by `ifgm-ref {shlex.join(args.argv)}`; do not edit.",
            "",
            f"- worlds: {source}",
            f"- planners: {', '.join(args.planners)}",
            f"- engine: {_engine_line(args)}",
            f"- robot: {_robot_line(args)}",
            *_noise_lines(args, conditions),
            f"- episode time limit: {limit}",
            f"- ran on: {where}; {machine()}",
            f"- wall time: {wall:.1f} s for {episodes} episodes",
        ]
    )


def _engine_line(args: argparse.Namespace) -> str:
    """What moved the robot (the rows' ``engine``), and its body."""
    if args.engine != EngineName.MUJOCO:
        return f"{args.engine} (the paper's instant robot)"
    body = args.body or "the Jackal in BARN's worlds, the paper's robot in the others"
    return f"mujoco (a robot with mass on the MuJoCo physics engine), body: {body}"


def _robot_line(args: argparse.Namespace) -> str:
    """What ``--robot`` and ``--speed`` changed of each world's robot (the rows' ``robot``)."""
    from ifgm_ref.apps.bench.tasks import robot_tags

    changes = robot_tags(tuple(robot_of(args).items()))
    return "each world's own" if changes == "none" else f"each world's, with {changes}"


def _noise_lines(args: argparse.Namespace, conditions: list[Condition]) -> list[str]:
    """The header's lines on the noise: its levels or the sweep's, and its seed."""
    from ifgm_ref.apps.bench.noise_sweep import level_label

    seed = (
        f"- noise seed: {_noise_seed(args)} (each world's noise is seeded from it and the "
        "world's name: the rows' `noise_seed`)"
    )
    if args.noise_sweep is None:
        levels = conditions[0].levels.tags()
        return [f"- noise: {levels}", seed] if levels != "none" else ["- noise: none"]
    swept: dict[str, list[str]] = {}
    for c in conditions[1:]:
        swept.setdefault(str(c.kind), []).append(level_label(str(c.kind), c.level or 0.0))
    background = conditions[0].levels.tags()
    return [
        "- noise sweep: "
        + "; ".join(f"{kind} {', '.join(levels)}" for kind, levels in swept.items())
        + "; one kind at a time, from the noise-free baseline (level 0)"
        + ("" if background == "none" else f", all over `--noise {background}`"),
        seed,
    ]
