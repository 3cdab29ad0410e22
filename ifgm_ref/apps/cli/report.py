"""``ifgm-ref report RUN.jsonl ...``: runs of the conformance suite side by side, one page."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

from ifgm_ref.apps.cli.common import output_folder

if TYPE_CHECKING:
    from ifgm_ref.apps.cli.common import Subcommands


def add_report(sub: Subcommands) -> None:
    """Add ``report`` to the subcommands."""
    report = sub.add_parser(
        "report",
        help="compare runs of the conformance suite on one page (Markdown and HTML)",
        description="Read run files of the conformance suite (JSON lines: one per case, then "
        "a summary) and write one page comparing them, OUT/NAME.md and OUT/NAME.html (a "
        "standalone file): a table of the runs, then a column per run and a row per case, "
        "grouped by property and tier (quick first), each failure linked to its "
        "counterexample's plot, each reason a tooltip (HTML) or a footnote (Markdown). Runs "
        "of variants broken on purpose (--broken) get tables of their own: the suite's teeth. "
        "Exit status 0, or 2 on a malformed run file or runs of different suite versions.",
    )
    report.add_argument(
        "runs", nargs="+", metavar="RUN.jsonl", help="a run file: a column of the page"
    )
    report.add_argument(
        "--broken",
        action="append",
        default=[],
        metavar="RUN.jsonl",
        help="a run of a variant broken on purpose, shown apart (repeat)",
    )
    report.add_argument("--out", default=".", metavar="DIR", help="output folder (default: here)")
    report.add_argument(
        "--name",
        default="suite-report",
        help="the page's file name, without .md or .html (default suite-report)",
    )
    report.add_argument(
        "--title",
        metavar="TEXT",
        help="the page's title (default: 'Conformance suite' and the suite version)",
    )
    report.set_defaults(func=run_report)


def run_report(args: argparse.Namespace) -> int:
    """Write the page comparing ``args.runs`` (and ``args.broken``); say where on stderr."""
    from ifgm_ref.oracle.suite.report import write_report
    from ifgm_ref.oracle.suite.runfile import read_runs

    comparison = read_runs(args.runs, args.broken)
    output_folder("--out", args.out, is_folder=True)
    for path in write_report(comparison, args.out, args.name, args.title):
        print(f"wrote {path}", file=sys.stderr)
    return 0
