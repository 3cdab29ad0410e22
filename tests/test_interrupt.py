"""Ctrl-C and SIGTERM stop every long command cleanly (issue 45, part 1).

Each command runs as ``ifgm-ref`` in a process group of its own, and the signal goes to the
whole group, as a terminal's Ctrl-C does, at a moment drawn from a seeded generator (the same
moments every run) within a window where the command is busy: after a line it prints, or
after its start. Every case asserts the contract of :mod:`ifgm_ref.apps.cli.interrupt` and
:mod:`ifgm_ref.core.outputs`: exit 130 (SIGINT) or 143 (SIGTERM), one ``ifgm-ref: interrupted``
line and no traceback, every file left whole (no temporary beside it), the files finished
kept, the missing ones named, and no process of the group left running.
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path

import pytest
from PIL import Image

from ifgm_ref.io.bags.read import read_log
from tests.test_cli import run_cli

ROOT = Path(__file__).resolve().parent.parent
#: The seed of the moments the signals are sent at.
SEED = 45


@dataclass
class Stopped:
    """How an interrupted command ended."""

    status: int
    stdout: str
    stderr: str

    @property
    def last(self) -> str:
        """The last line on stderr: the interruption's."""
        return self.stderr.rstrip("\n").splitlines()[-1]


def interrupt(
    args: list[str],
    cwd: Path,
    window: tuple[float, float],
    *,
    after: str = "",
    sig: signal.Signals = signal.SIGINT,
) -> Stopped:
    """Run ``ifgm-ref ARGS`` in ``cwd``; once it printed a stderr line holding ``after``
    (or at once), wait a seeded moment within ``window`` seconds and signal its group."""
    command = [sys.executable, "-m", "ifgm_ref", *args]
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(ROOT))
    child = subprocess.Popen(
        command, cwd=cwd, env=env, text=True, start_new_session=True,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=_heed_ctrl_c,
    )  # fmt: skip
    lines: list[str] = []
    printed: list[str] = []
    seen = threading.Event()

    def read_stderr() -> None:
        assert child.stderr is not None
        for line in child.stderr:
            lines.append(line)
            if after in line:
                seen.set()

    def read_stdout() -> None:
        assert child.stdout is not None
        printed.append(child.stdout.read())

    readers = [threading.Thread(target=read) for read in (read_stderr, read_stdout)]
    for reader in readers:
        reader.start()
    if after:
        assert seen.wait(120), f"{after!r} never came: {''.join(lines)}"
    time.sleep(random.Random(f"{SEED} {args[0]} {sig.name}").uniform(*window))
    assert child.poll() is None, f"finished before the signal: {''.join(lines)}"
    os.killpg(child.pid, sig)
    child.wait(timeout=60)
    for reader in readers:
        reader.join()
    time.sleep(0.2)
    with pytest.raises(ProcessLookupError):  # nothing of the group is left running
        os.killpg(child.pid, 0)
    stdout = "".join(printed)
    stopped = Stopped(child.returncode, stdout, "".join(lines))
    assert "Traceback" not in stopped.stderr, stopped.stderr
    expected = 130 if sig is signal.SIGINT else 143
    assert stopped.status == expected, stopped.stderr
    assert stopped.last.startswith(f"ifgm-ref: interrupted by {sig.name}: "), stopped.stderr
    return stopped


def _heed_ctrl_c() -> None:
    """In the child: take SIGINT as a terminal's Ctrl-C, even where the test runs with it
    ignored (a pytest-xdist worker), which a child would inherit and keep."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def no_temporaries(folder: Path) -> None:
    """No half-written file beside the outputs (:func:`ifgm_ref.core.outputs.written`)."""
    assert not [p.name for p in folder.rglob(".*partial*")]


def test_simulate_keeps_the_finished_bag_and_plot_and_no_half_gif(tmp_path: Path) -> None:
    """Stopped while it draws the animation (the slowest output, written last), ``simulate``
    has already printed its result and kept the bag and the plot, whole."""
    out = tmp_path / "out"
    bag, plot, gif = out / "run.mcap", out / "run.png", out / "run.gif"
    args = ["simulate", "post", "--planner", "ifgm", "--record", str(bag), "--plot", str(plot)]
    stopped = interrupt([*args, "--animate", str(gif)], tmp_path, (0.2, 1.5), after="run.png")
    assert stopped.stdout.startswith("ifgm in post: goal_reached")
    assert f"wrote {bag}\nwrote {plot}\n" in stopped.stderr
    assert stopped.last.endswith(f"while writing {gif}; wrote {bag}, {plot}; not written: {gif}")
    assert sorted(p.name for p in out.iterdir()) == ["run.mcap", "run.png"]
    assert read_log(bag).steps
    with Image.open(plot) as image:
        image.load()


def test_simulate_terminated_in_the_run_writes_nothing_and_says_so(tmp_path: Path) -> None:
    trace, plot = tmp_path / "t.csv", tmp_path / "p.png"
    args = ["simulate", "scenario2", "--planner", "ifgm", "--dt", "0.01"]
    stopped = interrupt(
        [*args, "--trace", str(trace), "--plot", str(plot)], tmp_path, (1.5, 3.0),
        sig=signal.SIGTERM,
    )  # fmt: skip
    assert stopped.last.endswith(
        f"while simulating scenario2; nothing written; not written: {trace}, {plot}"
    )
    assert not list(tmp_path.iterdir())


def test_figures_keeps_whole_figures_and_names_the_missing(tmp_path: Path) -> None:
    out = tmp_path / "figs"
    stopped = interrupt(["figures", "--out", str(out)], tmp_path, (0.0, 1.0), after="wrote")
    no_temporaries(out)
    kept = sorted(out.iterdir())
    assert kept, stopped.stderr
    for path in kept:
        assert f"wrote {path}\n" in stopped.stderr
        if path.suffix == ".png":
            with Image.open(path) as image:
                image.load()
        elif path.suffix == ".svg":
            assert path.read_text().rstrip().endswith("</svg>")
    missing = stopped.last.split("; not written: ")[1].split(", ")
    assert len(kept) + len(missing) == 14
    assert not {Path(m) for m in missing} & set(kept)


def test_oracle_stops_its_workers_with_one_line(tmp_path: Path) -> None:
    stopped = interrupt(
        ["oracle", "--planner", "ifgm", "--jobs", "2", "--artifacts", str(tmp_path / "a")],
        tmp_path, (0.5, 2.0), after="PASSED",  # the equations are done: the pool is at work
    )  # fmt: skip
    assert stopped.stderr.count("ifgm-ref: interrupted") == 1


def test_bench_keeps_its_rows_so_far(tmp_path: Path) -> None:
    out = tmp_path / "bench"
    args = ["bench", "--planners", "ifgm,bug1", "--classes", "u", "--per-class", "20"]
    stopped = interrupt(
        [*args, "--jobs", "1", "--out", str(out)], tmp_path, (1.0, 2.0), after="bench:"
    )
    assert stopped.last.endswith(f"the rows so far are in {out / 'results.partial.csv'}")
    no_temporaries(out)


def test_replay_keeps_whole_files(tmp_path: Path) -> None:
    bag = tmp_path / "run.mcap"
    assert (
        run_cli("simulate", "scenario2", "--planner", "ifgm", "--record", str(bag)).returncode == 0
    )
    steps, plot = tmp_path / "steps.csv", tmp_path / "replay.png"
    args = ["replay", str(bag), "--planner", "fgm", "--steps", str(steps), "--plot", str(plot)]
    # While it draws the plot (0.7 s of its 2 s on this machine), the steps written: a moment
    # after its start is not one where it is busy on every machine, as a faster start-up showed.
    stopped = interrupt(args, tmp_path, (0.05, 0.2), after=f"wrote {steps}")
    no_temporaries(tmp_path)
    assert sorted(p for p in tmp_path.iterdir() if p != bag) == [steps]
    assert stopped.last.endswith(f"not written: {plot}")
    assert steps.read_text().count("\n") > 1000  # every step, not part of them


def test_docs_stops_sphinx_and_says_the_site_is_incomplete(tmp_path: Path) -> None:
    pytest.importorskip("sphinx", reason="the docs extra is not installed")
    site = tmp_path / "site"
    args = ["docs", "--out", str(site), "--root", str(ROOT)]
    stopped = interrupt(args, tmp_path, (3.5, 5.0))
    assert stopped.last.endswith(f"while building the site in {site}, which a rerun completes; "
                                 "nothing written")  # fmt: skip
