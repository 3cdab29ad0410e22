"""The command line end to end: world file in, JSON out, clean errors.

Most tests run the command in the test's process (:func:`run_cli`: a child process costs about
a second of imports, and the command line is tested some 130 times); those that need what
only a process has (the entry point, its exit status, a closed pipe) start one
(:func:`run_process`)."""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from ifgm_ref.apps.cli import EXIT_BROKEN_PIPE, SUBCOMMANDS, build_parser, main
from ifgm_ref.io.scenarios import BUILTIN_WORLDS
from ifgm_ref.io.worldfile import (
    EXPORT_DIGITS,
    dumps_world,
    load_world,
    loads_world,
    world_from_dict,
    world_to_dict,
)
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.sim.simulator import Result, simulate

README = Path(__file__).resolve().parent.parent / "README.md"
WORLD = {
    "name": "one box",
    "start": [0.0, 0.0, 0.0],
    "goal": [12.0, 0.0],
    "obstacles": [{"polygon": [[5.0, 3.0], [7.0, 3.0], [7.0, 5.0], [5.0, 5.0]]}],
}


def run_cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    """``ifgm-ref ARGS`` run in this process (:func:`ifgm_ref.apps.cli.main`, from ``cwd``), its
    exit status and what it printed on stdout and stderr. What a process adds (the entry
    point, a closed pipe, signals) is tested with a real one (:func:`run_process`)."""
    out, err = io.StringIO(), io.StringIO()
    here = Path.cwd()
    try:
        os.chdir(cwd or here)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                status = main(list(args))
            except SystemExit as stop:  # argparse's usage errors and --help
                status = stop.code if isinstance(stop.code, int) else int(stop.code is not None)
    finally:
        os.chdir(here)
    return subprocess.CompletedProcess(["ifgm-ref", *args], status, out.getvalue(), err.getvalue())


def run_process(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    """``python -m ifgm_ref ARGS`` in a child process."""
    return subprocess.run(
        [sys.executable, "-m", "ifgm_ref", *args],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=cwd,
        check=False,
    )


def test_simulate_world_file_prints_one_json_result(tmp_path: Path) -> None:
    path = tmp_path / "world.json"
    path.write_text(json.dumps(WORLD))
    trace, plot = tmp_path / "trace.csv", tmp_path / "run.png"
    done = run_process(
        "simulate",
        str(path),
        "--planner",
        "straight",
        "--json",
        "--trace",
        str(trace),
        "--plot",
        str(plot),
    )
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    required = {
        "planner",
        "reached",
        "collided",
        "stop_reason",
        "time_s",
        "path_length",
        "min_clearance",
        "steps",
    }
    assert required <= set(result)
    assert set(result) == set(Result.__dataclass_fields__)
    assert result["planner"] == "straight" and result["reached"] is True
    assert result["path_length"] == pytest.approx(12.0, abs=0.5)
    # The box is 3 ft to the side of the straight line: clearance 3 - radius 1 = 2 ft.
    assert result["min_clearance"] == pytest.approx(2.0)
    assert len(trace.read_text().splitlines()) == result["steps"] + 2  # header + final sample
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_builtin_world_name_works_and_options_apply() -> None:
    done = run_cli(
        "simulate", "free", "--planner", "straight", "--json", "--max-time", "10", "--dt", "0.5"
    )
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert result["stop_reason"] == "time_limit" and result["steps"] == 20
    assert result["min_clearance"] is None


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["simulate", "no-such-world.json", "--planner", "straight"], "no such world file"),
        (["simulate", "free", "--planner", "straight", "--dt", "0"], "must be a finite number > 0"),
        (["simulate", "free", "--planner", "nope"], "'nope' is neither a built-in planner"),
        (["simulate", "BROKEN", "--planner", "straight"], "Expecting"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(tmp_path: Path, args: list[str], message: str) -> None:
    (tmp_path / "BROKEN").write_text('{"start": [0, 0, 0], "goal": [1, 1],,}')
    done = run_cli(*args, cwd=tmp_path)
    assert done.returncode == 2
    assert message in done.stderr
    assert "Traceback" not in done.stderr


def test_worlds_lists_and_exports_every_builtin(tmp_path: Path) -> None:
    listed = run_cli("worlds")
    assert listed.returncode == 0
    names = [line.split()[0] for line in listed.stdout.splitlines()]
    assert names == [*BUILTIN_WORLDS, "barn:N"]  # and one line for BARN's worlds
    exported = run_cli("worlds", "--export", str(tmp_path / "out"))
    assert exported.returncode == 0, exported.stderr
    for name, entry in BUILTIN_WORLDS.items():
        world = load_world(tmp_path / "out" / f"{name}.json")
        assert world == world_from_dict(world_to_dict(entry.build(), digits=EXPORT_DIGITS))


def test_exported_worlds_have_no_rounding_tails_and_drive_the_same(tmp_path: Path) -> None:
    assert run_cli("worlds", "--export", str(tmp_path)).returncode == 0
    texts = {path.stem: path.read_text() for path in tmp_path.glob("*.json")}
    assert set(texts) == set(BUILTIN_WORLDS)
    assert "11.999999999999998" in dumps_world(BUILTIN_WORLDS["u_trap"].build())  # the tail
    assert "[38.0, 12.0], [22.0, 12.0], [22.0, 11.0], [37.0, 11.0]" in texts["u_trap"]
    for name, text in texts.items():
        numbers = re.findall(r"-?\d+\.\d+(?:e-?\d+)?", text)
        digits = [len(n.partition("e")[0].lstrip("-").replace(".", "").strip("0")) for n in numbers]
        assert max(digits) <= EXPORT_DIGITS, name
        built, exported = world_to_dict(BUILTIN_WORLDS[name].build()), json.loads(text)
        assert _numbers(exported) == pytest.approx(_numbers(built), rel=5e-12, abs=1e-12)
    built = simulate(BUILTIN_WORLDS["u_trap"].build(), IFGMPlanner()).result
    exported = simulate(load_world(tmp_path / "u_trap.json"), IFGMPlanner()).result
    assert (exported.stop_reason, exported.steps) == (built.stop_reason, built.steps)
    assert exported.path_length == pytest.approx(built.path_length, rel=1e-9)


def _numbers(data: object) -> list[float]:
    """Every number in JSON data, depth first."""
    if isinstance(data, dict):
        return [x for value in data.values() for x in _numbers(value)]
    if isinstance(data, list):
        return [x for value in data for x in _numbers(value)]
    return [float(data)] if isinstance(data, int | float) else []


def test_planners_lists_straight() -> None:
    done = run_cli("planners")
    assert done.returncode == 0
    assert re.search(r"^straight\s+steer straight at the goal", done.stdout, re.MULTILINE)


def test_readme_world_example_loads_and_json_example_has_the_result_fields() -> None:
    blocks = re.findall(r"```json\n(.*?)```", README.read_text(), re.DOTALL)
    worlds = [b for b in blocks if '"start"' in b]
    results = [b for b in blocks if '"stop_reason"' in b]
    assert worlds and results
    world = loads_world(worlds[0], source="README.md")
    assert world.sensor.noise_std > 0 and len(world.obstacles) == 2
    assert set(json.loads(results[0])) == set(Result.__dataclass_fields__)


# -- rough edges a new user hit (issue 14) ---------------------------------------------------


@pytest.mark.parametrize(
    ("option", "name", "message"),
    [
        ("--plot", "run.xyz", "--plot run.xyz: cannot write .xyz; use one of .png"),
        ("--animate", "run.mp4", "--animate run.mp4: cannot write .mp4; use one of .gif"),
    ],
)
def test_an_output_type_it_cannot_write_is_refused_before_the_run(
    tmp_path: Path, option: str, name: str, message: str
) -> None:
    done = run_cli("simulate", "box", "--planner", "ifgm", option, name, cwd=tmp_path)
    assert done.returncode == 2
    assert done.stderr.strip() == f"ifgm-ref: error: {message}" + (
        ", .svg, .pdf, .jpg, .jpeg" if option == "--plot" else ""
    )
    assert not (tmp_path / name).exists()


def test_a_factory_that_makes_no_planner_is_a_one_line_error() -> None:
    done = run_cli("simulate", "box", "--planner", "os:getcwd")
    assert done.returncode == 2
    assert done.stderr.splitlines() == [
        "ifgm-ref: error: 'os:getcwd' made a str, not a planner: it has no name, reset, step "
        "(see ifgm_ref.core.protocol.Planner)"
    ]


def test_an_argument_error_is_one_line() -> None:
    done = run_process("simulate")
    assert done.returncode == 2
    assert done.stderr.splitlines() == [
        "ifgm-ref: error: the following arguments are required: WORLD "
        "(see ifgm-ref simulate --help)"
    ]


def test_a_factory_module_is_found_in_the_working_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from ifgm_ref.io.transport.loading import load_planner

    (tmp_path / "my_cwd_planner_module.py").write_text(
        "from ifgm_ref.planners.iba import IBAPlanner\n\ndef make():\n    return IBAPlanner()\n"
    )
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "path", [p for p in sys.path if p not in ("", str(tmp_path))])
    monkeypatch.delitem(sys.modules, "my_cwd_planner_module", raising=False)
    assert load_planner("my_cwd_planner_module:make").name == "iba"


@pytest.mark.parametrize(("planner", "status"), [("straight", 1), ("ifgm", 0)])
def test_require_goal_fails_a_run_that_misses_the_goal(planner: str, status: int) -> None:
    done = run_cli("simulate", "box", "--planner", planner, "--json", "--require-goal")
    assert done.returncode == status
    assert json.loads(done.stdout)["reached"] == (status == 0)
    assert run_cli("simulate", "box", "--planner", planner, "--json").returncode == 0


@pytest.mark.parametrize("args", [["planners"], ["vectors", "--out", "/dev/stdout"]])
def test_a_reader_that_left_ends_the_command_quietly(args: list[str]) -> None:
    """``ifgm-ref planners | head``: no ``[Errno 32] Broken pipe``, and the status a shell
    reports for a tool stopped by a closed pipe (128 + SIGPIPE)."""
    read, write = os.pipe()
    os.close(read)  # the reader is gone before the first line
    try:
        done = subprocess.run(
            [sys.executable, "-m", "ifgm_ref", *args],
            stdout=write,
            stderr=subprocess.PIPE,
            text=True,
            timeout=120,
            check=False,
        )
    finally:
        os.close(write)
    assert (done.returncode, done.stderr) == (EXIT_BROKEN_PIPE, "")


def test_simulate_and_vectors_make_their_output_folders(tmp_path: Path) -> None:
    """As ``figures --out`` does: missing folders of an output path are made."""
    trace, plot = tmp_path / "a" / "trace.csv", tmp_path / "b" / "c" / "run.png"
    done = run_cli(
        "simulate", "post", "--planner", "ifgm", "--trace", str(trace), "--plot", str(plot)
    )
    assert done.returncode == 0, done.stderr
    assert trace.read_text().startswith("t,x,y,theta") and plot.stat().st_size > 0
    vectors = tmp_path / "d" / "vectors.json"
    done = run_cli("vectors", "--out", str(vectors))
    assert done.returncode == 0, done.stderr
    assert json.loads(vectors.read_text())


def test_an_output_folder_that_cannot_be_made_is_refused_before_the_run(tmp_path: Path) -> None:
    """``--plot ok.png --animate blocked/x.gif``: one line naming the option, and no plot
    written first."""
    (tmp_path / "blocked").write_text("a file where the folder should be")
    plot, gif = tmp_path / "ok.png", tmp_path / "blocked" / "x.gif"
    done = run_cli(
        "simulate", "post", "--planner", "ifgm", "--plot", str(plot), "--animate", str(gif)
    )
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.splitlines() == [
        f"ifgm-ref: error: --animate {gif}: cannot make its folder {str(gif.parent)!r}: File exists"
    ]
    assert not plot.exists()


def _subcommand_names(argv: list[str]) -> list[str]:
    parser = build_parser(argv)
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return list(sub.choices)


def test_a_subcommand_is_parsed_by_its_own_parser_alone() -> None:
    """``ifgm-ref serve ...`` builds the parser of ``serve`` alone; no subcommand, or one
    misspelt, builds them all (the list ``--help`` and the error give)."""
    assert _subcommand_names(["serve", "--planner", "ifgm"]) == ["serve"]
    assert _subcommand_names(["--help"]) == list(SUBCOMMANDS)
    assert _subcommand_names(["serv"]) == list(SUBCOMMANDS)


def test_serve_starts_without_the_other_commands_imports() -> None:
    """A port's test harness starts ``ifgm-ref serve`` for every run: the process loads
    neither sympy (the formulas run from their table), nor the bag reader (``replay``), nor
    Hypothesis (the oracle's drawing), nor matplotlib (``-X importtime`` lists what it
    imported)."""
    done = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "ifgm_ref", "serve", "--planner", "ifgm"],
        input="",
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert "end of input after 0 line(s)" in done.stderr  # it started, and read its input
    imported = re.findall(r"^import time:.*\| +([\w.]+)$", done.stderr, flags=re.M)
    assert "ifgm_ref.planners.ifgm.planner" in imported
    heavy = {"sympy", "rosbags", "hypothesis", "matplotlib"}
    assert heavy.isdisjoint(name.split(".")[0] for name in imported)
