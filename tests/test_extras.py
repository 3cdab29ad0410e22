"""The extras of ``pyproject.toml`` hold what their commands import: the documentation site
(``pip install ".[docs]"``, then ``ifgm-ref docs``) imports every module of ``ifgm_ref`` for its
API pages, so every package a module imports at its top must come with the base install or
the ``docs`` extra (a missing one left the plugin's page empty, issue 25)."""

from __future__ import annotations

import ast
import re
import sys
import tomllib
from importlib.metadata import packages_distributions
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def _names(requirements: list[str]) -> set[str]:
    """The distribution names of requirement strings, normalised (PEP 503)."""
    found = (re.match(r"[A-Za-z0-9_.\-]+", r) for r in requirements)
    return {re.sub(r"[-_.]+", "-", m.group(0)).lower() for m in found if m}


def _top_level_imports(path: Path) -> set[str]:
    """The top-level packages a module imports outside functions and ``TYPE_CHECKING``."""
    found: set[str] = set()
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, ast.Import):
            found |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.add(node.module.split(".")[0])
    return found


def test_the_docs_extra_installs_what_the_api_pages_import() -> None:
    installed = _names(PROJECT["dependencies"]) | _names(PROJECT["optional-dependencies"]["docs"])
    distributions = packages_distributions()
    missing = {}
    for path in sorted((ROOT / "ifgm_ref").rglob("*.py")):
        for package in _top_level_imports(path):
            if package in sys.stdlib_module_names or package in ("ifgm_ref", "__future__"):
                continue
            needed = _names(distributions.get(package, [package]))
            if not needed & installed:
                missing[str(path.relative_to(ROOT))] = package
    assert missing == {}
