"""``ifgm-ref serve``: a Python planner as a program of the JSON-lines protocol."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ifgm_ref.cli.common import Subcommands


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
    serve.set_defaults(func=run_serve)


def run_serve(args: argparse.Namespace) -> int:
    """Serve the planner ``args.planner`` on stdin and stdout; return the exit status."""
    from ifgm_ref.transport.loading import load_planner_factory
    from ifgm_ref.transport.serve import serve

    factory = load_planner_factory(args.planner)
    if args.twist:
        from ifgm_ref.velocity import VelocityPlanner

        def twist_factory() -> VelocityPlanner:
            return VelocityPlanner(factory())

        return serve(twist_factory, sys.stdin, sys.stdout, sys.stderr)
    return serve(factory, sys.stdin, sys.stdout, sys.stderr)
