"""The ``ifgm-ref`` command line.

Every error that bad input can cause is reported as one line on stderr
(``ifgm-ref: error: ...``) with exit status 2, never as a traceback.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from ifgm_ref.errors import IfgmRefError, ParameterError
from ifgm_ref.params import SimParams
from ifgm_ref.planners import PLANNERS, make_planner
from ifgm_ref.scenarios import BUILTIN_WORLDS, resolve_world
from ifgm_ref.simulator import simulate
from ifgm_ref.worldfile import save_world

EXIT_USAGE = 2


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
    params = _planner_params(args.planner, args.param or [])
    run = simulate(world, make_planner(args.planner), sim, params=params, progress=None)
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
    return 0


def _planner_params(planner: str, pairs: list[str]) -> dict[str, float]:
    """Parse ``NAME=VALUE`` planner parameters, checking names against the planner's list."""
    allowed = PLANNERS[planner].parameters
    params: dict[str, float] = {}
    for pair in pairs:
        name, sep, text = pair.partition("=")
        if not sep:
            raise ParameterError(f"--param {pair!r}: expected NAME=VALUE")
        if name not in allowed:
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
            save_world(entry.build(), out / f"{name}.json")
        print(f"wrote {len(BUILTIN_WORLDS)} world files to {out}", file=sys.stderr)
        return 0
    width = max(map(len, BUILTIN_WORLDS))
    for name, entry in BUILTIN_WORLDS.items():
        print(f"{name:<{width}}  {entry.description}")
    return 0


def _planners(args: argparse.Namespace) -> int:
    width = max(map(len, PLANNERS))
    for name, info in PLANNERS.items():
        params = f" [params: {', '.join(info.parameters)}]" if info.parameters else ""
        print(f"{name:<{width}}  {info.description}{params}")
    return 0


def _figures(args: argparse.Namespace) -> int:
    from ifgm_ref.figures import write_all

    written = write_all(args.out, progress=None)
    print(f"wrote {len(written)} files to {args.out}", file=sys.stderr)
    return 0


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, got {text!r}") from None
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a finite number > 0, got {text!r}")
    return value


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``ifgm-ref`` (all subcommands)."""
    parser = argparse.ArgumentParser(
        prog="ifgm-ref",
        description="Reference implementation of IFGM and IBA (obstacle avoidance for "
        "mobile robots with U and H shaped obstacles).",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    sim = sub.add_parser("simulate", help="run one planner in one world")
    sim.add_argument("world", metavar="WORLD", help="a world file (JSON) or a built-in world name")
    sim.add_argument(
        "--planner",
        required=True,
        choices=sorted(PLANNERS),
        metavar="NAME",
        help=f"planner to run: {', '.join(sorted(PLANNERS))}",
    )
    sim.add_argument(
        "--param",
        action="append",
        metavar="NAME=VALUE",
        help="set a planner parameter (repeatable; see `ifgm-ref planners`)",
    )
    sim.add_argument("--json", action="store_true", help="print the result as one JSON object")
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
        help=f"goal radius in ft (default {SimParams.goal_tolerance})",
    )
    sim.set_defaults(func=_simulate)

    worlds = sub.add_parser("worlds", help="list the built-in worlds")
    worlds.add_argument(
        "--export", metavar="DIR", help="write every built-in world as DIR/NAME.json"
    )
    worlds.set_defaults(func=_worlds)

    figures = sub.add_parser(
        "figures", help="regenerate the paper's Figures 4-9 and the reproduction table"
    )
    figures.add_argument(
        "--out", default="paper_figs", metavar="DIR", help="output folder (default paper_figs)"
    )
    figures.set_defaults(func=_figures)

    planners = sub.add_parser("planners", help="list the planners")
    planners.set_defaults(func=_planners)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
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
