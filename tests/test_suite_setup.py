"""The suite's own set-up (``tests/conftest.py`` and ``pyproject.toml``): it runs on every core
(pytest-xdist), and the derandomized Hypothesis profile draws the same examples for a test
whichever tests ran before it in the same worker."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

DRAWING = """
import json, os
from hypothesis import given, strategies as st

def _log(name, value):
    with open(os.environ["DRAWS"], "a") as out:
        out.write(json.dumps([name, value]) + "\\n")

@given(st.lists(st.floats(allow_nan=False), max_size=4))
def test_first(values):
    _log("first", values)

@given(st.lists(st.floats(allow_nan=False), max_size=4))
def test_second(values):
    _log("second", values)
"""


def _draws(
    pytester: pytest.Pytester, monkeypatch: pytest.MonkeyPatch, *tests: str
) -> dict[str, list[object]]:
    """The examples each test of ``DRAWING`` drew when pytest ran ``tests`` (all if none), in
    that order."""
    log = pytester.path / f"draws-{len(list(pytester.path.glob('draws-*')))}.jsonl"
    monkeypatch.setenv("DRAWS", str(log))
    result = pytester.runpytest_inprocess("-p", "no:cacheprovider", *tests)
    result.assert_outcomes(passed=len(tests) or 2)
    draws: dict[str, list[object]] = {}
    for line in log.read_text().splitlines():
        name, value = json.loads(line)
        draws.setdefault(name, []).append(value)
    return draws


def test_a_tests_draws_do_not_depend_on_the_tests_before_it(
    pytester: pytest.Pytester, monkeypatch: pytest.MonkeyPatch
) -> None:
    """What an xdist worker ran before a test (any subset, in any order) changes nothing."""
    pytester.makeconftest((ROOT / "tests" / "conftest.py").read_text())  # the suite's profiles
    pytester.makepyfile(test_drawing=DRAWING)
    both = _draws(pytester, monkeypatch)
    alone = _draws(pytester, monkeypatch, "test_drawing.py::test_second")
    second_first = ["test_drawing.py::test_second", "test_drawing.py::test_first"]
    swapped = _draws(pytester, monkeypatch, *second_first)
    assert len(both["second"]) > 10
    assert alone["second"] == both["second"] == swapped["second"]
    assert swapped["first"] == both["first"]


def test_the_default_run_uses_every_core_and_names_the_slowest_tests() -> None:
    pytest_options = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["pytest"]
    options = pytest_options["ini_options"]["addopts"].split()
    assert options[options.index("-n") + 1] == "auto"
    assert "--durations=20" in options
