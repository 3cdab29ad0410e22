"""``ifgm-ref docs``: build the documentation site (Sphinx with MyST-NB, ``docs/conf.py``).

The site gathers the Markdown pages of ``docs/``, the README, the notebooks (executed during
the build), one page per sympy proof (run during the build) and the API reference from the
docstrings; ``docs/site.md`` says why Sphinx and what is built. It needs the ``docs`` extra
(``pip install -e ".[docs]"``) and a project folder (a checkout, not an installed wheel).
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING

from ifgm_ref.core.errors import IfgmRefError
from ifgm_ref.core.outputs import LEDGER

if TYPE_CHECKING:
    from ifgm_ref.apps.cli.common import Subcommands

#: What the build imports: the Sphinx extensions of ``docs/conf.py`` (the ``docs`` extra).
DOCS_PACKAGES = ("sphinx", "myst_nb", "furo")


def add_docs(sub: Subcommands) -> None:
    """Add ``docs`` to the subcommands."""
    docs = sub.add_parser(
        "docs",
        help="build the documentation site (HTML): pages, executed notebooks, proofs, API",
        description="Build the documentation site with Sphinx (docs/conf.py) from the project "
        "folder ROOT into OUT: the docs/ pages, the README, the notebooks executed at build "
        "time, the sympy proofs rendered as math, and the API reference. Needs the docs "
        'extra: pip install -e ".[docs]". Read it with: python -m http.server -d OUT.',
    )
    docs.add_argument("--out", default="site", metavar="DIR", help="output folder (default site)")
    docs.add_argument(
        "--root", default=".", metavar="DIR", help="the project folder (default: here)"
    )
    docs.add_argument(
        "--fresh", action="store_true", help="rebuild every page (default: only what changed)"
    )
    docs.add_argument("--strict", action="store_true", help="fail on any warning (sphinx-build -W)")
    docs.set_defaults(func=run_docs)


def sphinx_command(root: Path, out: Path, *, fresh: bool, strict: bool) -> list[str]:
    """The ``sphinx-build`` command line that builds the site of ``root`` into ``out``.

    Sphinx reports its progress (reading, executing the notebooks, writing) page by page: a
    build takes about two minutes.

    >>> " ".join(sphinx_command(Path("/p"), Path("/p/site"), fresh=False, strict=True)[3:])
    '-b html -c /p/docs -d /p/site/.doctrees -W --keep-going /p /p/site'
    """
    command = [sys.executable, "-m", "sphinx", "-b", "html", "-c", str(root / "docs")]
    command += ["-d", str(out / ".doctrees")]
    if fresh:
        command += ["-E", "-a"]
    if strict:
        command += ["-W", "--keep-going"]
    return [*command, str(root), str(out)]


def run_docs(args: argparse.Namespace) -> int:
    """Build the site of ``args.root`` into ``args.out``; return sphinx-build's exit status."""
    root = Path(args.root).resolve()
    if not (root / "docs" / "conf.py").is_file():
        raise IfgmRefError(f"{root} has no docs/conf.py: run from the project folder or --root")
    missing = [name for name in DOCS_PACKAGES if importlib.util.find_spec(name) is None]
    if missing:
        raise IfgmRefError(
            f'the site needs {", ".join(missing)}: install the docs extra, pip install -e ".[docs]"'
        )
    out = Path(args.out).resolve()
    env = dict(os.environ, MPLBACKEND="Agg")
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(root), env.get("PYTHONPATH")]))
    started = time.perf_counter()
    LEDGER.doing(f"building the site in {out}, which a rerun completes")
    command = sphinx_command(root, out, fresh=args.fresh, strict=args.strict)
    # Sphinx runs in a process group of its own, out of the terminal's Ctrl-C: this process
    # stops it, waits for it and says what is left, in one line (ifgm_ref.apps.cli.interrupt).
    with subprocess.Popen(command, env=env, process_group=0) as sphinx:
        try:
            status = sphinx.wait()
        except KeyboardInterrupt:
            sphinx.terminate()
            sphinx.wait()
            raise
    seconds = time.perf_counter() - started
    if status == 0:
        print(
            f"built the site in {out} ({seconds:.0f} s); read it with "
            f"`python -m http.server -d {args.out}` and http://localhost:8000/",
            file=sys.stderr,
        )
    return status
