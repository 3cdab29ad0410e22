"""BARN worlds (ifgm_ref/io/barn.py): layouts, reference length, score, ``bench --barn``."""

from __future__ import annotations

import csv
import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from ifgm_ref.apps.bench.tasks import WorldSpec, barn_specs, run_world
from ifgm_ref.apps.cli import main
from ifgm_ref.core.errors import ParameterError, WorldError
from ifgm_ref.io import barn
from ifgm_ref.io.barn import BUNDLED_INDICES, MissingWorlds
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import Circle
from tests.test_cli import run_cli

BARN = Path(__file__).parent / "worlds" / "barn"
INDICES = [1, 2, 4, 245]


def test_world_has_barns_task_robot_and_sensor() -> None:
    world = barn.load_barn_world(BARN / "world_2.world")
    assert (world.start, world.goal) == ((-2.0, 3.0, math.pi / 2), (-2.0, 13.0))
    assert (world.robot.radius, world.robot.speed, world.robot.max_turn_rate) == (
        0.22, 1.0, math.pi,
    )  # fmt: skip
    assert world.sensor.rays == 720 and world.bounds is None
    assert len(world.obstacles) == 234
    assert all(isinstance(ob, Circle) and ob.radius == 0.075 for ob in world.obstacles)
    ir = barn.load_barn_world(BARN / "world_2.world", sensor="paper_ir").sensor
    assert (ir.rays, round(ir.range_max, 9)) == (76, 3.3)  # 15 ft scaled by 0.22


def test_unknown_sensor() -> None:
    with pytest.raises(ParameterError, match="unknown sensor 'sonar'"):
        barn.barn_sensor("sonar")


def test_reference_length_by_hand(tmp_path: Path) -> None:
    path = tmp_path / "path_9.npy"
    np.save(path, np.array([[13, 0], [13, 1]]))
    # Cells (13, 0) and (13, 1): x = 13 * 0.15 - 0.075 - 4.5 = -2.625, y = 5.075 and 5.225;
    # from the start (-2, 3) through both to the goal (-2, 13).
    expected = math.hypot(0.625, 2.075) + 0.15 + math.hypot(0.625, 7.775)
    assert barn.reference_length(path) == pytest.approx(expected, abs=1e-12)


def test_reference_length_of_a_barn_path() -> None:
    cells = np.load(BARN / "path_1.npy")
    assert cells.shape == (37, 2)
    length = barn.reference_length(BARN / "path_1.npy")
    assert 10.0 < length < 15.0  # at least the 10 m from start to goal
    assert length == pytest.approx(12.312491040890126, abs=1e-9)


def test_reference_length_bad_file(tmp_path: Path) -> None:
    path = tmp_path / "path_1.npy"
    np.save(path, np.zeros(3))
    with pytest.raises(WorldError, match=r"expected an \(n, 2\) array"):
        barn.reference_length(path)


def test_barn_score_edges() -> None:
    length = 12.0  # t_opt = 6 s: the score is t_opt / clip(t, 12 s, 48 s)
    assert barn.barn_score(False, 10.0, length) == 0.0
    assert barn.barn_score(True, 1.0, length) == 0.5  # below 2 t_opt
    assert barn.barn_score(True, 12.0, length) == 0.5
    assert barn.barn_score(True, 24.0, length) == 0.25
    assert barn.barn_score(True, 48.0, length) == 0.125  # 1/8 at 8 t_opt ...
    assert barn.barn_score(True, 99.0, length) == 0.125  # ... and above it
    with pytest.raises(ParameterError):
        barn.barn_score(True, 1.0, 0.0)


def test_flat_and_repository_layouts(tmp_path: Path) -> None:
    flat = barn.find_barn_worlds(BARN)
    assert [f.index for f in flat] == INDICES
    assert flat[0].world == BARN / "world_1.world" and flat[0].path == BARN / "path_1.npy"
    repo = tmp_path / "jackal_helper" / "worlds" / "BARN"
    (repo / "path_files").mkdir(parents=True)
    for k in INDICES:
        shutil.copy(BARN / f"world_{k}.world", repo)
        shutil.copy(BARN / f"path_{k}.npy", repo / "path_files")
    found = barn.find_barn_worlds(tmp_path)
    assert [f.index for f in found] == INDICES
    assert found[2].path == repo / "path_files" / "path_4.npy"
    assert [f.index for f in barn.find_barn_worlds(tmp_path, {2, 4})] == [2, 4]


def test_layout_errors(tmp_path: Path) -> None:
    with pytest.raises(WorldError, match="no BARN worlds"):
        barn.find_barn_worlds(tmp_path)
    shutil.copy(BARN / "world_1.world", tmp_path)
    with pytest.raises(WorldError, match=r"no path file path_1\.npy"):
        barn.find_barn_worlds(tmp_path)
    with pytest.raises(MissingWorlds, match=f"^barn:3, barn:7 are not in {BARN}: BARN's worlds"):
        barn.find_barn_worlds(BARN, {1, 3, 7})


def test_parse_selection() -> None:
    assert barn.parse_selection("0-2, 7") == {0, 1, 2, 7}
    for bad in ("", "a", "5-2"):
        with pytest.raises(ParameterError):
            barn.parse_selection(bad)


def test_rows_carry_the_barn_columns() -> None:
    (spec,) = barn_specs(BARN, indices={1})
    assert spec == WorldSpec("barn-001", "barn", str(BARN / "world_1.world"), None, 1,
                             str(BARN / "path_1.npy"), "jackal_lidar")  # fmt: skip
    (row,) = run_world(spec, ("straight",))
    assert (row.world_class, row.collided, row.optimal_length) == ("barn", True, None)
    assert row.reference_length == pytest.approx(12.312491040890126)
    assert row.barn_score == 0.0


def test_cli_bench_barn(tmp_path: Path) -> None:
    out = tmp_path / "out"
    argv = ["bench", "--barn", str(BARN), "--barn-worlds", "1,2,4", "--planners", "straight"]
    argv += ["--jobs", "1"]
    assert main([*argv, "--out", str(out)]) == 0
    with (out / "results.csv").open() as source:
        rows = list(csv.DictReader(source))
    assert [r["world"] for r in rows] == ["barn-001", "barn-002", "barn-004"]
    assert rows[0]["optimal_length"] == ""  # BARN worlds skip the shortest path
    assert float(rows[0]["reference_length"]) == pytest.approx(12.312491040890126)
    assert {r["barn_score"] for r in rows} == {"0.0"}  # straight ahead hits a cylinder
    with (out / "summary.csv").open() as source:
        (summary,) = list(csv.DictReader(source))
    assert (summary["barn_score_mean"], summary["collision_rate"]) == ("0.0", "1.0")
    summary_md = (out / "summary.md").read_text()
    assert "| straight | barn | 3 | 0.000 | 0.0% | 100.0% | 0.0% |" in summary_md
    # No shortest path in BARN's worlds: no such title, column or empty plot; lengths in metres.
    assert summary_md.startswith("# Benchmark on BARN's worlds, with BARN's score\n")
    assert "optimal" not in summary_md and not (out / "path_ratio.png").exists()
    assert "| min clearance m |" in summary_md and " ft " not in summary_md
    assert main(["bench", "--sensor", "paper_ir", "--out", str(out)]) == 2  # BARN only


def test_ifgm_crosses_the_clutter_it_used_to_circle_for_ever() -> None:
    """Errata row 34: in BARN's world 245 IFGM went round the inside of the start box, saw no
    remembered obstacle between itself and the goal 12 m away (it remembers returns only
    within ``view_range``, 3.3 m for BARN's robot), took the goal for visible (DistBug's
    ``F = d``, with the LiDAR's 30 m ``range_max``), left, met the same clutter and went
    round again until BARN's 100 s ran out. ``F = d`` now needs the goal within
    ``view_range``."""
    world = barn.load_barn_world(BARN / "world_245.world")
    result = simulate(world, make_planner("ifgm"), barn.SIM).result
    assert result.reached and not result.collided, result


def test_the_bundled_worlds_are_unpacked_once_into_the_cache(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """BARN's 200 worlds with ``N % 3 != 0`` ship with the package, with their licence and
    README, and are unpacked on first use into the user's cache folder."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert {p.name for p in barn.BUNDLED.parent.iterdir()} >= {"LICENSE", "README.md"}
    folder = barn.bundled_barn_folder()
    assert folder.parent == tmp_path / "ifgm-ref"
    found = barn.find_barn_worlds(folder)
    assert len(found) == 200 and all(f.index % 3 != 0 for f in found)
    assert {f.index for f in found} == {n for n in range(300) if n % 3} == BUNDLED_INDICES
    stamp = (folder / "world_1.world").stat().st_mtime_ns
    assert barn.bundled_barn_folder() == folder  # reused, not unpacked again
    assert (folder / "world_1.world").stat().st_mtime_ns == stamp
    assert [p.name for p in (tmp_path / "ifgm-ref").iterdir()] == [folder.name]  # no leftovers
    assert (folder / "world_1.world").read_bytes() == (BARN / "world_1.world").read_bytes()


def test_cli_bench_barn_runs_the_bundled_worlds_without_a_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    out = tmp_path / "out"
    argv = ["bench", "--barn", "--barn-worlds", "1,2", "--planners", "straight", "--jobs", "1"]
    assert main([*argv, "--out", str(out)]) == 0
    with (out / "results.csv").open() as source:
        assert [r["world"] for r in csv.DictReader(source)] == ["barn-001", "barn-002"]
    assert "- worlds: 2 BARN worlds from ifgm-ref's bundled set" in (out / "summary.md").read_text()


def _simulate_json(*args: str) -> dict[str, object]:
    done = run_cli("simulate", *args, "--json")
    assert done.returncode == 0, done.stderr
    result: dict[str, object] = json.loads(done.stdout)
    return result


def test_simulate_runs_a_barn_world_as_the_bench_does(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``simulate barn:N`` (and the world file itself) prints the BARN score ``bench --barn``
    gives that world: the same robot, sensor, time step, limit and success radius."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    (spec,) = barn_specs(BARN, indices={4})
    (row,) = run_world(spec, ("ifgm",))
    assert row.reached and row.barn_score is not None
    for args in (
        ["barn:4", "--barn-dir", str(BARN)],
        ["barn:4"],  # the bundled set
        [str(BARN / "world_4.world")],
    ):
        result = _simulate_json(*args, "--planner", "ifgm")
        assert (result["world"], result["time_s"]) == ("barn-004", row.time_s), args
        assert result["barn_score"] == row.barn_score
        assert result["reference_length"] == row.reference_length


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["barn:7", "--barn-dir", str(BARN)], f"barn:7 is not in {BARN}: BARN's worlds are"),
        (["post", "--sensor", "paper_ir"], "--sensor applies to Gazebo worlds"),
        (["post", "--start", "0,0,0"], "--start applies to Gazebo worlds"),
        ([str(BARN / "world_1.world"), "--barn-dir", str(BARN)], "--barn-dir applies to barn:N"),
        (["missing.world"], "missing.world: no such Gazebo world file"),
    ],
)
def test_simulate_refuses_what_a_barn_world_cannot_take(args: list[str], message: str) -> None:
    done = run_cli("simulate", *args, "--planner", "straight")
    assert done.returncode == 2 and done.stdout == ""
    assert len(done.stderr.splitlines()) == 1 and message in done.stderr, done.stderr


#: What ``simulate barn:N`` says of any N that is not bundled, in or out of BARN's range.
NOT_BUNDLED = (
    "ifgm-ref: error: {} is not in the bundled set: BARN's worlds are barn:N for N = 0-299, of "
    "which ifgm-ref bundles the 200 with N % 3 != 0; for the others give a folder of all 300 "
    "(a clone of BARN's repository) with --barn-dir DIR\n"
)


@pytest.mark.parametrize("spec", ["barn:3", "barn:300", "barn:9998", "barn:9999", "barn:-1",
                                  "barn:x"])  # fmt: skip
def test_a_barn_world_not_there_is_one_message_with_the_range(spec: str) -> None:
    """Issue 45: whether N is out of 0-299, a multiple of 3 or no number, one message states
    BARN's range, what is bundled and how to get the rest (no cache path)."""
    done = run_cli("simulate", spec, "--planner", "straight")
    assert (done.returncode, done.stdout, done.stderr) == (2, "", NOT_BUNDLED.format(spec))


def test_worlds_lists_the_bundled_barn_worlds_in_one_line() -> None:
    """``ifgm-ref worlds`` ends with the bundled BARN worlds, in one line, and each world that
    line promises loads (a sample of them: the first, the last, one in between)."""
    done = run_cli("worlds")
    assert done.returncode == 0
    last = done.stdout.splitlines()[-1]
    assert last.split(maxsplit=1) == [
        "barn:N",
        "BARN's world N, for N in 0-299 with N % 3 != 0 (200 worlds, metres); the others need "
        "--barn-dir DIR",
    ]
    assert len(BUNDLED_INDICES) == 200
    for index in (min(BUNDLED_INDICES), 100, max(BUNDLED_INDICES)):
        task = barn.gazebo_task(f"barn:{index}")
        assert task is not None and task.world.name == f"barn-{index:03d}"


def test_a_gazebo_world_takes_its_start_and_goal_from_options() -> None:
    result = _simulate_json(
        str(BARN / "world_1.world"), "--planner", "ifgm", "--start=-2,3,1.5708",
        "--goal=-2,11",
    )  # fmt: skip
    assert result["reached"] is True
    assert "barn_score" in result  # still BARN's world 1, with its path
