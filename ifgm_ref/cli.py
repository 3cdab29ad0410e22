"""The ``ifgm-ref`` command line.

Every error that bad input can cause is reported as one line on stderr
(``ifgm-ref: error: ...``) with exit status 2, never as a traceback.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn, TextIO

from ifgm_ref.errors import IfgmRefError, ParameterError
from ifgm_ref.params import SimParams
from ifgm_ref.planners import PLANNERS, parameters_markdown
from ifgm_ref.planners.tuning import Scale
from ifgm_ref.scenarios import BUILTIN_WORLDS, resolve_world
from ifgm_ref.simulator import simulate
from ifgm_ref.worldfile import EXPORT_DIGITS, save_world

EXIT_USAGE = 2
#: What ``ifgm-ref bench`` runs by default: the paper's seven planners on four classes.
DEFAULT_BENCH_PLANNERS = ("bug1", "bug2", "distbug", "iba", "fgm", "ifgm", "apf")
DEFAULT_BENCH_CLASSES = ("open", "u", "h", "symmetric")


def _simulate(args: argparse.Namespace) -> int:
    world = resolve_world(args.world)
    defaults = SimParams()
    sim = SimParams(
        dt=defaults.dt if args.dt is None else args.dt,
        max_time=defaults.max_time if args.max_time is None else args.max_time,
        goal_tolerance=defaults.goal_tolerance
        if args.goal_tolerance is None
        else args.goal_tolerance,
    )
    if (args.planner is None) == (args.cmd is None):
        raise ParameterError("give exactly one of --planner NAME and --cmd 'PROGRAM'")
    _check_outputs(args)  # before the run, not after it
    if args.cmd is not None:
        from ifgm_ref.transport.external import ExternalPlanner

        params = _planner_params(None, args.param or [])
        with ExternalPlanner(args.cmd, timeout=args.timeout) as external:
            run = simulate(world, external, sim, params=params, progress=None)
    else:
        from ifgm_ref.transport.loading import load_planner

        params = _planner_params(args.planner, args.param or [])
        run = simulate(world, load_planner(args.planner), sim, params=params, progress=None)
    result = run.result
    if args.trace:
        path = Path(args.trace)
        path.write_text(run.trace_json() if path.suffix == ".json" else run.trace_csv())
    if args.plot or args.animate:
        from ifgm_ref.plotting import animate_run, plot_run, save_figure

        if args.plot:
            save_figure(plot_run(world, run.trace, result, colour_by=args.colour_by), args.plot)
        if args.animate:
            animate_run(world, run.trace, result, args.animate)
    if args.json:
        print(json.dumps(result.to_json_dict()))
    else:
        clearance = (
            "n/a" if result.min_clearance == float("inf") else f"{result.min_clearance:.3f} ft"
        )
        print(
            f"{result.planner} in {result.world or args.world}: {result.stop_reason} "
            f"(reached={result.reached}, collided={result.collided}) after {result.time_s:.1f} s, "
            f"{result.steps} steps, path {result.path_length:.2f} ft, min clearance {clearance}"
        )
        if result.detail:
            print(f"detail: {result.detail}")
    return 1 if args.require_goal and not result.reached else 0


#: The file types ``--plot`` and ``--animate`` can write.
PLOT_SUFFIXES = (".png", ".svg", ".pdf", ".jpg", ".jpeg")
ANIMATION_SUFFIXES = (".gif",)


def _check_outputs(args: argparse.Namespace) -> None:
    """Refuse an output file type the run could not write, before the run."""
    for option, name, allowed in (
        ("--plot", args.plot, PLOT_SUFFIXES),
        ("--animate", args.animate, ANIMATION_SUFFIXES),
    ):
        if name and Path(name).suffix.lower() not in allowed:
            raise ParameterError(
                f"{option} {name}: cannot write {Path(name).suffix or 'a file without suffix'}; "
                f"use one of {', '.join(allowed)}"
            )


def _planner_params(planner: str | None, pairs: list[str]) -> dict[str, float]:
    """Parse ``NAME=VALUE`` planner parameters, checking names against a built-in planner's
    list (any name goes for other implementations)."""
    allowed = PLANNERS[planner].parameters if planner in PLANNERS else None
    params: dict[str, float] = {}
    for pair in pairs:
        name, sep, text = pair.partition("=")
        if not sep:
            raise ParameterError(f"--param {pair!r}: expected NAME=VALUE")
        if allowed is not None and name not in allowed:
            known = ", ".join(allowed) or "none"
            raise ParameterError(
                f"--param {name!r}: {planner} has no such parameter; it has: {known}"
            )
        try:
            params[name] = float(text)
        except ValueError:
            raise ParameterError(f"--param {name}: must be a number, got {text!r}") from None
    return params


def _worlds(args: argparse.Namespace) -> int:
    if args.export:
        out = Path(args.export)
        out.mkdir(parents=True, exist_ok=True)
        for name, entry in BUILTIN_WORLDS.items():
            save_world(entry.build(), out / f"{name}.json", digits=EXPORT_DIGITS)
        print(f"wrote {len(BUILTIN_WORLDS)} world files to {out}", file=sys.stderr)
        return 0
    width = max(map(len, BUILTIN_WORLDS))
    for name, entry in BUILTIN_WORLDS.items():
        print(f"{name:<{width}}  {entry.description}")
    return 0


def _planners(args: argparse.Namespace) -> int:
    if args.markdown:
        print(parameters_markdown(), end="")
        return 0
    width = max(map(len, PLANNERS))
    paper = Scale.paper()
    for name, info in PLANNERS.items():
        print(f"{name:<{width}}  {info.description}")
        for param in info.infos:
            print(
                f"{'':<{width}}    {param.name:<16} = {param.formula:<9} {param.unit:<9}"
                f"  {param.value(paper):.6g}"
            )
    print(
        "\nEach parameter: its default as a formula in the robot radius r, speed v, turn rate"
        " w,\ntime step dt, sensor range R, ray spacing res and field of view fov; its unit;"
        " and its\nvalue for the paper's robot (r 1 ft, v 197/149 ft/s, w pi/2, dt 0.1 s,"
        " R 15 ft).\nSet one with --param NAME=VALUE, in the same length unit as the world."
    )
    return 0


def _figures(args: argparse.Namespace) -> int:
    from ifgm_ref.figures import write_all

    written = write_all(args.out, progress=None)
    print(f"wrote {len(written)} files to {args.out}", file=sys.stderr)
    return 0


def _serve(args: argparse.Namespace) -> int:
    from ifgm_ref.transport.loading import load_planner_factory
    from ifgm_ref.transport.serve import serve

    factory = load_planner_factory(args.planner)
    return serve(factory, sys.stdin, sys.stdout, sys.stderr)


def _vectors(args: argparse.Namespace) -> int:
    from ifgm_ref.oracle.vectors import summarize, write_vectors

    vectors = write_vectors(args.out)
    size = Path(args.out).stat().st_size
    print(f"wrote {summarize(vectors)} to {args.out} ({size} bytes)", file=sys.stderr)
    return 0


def _oracle(args: argparse.Namespace) -> int:
    from ifgm_ref.oracle.implementation import Implementation, load_equations
    from ifgm_ref.oracle.runner import PROFILE_ALIASES, check_planner

    if (args.planner is None) == (args.cmd is None):
        raise ParameterError("give exactly one of --planner NAME and --cmd 'PROGRAM'")
    if args.profile in PROFILE_ALIASES:
        new = PROFILE_ALIASES[args.profile]
        print(f"ifgm-ref: note: profile {args.profile!r} is now called {new!r}", file=sys.stderr)
    expected = {}
    for item in args.expect_failure or []:
        name, _, reason = item.partition("=")
        expected[name] = reason or "expected"
    equations = None if args.equations is None else load_equations(args.equations)
    if args.cmd is not None:
        impl = Implementation.from_command(
            args.cmd, timeout=args.timeout, promises=args.promises, equations=equations
        )
    else:
        impl = Implementation.from_spec(args.planner, promises=args.promises, equations=equations)
    try:
        report = check_planner(
            impl,
            profile=args.profile,
            checks=args.check,
            expected_failed_checks=expected,
            artifacts=args.artifacts,
            progress=True,
            stop_on_failure=args.stop_on_failure,
            jobs=args.jobs,
        )
    finally:
        impl.close()
    # Each check's line went to stderr as it finished; a terminal that shows stderr as stdout
    # has them already and gets the summary only. Redirected stdout gets the whole report.
    print(report.summary() if _same_terminal(sys.stdout, sys.stderr) else report.text())
    return 0 if report.ok else 1


def _same_terminal(out: TextIO, err: TextIO) -> bool:
    """Whether ``out`` and ``err`` are the same terminal (what one sees, the other shows)."""
    try:
        return (
            out.isatty()
            and err.isatty()
            and os.path.samestat(os.fstat(out.fileno()), os.fstat(err.fileno()))
        )
    except (AttributeError, OSError, ValueError):  # a stream without a file: not a terminal
        return False


def _names(text: str) -> list[str]:
    names = [name.strip() for name in text.split(",") if name.strip()]
    if not names:
        raise argparse.ArgumentTypeError(f"expected comma-separated names, got {text!r}")
    return names


def _bench(args: argparse.Namespace) -> int:
    import shlex
    import time

    from ifgm_ref.bench.optimal import require_pathfinder
    from ifgm_ref.bench.report import PARTIAL, machine, write_csv, write_report
    from ifgm_ref.bench.runner import run_bench
    from ifgm_ref.bench.tasks import (
        Row,
        barn_specs,
        builtin_specs,
        folder_specs,
        generated_specs,
    )
    from ifgm_ref.transport.loading import load_planner

    if args.barn is None:
        require_pathfinder()  # BARN worlds skip the shortest path (ifgm_ref/bench/tasks.py)
        for option in ("barn_worlds", "sensor"):
            if getattr(args, option) is not None:
                flag = "--" + option.replace("_", "-")
                raise ParameterError(f"{flag} applies to BARN worlds only: give --barn DIR")
    for planner in args.planners:
        load_planner(planner)  # a bad name or factory is one error now, not one per episode
    if args.barn is not None:
        from ifgm_ref.bench.barn import DEFAULT_SENSOR, parse_selection

        sensor = args.sensor or DEFAULT_SENSOR
        chosen = None if args.barn_worlds is None else parse_selection(args.barn_worlds)
        specs = barn_specs(args.barn, sensor, chosen)
        source = f"{len(specs)} BARN worlds in {args.barn}, sensor {sensor}"
    elif args.builtin:
        specs, source = builtin_specs(), "the built-in worlds"
    elif args.world_dir is not None:
        specs, source = folder_specs(args.world_dir), f"the world files in {args.world_dir}"
    else:
        if args.per_class < 1:
            raise ParameterError(f"--per-class must be at least 1, got {args.per_class}")
        specs = generated_specs(args.classes, args.per_class, args.seed)
        source = (
            f"{args.per_class} generated worlds per class ({', '.join(args.classes)}), "
            f"seed {args.seed}"
        )
    where = f"Dask scheduler {args.scheduler}" if args.scheduler else f"{args.jobs} process(es)"
    print(
        f"bench: {len(args.planners)} planners x {len(specs)} worlds ({source}) on {where}",
        file=sys.stderr,
    )
    partial = Path(args.out) / PARTIAL
    partial.parent.mkdir(parents=True, exist_ok=True)
    partial.unlink(missing_ok=True)
    begin = time.perf_counter()
    try:
        rows = run_bench(
            specs,
            args.planners,
            jobs=args.jobs,
            scheduler=args.scheduler,
            max_time=args.max_time,
            progress=None,
            on_rows=lambda done: write_csv(partial, Row.columns(), done, append=True),
        )
    except KeyboardInterrupt:
        print(f"interrupted: the rows so far are in {partial}", file=sys.stderr)
        return 130
    wall = time.perf_counter() - begin
    limit = f"{args.max_time:g} s" if args.max_time else "each world's convergence budget"
    if args.barn is not None and not args.max_time:
        limit = "BARN's 100 s"
    header = "\n".join(
        [
            "# Benchmark against the shortest collision-free path",
            "",
            f"Generated by `ifgm-ref {shlex.join(args.argv)}`; do not edit.",
            "",
            f"- worlds: {source}",
            f"- planners: {', '.join(args.planners)}",
            f"- episode time limit: {limit}",
            f"- ran on: {where}; {machine()}",
            f"- wall time: {wall:.1f} s for {len(rows)} episodes",
        ]
    )
    written = write_report(rows, specs, args.out, header)
    partial.unlink()
    print(
        f"wrote {', '.join(p.name for p in written)} to {args.out} ({wall:.1f} s)",
        file=sys.stderr,
    )
    return 0


def _trace_matrix(args: argparse.Namespace) -> int:
    from ifgm_ref.traceability import build_matrix, render_markdown

    text = render_markdown(build_matrix(args.root))
    out = Path(args.root) / args.out
    if args.check:
        current = out.read_text(encoding="utf-8") if out.is_file() else ""
        if current != text:
            print(f"{out} is out of date: run `ifgm-ref trace-matrix`", file=sys.stderr)
            return 1
        print(f"{out} is current", file=sys.stderr)
        return 0
    out.write_text(text, encoding="utf-8")
    print(f"wrote {out}", file=sys.stderr)
    return 0


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, got {text!r}") from None
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a finite number > 0, got {text!r}")
    return value


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line, as the README promises."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``ifgm-ref`` (all subcommands)."""
    parser = _Parser(
        prog="ifgm-ref",
        description="Reference implementation of IFGM and IBA (obstacle avoidance for "
        "mobile robots with U and H shaped obstacles).",
    )
    sub = parser.add_subparsers(
        dest="command", required=True, metavar="COMMAND", parser_class=_Parser
    )

    sim = sub.add_parser("simulate", help="run one planner in one world")
    sim.add_argument("world", metavar="WORLD", help="a world file (JSON) or a built-in world name")
    sim.add_argument(
        "--planner",
        metavar="NAME",
        help=f"planner to run: {', '.join(sorted(PLANNERS))}, or module:attribute (a factory)",
    )
    sim.add_argument(
        "--cmd",
        metavar="PROGRAM",
        help="run a program speaking the JSON-lines protocol instead (docs/oracle-protocol.md)",
    )
    sim.add_argument(
        "--timeout",
        type=_positive_float,
        default=10.0,
        help="per-reply timeout for --cmd, s (default 10)",
    )
    sim.add_argument(
        "--param",
        action="append",
        metavar="NAME=VALUE",
        help="set a planner parameter (repeatable; see `ifgm-ref planners`)",
    )
    sim.add_argument("--json", action="store_true", help="print the result as one JSON object")
    sim.add_argument(
        "--require-goal",
        action="store_true",
        help="exit with status 1 unless the goal is reached (a collision, a time-out or a "
        "planner's stop fails): for CI scripts",
    )
    sim.add_argument("--trace", metavar="FILE", help="write the trace (.json for JSON, else CSV)")
    sim.add_argument("--plot", metavar="FILE", help="write a plot of the run (e.g. run.png)")
    sim.add_argument(
        "--colour-by",
        choices=("behaviour", "branch"),
        default="behaviour",
        help="colour the plotted path by behaviour (default) or flowchart branch",
    )
    sim.add_argument("--animate", metavar="FILE.gif", help="write an animation of the run")
    sim.add_argument("--dt", type=_positive_float, help=f"time step in s (default {SimParams.dt})")
    sim.add_argument(
        "--max-time", type=_positive_float, help=f"time limit in s (default {SimParams.max_time})"
    )
    sim.add_argument(
        "--goal-tolerance",
        type=_positive_float,
        help=f"goal radius, in the world's length unit (default {SimParams.goal_tolerance})",
    )
    sim.set_defaults(func=_simulate)

    worlds = sub.add_parser("worlds", help="list the built-in worlds")
    worlds.add_argument(
        "--export",
        metavar="DIR",
        help=f"write every built-in world as DIR/NAME.json (geometry to {EXPORT_DIGITS} "
        "significant digits)",
    )
    worlds.set_defaults(func=_worlds)

    figures = sub.add_parser(
        "figures", help="regenerate the paper's Figures 4-9 and the reproduction table"
    )
    figures.add_argument(
        "--out", default="paper_figs", metavar="DIR", help="output folder (default paper_figs)"
    )
    figures.set_defaults(func=_figures)

    planners = sub.add_parser("planners", help="list the planners and their parameters")
    planners.add_argument(
        "--markdown", action="store_true", help="print the parameter table of docs/parameters.md"
    )
    planners.set_defaults(func=_planners)

    vectors = sub.add_parser(
        "vectors",
        help="write equation test vectors and reference traces (JSON) for ports",
        description="Write the conformance vectors (docs/vectors-format.md): inputs and "
        "outputs of equations (1)-(4), literal and interpreted, and short IFGM and IBA "
        "reference traces, for implementations that cannot run Python.",
    )
    vectors.add_argument("--out", required=True, metavar="FILE.json", help="output file")
    vectors.set_defaults(func=_vectors)

    oracle = sub.add_parser(
        "oracle",
        help="check a planner against the oracle's properties (docs/oracle.md)",
        description="Run the oracle's property checks against a built-in or Python planner "
        "(--planner) or a program speaking the JSON-lines protocol (--cmd). Prints each "
        "check's line on stderr as it finishes, then the report on stdout: every check's line "
        "and a summary (only the summary when stdout is the terminal that showed the lines). "
        "Exit status 0 when every check passed (or failed as expected), 1 otherwise. "
        "Counterexamples go to --artifacts.",
    )
    oracle.add_argument("--planner", metavar="NAME", help="built-in name or module:attribute")
    oracle.add_argument("--cmd", metavar="PROGRAM", help="a JSON-lines protocol program")
    oracle.add_argument(
        "--profile",
        default="quick",
        choices=("quick", "standard", "thorough", "default"),
        help="examples per check: quick 50 (the default), standard 200, thorough 1000 "
        "('default' is the old name of standard)",
    )
    oracle.add_argument(
        "--equations",
        metavar="MODULE",
        help="check the eqs. (1)-(4) of this module (or module:attribute), which exposes "
        "eq1_gap_midpoint ... as ifgm_ref.equations does (a --cmd program's own equations are "
        "checked with the vectors of `ifgm-ref vectors` instead)",
    )
    oracle.add_argument(
        "--promises",
        metavar="PLANNER",
        help="check what this built-in planner promises (default: its own, or ifgm's)",
    )
    oracle.add_argument(
        "--check", action="append", metavar="NAME", help="run only this check (repeatable)"
    )
    oracle.add_argument(
        "--expect-failure",
        action="append",
        metavar="CHECK=REASON",
        help="a check known to fail, reported as an expected failure (repeatable)",
    )
    oracle.add_argument(
        "--artifacts",
        default="oracle-failures",
        metavar="DIR",
        help="where counterexamples are written (default oracle-failures)",
    )
    oracle.add_argument(
        "--timeout", type=_positive_float, default=10.0, help="per-reply timeout for --cmd, s"
    )
    oracle.add_argument(
        "--stop-on-failure", action="store_true", help="stop at the first failing check"
    )
    oracle.add_argument(
        "--jobs",
        type=int,
        default=os.cpu_count() or 1,
        metavar="N",
        help="run the simulation checks in N processes (default: the number of CPUs; a "
        "--cmd program is started once per process)",
    )
    oracle.set_defaults(func=_oracle)

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
        type=_names,
        default=list(DEFAULT_BENCH_PLANNERS),
        metavar="A,B,...",
        help=f"planners to run (default {','.join(DEFAULT_BENCH_PLANNERS)}); built-in names "
        "or module:attribute factories",
    )
    source = bench.add_mutually_exclusive_group()
    source.add_argument(
        "--classes",
        type=_names,
        default=list(DEFAULT_BENCH_CLASSES),
        metavar="A,B,...",
        help=f"generated world classes (default {','.join(DEFAULT_BENCH_CLASSES)}; also: mixed)",
    )
    source.add_argument("--builtin", action="store_true", help="use the built-in worlds instead")
    source.add_argument("--world-dir", metavar="DIR", help="use the world files DIR/*.json instead")
    source.add_argument(
        "--barn",
        metavar="DIR",
        help="use BARN's worlds instead: DIR holds world_N.world and path_N.npy, or is a clone "
        "of BARN's repository (jackal_helper/worlds/BARN); adds BARN's reference_length and "
        "barn_score to the results (docs/benchmark.md)",
    )
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
        "--per-class", type=int, default=50, metavar="N", help="worlds per class (default 50)"
    )
    bench.add_argument("--seed", type=int, default=0, help="seed of the generated worlds (0)")
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
        type=_positive_float,
        help="episode time limit, s (default: each world's convergence budget, docs/oracle.md; "
        "BARN's 100 s for BARN worlds)",
    )
    bench.add_argument(
        "--out", default="bench-results", metavar="DIR", help="output folder (bench-results)"
    )
    bench.set_defaults(func=_bench)

    matrix = sub.add_parser(
        "trace-matrix",
        help="write the traceability matrix: each paper element's code, proofs, tests, figures",
        description="Gather the paper-element markers of the code (@traces), proofs, tests "
        "(@pytest.mark.paper) and notebooks of the project folder ROOT into a Markdown "
        "matrix (docs/trace-matrix.md). With --check, only compare: exit 1 if the file is "
        "out of date.",
    )
    matrix.add_argument(
        "--root", default=".", metavar="DIR", help="the project folder (default: here)"
    )
    matrix.add_argument(
        "--out",
        default="docs/trace-matrix.md",
        metavar="FILE",
        help="output file, relative to --root (default docs/trace-matrix.md)",
    )
    matrix.add_argument("--check", action="store_true", help="compare instead of writing")
    matrix.set_defaults(func=_trace_matrix)

    serve = sub.add_parser(
        "serve",
        help="answer the oracle's JSON-lines protocol on stdin/stdout with a Python planner",
        description="Run a Python planner as a program of the JSON-lines planner protocol "
        "(docs/oracle-protocol.md): read reset/observe/bye on stdin, answer ready/command on "
        "stdout. A fresh planner is built at every reset. Exit status 0 after bye, 2 on a "
        "malformed message, 1 if the planner crashes.",
    )
    serve.add_argument(
        "--planner",
        required=True,
        metavar="NAME",
        help="a built-in planner name (see `ifgm-ref planners`) or module:attribute, a "
        "callable that returns a new planner",
    )
    serve.set_defaults(func=_serve)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)
    try:
        return int(args.func(args))
    except IfgmRefError as err:
        print(f"ifgm-ref: error: {err}", file=sys.stderr)
        return EXIT_USAGE
    except OSError as err:
        print(f"ifgm-ref: error: {err}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
