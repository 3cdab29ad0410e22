"""Progress on stderr: a bar on a terminal, whole lines now and then in a log, nothing for a
short job in a log."""

from __future__ import annotations

import io
from typing import Any

import pytest

from ifgm_ref.core import progress
from ifgm_ref.core.progress import progress_bar


class _Log(io.StringIO):
    """stderr redirected to a file."""

    def isatty(self) -> bool:
        return False


def _run(steps: int, **options: Any) -> None:
    with progress_bar(total=steps, desc="bench", unit="episode", **options) as bar:
        for _ in range(steps):
            bar.update()


def test_a_long_job_writes_whole_lines_to_a_log(monkeypatch: pytest.MonkeyPatch) -> None:
    log = _Log()
    monkeypatch.setattr("sys.stderr", log)
    monkeypatch.setattr(progress, "LOG_INTERVAL", 0.0)  # every update is "long enough"
    _run(3, progress=None)
    lines = log.getvalue().split("\n")
    assert "\r" not in log.getvalue()
    assert lines[-1] == "" and len(lines) == 4, log.getvalue()
    assert lines[0].startswith("bench: 1/3 episode (33%), ")
    assert lines[2].startswith("bench: 3/3 episode (100%), ") and lines[2].endswith(" left")


def test_a_short_job_leaves_a_log_clean(monkeypatch: pytest.MonkeyPatch) -> None:
    log = _Log()
    monkeypatch.setattr("sys.stderr", log)
    _run(3, progress=None)
    assert log.getvalue() == ""


def test_the_lines_of_a_long_job_end_with_its_last_count(monkeypatch: pytest.MonkeyPatch) -> None:
    """Lines come at most every LOG_INTERVAL; the end is written once, however it falls."""
    log = _Log()
    monkeypatch.setattr("sys.stderr", log)
    monkeypatch.setattr(progress, "LOG_INTERVAL", 0.0)
    with progress_bar(total=10, desc="soak", unit="world", progress=None) as bar:
        bar.update(4)
        bar.update(6)
    assert [line.split(",")[0] for line in log.getvalue().splitlines()] == [
        "soak: 4/10 world (40%)",
        "soak: 10/10 world (100%)",
    ]


def test_false_is_silent_and_true_is_a_bar_anywhere(monkeypatch: pytest.MonkeyPatch) -> None:
    log = _Log()
    monkeypatch.setattr("sys.stderr", log)
    _run(3, progress=False)
    assert log.getvalue() == ""
    _run(3, progress=True)
    assert "\r" in log.getvalue() and "3/3" in log.getvalue()
