"""The traceability matrix: for every paper element, the code, proof, tests and figures.

Built from markers, never from a hand-kept list (:mod:`ifgm_ref.core.elements`):

* **code**: functions, classes and methods of the ``ifgm_ref`` package marked with
  :func:`ifgm_ref.core.elements.traces` -- found by importing every module and reading the
  ``__paper__`` attribute of what it defines (the oracle's checks count as *tests*, the
  figure functions of :mod:`ifgm_ref.apps.figures` as *figures*);
* **proofs**: functions of the ``proofs`` package marked the same way;
* **tests**: test functions with ``@pytest.mark.paper("key", ...)`` in ``tests/``, found by
  reading the source (the suite is not run);
* **notebooks**: the ``"paper"`` list in a notebook's metadata;
* **ports**: the C port's sources (``examples/c/src/``) count as code where a comment line
  reads ``paper: key key ...`` (:data:`C_MARK`).

An element is *covered* when something implements it (code, or a figure for a result) and
something checks it (a test or a proof); *partly covered* when only one of the two exists;
*not covered* when nothing does. ``ifgm-ref trace-matrix`` writes the matrix as Markdown;
``tests/test_traceability.py`` regenerates it and compares it with ``docs/trace-matrix.md``, so
an element that loses its code or its test changes the committed matrix and fails the suite.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import json
import pkgutil
import sys
from collections import defaultdict
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from ifgm_ref.core.elements import ELEMENTS
from ifgm_ref.core.errors import ParameterError

#: Modules not imported while gathering: they need pytest (and hold no marked code).
SKIPPED_MODULES = frozenset({"ifgm_ref.oracle.pytest_plugin", "ifgm_ref.oracle.test_conformance"})
#: Modules whose marked objects are listed as tests (the oracle's properties) or figures.
TEST_MODULES = frozenset({"ifgm_ref.oracle.checks", "ifgm_ref.oracle.equation_checks"})
FIGURE_MODULES = frozenset({"ifgm_ref.apps.figures"})
COLUMNS = ("code", "proofs", "tests", "figures")


@dataclass
class Coverage:
    """What covers one paper element, by column, each a sorted list of names."""

    code: list[str] = field(default_factory=list)
    proofs: list[str] = field(default_factory=list)
    tests: list[str] = field(default_factory=list)
    figures: list[str] = field(default_factory=list)

    @property
    def status(self) -> str:
        """``covered``, ``partly covered: no check``, ``partly covered: no code`` or
        ``not covered`` (a figure stands for code, a proof for a check)."""
        implemented = bool(self.code or self.figures)
        checked = bool(self.tests or self.proofs)
        if implemented and checked:
            return "covered"
        if implemented:
            return "partly covered: no check"
        if checked:
            return "partly covered: no code"
        return "not covered"


def _marked(module_name: str) -> Iterator[tuple[str, tuple[str, ...]]]:
    """``(qualified name, keys)`` of every marked object defined in the module."""
    module = importlib.import_module(module_name)
    for name, obj in vars(module).items():
        if getattr(obj, "__module__", None) != module_name:
            continue
        keys = vars(obj).get("__paper__", ()) if hasattr(obj, "__dict__") else ()
        if keys:
            yield f"{module_name}.{name}", keys
        if inspect.isclass(obj):
            for attr, member in vars(obj).items():
                inner = getattr(member, "__func__", member)
                keys = getattr(inner, "__dict__", {}).get("__paper__", ())
                if keys:
                    yield f"{module_name}.{name}.{attr}", keys


def _modules(package: str) -> list[str]:
    root = importlib.import_module(package)
    names = [package]
    for info in pkgutil.walk_packages(root.__path__, prefix=f"{package}."):
        if info.name not in SKIPPED_MODULES:
            names.append(info.name)
    return sorted(names)


def _column(module_name: str) -> str:
    if module_name in TEST_MODULES:
        return "tests"
    if module_name in FIGURE_MODULES:
        return "figures"
    return "proofs" if module_name.startswith("proofs") else "code"


def _literal_keys(call: ast.Call, where: str) -> tuple[str, ...]:
    keys = []
    for arg in call.args:
        if not (isinstance(arg, ast.Constant) and isinstance(arg.value, str)):
            raise ParameterError(f"{where}: pytest.mark.paper takes string literals only")
        keys.append(arg.value)
    return tuple(keys)


def _is_paper_mark(node: ast.expr) -> bool:
    return (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Attribute)
        and node.func.attr == "paper"
        and isinstance(node.func.value, ast.Attribute)
        and node.func.value.attr == "mark"
    )


def marked_tests(tests: Path, root: Path) -> Iterator[tuple[str, tuple[str, ...]]]:
    """``(pytest id, keys)`` of every ``@pytest.mark.paper(...)`` test in ``tests/*.py``."""
    for path in sorted(tests.glob("test_*.py")):
        rel = path.relative_to(root).as_posix()
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        scopes: list[tuple[str, list[ast.stmt]]] = [("", tree.body)]
        scopes += [(f"{n.name}::", n.body) for n in tree.body if isinstance(n, ast.ClassDef)]
        for prefix, body in scopes:
            for node in body:
                if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                    continue
                for deco in node.decorator_list:
                    if _is_paper_mark(deco):
                        where = f"{rel}::{prefix}{node.name}"
                        yield where, _literal_keys(deco, where)  # type: ignore[arg-type]


#: The marker of a paper element in a C source: a comment line ``paper: key key ...``.
C_MARK = "paper:"


def marked_c_sources(sources: Path, root: Path) -> Iterator[tuple[str, tuple[str, ...]]]:
    """``(path, keys)`` of every C source or header in ``sources`` with ``paper:`` lines
    (in a comment: ``/* paper: s3.cheap */`` or a line of a block comment)."""
    for path in sorted([*sources.glob("*.c"), *sources.glob("*.h")]):
        keys: list[str] = []
        for line in path.read_text(encoding="utf-8").splitlines():
            text = line.strip().removeprefix("/*").removeprefix("*").strip()
            if text.startswith(C_MARK):
                keys += text.removeprefix(C_MARK).removesuffix("*/").split()
        if keys:
            yield path.relative_to(root).as_posix(), tuple(keys)


def marked_notebooks(notebooks: Path, root: Path) -> Iterator[tuple[str, tuple[str, ...]]]:
    """``(path, keys)`` of every notebook whose metadata lists ``"paper"`` elements."""
    for path in sorted(notebooks.glob("*.ipynb")):
        keys = json.loads(path.read_text(encoding="utf-8"))["metadata"].get("paper", [])
        if keys:
            yield path.relative_to(root).as_posix(), tuple(keys)


def build_matrix(root: str | Path = ".") -> dict[str, Coverage]:
    """The coverage of every element of :data:`~ifgm_ref.core.elements.ELEMENTS`, from the markers
    in the package, and in ``proofs/``, ``tests/`` and ``notebooks/`` under ``root``.

    Raises :class:`~ifgm_ref.core.errors.ParameterError` if ``root`` is not the project folder or
    a marker names an element that does not exist.
    """
    root = Path(root).resolve()
    missing = [d for d in ("proofs", "tests", "notebooks") if not (root / d).is_dir()]
    if missing:
        raise ParameterError(f"{root} is not the project folder: no {', '.join(missing)}/")
    found: dict[str, dict[str, set[str]]] = defaultdict(lambda: defaultdict(set))

    def add(column: str, name: str, keys: tuple[str, ...]) -> None:
        for key in keys:
            if key not in ELEMENTS:
                raise ParameterError(f"{name} names an unknown paper element {key!r}")
            found[key][column].add(name)

    sys.path.insert(0, str(root))  # the proofs package lives in the project folder
    try:
        for package in ("ifgm_ref", "proofs"):
            for module_name in _modules(package):
                for name, keys in _marked(module_name):
                    add(_column(module_name), name, keys)
    finally:
        sys.path.remove(str(root))
    for name, keys in marked_tests(root / "tests", root):
        add("tests", name, keys)
    for name, keys in marked_notebooks(root / "notebooks", root):
        add("figures", name, keys)
    for name, keys in marked_c_sources(root / "examples" / "c" / "src", root):
        add("code", name, keys)
    return {key: Coverage(**{c: sorted(found[key][c]) for c in COLUMNS}) for key in ELEMENTS}


#: Where a claim's verdict (does it hold?) is measured, by element kind; covered means
#: implemented and checked, not that the paper's claim holds.
VERDICTS = {
    "result": "[reproduction](../paper_figs/reproduction.md)",
    "limitation": "[benchmark](benchmark.md)",
    "novelty": "[benchmark](benchmark.md)",
    "claim": "[decision cost](../benchmarks/README.md#decision-cost-benchmark-issue)",
}


#: Where the verdict of a single element is measured, where it is not its kind's place.
ELEMENT_VERDICTS = {
    "s3.cheap": "[C port's cost](benchmark.md#the-c-port)",
    "s6.simpler_than_fgm": "[C port's cost](benchmark.md#the-c-port)",
}


def _cell(names: list[str]) -> str:
    return "<br>".join(f"`{n}`" for n in names) or "-"


def render_markdown(matrix: dict[str, Coverage]) -> str:
    """The matrix as Markdown: a summary line, then one table row per element."""
    counts: dict[str, int] = defaultdict(int)
    for coverage in matrix.values():
        counts[coverage.status.split(":")[0]] += 1
    lines = [
        "# Traceability matrix: the paper, element by element",
        "",
        "Generated by `ifgm-ref trace-matrix` from the markers in the code (`@traces`), the "
        "proofs, the tests (`@pytest.mark.paper`) and the notebooks' metadata; do not edit "
        "(`tests/test_traceability.py` checks that it is current). The elements are listed "
        "in `ifgm_ref/core/elements.py`; why each reading was chosen is in [errata.md](errata.md).",
        "",
        f"{len(matrix)} elements: {counts['covered']} covered, {counts['partly covered']} "
        f"partly covered, {counts['not covered']} not covered. *Covered* means implemented "
        "(code, or a figure for a result) and checked (a test or a proof); whether a claim "
        "of the paper *holds* is measured where the last column points.",
        "",
        "| element | section | the paper | code | proofs | tests | figures, notebooks | status "
        "| verdict |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for key, coverage in matrix.items():
        element = ELEMENTS[key]
        verdict = ELEMENT_VERDICTS.get(key) or VERDICTS.get(element.kind, "-")
        lines.append(
            f"| `{key}` | {element.section} | {element.text} | {_cell(coverage.code)} | "
            f"{_cell(coverage.proofs)} | {_cell(coverage.tests)} | {_cell(coverage.figures)} "
            f"| {coverage.status} | {verdict} |"
        )
    return "\n".join(lines) + "\n"
