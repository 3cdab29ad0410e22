"""``ifgm-ref worlds`` and ``ifgm-ref planners``: what is built in (and bundled)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ifgm_ref.core.formulas import Scale
from ifgm_ref.io.scenarios import BUILTIN_WORLDS
from ifgm_ref.io.worldfile import EXPORT_DIGITS, save_world
from ifgm_ref.planners import PLANNERS, parameters_markdown

if TYPE_CHECKING:
    from ifgm_ref.apps.cli.common import Subcommands


def add_worlds(sub: Subcommands) -> None:
    """Add ``worlds`` to the subcommands."""
    worlds = sub.add_parser(
        "worlds",
        help="list the built-in worlds and the bundled BARN worlds",
        description="List the built-in worlds, one a line, then in one line the BARN worlds "
        "that ship with ifgm-ref (barn:N; docs/benchmark.md).",
    )
    worlds.add_argument(
        "--export",
        metavar="DIR",
        help=f"write every built-in world as DIR/NAME.json (geometry to {EXPORT_DIGITS} "
        "significant digits)",
    )
    worlds.set_defaults(func=run_worlds)


def run_worlds(args: argparse.Namespace) -> int:
    """List the built-in worlds and, in one line, the bundled BARN worlds (:func:`barn_line`);
    or write the built-in worlds as world files (``--export``)."""
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
    print(f"{'barn:N':<{width}}  {barn_line()}")
    return 0


def barn_line() -> str:
    """The bundled BARN worlds, described in one line.

    >>> barn_line()
    "BARN's world N, for N in 0-299 with N % 3 != 0 (200 worlds, metres); the others need \
--barn-dir DIR"
    """
    from ifgm_ref.io.barn import BUNDLED_INDICES, INDICES

    return (
        f"BARN's world N, for N in {INDICES[0]}-{INDICES[-1]} with N % 3 != 0 "
        f"({len(BUNDLED_INDICES)} worlds, metres); the others need --barn-dir DIR"
    )


def add_planners(sub: Subcommands) -> None:
    """Add ``planners`` to the subcommands."""
    planners = sub.add_parser("planners", help="list the planners and their parameters")
    planners.add_argument(
        "--markdown", action="store_true", help="print the parameter table of docs/parameters.md"
    )
    planners.set_defaults(func=run_planners)


def run_planners(args: argparse.Namespace) -> int:
    """List the planners and their parameters, or print their Markdown table."""
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
