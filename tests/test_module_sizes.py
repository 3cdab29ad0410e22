"""Small clear modules: no module of the package over 600 lines, no function over 60.

The reference is read more than it is run (issue "IFGM readable as the paper"): a reader who
opens a module should find one concept in it, and a function that fits on a screen. A
function's length runs from its ``def`` line to its last line, docstring included.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "ifgm_ref"
#: The largest module, in lines.
MAX_MODULE_LINES = 600
#: The largest function or method, in lines.
MAX_FUNCTION_LINES = 60

MODULES = sorted(PACKAGE.rglob("*.py"))


def long_functions(source: str) -> list[tuple[str, int, int]]:
    """Every function of ``source`` longer than :data:`MAX_FUNCTION_LINES`: its name, first
    line and length.

    >>> long_functions("def f():\\n" + "    x = 1\\n" * 60)
    [('f', 1, 61)]
    >>> long_functions("def f():\\n    return 1\\n")
    []
    """
    return [
        (node.name, node.lineno, node.end_lineno - node.lineno + 1)
        for node in ast.walk(ast.parse(source))
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
        and node.end_lineno is not None
        and node.end_lineno - node.lineno + 1 > MAX_FUNCTION_LINES
    ]


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_modules_and_functions_are_small(path: Path) -> None:
    source = path.read_text(encoding="utf-8")
    lines = source.count("\n")
    assert lines <= MAX_MODULE_LINES, f"lines={lines}, but should be <= {MAX_MODULE_LINES}"
    assert long_functions(source) == [], f"functions over {MAX_FUNCTION_LINES} lines"
