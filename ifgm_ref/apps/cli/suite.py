"""``ifgm-ref suite`` (build, promote, tiers, list) and ``oracle --suite``: the frozen suite.

``oracle --suite v1 [--tier quick|full]`` runs exactly the suite's cases against the
implementation ``oracle`` was given, with no drawing: one JSON line per case on stdout (or
``--results FILE``: a counterexample's folder is then relative to the file's), as it
finishes, then a summary line; each verdict's line on stderr; exit
status 0 when every case that applies passed (:mod:`ifgm_ref.oracle.suite.run`).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING, TextIO

from ifgm_ref.apps.cli.common import EXIT_USAGE
from ifgm_ref.core.errors import ParameterError

if TYPE_CHECKING:
    from ifgm_ref.apps.cli.common import Subcommands
    from ifgm_ref.oracle.implementation import Implementation
    from ifgm_ref.oracle.suite.run import CaseResult

#: The ``oracle`` options a suite run refuses: a case fixes its world, robot, engine and noise.
DRAWING_OPTIONS = {
    "--profile": ("profile", "quick"),
    "--noise": ("noise", None),
    "--robot": ("robot", None),
    "--speed": ("speed", None),
    "--engine": ("engine", "kinematic"),
    "--body": ("body", None),
    "--no-shrink": ("no_shrink", False),
    "--expect-failure": ("expect_failure", None),
    "--spec": ("spec", None),
}


def add_suite_options(oracle: argparse.ArgumentParser) -> None:
    """``--suite``, ``--tier`` and ``--results`` of ``oracle``."""
    oracle.add_argument(
        "--suite",
        metavar="VERSION",
        help="run the frozen cases of this suite version (v1, or a folder holding one) "
        "instead of drawing examples: one JSON line per case (docs/oracle.md, 'The "
        "conformance suite')",
    )
    oracle.add_argument(
        "--tier",
        choices=("quick", "full"),
        default="full",
        help="with --suite: the quick tier's cases only, or every case (the default)",
    )
    oracle.add_argument(
        "--results",
        metavar="FILE.jsonl",
        help="with --suite: write the JSON lines here instead of stdout",
    )


def refuse_drawing_options(args: argparse.Namespace) -> None:
    """A suite run's refusal of the options that change what a case is."""
    for option, (name, default) in DRAWING_OPTIONS.items():
        if getattr(args, name, default) not in (default, None, False):
            raise ParameterError(f"{option} does not apply with --suite: each case fixes it")


def run_suite(args: argparse.Namespace, impl: Implementation) -> int:
    """Run ``args.suite``'s cases of ``args.tier`` against ``impl``; 0 if all passed."""
    from ifgm_ref.oracle.check_types import levels_up_to
    from ifgm_ref.oracle.checks import CHECKS
    from ifgm_ref.oracle.suite.run import run_cases, summary
    from ifgm_ref.oracle.suite.versions import load_suite

    suite = load_suite(args.suite)
    cases = suite.tier(args.tier)
    if args.check:
        unknown = sorted(set(args.check) - {c.check for c in suite.cases})
        if unknown:
            raise ParameterError(f"--check {unknown[0]}: suite {suite.version} has no such check")
        cases = [case for case in cases if case.check in args.check]
    levels = levels_up_to(args.level or "paper")
    skipped = [c for c in cases if CHECKS[c.check].level not in levels]
    cases = [c for c in cases if CHECKS[c.check].level in levels]
    left = f" ({len(skipped)} of the reference level left out: --level reference)"
    head = f"suite {suite.version}, tier {args.tier}: {len(cases)} cases for {impl.label}"
    print(head + (left if skipped else ""), file=sys.stderr)
    out: TextIO = sys.stdout if args.results is None else _opened(args.results)
    base = Path.cwd() if args.results is None else Path(args.results).resolve().parent
    results: list[CaseResult] = []

    def finished(result: CaseResult) -> None:
        results.append(result)
        line = result.to_json(suite.version)
        if result.counterexample is not None:  # relative to the run file's folder
            line["counterexample"] = os.path.relpath(result.counterexample.resolve(), base)
        print(json.dumps(line), file=out, flush=True)
        note = f": {result.reason}" if result.reason else ""
        verdict = f"{result.verdict.upper():<5} {result.case.id} {result.seconds:.1f} s{note}"
        print(verdict, file=sys.stderr)

    try:
        for _ in run_cases(cases, impl, Path(args.artifacts), finished=finished):
            if args.stop_on_failure and results[-1].verdict in ("fail", "error"):
                break
        line = summary(results, suite=suite.version, implementation=impl.label, tier=args.tier)
        print(json.dumps(line), file=out, flush=True)
    finally:
        if out is not sys.stdout:
            out.close()
    counts = ", ".join(f"{line[v]} {v}" for v in ("pass", "fail", "skip", "error") if line[v])
    print(f"{impl.label} (suite {suite.version}, tier {args.tier}): {counts}", file=sys.stderr)
    return 0 if line["ok"] else 1


def _opened(path: str) -> TextIO:
    try:
        return open(path, "w")  # closed by the caller
    except OSError as err:
        raise ParameterError(f"--results {path}: {err.strerror}") from err


def add_suite(sub: Subcommands) -> None:
    """Add ``suite`` (``build``, ``promote``, ``tiers``, ``list``) to the subcommands."""
    suite = sub.add_parser(
        "suite",
        help="build or list versions of the frozen conformance suite (docs/oracle.md)",
        description="The conformance suite's versions: `suite list` shows them, `suite "
        "build` writes a new one (maintainers; a version, once released, never changes). "
        "Run one with `ifgm-ref oracle --suite VERSION`.",
    )
    actions = suite.add_subparsers(dest="action", required=True, metavar="ACTION")
    build = actions.add_parser("build", help="draw, judge and write a new suite version")
    build.add_argument("--version", required=True, metavar="VN", help="its name: v1, v2, ...")
    build.add_argument("--examples", type=int, default=50, metavar="N", help="drawn per check")
    build.add_argument("--seed", type=int, default=0, help="the draw's seed (default 0)")
    build.add_argument("--root", type=Path, help="where versions live (default: the package's)")
    build.add_argument(
        "--jobs", type=int, default=os.cpu_count() or 1, metavar="N",
        help="processes for the kill matrix (default: the number of CPUs)",
    )  # fmt: skip
    build.set_defaults(func=run_suite_build)
    promote = actions.add_parser(
        "promote",
        help="add a drawn profile's counterexample (its folder) to the next version as a case",
    )
    promote.add_argument("folder", type=Path, help="the counterexample's folder (report.md)")
    promote.add_argument("--to", required=True, metavar="VN", help="the (new) version")
    promote.add_argument("--root", type=Path, help="where versions live (default: the package's)")
    promote.set_defaults(func=run_suite_promote)
    tiers = actions.add_parser(
        "tiers",
        help="choose a version's quick tier again, with the kills of these runs (before release)",
    )
    tiers.add_argument("--version", required=True, metavar="VN", help="the version")
    tiers.add_argument(
        "--runs", nargs="+", required=True, type=Path, metavar="RUN.jsonl",
        help="full-tier runs of broken implementations, every case run (bench_mutation.py's "
        "suite_cases level writes them)",
    )  # fmt: skip
    tiers.add_argument("--root", type=Path, help="where versions live (default: the package's)")
    tiers.set_defaults(func=run_suite_tiers)
    listing = actions.add_parser("list", help="the versions and their cases per tier")
    listing.set_defaults(func=run_suite_list)


def run_suite_build(args: argparse.Namespace) -> int:
    """Write suite ``args.version``."""
    from ifgm_ref.oracle.suite.build import build_suite
    from ifgm_ref.oracle.suite.versions import SUITES

    if args.examples < 1:
        raise ParameterError(f"--examples {args.examples}: must be at least 1")
    if args.jobs < 1:
        raise ParameterError(f"--jobs {args.jobs}: must be at least 1")
    root = args.root or SUITES

    def progress(line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    folder = build_suite(
        args.version,
        examples=args.examples,
        seed=args.seed,
        root=root,
        progress=progress,
        jobs=args.jobs,
    )
    print(f"wrote suite {args.version} in {folder}")
    return 0


def run_suite_promote(args: argparse.Namespace) -> int:
    """Add ``args.folder``'s counterexample to suite ``args.to``."""
    from ifgm_ref.oracle.suite.build import promote
    from ifgm_ref.oracle.suite.versions import SUITES

    case = promote(args.folder, args.to, root=args.root or SUITES)
    print(f"added {case.id} to suite {args.to} (tier full)")
    return 0


def run_suite_tiers(args: argparse.Namespace) -> int:
    """Choose suite ``args.version``'s quick tier again with ``args.runs``' kills."""
    from ifgm_ref.oracle.suite.tiers import kills_in_runs, retier
    from ifgm_ref.oracle.suite.versions import SUITES, load_suite

    suite = load_suite(args.version, root=args.root or SUITES)
    extra = kills_in_runs(args.runs)
    quick = retier(suite.folder, extra)
    missed = sorted(name for name, ids in extra.items() if ids and not set(ids) & set(quick))
    print(f"suite {suite.version}: {len(quick)} quick cases; {len(extra)} runs added, "
          f"{sum(bool(ids) for ids in extra.values())} of them killed by the full tier"
          + (f"; not by the quick one: {', '.join(missed)}" if missed else ""))  # fmt: skip
    return 0


def run_suite_list(args: argparse.Namespace) -> int:
    """Print every version with its cases per tier."""
    from ifgm_ref.oracle.suite.versions import load_suite, versions

    found = versions()
    if not found:
        print("no suite versions installed", file=sys.stderr)
        return EXIT_USAGE
    for version in found:
        suite = load_suite(version)
        quick = len(suite.tier("quick"))
        protocol = suite.manifest["protocol"]
        print(f"{version}: {len(suite.cases)} cases ({quick} quick), protocol {protocol}")
    return 0
