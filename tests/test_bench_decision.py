"""``benchmarks/bench_decision.py``: the cost of one planner decision.

The benchmark is a script (``benchmarks/`` is not a package), loaded here from its path. It
records episodes, replays them through :func:`ifgm_ref.core.recording.replay` asserting
that every replayed command is the recorded one, and counts what each decision executes. The
tests check what could silently go wrong: a planner missing from the report, a replay that
would time other decisions than the recorded ones, counts that change from run to run, and
an element count that is off.
"""

from __future__ import annotations

import importlib.util
import re
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from ifgm_ref.core.protocol import Command, Observation
from ifgm_ref.planners import IBAPlanner

SCRIPT = Path(__file__).resolve().parent.parent / "benchmarks" / "bench_decision.py"


@pytest.fixture(scope="module")
def bench() -> ModuleType:
    """The benchmark script as a module."""
    spec = importlib.util.spec_from_file_location("bench_decision", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def test_a_tiny_run_reports_every_planner(
    bench: ModuleType, capsys: pytest.CaptureFixture[str]
) -> None:
    assert bench.main(["--max-time", "0.5", "--repeats", "1", "--count-every", "1"]) == 0
    out = capsys.readouterr().out
    table = out.split("wall-clock per decision, us\n", 1)[1].split("\n\n", 1)[0]
    rows = {}
    for line in table.splitlines()[1:]:
        match = re.match(r"(\w+) +(\d+) +(\d+) \( *(\d+)\) +(\d+) \( *(\d+)\)$", line)
        if match:
            rows[match[1]] = (int(match[2]), int(match[3]))
    assert set(rows) == set(bench.PLANNERS), table
    for name, (decisions, median_us) in rows.items():
        assert decisions == 2 * 5, f"{name}: {decisions} decisions, but should be 10 (2 x 0.5 s)"
        assert median_us > 0, f"{name}: median {median_us} us, but should be positive"
    for name in bench.PLANNERS:
        assert re.search(rf"^{name} +median +\S+", out, re.MULTILINE), name


def test_timings_are_positive_for_every_branch(bench: ModuleType) -> None:
    episodes = {"iba": [bench.record("iba", "scenario1", 0.5)]}
    timing = bench.time_decisions(["iba"], episodes, repeats=2)["iba"]
    assert timing.median > 0 and timing.p90 >= timing.median_best > 0
    assert sum(n for _, n in timing.branches.values()) == len(episodes["iba"][0].steps)


class Drifting(IBAPlanner):
    """IBA that answers a hair (1e-12 rad) off on every step: not what was recorded."""

    def step(self, observation: Observation) -> Command:
        command = super().step(observation)
        return Command(command.heading + 1e-12, command.speed, branch=command.branch)


def test_the_replay_catches_a_planner_that_answers_differently(
    bench: ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    episode = bench.record("iba", "scenario1", 0.5)
    bench.replay("iba", [episode], lambda planner, obs: planner.step(obs))  # the same: passes
    monkeypatch.setattr(bench, "make_planner", lambda name: Drifting())
    with pytest.raises(AssertionError, match=r"iba in scenario1, step 0: command=.*recorded"):
        bench.replay("iba", [episode], lambda planner, obs: planner.step(obs))


@pytest.mark.parametrize("planner", ["ifgm", "fgm"])
def test_operation_counts_are_deterministic(bench: ModuleType, planner: str) -> None:
    episodes = [bench.record(planner, "u_trap", 0.5)]
    first = bench.count_operations(planner, episodes, 1)
    second = bench.count_operations(planner, episodes, 1)
    assert first == second
    assert len(first) == len(episodes[0].steps)
    assert all(c.own_bytecodes > 0 and c.elements > 0 and c.array_ops > 0 for c in first)


def test_counted_array_counts_the_elements_of_known_operations(bench: ModuleType) -> None:
    counted = bench.CountedArray
    a = np.arange(10.0).view(counted)
    counted.clear()
    b = a + 1.0  # a ufunc: 10 elements
    assert (counted.ops, counted.elements, counted.transcendental) == (1, 10, 0)
    assert isinstance(b, counted)
    np.cos(b)  # a transcendental ufunc on a derived array: counted again
    assert (counted.ops, counted.elements, counted.transcendental) == (2, 20, 10)
    counted.clear()
    np.where(a > 3.0, a, 0.0)  # a comparison (10) and a numpy function (10)
    assert (counted.ops, counted.elements) == (2, 20)
    counted.clear()
    a.sum()  # a reduction: a pass over 10 elements
    assert (counted.ops, counted.elements) == (1, 10)
    counted.clear()
    picked = a[np.array([1, 2, 7])]  # fancy indexing: a pass over the 3 indices
    assert (counted.ops, counted.elements) == (1, 3)
    assert picked.tolist() == [1.0, 2.0, 7.0]
    counted.clear()
    a[2:5]  # a basic slice is a view: nothing
    assert (counted.ops, counted.elements) == (0, 0)


def test_counting_scans_hold_the_same_values(bench: ModuleType) -> None:
    episode = bench.record("fgm", "scenario1", 0.2)
    observation = episode.steps[0][0]
    counting = bench.counting_observation(observation)
    assert isinstance(counting.scan.ranges, bench.CountedArray)
    assert isinstance(counting.scan.angles, bench.CountedArray)
    plain = counting.scan.ranges.view(np.ndarray)
    np.testing.assert_array_equal(plain, observation.scan.ranges)


def test_the_microcontroller_model_adds_up(bench: ModuleType) -> None:
    ops = bench.OpCount(
        own_bytecodes=100,
        other_bytecodes=999,  # the interpreter's own work: not ported
        math_calls=5,
        math_transcendental=2,
        array_ops=3,
        elements=50,
        transcendental_elements=10,
        returns=0,
        remembered=0,
    )
    mcu = bench.McuModel()
    # 100 bytecodes, 40 plain elements, 12 transcendental calls, at 2/2/30 and 8/6/150.
    assert mcu.cycles(ops) == (100 * 2 + 40 * 2 + 12 * 30, 100 * 8 + 40 * 6 + 12 * 150)
    low, high = mcu.microseconds(ops)
    assert low == pytest.approx(640 / 200) and high == pytest.approx(2840 / 100)


def test_the_element_count_covers_the_remembered_points(bench: ModuleType) -> None:
    """Every decision of IFGM and DistBug tests the corridor towards the goal against every
    remembered point, so its element count is at least the number of remembered points: the
    counting arrays must survive from the scan into the memory (a percept built with a plain
    ``np.empty`` lost them, and the counts fell by a factor of 30 unnoticed)."""
    for name in ("ifgm", "distbug"):
        episodes = [bench.record(name, "u_trap", 20.0)]
        counts = bench.count_operations(name, episodes, every=1)
        short = [c for c in counts if c.elements < c.remembered]
        assert not short, (
            f"{name}: {len(short)} decisions counted fewer elements than remembered points, "
            f"e.g. {short[0]}"
        )
        assert max(c.remembered for c in counts) > 0
