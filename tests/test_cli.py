"""The command line end to end, in a subprocess: world file in, JSON out, clean errors."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from ifgm_ref.scenarios import BUILTIN_WORLDS
from ifgm_ref.simulator import Result
from ifgm_ref.worldfile import load_world, loads_world

README = Path(__file__).resolve().parent.parent / "README.md"
WORLD = {
    "name": "one box",
    "start": [0.0, 0.0, 0.0],
    "goal": [12.0, 0.0],
    "obstacles": [{"polygon": [[5.0, 3.0], [7.0, 3.0], [7.0, 5.0], [5.0, 5.0]]}],
}


def run_cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
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
    done = run_cli(
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
    assert names == list(BUILTIN_WORLDS)
    exported = run_cli("worlds", "--export", str(tmp_path / "out"))
    assert exported.returncode == 0, exported.stderr
    for name, entry in BUILTIN_WORLDS.items():
        assert load_world(tmp_path / "out" / f"{name}.json") == entry.build()


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
