"""The oracle's face (``ifgm_ref.oracle``): the few names an implementer needs, cheap to import.

The pytest plugin imports the package in every pytest session, so importing it must load none
of the oracle's modules and not Hypothesis; each name of the face is its module's own.
"""

from __future__ import annotations

import importlib
import subprocess
import sys

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
