"""The oracle's face (``ifgm_ref.oracle``): the few names an implementer needs, cheap to import.

The pytest plugin imports the package in every pytest session, so importing it must load none
of the oracle's modules and not Hypothesis; each name of the face is its module's own.
"""

from __future__ import annotations

import importlib
import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import pytest

import ifgm_ref.oracle as face


def test_importing_the_package_loads_no_oracle_module_and_not_hypothesis() -> None:
    probe = (
        "import sys, ifgm_ref.oracle; "
        "print(sorted(m for m in sys.modules if m.startswith(('ifgm_ref.oracle.', 'hypothesis'))))"
    )
    out = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == "[]", f"importing ifgm_ref.oracle loaded {out.strip()}"


@pytest.mark.parametrize(
    ("name", "home"),
    [
        ("Promises", "ifgm_ref.oracle.implementation"),
        ("Profile", "ifgm_ref.oracle.profiles"),
        ("Report", "ifgm_ref.oracle.runner"),
        ("CheckResult", "ifgm_ref.oracle.runner"),
        ("Status", "ifgm_ref.oracle.runner"),
    ],
)
def test_each_name_of_the_face_is_its_modules_own(name: str, home: str) -> None:
    assert getattr(face, name) is getattr(importlib.import_module(home), name)
    assert name in face.__all__
    assert name in dir(face)


def test_a_name_the_face_lacks_is_an_attribute_error() -> None:
    with pytest.raises(AttributeError, match="has no attribute 'check_planner'"):
        face.check_planner  # noqa: B018


def test_check_passes_its_arguments_to_check_planner() -> None:
    """The promises, the checks, an expected failure and ``on_fail`` all reach the runner."""
    arguments = {
        "profile": face.Profile("tiny", max_examples=2),
        "promises": face.Promises(converges_in=frozenset({"open"})),
        "checks": ["converges_open", "collision_free"],
        "expected_failed_checks": {"converges_open": "drives into the first obstacle"},
        "artifacts": None,
    }
    report = face.check("straight", **arguments)
    statuses = {r.check: r.status for r in report.results}
    assert statuses == {
        "converges_open": face.Status.EXPECTED_FAILURE,
        "collision_free": face.Status.FAILED,
    }
    with pytest.raises(AssertionError, match="collision_free"):
        face.check("straight", **arguments, on_fail="raise")


def _oracle_layers() -> tuple[tuple[tuple[str, ...], ...], tuple[str, ...]]:
    """``ORACLE_LAYERS`` of tests/test_layers.py, where the oracle's layers are checked, and
    its ``_PACKAGES`` (whose modules have layers of their own)."""
    path = Path(__file__).with_name("test_layers.py")
    spec = importlib.util.spec_from_file_location("_oracle_layers_of_test_layers", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.ORACLE_LAYERS, module._PACKAGES


def test_every_oracle_module_has_its_line_in_the_docs_with_its_layer() -> None:
    """docs/oracle-modules.md says why each module is there, at the layer it is checked at."""
    package = Path(face.__file__).parent
    modules = {
        ".".join(("ifgm_ref", *p.relative_to(package.parent).with_suffix("").parts)).removesuffix(
            ".__init__"
        )
        for p in package.rglob("*.py")
    }
    doc = (package.parents[1] / "docs" / "oracle-modules.md").read_text()
    rows = dict(re.findall(r"^\| `(ifgm_ref\.oracle[\w.]*)` \| (\d) \|", doc, re.MULTILINE))
    assert set(rows) == modules, (
        f"missing from the docs: {sorted(modules - set(rows))}; "
        f"no such module: {sorted(set(rows) - modules)}"
    )
    layers, packages = _oracle_layers()
    for module, layer in rows.items():
        placed = [
            level
            for level, members in enumerate(layers)
            for m in members
            if module == m or (m not in packages and module.startswith(f"{m}."))
        ]
        assert placed == [int(layer)], (
            f"{module}: the docs say layer {layer}, ORACLE_LAYERS {placed}"
        )
