"""``ifgm-ref figures``, ``ifgm-ref vectors`` and ``ifgm-ref trace-matrix``: files the
project publishes (the paper's figures, the test vectors, the traceability matrix)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ifgm_ref.apps.cli.common import output_folder
from ifgm_ref.core.outputs import written

if TYPE_CHECKING:
    from ifgm_ref.apps.cli.common import Subcommands


def add_figures(sub: Subcommands) -> None:
    """Add ``figures`` to the subcommands."""
    figures = sub.add_parser(
        "figures", help="regenerate the paper's Figures 4-9 and the reproduction table"
    )
    figures.add_argument(
        "--out", default="paper_figs", metavar="DIR", help="output folder (default paper_figs)"
    )
    figures.set_defaults(func=run_figures)


def run_figures(args: argparse.Namespace) -> int:
    """Write Figures 4-9 and the reproduction table to ``args.out``."""
    from ifgm_ref.apps.figures import write_all

    written = write_all(args.out, progress=None)
    print(f"wrote {len(written)} files to {args.out}", file=sys.stderr)
    return 0


def add_vectors(sub: Subcommands) -> None:
    """Add ``vectors`` to the subcommands."""
    vectors = sub.add_parser(
        "vectors",
        help="write equation test vectors and reference traces (JSON) for ports",
        description="Write the test vectors (docs/vectors-format.md): inputs and "
        "outputs of equations (1)-(4), literal and interpreted, and short IFGM and IBA "
        "reference traces, for implementations that cannot run Python.",
    )
    vectors.add_argument("--out", required=True, metavar="FILE.json", help="output file")
    vectors.set_defaults(func=run_vectors)


def run_vectors(args: argparse.Namespace) -> int:
    """Write the test vectors to ``args.out``."""
    from ifgm_ref.oracle.vectors import summarize, write_vectors

    output_folder("--out", args.out)
    vectors = write_vectors(args.out)
    size = Path(args.out).stat().st_size
    print(f"wrote {summarize(vectors)} to {args.out} ({size} bytes)", file=sys.stderr)
    return 0


def add_trace_matrix(sub: Subcommands) -> None:
    """Add ``trace-matrix`` to the subcommands."""
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
    matrix.set_defaults(func=run_trace_matrix)


def run_trace_matrix(args: argparse.Namespace) -> int:
    """Write the traceability matrix, or (``--check``) say whether it is current."""
    from ifgm_ref.paper.traceability import build_matrix, render_markdown

    text = render_markdown(build_matrix(args.root))
    out = Path(args.root) / args.out
    if args.check:
        current = out.read_text(encoding="utf-8") if out.is_file() else ""
        if current != text:
            print(f"{out} is out of date: run `ifgm-ref trace-matrix`", file=sys.stderr)
            return 1
        print(f"{out} is current", file=sys.stderr)
        return 0
    output_folder("--out", str(out))
    with written(out) as partial:  # said as it lands
        partial.write_text(text, encoding="utf-8")
    return 0
