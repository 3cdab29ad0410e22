"""mypy --strict over the package, run by the test suite (and so by CI).

``test_mypy_strict`` runs mypy in-process with the project's configuration (``[tool.mypy]`` in
``pyproject.toml``: strict, Python 3.11, ``files = ["ifgm_ref"]``) and fails on any error,
printing them all.

``test_planner_protocol`` checks, with the same configuration, that a class with a
``name: ClassVar[str]``, ``reset`` and ``step`` is a :class:`~ifgm_ref.core.protocol.Planner` to
mypy and that one without ``step`` is not.

Time on the 2-core machine: 7 to 12 s cold (no ``.mypy_cache``, as in CI's fresh clone; about
430 MB at most), under 1 s warm.
"""

from __future__ import annotations

import re
from pathlib import Path

import mypy.api
import pytest

ROOT = Path(__file__).resolve().parent.parent

#: A message line of mypy: ``path:line: error|note: text``.
MESSAGE = re.compile(r"^(?P<path>[^:]+):(?P<line>\d+): (?P<kind>error|note): ")


def _mypy(*args: str) -> tuple[list[re.Match[str]], str]:
    """Run mypy with the project's configuration; its messages and its whole report.

    mypy's own failure (exit status 2: a bad configuration, a crash) fails the test at once.
    """
    __tracebackhide__ = True
    stdout, stderr, status = mypy.api.run(["--config-file", str(ROOT / "pyproject.toml"), *args])
    report = stdout + stderr
    if status not in (0, 1):
        pytest.fail(f"mypy exit status={status}, but should be 0 or 1:\n{report}")
    return [m for m in map(MESSAGE.match, stdout.splitlines()) if m], report


@pytest.fixture
def in_root(monkeypatch: pytest.MonkeyPatch) -> None:
    """Run from the project root: the configuration's ``files`` and mypy's cache are there."""
    monkeypatch.chdir(ROOT)


@pytest.mark.usefixtures("in_root")
def test_mypy_strict() -> None:
    """``mypy`` with the project's configuration finds no error in the package."""
    messages, report = _mypy()
    assert "Success" in report or "Found" in report, f"mypy said neither:\n{report}"
    errors = [m.string for m in messages if m["kind"] == "error"]
    assert not errors, f"mypy --strict errors={len(errors)}, but should be 0:\n{report}"


PROTOCOL_CHECK = """\
from collections.abc import Callable
from typing import ClassVar

from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner


class WithClassVar:
    name: ClassVar[str] = "class_var"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None: ...

    def step(self, observation: Observation) -> Command:
        return Command(heading=0.0, speed=0.0)


class WithAttribute:
    def __init__(self) -> None:
        self.name = "attribute"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None: ...

    def step(self, observation: Observation) -> Command:
        return Command(heading=0.0, speed=0.0)


class WithoutStep:
    name: ClassVar[str] = "without_step"

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None: ...


factories: list[Callable[[], Planner]] = [WithClassVar, WithAttribute]
planner: Planner = WithClassVar()
name: str = planner.name
broken: Callable[[], Planner] = WithoutStep  # rejected
"""


@pytest.mark.usefixtures("in_root")
def test_planner_protocol(tmp_path: Path) -> None:
    """mypy accepts a class with a ClassVar name as a Planner factory, and rejects one
    without ``step``."""
    check = tmp_path / "planner_protocol_check.py"
    check.write_text(PROTOCOL_CHECK)
    messages, report = _mypy(str(check))
    # By name: from its cache, mypy may report the same text under the path of an earlier run.
    errors = {
        int(m["line"]) for m in messages if m["path"].endswith(check.name) and m["kind"] == "error"
    }
    expected = {
        i for i, line in enumerate(PROTOCOL_CHECK.splitlines(), 1) if line.endswith("# rejected")
    }
    assert errors == expected, (
        f"mypy error lines={sorted(errors)}, but should be {sorted(expected)}:\n{report}"
    )
