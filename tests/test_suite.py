"""The frozen conformance suite (ifgm_ref/oracle/suite): its files, its runs, its tiers.

The suite's shipped version must pass for the reference, in both tiers' quick cases here (the
full tier under ``-m slow``); every known-broken implementation must fail the quick tier, as
the kill matrix it was chosen from says; a case file says what it holds and nothing is lost
between writing and reading; and a version is frozen: a changed tolerance, sentence or
protocol is caught here and needs a new version (docs/oracle.md, "The conformance suite").
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import pytest

from ifgm_ref.apps.cli import main
from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.io.transport.wire import PROTOCOL_VERSION
from ifgm_ref.io.worldfile import save_world
from ifgm_ref.oracle.agreement import HEADING_TOL, POINT_TIE, SPEED_TOL, TIE, reference_episode
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.suite.build import build_suite
from ifgm_ref.oracle.suite.cases import Case, decode_example, encode_example, read_cases
from ifgm_ref.oracle.suite.recorded import rebuilt
from ifgm_ref.oracle.suite.run import reference_of, run_case, run_cases
from ifgm_ref.oracle.suite.tiers import broken_implementations, kills_in_runs, quick_cover
from ifgm_ref.oracle.suite.versions import load_suite, versions
from ifgm_ref.planners import make_planner

V1 = load_suite("v1")


def test_v1_is_frozen_against_what_decides_its_verdicts() -> None:
    """A changed tolerance, property sentence or protocol changes what "passes v1" means:
    it must come with a new version, never an edited one."""
    manifest = V1.manifest
    assert manifest["protocol"] == PROTOCOL_VERSION
    tolerances = {"heading": HEADING_TOL, "speed": SPEED_TOL, "tie": TIE, "point_tie": POINT_TIE}
    assert manifest["tolerances"] == tolerances
    assert manifest["properties"] == {n: CHECKS[n].sentence for n in manifest["properties"]}
    assert "v1" in versions()


def test_case_ids_are_unique_and_every_property_has_a_quick_case() -> None:
    ids = [case.id for case in V1.cases]
    assert len(ids) == len(set(ids))
    quick = {case.check for case in V1.tier("quick")}
    assert quick == set(V1.manifest["properties"])
    assert len(V1.tier("quick")) < len(V1.tier("full")) == len(V1.cases)


@pytest.mark.slow
def test_the_reference_passes_the_full_tier() -> None:
    for name in ("ifgm", "iba"):
        impl = Implementation.from_spec(name)
        failed = [r for r in run_cases(V1.cases, impl) if r.verdict in ("fail", "error")]
        assert not failed, [(r.case.id, r.reason) for r in failed]


@pytest.mark.parametrize("name", sorted(broken_implementations()))
def test_every_broken_implementation_fails_the_quick_tier(name: str) -> None:
    """The kill matrix's promise, checked on today's code: what the full tier killed when v1
    was built, its quick tier kills now."""
    matrix = json.loads((V1.folder / "kill-matrix.json").read_text())
    if not matrix["killed"][name]:
        pytest.skip(f"{name} was not killed by the full tier either")
    impl = broken_implementations()[name]
    quick = [case for case in V1.tier("quick") if case.id in matrix["killed"][name]]
    assert quick, f"{name}: no quick case in the kill matrix"
    verdicts = [run_case(case, impl).verdict for case in quick[:1]]
    assert verdicts == ["fail"] or verdicts == ["error"], (name, quick[0].id)


def test_a_recorded_episode_is_rebuilt_as_the_reference_ran_it() -> None:
    """The reference level's cases need no reference planner: the recorded commands drive the
    simulator to the same observations, and the margins kept are the reference's."""
    case = next(c for c in V1.cases if c.check == "agrees_with_reference")
    assert case.recorded is not None
    world = case.example
    from ifgm_ref.oracle.check_types import Recorder

    sim = Recorder(sim=case.sim).sim_for(world)
    live, again = reference_episode(world, sim), rebuilt(world, sim, case.recorded)
    assert again.recording.steps == live.recording.steps
    for kept, found in zip(again.margins, live.margins, strict=True):
        assert all(found[name] == value for name, value in kept.items())


def test_a_replay_that_ends_otherwise_is_refused() -> None:
    case = next(c for c in V1.cases if c.recorded is not None)
    assert case.recorded is not None
    broken = {**case.recorded, "end": "collision"}
    with pytest.raises(ImplementationError, match="but was recorded as"):
        rebuilt(case.example, case.sim, broken)


def test_a_rebuilt_episode_is_kept_for_the_same_case_loaded_again() -> None:
    """:func:`reference_of` rebuilds a case's episode once per process: the same case read
    again from its file finds it; a case that differs in anything its line holds does not;
    a case of the paper level has none."""
    case = next(c for c in V1.cases if c.recorded is not None)
    again = next(c for c in load_suite("v1").cases if c.id == case.id)
    assert again is not case and reference_of(again) is reference_of(case)
    renamed = replace(case, id=f"{case.id}-again")
    assert reference_of(renamed) is not reference_of(case)
    paper = next(c for c in V1.cases if c.recorded is None)
    with pytest.raises(ValueError, match="not a reference-level case"):
        reference_of(paper)


def test_examples_survive_the_file() -> None:
    world = resolve_world("u_trap")
    examples = [world, (world, (0.5, (1.0, -2.0))), (world, 2.0), (world, 0.1, 3.0, 1.5)]
    for example in examples:
        assert decode_example(json.loads(json.dumps(encode_example(example)))) == example
    with pytest.raises(ImplementationError, match="cannot hold"):
        encode_example(object())


def test_every_case_file_reads_back_with_its_header() -> None:
    for name in V1.manifest["properties"]:
        header, cases = read_cases(V1.folder / f"{name}.jsonl")
        assert header == {"suite": "v1", "protocol": PROTOCOL_VERSION, "property": name}
        assert cases and all(case.check == name for case in cases)


def test_a_damaged_case_file_names_its_line(tmp_path: Path) -> None:
    path = tmp_path / "x.jsonl"
    path.write_text('{"suite": "v1", "protocol": 1, "property": "x"}\n{"id": 3}\n')
    with pytest.raises(ImplementationError, match=r"x.jsonl:2: not a suite case"):
        read_cases(path)


def test_a_version_is_never_rebuilt_in_place(tmp_path: Path) -> None:
    (tmp_path / "v9").mkdir()
    (tmp_path / "v9" / "manifest.json").write_text("{}")
    with pytest.raises(ImplementationError, match="versions are frozen"):
        build_suite("v9", root=tmp_path)


def test_the_quick_tier_kills_each_known_implementation_as_often_as_held_out_kills_ask() -> None:
    """v1's quick tier: every implementation its kill matrix holds is killed by the quick
    cases ``times`` times (or by all that kill it), and leaving each out of the choice in
    turn, the tier still kills the share the issue asks of unseen ones; every case of the
    reference level is quick (tiers.quick_cover says why)."""
    matrix = json.loads((V1.folder / "kill-matrix.json").read_text())
    quick = {case.id for case in V1.tier("quick")}
    assert quick == set(matrix["quick"])
    assert {c.id for c in V1.cases if c.check == "agrees_with_reference"} <= quick
    for name, killed in matrix["killed"].items():
        assert len(set(killed) & quick) >= min(matrix["times"], len(killed)), name
    caught, killed = matrix["held_out"]
    assert caught >= 0.95 * killed


def test_the_greedy_cover_keeps_every_kill_with_fewer_cases() -> None:
    cases = [Case(f"p/{k}", "p", None) for k in range(4)]
    matrix = {"a": ["p/1", "p/3"], "b": ["p/3"], "c": ["p/2"], "d": []}
    seconds = {c.id: 1.0 for c in cases}
    chosen = quick_cover(cases, matrix, seconds)
    assert chosen == ["p/0", "p/3", "p/2"]
    assert all(set(killed) & set(chosen) for killed in matrix.values() if killed)


def test_the_cli_writes_a_line_per_case_and_a_summary(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "run.jsonl"
    args = ["oracle", "--suite", "v1", "--tier", "quick", "--planner", "straight"]
    args += ["--promises", "ifgm"]
    artifacts = tmp_path / "failures"
    status = main(
        [*args, "--check", "converges_u", "--results", str(out), "--artifacts", str(artifacts)]
    )
    lines = [json.loads(line) for line in out.read_text().splitlines()]
    assert status == 1
    assert [line["type"] for line in lines] == ["case"] * (len(lines) - 1) + ["summary"]
    assert lines[0]["verdict"] == "fail" and lines[0]["id"].startswith("converges_u/")
    assert (tmp_path / lines[0]["counterexample"] / "report.md").is_file()  # relative to the file
    assert lines[-1]["ok"] is False and lines[-1]["fail"] >= 1
    assert "straight" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--suite", "v1", "--profile", "brief"], "--profile does not apply with --suite"),
        (["--suite", "v1", "--noise", "range=0.02"], "--noise does not apply with --suite"),
        (["--tier", "quick"], "--tier and --results apply only with --suite"),
        (["--suite", "v7"], "no suite 'v7'; versions: v1"),
        (["--suite", "v1", "--check", "nonsense"], "suite v1 has no such check"),
    ],
)
def test_bad_suite_options_are_one_line(
    extra: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["oracle", "--planner", "ifgm", *extra]) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1


def test_a_counterexample_is_promoted_into_the_next_version(tmp_path: Path) -> None:
    """A drawn profile's failure folder becomes a full-tier case of a new version, judged by
    the reference; the version it started from is left as it was."""
    import shutil

    shutil.copytree(V1.folder, tmp_path / "v1")
    found = tmp_path / "found"
    found.mkdir()
    save_world(resolve_world("u_trap"), found / "world.json")
    (found / "report.md").write_text("# converges_u: failed\n")
    assert main(["suite", "promote", str(found), "--to", "v2", "--root", str(tmp_path)]) == 0
    v2 = load_suite("v2", root=tmp_path)
    assert len(v2.cases) == len(V1.cases) + 1
    added = [c for c in v2.cases if c.id not in {old.id for old in V1.cases}]
    assert [(c.check, c.tier, c.example) for c in added] == [
        ("converges_u", "full", resolve_world("u_trap"))
    ]
    assert len(load_suite("v1", root=tmp_path).cases) == len(V1.cases)
    assert "converges_u/" in (tmp_path / "v2" / "CHANGELOG.md").read_text()


def test_v1s_vectors_still_hold_for_the_reference() -> None:
    """Each version ships the equation vectors and traces it was built with, in the file
    ``ifgm-ref vectors`` writes: the reference still meets them all."""
    import ifgm_ref.paper.equations
    from ifgm_ref.oracle.vectors import check_vectors, replay_traces

    vectors = json.loads((V1.folder / "vectors.json").read_text())
    assert vectors["traces"] and check_vectors(vectors, ifgm_ref.paper.equations) == []
    for planner in ("ifgm", "iba"):
        assert replay_traces(vectors, lambda p=planner: make_planner(p), planner=planner) == []


def test_the_quick_tier_is_chosen_again_with_the_kills_of_runs_made_elsewhere(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A mutant that only a full-tier case kills (a run file, as bench_mutation.py's
    suite_cases level writes it) gets that case into the quick tier; the run of one nothing
    killed adds nothing; an unfinished run is refused."""
    import shutil

    shutil.copytree(V1.folder, tmp_path / "v1")
    full_only = next(c for c in V1.cases if c.tier == "full")
    lines = [{"type": "case", "id": full_only.id, "verdict": "fail"}, {"type": "summary"}]
    (tmp_path / "7.jsonl").write_text("".join(json.dumps(line) + "\n" for line in lines))
    (tmp_path / "8.jsonl").write_text(json.dumps({"type": "summary"}) + "\n")
    runs = [str(tmp_path / "7.jsonl"), str(tmp_path / "8.jsonl")]
    status = main(["suite", "tiers", "--version", "v1", "--root", str(tmp_path), "--runs", *runs])
    again = load_suite("v1", root=tmp_path)
    assert status == 0
    assert full_only.id in {c.id for c in again.tier("quick")}
    matrix = json.loads((tmp_path / "v1" / "kill-matrix.json").read_text())
    assert matrix["killed"]["run:7"] == [full_only.id] and matrix["killed"]["run:8"] == []
    assert "1 of them killed by the full tier" in capsys.readouterr().out
    changes = (tmp_path / "v1" / "CHANGELOG.md").read_text().splitlines()
    assert changes[-1].startswith(f"- quick tier chosen again: {len(matrix['quick'])} cases")
    (tmp_path / "9.jsonl").write_text(json.dumps(lines[0]) + "\n")
    with pytest.raises(ImplementationError, match="not a finished suite run"):
        kills_in_runs([tmp_path / "9.jsonl"])
