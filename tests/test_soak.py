"""The soak (issue 24): worlds named by class and seed, rows as the episodes run directly,
counts and the Wilson bound, failures that replay, the same rows on any number of processes,
and ``benchmarks/bench_soak.py`` (loaded from its path: ``benchmarks/`` is not a package).

The soaks here are small: two worlds per class, with ``straight`` (it never avoids, so it
collides) and FGM (it stalls in some U traps). What each episode should give is computed
independently, by :func:`ifgm_ref.sim.simulator.simulate` on ``random_world(class, seed)`` to its
time bound, never hard-coded.
"""

from __future__ import annotations

import dataclasses
import importlib.util
import json
import sys
import time
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pytest

from ifgm_ref.apps.bench.runner import map_tasks
from ifgm_ref.apps.bench.soak import (
    SOAK_CLASSES,
    SoakRow,
    read_rows,
    replay,
    run_soak,
    soak_world,
    world_name,
    write_rows,
)
from ifgm_ref.apps.bench.soak_report import ALL, Tally, describe, failure_report, summarise
from ifgm_ref.apps.bench.tasks import ERROR
from ifgm_ref.core.errors import ParameterError, WorldError
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.stats import wilson_interval
from ifgm_ref.io.worldfile import load_world, save_world
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.convergence import time_bound
from ifgm_ref.sim.simulator import Result, simulate
from ifgm_ref.sim.worldgen.classes import random_world
from tests.planner_doubles import CRASHES
from tests.test_cli import run_cli

SCRIPT = Path(__file__).resolve().parent.parent / "benchmarks" / "bench_soak.py"
CLASSES = list(SOAK_CLASSES)
SEEDS = range(1, 3)
PLANNERS = ("straight", "fgm")


def direct(planner: str, world_class: str, seed: int) -> Result:
    """The episode run without the soak: ``random_world`` to its time bound, the defaults."""
    world = random_world(world_class, seed)
    sim = SimParams(max_time=time_bound(world))
    return simulate(world, make_planner(planner), sim).result


@pytest.fixture(scope="module")
def rows() -> list[SoakRow]:
    return run_soak(PLANNERS, CLASSES, SEEDS, jobs=1, progress=False)


@pytest.fixture(scope="module")
def expected() -> dict[tuple[str, str, int], Result]:
    return {(p, c, s): direct(p, c, s) for c in CLASSES for s in SEEDS for p in PLANNERS}


def test_the_world_of_a_class_and_seed_is_random_worlds(rows: list[SoakRow]) -> None:
    world = soak_world("open", 5000)
    assert world.name == "open-seed5000" == world_name("open", 5000)
    assert dataclasses.replace(world, name=None) == dataclasses.replace(
        random_world("open", 5000), name=None
    )
    assert soak_world("open", 5001) != world
    with pytest.raises(WorldError, match="unknown world class 'donut'"):
        soak_world("donut", 1)
    with pytest.raises(ParameterError, match="seed must be an integer >= 0"):
        soak_world("open", -1)


def test_rows_are_the_episodes_run_directly(
    rows: list[SoakRow], expected: dict[tuple[str, str, int], Result]
) -> None:
    assert [(r.planner, r.world_class, r.seed) for r in rows] == list(expected)
    for row in rows:
        result = expected[row.planner, row.world_class, row.seed]
        got = (row.reached, row.collided, row.stop_reason, row.time_s, row.path_length, row.steps)
        want = (result.reached, result.collided, result.stop_reason, result.time_s,
                result.path_length, result.steps)  # fmt: skip
        assert got == want, row
        assert row.time_bound == time_bound(random_world(row.world_class, row.seed))
    reasons = {r.stop_reason for r in rows if not r.reached}
    assert {"collision", "stalled"} <= reasons, "the soak should see both kinds of failure"
    assert any(r.reached for r in rows), "and successes"


def test_counts_and_the_wilson_bound(
    rows: list[SoakRow], expected: dict[tuple[str, str, int], Result]
) -> None:
    tallies = {(t.planner, t.world_class): t for t in summarise(rows)}
    assert set(tallies) == {(p, c) for p in PLANNERS for c in [*CLASSES, ALL]}
    for (planner, world_class), tally in tallies.items():
        mine = [
            result
            for (p, c, _), result in expected.items()
            if p == planner and world_class in (c, ALL)
        ]
        failed = [r.stop_reason for r in mine if not r.reached]
        assert tally.worlds == len(mine) and tally.reached == len(mine) - len(failed)
        assert dict(tally.failures) == {reason: failed.count(reason) for reason in set(failed)}
        assert tally.failure_rate_bound == wilson_interval(len(failed), len(mine)).high


def test_no_failure_in_2000_worlds_bounds_the_rate_below_0_2_percent() -> None:
    """The issue's arithmetic: 0 failures in 2,000 bound the rate below 0.2 % at 95 %; one
    failure does not."""
    clean = Tally("ifgm", "open", 2000, 2000, ())
    assert clean.failure_rate_bound == wilson_interval(0, 2000).high < 0.002
    assert Tally("ifgm", "open", 2000, 1999, (("time_limit", 1),)).failure_rate_bound > 0.002


def test_failures_are_ordered_by_count_then_name() -> None:
    base = SoakRow("p", "u", 0, False, False, "stalled", 1.0, 9.0, 1.0, 10)
    rows = [
        dataclasses.replace(base, seed=k, stop_reason=reason)
        for k, reason in enumerate(["time_limit", "stalled", "collision", "stalled"])
    ]
    (tally,) = summarise(rows)
    assert tally.failures == (("stalled", 2), ("collision", 1), ("time_limit", 1))


def test_every_failure_replays_from_its_seed(rows: list[SoakRow]) -> None:
    failures = [r for r in rows if not r.reached]
    assert failures
    for row in failures:
        world, again, run = replay(row.planner, row.world_class, row.seed)
        assert again == row
        assert run is not None and run.result.stop_reason == row.stop_reason
        assert world == soak_world(row.world_class, row.seed)


def test_a_failure_replays_from_its_world_file(rows: list[SoakRow], tmp_path: Path) -> None:
    """The failure list's ``ifgm-ref simulate`` command gives the same episode."""
    row = next(r for r in rows if r.stop_reason == "stalled")
    path = tmp_path / f"{row.world}.json"
    save_world(soak_world(row.world_class, row.seed), path)
    assert load_world(path) == soak_world(row.world_class, row.seed)
    (command,) = [
        line.split("or: ", 1)[1]
        for line in failure_report([row], "soak", tmp_path).splitlines()
        if "or: " in line
    ]
    assert command.startswith("ifgm-ref simulate ")
    args = [*command.split()[2:], "--json"]
    done = run_cli("simulate", *args)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert (result["stop_reason"], result["time_s"], result["path_length"], result["steps"]) == (
        row.stop_reason, row.time_s, row.path_length, row.steps,
    )  # fmt: skip


def test_two_processes_give_the_same_rows(rows: list[SoakRow]) -> None:
    seen: list[str] = []
    pooled = run_soak(PLANNERS, CLASSES, SEEDS, jobs=2, progress=False,
                      on_rows=lambda done: seen.append(done[0].world))  # fmt: skip
    assert pooled == rows
    assert sorted(seen) == sorted(world_name(c, s) for c in CLASSES for s in SEEDS)


@pytest.mark.slow  # a Dask cluster takes seconds to start; tests/test_bench.py covers the runner's
def test_a_dask_cluster_gives_the_same_rows(rows: list[SoakRow]) -> None:
    distributed = pytest.importorskip("distributed")
    chosen = [r for r in rows if r.world_class in ("u", "h")]
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        remote = run_soak(PLANNERS, ["u", "h"], SEEDS, scheduler=cluster.scheduler_address,
                          progress=False)  # fmt: skip
    assert remote == chosen


def test_a_crashing_planner_is_a_failure_not_the_end() -> None:
    crashed, fine = run_soak((CRASHES, "fgm"), ["open"], [1], progress=False)
    assert (crashed.stop_reason, crashed.detail, crashed.reached) == (
        ERROR, "RuntimeError: boom", False,
    )  # fmt: skip
    assert (crashed.time_s, crashed.path_length, crashed.steps) == (None, None, None)
    assert fine.reached
    (tally, _) = summarise([crashed, fine])
    assert tally.failures == ((ERROR, 1),)
    assert "RuntimeError: boom" in describe(crashed)


def test_rows_read_back_as_written(rows: list[SoakRow], tmp_path: Path) -> None:
    path = tmp_path / "rows.jsonl"
    write_rows(path, rows[:3])
    write_rows(path, rows[3:], append=True)
    assert read_rows(path) == rows
    write_rows(path, rows[:1])
    assert read_rows(path) == rows[:1]


def test_bad_soaks_are_refused() -> None:
    with pytest.raises(WorldError, match="unknown world class 'donut'"):
        run_soak(PLANNERS, ["u", "donut"], SEEDS)
    with pytest.raises(ParameterError, match="seed must be an integer >= 0"):
        run_soak(PLANNERS, ["u"], [-1])
    with pytest.raises(ParameterError, match="at least one planner"):
        run_soak([], ["u"], SEEDS)
    with pytest.raises(ParameterError, match="jobs must be at least 1"):
        run_soak(PLANNERS, ["u"], SEEDS, jobs=0)


def _mark_and_wait(folder: str, k: int) -> int:
    (Path(folder) / f"{k}.started").touch()
    time.sleep(0.05)
    return k


def test_an_interrupted_run_does_not_wait_for_the_tasks_not_started(tmp_path: Path) -> None:
    """Ctrl-C (or a failing callback) cancels the queued tasks rather than running them all."""

    def interrupt(result: int) -> None:
        raise KeyboardInterrupt

    tasks = [(str(tmp_path), k) for k in range(60)]
    with pytest.raises(KeyboardInterrupt):
        map_tasks(_mark_and_wait, tasks, jobs=2, progress=False, on_result=interrupt)
    assert 1 <= len(list(tmp_path.glob("*.started"))) < len(tasks)


# --- benchmarks/bench_soak.py ------------------------------------------------------------


@pytest.fixture(scope="module")
def script() -> ModuleType:
    """The soak script as a module."""
    spec = importlib.util.spec_from_file_location("bench_soak", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def _soak_args(out: Path, jobs: int) -> list[str]:
    return ["--planners", ",".join(PLANNERS), "--classes", "u,h", "--per-class", "2",
            "--first-seed", str(SEEDS.start), "--jobs", str(jobs), "--out", str(out)]  # fmt: skip


def test_the_script_writes_rows_worlds_and_the_report(
    script: ModuleType, rows: list[SoakRow], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    chosen = [r for r in rows if r.world_class in ("u", "h")]
    assert script.main(_soak_args(tmp_path / "one", 1)) == 0
    out = capsys.readouterr().out
    assert read_rows(tmp_path / "one" / "rows.jsonl") == chosen
    assert not (tmp_path / "one" / "rows.partial.jsonl").exists()
    failed = {r.world for r in chosen if not r.reached}
    assert {p.stem for p in (tmp_path / "one" / "worlds").glob("*.json")} == failed
    for tally in summarise(chosen):
        assert f"{tally.reached}/{tally.worlds}" in out
    for row in chosen:
        replay_line = f"--replay {row.world_class}:{row.seed} --planner {row.planner}"
        assert (replay_line in out) == (not row.reached), row
    assert out == (tmp_path / "one" / "summary.txt").read_text()

    assert script.main(_soak_args(tmp_path / "two", 2)) == 0
    first, second = (tmp_path / name / "rows.jsonl" for name in ("one", "two"))
    assert first.read_bytes() == second.read_bytes()


def test_the_script_replays_a_failure(
    script: ModuleType, rows: list[SoakRow], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    row = next(r for r in rows if r.stop_reason == "stalled")
    plot = tmp_path / "replay.png"
    args = ["--replay", f"{row.world_class}:{row.seed}", "--planner", row.planner]
    assert script.main([*args, "--plot", str(plot)]) == 0
    assert capsys.readouterr().out.splitlines()[0] == describe(row)
    assert plot.read_bytes().startswith(b"\x89PNG")


def test_an_interrupted_script_keeps_the_rows_so_far(
    script: ModuleType, rows: list[SoakRow], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    def one_world_then_ctrl_c(*args: object, on_rows: Callable[[list[SoakRow]], None],
                              **kwargs: object) -> list[SoakRow]:  # fmt: skip
        on_rows(rows[:2])
        raise KeyboardInterrupt

    monkeypatch.setattr(script, "run_soak", one_world_then_ctrl_c)
    assert script.main(_soak_args(tmp_path, 1)) == script.EXIT_INTERRUPTED
    assert read_rows(tmp_path / "rows.partial.jsonl") == rows[:2]
    assert not (tmp_path / "rows.jsonl").exists()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--classes", "u,donut"], "unknown world class 'donut'"),
        (["--planners", "fgm,nope"], "'nope' is neither a built-in planner"),
        (["--per-class", "0"], "--per-class must be at least 1"),
        (["--jobs", "0"], "--jobs must be at least 1"),
        (["--first-seed", "-1"], "must be an integer >= 0"),
        (["--planner", "fgm"], "--planner and --plot go with --replay"),
        (["--replay", "open:3"], "--replay needs --planner"),
        (["--replay", "open", "--planner", "fgm"], "expected CLASS:SEED"),
        (["--replay", "open:x", "--planner", "fgm"], "expected CLASS:SEED"),
        (["--replay", "donut:3", "--planner", "fgm"], "unknown world class 'donut'"),
        (["--replay", "open:3", "--planner", "nope"], "'nope' is neither a built-in planner"),
        (["--replay", "open:3", "--planner", "fgm", "--plot", "a.txt"], "--plot a.txt: use"),
    ],
)
def test_the_script_refuses_bad_input(
    script: ModuleType,
    args: list[str],
    message: str,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    out = tmp_path / "out"
    try:
        status = script.main([*args, "--out", str(out)])
    except SystemExit as stop:  # argparse's own errors
        status = stop.code
    err = capsys.readouterr().err
    assert status == 2
    assert message in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists()
