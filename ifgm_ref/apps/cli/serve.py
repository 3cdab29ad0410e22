"""``ifgm-ref serve``: a Python planner as a program of the JSON-lines protocol."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

from ifgm_ref.core.errors import ParameterError

if TYPE_CHECKING:
    from collections.abc import Callable

    from ifgm_ref.apps.cli.common import Subcommands
    from ifgm_ref.core.protocol import Planner


def add_serve(sub: Subcommands) -> None:
    """Add ``serve`` to the subcommands."""
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
    serve.add_argument(
        "--twist",
        action="store_true",
        help="answer velocity commands (linear, angular: ROS's Twist) instead of heading and "
        "speed, for the same robot motion",
    )
    serve.add_argument(
        "--reading",
        action="append",
        metavar="NAME=VALUE",
        help="with --planner ifgm: run this reading of one of the paper's open choices "
        "instead of ours (repeatable; docs/oracle.md, 'Readings as options')",
    )
    serve.set_defaults(func=run_serve)


def run_serve(args: argparse.Namespace) -> int:
    """Serve the planner ``args.planner`` on stdin and stdout; return the exit status."""
    from ifgm_ref.io.transport.loading import load_planner_factory
    from ifgm_ref.io.transport.serve import serve

    factory = _readings_factory(args) if args.reading else load_planner_factory(args.planner)
    if args.twist:
        from ifgm_ref.core.velocity import VelocityPlanner

        def twist_factory() -> VelocityPlanner:
            return VelocityPlanner(factory())

        return serve(twist_factory, sys.stdin, sys.stdout, sys.stderr)
    return serve(factory, sys.stdin, sys.stdout, sys.stderr)


def _readings_factory(args: argparse.Namespace) -> Callable[[], Planner]:
    """The reference IFGM running the readings ``--reading`` names."""
    from ifgm_ref.planners.ifgm import IFGMPlanner
    from ifgm_ref.planners.ifgm.readings import Readings, parse_readings

    if args.planner != "ifgm":
        raise ParameterError(f"--reading runs with --planner ifgm only, not {args.planner!r}")
    readings = Readings.declared(parse_readings(args.reading))
    return lambda: IFGMPlanner(readings)
