"""The share of docstring lines in the package's modules, by folder (issue 44: lean docstrings).

A docstring line is a line of a module's, class's or function's docstring; the share is those
lines over all lines of the folder's modules. ``--rev REV`` measures a commit (through
``git show``) instead of the working tree::

    python benchmarks/docstring_share.py
    python benchmarks/docstring_share.py --rev 3d114f4
"""

from __future__ import annotations

import argparse
import ast
import subprocess
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DOCUMENTED = (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)


def docstring_lines(source: str) -> int:
    """The lines of every docstring in ``source``."""
    lines = 0
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, DOCUMENTED) and node.body:
            first = node.body[0]
            value = first.value if isinstance(first, ast.Expr) else None
            if isinstance(value, ast.Constant) and isinstance(value.value, str):
                lines += (first.end_lineno or first.lineno) - first.lineno + 1
    return lines


def sources(rev: str | None) -> dict[str, str]:
    """The package's modules by path, in the working tree or at ``rev``."""
    if rev is None:
        return {str(p.relative_to(ROOT)): p.read_text() for p in (ROOT / "ifgm_ref").rglob("*.py")}
    names = subprocess.run(
        ["git", "ls-tree", "-r", "--name-only", rev, "ifgm_ref"],
        capture_output=True, text=True, check=True, cwd=ROOT,
    ).stdout.split()  # fmt: skip
    show = ["git", "show"]
    return {
        name: subprocess.run([*show, f"{rev}:{name}"], capture_output=True, text=True,
                             check=True, cwd=ROOT).stdout
        for name in names if name.endswith(".py")
    }  # fmt: skip


def main() -> None:
    """Print each folder's share, then the whole package's."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rev", help="a commit to measure instead of the working tree")
    args = parser.parse_args()
    doc, total = Counter[str](), Counter[str]()
    for path, text in sources(args.rev).items():
        parts = path.split("/")
        folder = "/".join(parts[:2]) if len(parts) > 2 else "ifgm_ref (root modules)"
        doc[folder] += docstring_lines(text)
        total[folder] += len(text.splitlines())
    doc["the package"], total["the package"] = sum(doc.values()), sum(total.values())
    for folder in sorted(total):
        share = doc[folder] / total[folder]
        print(f"{folder:32} {doc[folder]:6} / {total[folder]:6} lines = {share:6.1%}")


if __name__ == "__main__":
    main()
