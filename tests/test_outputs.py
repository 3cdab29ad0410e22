"""Output files are written whole or not at all (:mod:`ifgm_ref.core.outputs`), never over what is
not a regular file."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from ifgm_ref.core.outputs import LEDGER, written


def test_a_failed_writer_leaves_the_old_file_and_no_temporary(tmp_path: Path) -> None:
    path = tmp_path / "run.csv"
    path.write_text("old")
    with pytest.raises(KeyboardInterrupt), written(path) as partial:
        partial.write_text("half")
        raise KeyboardInterrupt
    assert path.read_text() == "old" and sorted(tmp_path.iterdir()) == [path]


def test_a_device_is_written_in_place_not_replaced() -> None:
    """``--out /dev/stdout``-like paths: a rename would put a regular file in their place."""
    with written("/dev/null") as partial:
        assert partial == Path("/dev/null")
        partial.write_text("discarded")
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_a_symbolic_link_keeps_pointing_at_the_new_file(tmp_path: Path) -> None:
    target, link = tmp_path / "real.json", tmp_path / "link.json"
    target.write_text("old")
    link.symlink_to(target)
    with written(link) as partial:
        partial.write_text("new")
    assert link.is_symlink() and link.resolve() == target and target.read_text() == "new"


def test_the_ledger_says_what_landed_and_what_is_missing(tmp_path: Path) -> None:
    said: list[Path] = []
    LEDGER.reset(announce=said.append)
    try:
        a, b = tmp_path / "a.txt", tmp_path / "b.txt"
        LEDGER.plan(a, b)
        with written(a) as partial:
            partial.write_text("a")
        with written(tmp_path / "quiet.txt", announce=False) as partial:
            partial.write_text("q")
        assert said == [a]
        assert LEDGER.summary() == f"wrote {a}; not written: {b}"  # the quiet one unlisted
    finally:
        LEDGER.reset()


def test_an_interruption_a_library_turned_into_its_own_error_is_still_one(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    """matplotlib's SVG writer, interrupted inside C, raised ``ValueError: Invalid affine
    transformation matrix`` (a ``figures`` run stopped at a seeded moment): the command is
    still reported as interrupted, in one line, with the signal's exit status."""
    import signal
    import time

    from ifgm_ref.apps.cli import artefacts, main

    def garbled(args: object) -> int:
        try:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)  # the handler raises here
        except KeyboardInterrupt:
            raise ValueError("Invalid affine transformation matrix") from None
        return 0

    monkeypatch.setattr(artefacts, "run_vectors", garbled)
    assert main(["vectors", "--out", str(tmp_path / "v.json")]) == 143
    assert capsys.readouterr().err == "ifgm-ref: interrupted by SIGTERM: nothing written\n"
