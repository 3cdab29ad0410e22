"""The benchmark under noise: ``--noise`` and ``--noise-sweep``, the noise columns, the seeds,
the sweep's summary and plots, and the Wilson interval (``ifgm_ref/apps/bench/noise_sweep.py``,
``ifgm_ref/core/stats.py``)."""

from __future__ import annotations

import csv
import dataclasses
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.apps.bench.noise_sweep import (
    AXIS_LABELS,
    DEFAULT_SWEEP,
    parse_sweep,
    plot_sweep,
    summarize_sweep,
    sweep_conditions,
    write_sweep_report,
)
from ifgm_ref.apps.bench.report import read_rows
from ifgm_ref.apps.bench.runner import run_bench
from ifgm_ref.apps.bench.tasks import (
    Condition,
    Row,
    WorldSpec,
    generated_specs,
    noise_seed,
    run_world,
)
from ifgm_ref.apps.cli import main
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.stats import wilson_interval
from ifgm_ref.io.transport.loading import load_factory
from ifgm_ref.sim.noise import KINDS, NoiseLevels
from ifgm_ref.sim.simulator import simulate

#: The tiny sweep: 2 planners x 2 worlds x (the baseline and 2 levels of range noise).
SPECS = generated_specs(["open", "u"], 1, seed=0)
PLANNERS = ("ifgm", "bug2")
GRID = {"range": (0.05, 0.1)}


def _stable(rows: list[Row]) -> list[Row]:
    """Rows without the CPU-timing column, the only one that varies between runs."""
    return [dataclasses.replace(r, decisions_per_cpu_s=None) for r in rows]


@pytest.fixture(scope="module")
def sweep_rows() -> list[Row]:
    return run_bench(SPECS, PLANNERS, conditions=sweep_conditions(GRID), noise_seed=3)


# The Wilson interval.


@pytest.mark.parametrize(
    ("successes", "trials", "low", "high"),
    [(81, 263, 0.2553, 0.3662), (15, 148, 0.0624, 0.1605), (0, 20, 0.0, 0.1611),
     (1, 29, 0.0061, 0.1718)],
)  # fmt: skip
def test_wilson_interval_matches_newcombes_table(
    successes: int, trials: int, low: float, high: float
) -> None:
    """The score intervals of Newcombe, "Two-sided confidence intervals for the single
    proportion: comparison of seven methods", Statistics in Medicine 17:857-872 (1998),
    Table II (method 3), to the 4 decimals printed there."""
    interval = wilson_interval(successes, trials)
    assert (round(interval.low, 4), round(interval.high, 4)) == (low, high)


@given(st.integers(1, 500).flatmap(lambda n: st.tuples(st.integers(0, n), st.just(n))))
def test_wilson_interval_contains_the_rate_and_mirrors(case: tuple[int, int]) -> None:
    """The interval lies in [0, 1], contains the observed rate, is exactly 0 (1) at its end
    for no (all) successes, and swapping successes and failures mirrors it."""
    k, n = case
    low, high = wilson_interval(k, n)
    assert 0.0 <= low <= k / n <= high <= 1.0
    assert (low == 0.0) == (k == 0) and (high == 1.0) == (k == n)
    mirror = wilson_interval(n - k, n)
    assert (mirror.low, mirror.high) == pytest.approx((1 - high, 1 - low), abs=1e-12)


@given(st.integers(1, 300).flatmap(lambda n: st.tuples(st.integers(0, n), st.just(n))))
def test_wilson_interval_matches_scipy(case: tuple[int, int]) -> None:
    """SciPy's ``binomtest(...).proportion_ci(method="wilson")`` agrees (where SciPy is)."""
    stats = pytest.importorskip("scipy.stats")
    k, n = case
    theirs = stats.binomtest(k, n).proportion_ci(0.95, method="wilson")
    assert tuple(wilson_interval(k, n)) == pytest.approx((theirs.low, theirs.high), abs=1e-9)


@pytest.mark.parametrize(
    ("args", "message"),
    [((1, 0), "`trials` must be an integer >= 1"), ((-1, 5), "`successes` must be in"),
     ((1.0, 5), "`successes` must be an integer"), ((1, 5, 1.0), "`confidence` must be in")],
)  # fmt: skip
def test_wilson_interval_refuses_bad_counts(args: tuple[float, ...], message: str) -> None:
    with pytest.raises(ParameterError, match=message):
        wilson_interval(*args)  # type: ignore[arg-type]


# The grid and the conditions.


def test_default_sweep_is_three_kinds_of_four_levels_with_the_targets() -> None:
    """The issue's sweep: range, dropout and odometry noise at four levels each, among them
    the target levels (2 %, 5 %, 1 %); the baseline once: 13 points."""
    assert parse_sweep("") == DEFAULT_SWEEP
    assert {kind: len(levels) for kind, levels in DEFAULT_SWEEP.items()} == {
        "range": 4, "dropout": 4, "odometry": 4,
    }  # fmt: skip
    assert 0.02 in DEFAULT_SWEEP["range"] and 0.05 in DEFAULT_SWEEP["dropout"]
    assert 0.01 in DEFAULT_SWEEP["odometry"]
    points = sweep_conditions(DEFAULT_SWEEP)
    assert len(points) == 13 and [p.kind for p in points].count("none") == 1


def test_sweep_points_lie_over_the_background() -> None:
    """With ``--noise`` the baseline is that noise alone and every point adds its level; a
    latency level stays a whole number of steps."""
    background = NoiseLevels(odometry=0.01)
    points = sweep_conditions(parse_sweep("range=0.02,latency=2:1"), background)
    assert [(p.kind, p.level, p.levels.tags()) for p in points] == [
        ("none", 0.0, "odometry=0.01"),
        ("range", 0.02, "range=0.02,odometry=0.01"),
        ("latency", 1, "odometry=0.01,latency=1"),
        ("latency", 2, "odometry=0.01,latency=2"),
    ]
    assert isinstance(points[-1].levels.latency, int)


def test_every_kind_has_an_axis_label() -> None:
    assert set(AXIS_LABELS) == set(KINDS)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--noise", "range=x"], "--noise range=x: the level must be a number"),
        (["--noise", "sonar=0.1"], "--noise sonar=0.1: expected KIND=LEVEL with KIND one of"),
        (["--noise", "dropout=1.5"], "--noise dropout=1.5: the level must be a probability in"),
        (["--noise", "range=-0.1"], "--noise range=-0.1: the level must be a finite number >= 0"),
        (["--noise", "range_const=-1"], "--noise range_const=-1: the level must be a finite"),
        (["--noise", "latency=0.5"], "--noise latency=0.5: the level must be an integer >= 0"),
        (["--noise-sweep", "range"], "--noise-sweep 'range': expected KIND=LEVEL:LEVEL:..."),
        (["--noise-sweep", "range=0:0.1"], "the levels must be distinct and > 0"),
        (["--noise-sweep", "range=0.1:0.1"], "the levels must be distinct and > 0"),
        (["--noise-sweep", "dropout=0.1:2"], "dropout=2: the level must be a probability in"),
        (["--noise-sweep", "range=0.1:-1"], "range=-1: the level must be a finite number >= 0"),
        (["--noise-sweep", "range=0.1,range=0.2"], "range is given twice"),
        (["--noise-sweep", "range=0.1", "--noise", "range=0.02"], "--noise sets it already"),
        (["--noise-seed", "-1"], "must be an integer >= 0, got '-1'"),
    ],
)
def test_bad_noise_is_one_error_before_anything_runs(
    args: list[str], message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Each mistake is one line on stderr and exit status 2, and nothing is written."""
    try:
        status = main(["bench", *args, "--out", str(tmp_path / "out")])
    except SystemExit as done:  # argparse's own checks (the seed's type)
        status = int(str(done.code))
    err = capsys.readouterr().err
    assert status == 2
    assert message in err and err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / "out").exists()


# The noise columns and the seeds.


def test_noise_seed_is_the_worlds_not_the_runs() -> None:
    """A world's noise seed depends on the run's seed and the world's name only: world
    u-0007 meets the same noise however many worlds run, and other worlds other noise."""
    assert noise_seed(0, "u-0007") == noise_seed(0, "u-0007")
    seeds = {noise_seed(s, f"{c}-{i:04d}") for s in (0, 1) for c in "uh" for i in range(50)}
    assert len(seeds) == 200 and all(0 <= s < 2**32 for s in seeds)


def test_a_noisy_row_replays_with_its_noise_and_seed() -> None:
    """``--noise`` mode: every row carries the levels and the world's seed, no sweep point;
    the episode is the one ``simulate`` runs with the row's ``noise`` and ``noise_seed``
    (``ifgm-ref simulate WORLD --noise NOISE --noise-seed NOISE_SEED``)."""
    spec = SPECS[1]
    levels = NoiseLevels.parse("range=0.02,dropout=0.05,odometry=0.01")
    (row,) = run_world(spec, ("ifgm",), None, (Condition(levels),), seed=5)
    assert (row.noise, row.noise_kind, row.noise_level) == (levels.tags(), None, None)
    assert row.noise_seed == noise_seed(5, spec.name)
    world = NoiseLevels.parse(row.noise).apply(spec.build(), row.noise_seed)
    (quiet,) = run_world(spec, ("ifgm",))
    replay = simulate(world, load_factory("ifgm")(), SimParams(max_time=quiet.time_s * 10))
    assert (replay.result.stop_reason, replay.result.path_length) == (
        row.stop_reason,
        row.path_length,
    )
    assert (quiet.noise, quiet.noise_seed) == ("none", None)
    assert quiet.path_length != row.path_length


def test_sweep_rows_world_then_point_then_planner(sweep_rows: list[Row]) -> None:
    """One row per (world, point, planner) in that order; the baseline first, noise-free
    and equal to a run without noise; every noisy row of a world has the world's seed."""
    points = [("none", 0.0), ("range", 0.05), ("range", 0.1)]
    assert [(r.world, (r.noise_kind, r.noise_level), r.planner) for r in sweep_rows] == [
        (s.name, p, planner) for s in SPECS for p in points for planner in PLANNERS
    ]
    baseline = [r for r in sweep_rows if r.noise_kind == "none"]
    assert all(r.noise == "none" and r.noise_seed is None for r in baseline)
    plain = run_bench(SPECS, PLANNERS)
    assert _stable(
        [dataclasses.replace(r, noise_kind=None, noise_level=None) for r in baseline]
    ) == _stable(plain)
    for row in sweep_rows:
        if row.noise_kind == "range":
            assert row.noise == f"range={row.noise_level}"
            assert row.noise_seed == noise_seed(3, row.world)


def test_the_same_seed_gives_the_same_rows_anywhere(sweep_rows: list[Row]) -> None:
    """The sweep's rows are a function of the seeds: again inline, on a 2-process pool, the
    same rows (but the CPU timing); another noise seed changes the noisy ones."""
    conditions = sweep_conditions(GRID)
    pool = run_bench(SPECS, PLANNERS, jobs=2, conditions=conditions, noise_seed=3)
    assert _stable(pool) == _stable(sweep_rows)
    other = run_bench(SPECS[:1], PLANNERS, conditions=conditions, noise_seed=4)
    noisy = [r for r in sweep_rows[: len(other)] if r.noise_kind == "range"]
    assert [r.path_length for r in other if r.noise_kind == "range"] != [
        r.path_length for r in noisy
    ]


# The summary and the report.


def _row(planner: str, kind: str | None, level: float | None, **kw: object) -> Row:
    base = dict(
        planner=planner, world="w", world_class="u", reached=True, collided=False,
        stop_reason="goal_reached", time_s=10.0, path_length=12.0, optimal_length=10.0,
        path_ratio=1.2, min_clearance=0.5, heading_change=1.0, steps=100,
        decisions_per_cpu_s=1000.0, noise_kind=kind, noise_level=level,
    )  # fmt: skip
    return Row(**{**base, **kw})  # type: ignore[arg-type]


def test_sweep_summary_shares_the_baseline_and_counts_with_wilson() -> None:
    """The baseline is level 0 of every kind; each point counts its episodes, its success
    and collision rates with Wilson intervals, time-outs and stalls; the path ratio's
    quartiles and the median turning are over the episodes that reached the goal; rows
    outside a sweep are left out."""
    rows = [_row("p", "none", 0.0, path_ratio=1.0 + k / 10) for k in range(5)]
    rows += [_row("p", "range", 0.1, path_ratio=1.5), _row("p", "range", 0.1, path_ratio=2.5)]
    rows += [_row("p", "range", 0.1, reached=False, collided=True, stop_reason="collision",
                  path_ratio=None)]  # fmt: skip
    rows += [_row("p", "range", 0.1, reached=False, stop_reason="stalled", path_ratio=None)]
    rows += [_row("p", "odometry", 0.05, reached=False, stop_reason="time_limit",
                  path_ratio=None)]  # fmt: skip
    rows += [_row("p", None, None)]
    points = summarize_sweep(rows)
    assert [(p.kind, p.level, p.episodes) for p in points] == [
        ("range", 0.0, 5), ("range", 0.1, 4), ("odometry", 0.0, 5), ("odometry", 0.05, 1),
    ]  # fmt: skip
    base, noisy, _, drift = points
    assert base.path_ratio_median == pytest.approx(1.2)
    assert (base.path_ratio_q1, base.path_ratio_q3) == pytest.approx((1.1, 1.3))
    assert (noisy.success_rate, noisy.collision_rate, noisy.stall_rate) == (0.5, 0.25, 0.25)
    assert (noisy.success_low, noisy.success_high) == wilson_interval(2, 4)
    assert (noisy.collision_low, noisy.collision_high) == wilson_interval(1, 4)
    assert noisy.path_ratio_median == 2.0 and noisy.heading_change_median == 1.0
    assert drift.timeout_rate == 1.0 and drift.path_ratio_median is None
    assert drift.heading_change_median is None


def test_sweep_plot_leaves_gaps_where_there_is_nothing_to_draw(tmp_path: Path) -> None:
    """A planner that never reached the goal has no path ratio, and one missing at a level
    has no point there: the plot leaves those out rather than failing."""
    rows = [_row("p", "none", 0.0), _row("p", "dropout", 0.5)]
    rows += [_row("q", "none", 0.0, reached=False, stop_reason="stalled", path_ratio=None)]
    points = summarize_sweep(rows)
    assert [(p.planner, p.level, p.path_ratio_median) for p in points] == [
        ("p", 0.0, 1.2), ("p", 0.5, 1.2), ("q", 0.0, None),
    ]  # fmt: skip
    plot_sweep(points, "dropout", tmp_path / "sweep.png")
    assert (tmp_path / "sweep.png").stat().st_size > 10_000


def test_sweep_report_files(tmp_path: Path, sweep_rows: list[Row]) -> None:
    """results.csv reads back as the rows; sweep.csv has a line per (kind, planner, level);
    sweep.md a table per kind under the header; a plot per kind."""
    written = write_sweep_report(sweep_rows, SPECS, tmp_path, "# header")
    names = {p.name for p in written}
    assert {"results.csv", "sweep.csv", "sweep.md", "sweep_range.png"} <= names
    assert read_rows(tmp_path / "results.csv") == sweep_rows
    with (tmp_path / "sweep.csv").open() as f:
        lines = list(csv.DictReader(f))
    assert [(r["kind"], r["planner"], float(r["level"]), int(r["episodes"])) for r in lines] == [
        ("range", p, level, 2) for p in PLANNERS for level in (0.0, 0.05, 0.1)
    ]
    text = (tmp_path / "sweep.md").read_text()
    assert text.startswith("# header") and "## range:" in text
    assert "| planner | 0% | 5% | 10% |" in text
    assert (tmp_path / "sweep_range.png").stat().st_size > 10_000


def test_sweep_command_end_to_end(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``ifgm-ref bench --noise-sweep KIND=...`` over a background ``--noise``: the header
    says the sweep, the background and the seed; the rows are those of the runner."""
    out = tmp_path / "out"
    args = ["bench", "--planners", "ifgm", "--classes", "open", "--per-class", "1", "--jobs",
            "1", "--noise-sweep", "dropout=0.2", "--noise", "odometry=0.01", "--noise-seed",
            "9", "--out", str(out)]  # fmt: skip
    assert main(args) == 0
    assert "1 planner x 1 world x 2 noise levels" in capsys.readouterr().err
    text = (out / "sweep.md").read_text()
    assert "- noise sweep: dropout 20%; one kind at a time, from the noise-free baseline" in text
    assert "all over `--noise odometry=0.01`" in text and "- noise seed: 9" in text
    background = NoiseLevels(odometry=0.01)
    expected = run_bench(
        generated_specs(["open"], 1, 0),
        ("ifgm",),
        conditions=sweep_conditions({"dropout": (0.2,)}, background),
        noise_seed=9,
    )
    assert _stable(read_rows(out / "results.csv")) == _stable(expected)
    assert not (out / "summary.md").exists() and (out / "sweep_dropout.png").exists()


def test_noise_command_says_the_levels(tmp_path: Path) -> None:
    """``ifgm-ref bench --noise ...``: the usual report, whose header gives the levels and
    the seed, and whose rows carry them."""
    out = tmp_path / "out"
    args = ["bench", "--planners", "iba", "--classes", "open", "--per-class", "1", "--jobs",
            "1", "--noise", "range=0.02,dropout=0.05", "--out", str(out)]  # fmt: skip
    assert main(args) == 0
    text = (out / "summary.md").read_text()
    assert "- noise: range=0.02,dropout=0.05\n- noise seed: 0 (" in text
    (row,) = read_rows(out / "results.csv")
    assert (row.noise, row.noise_seed) == ("range=0.02,dropout=0.05", noise_seed(0, "open-0000"))


def test_noise_free_header_says_so(tmp_path: Path) -> None:
    out = tmp_path / "out"
    args = ["bench", "--planners", "iba", "--classes", "open", "--per-class", "1", "--jobs",
            "1", "--out", str(out)]  # fmt: skip
    assert main(args) == 0
    assert "- noise: none\n" in (out / "summary.md").read_text()


def test_a_condition_without_noise_leaves_the_world_as_it_is() -> None:
    """Level 0 everywhere runs the world itself, its own noise settings and seeds kept."""
    world = NoiseLevels(range=0.1).apply(WorldSpec.generated("open", 0, 0).build(), 42)
    assert Condition().apply(world, 7) is world
    assert Condition(NoiseLevels(dropout=0.1)).apply(world, 7).sensor.seed == 7
