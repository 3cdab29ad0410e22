"""The benchmark's engine: ``bench --engine``/``--body`` reach every episode, in the workers too,
each row says its engine, and the kinematic default is the table it was."""

from __future__ import annotations

import csv
import dataclasses
from pathlib import Path

import pytest

from ifgm_ref.apps.bench.report import read_rows
from ifgm_ref.apps.bench.runner import run_bench
from ifgm_ref.apps.bench.tasks import Row, generated_specs, run_world
from ifgm_ref.apps.cli import main
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.io.barn import gazebo_task
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.simulator import simulate

BARN = Path(__file__).parent / "worlds" / "barn"
#: The columns of ``results.csv`` before the engine's: they keep their names and order.
COLUMNS_BEFORE_ENGINE = (
    "planner", "world", "world_class", "reached", "collided", "stop_reason", "time_s",
    "path_length", "optimal_length", "path_ratio", "min_clearance", "heading_change", "steps",
    "decisions_per_cpu_s", "detail", "reference_length", "barn_score", "noise", "noise_kind",
    "noise_level", "noise_seed",
)  # fmt: skip
#: A short time limit, s: enough for the engines to part (the paper's body needs 0.25 s to
#: reach full speed, the kinematic robot none), short enough for a fast test.
MAX_TIME = "4"


def _episode(row: Row) -> tuple[object, ...]:
    """What the simulation decides in a row (not the CPU timing)."""
    return (row.world, row.planner, row.stop_reason, row.steps, row.path_length, row.time_s)


def test_the_columns_are_the_old_ones_then_engine_then_robot() -> None:
    assert Row.columns() == (*COLUMNS_BEFORE_ENGINE, "engine", "robot")


def test_the_engine_reaches_every_episode_in_the_workers(tmp_path: Path) -> None:
    """``--engine mujoco`` with two worker processes: every row says mujoco, and is the
    episode the mujoco engine runs in this process, not the kinematic one."""
    out = tmp_path / "out"
    argv = ["bench", "--classes", "u", "--per-class", "2", "--planners", "ifgm"]
    argv += ["--max-time", MAX_TIME, "--jobs", "2", "--engine", "mujoco", "--out", str(out)]
    assert main(argv) == 0
    rows = read_rows(out / "results.csv")
    assert {r.engine for r in rows} == {"mujoco"}
    specs = generated_specs(["u"], 2, 0)
    here = [r for s in specs for r in run_world(s, ("ifgm",), float(MAX_TIME), engine="mujoco")]
    kinematic = [r for s in specs for r in run_world(s, ("ifgm",), float(MAX_TIME))]
    assert [_episode(r) for r in rows] == [_episode(r) for r in here]
    for mujoco, kin in zip(rows, kinematic, strict=True):
        assert kin.engine == "kinematic"
        assert mujoco.path_length != kin.path_length, (mujoco, kin)
    summary = (out / "summary.md").read_text()
    assert "- engine: mujoco (a robot with mass" in summary


def test_a_barn_row_is_the_episode_simulate_runs_on_the_same_engine(tmp_path: Path) -> None:
    """``bench --barn --engine mujoco``: BARN's world 1 with the default body (the Jackal), as
    ``simulate barn:1 --engine mujoco`` runs it."""
    out = tmp_path / "out"
    argv = ["bench", "--barn", str(BARN), "--barn-worlds", "1", "--planners", "ifgm"]
    argv += ["--max-time", MAX_TIME, "--jobs", "1", "--engine", "mujoco", "--out", str(out)]
    assert main(argv) == 0
    with (out / "results.csv").open() as source:
        (row,) = list(csv.DictReader(source))
    task = gazebo_task("barn:1", folder=BARN)
    assert task is not None
    sim = dataclasses.replace(task.sim, max_time=float(MAX_TIME), engine="mujoco")
    result = simulate(task.world, make_planner("ifgm"), sim, progress=None).result
    assert row["engine"] == "mujoco"
    assert (int(row["steps"]), float(row["path_length"])) == (result.steps, result.path_length)


def test_a_body_without_the_mujoco_engine_is_a_usage_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = ["bench", "--classes", "u", "--per-class", "1", "--body", "paper"]
    assert main([*argv, "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err == "ifgm-ref: error: `body` applies to the mujoco engine only, got 'paper'\n"
    assert not (tmp_path / "out").exists()  # refused before anything ran


@pytest.mark.parametrize(
    ("engine", "body", "message"),
    [
        ("kinematic", "paper", "`body` applies to the mujoco engine only, got 'paper'"),
        ("mujoco", "segway", "unknown body 'segway'; choose one of jackal, jackal-disc, paper"),
        ("physx", None, "`engine` must be one of kinematic, mujoco, got 'physx'"),
    ],
)
def test_run_bench_refuses_an_engine_that_cannot_run(
    engine: str, body: str | None, message: str
) -> None:
    """One error before any task, not an ``error`` row per episode."""
    with pytest.raises(ParameterError, match=message):
        run_bench(generated_specs(["u"], 1, 0), ("ifgm",), engine=engine, body=body)


def test_the_kinematic_default_says_so_and_reads_back(tmp_path: Path) -> None:
    """Without ``--engine`` the rows are the kinematic episodes, ``--engine kinematic``'s; a
    ``results.csv`` written before the column reads back as kinematic."""
    runs = {}
    for name, extra in (("default", []), ("explicit", ["--engine", "kinematic"])):
        out = tmp_path / name
        argv = ["bench", "--classes", "h", "--per-class", "1", "--planners", "ifgm,iba"]
        assert main([*argv, "--max-time", MAX_TIME, "--jobs", "1", *extra, "--out", str(out)]) == 0
        runs[name] = read_rows(out / "results.csv")
        assert "- engine: kinematic (the paper's instant robot)" in (out / "summary.md").read_text()
    assert [_episode(r) for r in runs["default"]] == [_episode(r) for r in runs["explicit"]]
    assert {r.engine for r in runs["default"]} == {"kinematic"}
    old = tmp_path / "old.csv"
    with (tmp_path / "default" / "results.csv").open() as source:
        lines = [line.rstrip("\n").rsplit(",", 2)[0] for line in source]
    old.write_text("\n".join(lines) + "\n")
    assert old.read_text().startswith(",".join(COLUMNS_BEFORE_ENGINE) + "\n")
    assert read_rows(old) == runs["default"]  # neither engine nor robot: kinematic, none
