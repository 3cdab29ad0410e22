"""Writes :mod:`ifgm_ref.core.lambdified`: the code sympy prints for every declared formula.

``python -m ifgm_ref.apps.formula_table`` imports every module of the package (so that every
formula is declared: the planners' parameters, the simulator's stall rules), prints each
formula with :func:`~ifgm_ref.core.formulas.lambdified_code` and writes the table;
``--check`` only says whether the committed table is current (``tests/test_formulas.py``
checks it too). Why a table: :mod:`ifgm_ref.core.formulas`.
"""

from __future__ import annotations

import argparse
import importlib
import json
import pkgutil
import sys
from pathlib import Path

import ifgm_ref
from ifgm_ref.core import lambdified
from ifgm_ref.core.formulas import declared, lambdified_code

__all__ = ["TABLE", "main", "render"]

#: The committed table.
TABLE = Path(lambdified.__file__)

_HEADER = '''"""The Python code :func:`sympy.lambdify` prints for each formula the package declares.

Written by ``python -m ifgm_ref.apps.formula_table``; ``tests/test_formulas.py`` checks it
against the installed sympy. :func:`ifgm_ref.core.formulas.evaluate` runs this code, so a
process that evaluates a declared formula does not import sympy.
"""

#: Formula -> the expression lambdify prints for it, over ``r, v, w, dt, R, res, fov``.
LAMBDIFIED: dict[str, str] = {
'''


def render() -> str:
    """The text of :mod:`ifgm_ref.core.lambdified` for the formulas of every module."""
    for info in pkgutil.walk_packages(ifgm_ref.__path__, prefix="ifgm_ref."):
        importlib.import_module(info.name)
    rows = [
        f"    {json.dumps(formula)}: {json.dumps(lambdified_code(formula))},\n"
        for formula in sorted(declared())
    ]
    return _HEADER + "".join(rows) + "}\n"


def main(argv: list[str] | None = None) -> int:
    """Write the table, or with ``--check`` exit 1 if it is not current."""
    parser = argparse.ArgumentParser(prog="python -m ifgm_ref.apps.formula_table")
    parser.add_argument("--check", action="store_true", help="only check the committed table")
    args = parser.parse_args(argv)
    text = render()
    if args.check:
        current = TABLE.read_text(encoding="utf-8") == text
        print(f"{TABLE}: {'current' if current else 'not current; run without --check'}")
        return 0 if current else 1
    TABLE.write_text(text, encoding="utf-8")
    print(f"wrote {TABLE}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
