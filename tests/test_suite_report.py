"""The page comparing runs of the conformance suite (``ifgm_ref.oracle.suite.report``) and
``ifgm-ref report``: small run files written here, the page read back."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest

from ifgm_ref.apps.cli import main
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.oracle.suite.report import (
    case_groups,
    render_html,
    render_markdown,
    write_report,
)
from ifgm_ref.oracle.suite.runfile import Verdict, read_runs


def case(
    case_id: str, verdict: str = "pass", *, tier: str = "quick", reason: str = "",
    counterexample: str | None = None, suite: str = "v1",
) -> dict[str, Any]:  # fmt: skip
    """A case line; its property is the id's part before the ``/``."""
    return {
        "type": "case",
        "suite": suite,
        "id": case_id,
        "property": case_id.split("/")[0],
        "level": "paper",
        "tier": tier,
        "verdict": verdict,
        "reason": reason,
        "counterexample": counterexample,
        "seconds": 0.25,
    }


def summary_of(cases: list[dict[str, Any]], implementation: str) -> dict[str, Any]:
    """The summary line that agrees with ``cases``."""
    counts = {v.value: sum(c["verdict"] == v.value for c in cases) for v in Verdict}
    return {
        "type": "summary",
        "suite": cases[0]["suite"] if cases else "v1",
        "implementation": implementation,
        "tier": "full",
        "cases": len(cases),
        **counts,
        "ok": counts["fail"] + counts["error"] == 0,
        "seconds": 1.5,
    }


def write_run(path: Path, implementation: str, cases: list[dict[str, Any]]) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    lines = [*cases, summary_of(cases, implementation)]
    path.write_text("".join(json.dumps(line) + "\n" for line in lines))
    return path


def test_cases_are_grouped_by_property_then_tier_quick_first(tmp_path: Path) -> None:
    run = write_run(
        tmp_path / "a.jsonl",
        "ifgm",
        [
            case("converges_u/0002", tier="full"),
            case("collision_free/0001"),
            case("converges_u/0001"),
            case("converges_u/0003", tier="nightly"),
        ],
    )
    groups = case_groups(read_runs([run]).runs)
    assert [(g.property, g.tier, g.case_ids) for g in groups] == [
        ("converges_u", "quick", ("converges_u/0001",)),
        ("converges_u", "full", ("converges_u/0002",)),
        ("converges_u", "nightly", ("converges_u/0003",)),
        ("collision_free", "quick", ("collision_free/0001",)),
    ]
    page = render_markdown(read_runs([run]), tmp_path)
    headings = re.findall(r"^### (.*)$", page, flags=re.MULTILINE)
    assert headings == ["The quick tier", "The full tier", "The nightly tier"]
    quick = page.split("### The quick tier")[1].split("###")[0]
    rows = [line.split(" | ")[:2] for line in quick.splitlines() if line.startswith("| ")]
    assert rows[1:] == [
        ["| converges\\_u", "converges\\_u/0001"],
        ["| collision\\_free", "collision\\_free/0001"],
    ]


def header_row(page: str, first: str) -> list[str]:
    """The cells of the first Markdown table row that starts with ``first``."""
    line = next(line for line in page.splitlines() if line.startswith(f"| {first} |"))
    return [cell.strip() for cell in line.strip("|").split(" | ")]


def case_row(page: str, case_id: str) -> list[str]:
    """The cells of the first case table row of ``case_id`` (its second cell)."""
    rows = (line.strip("|").split(" | ") for line in page.splitlines() if line.startswith("| "))
    return [cell.strip() for cell in next(r for r in rows if r[1:2] == [case_id])]


def test_columns_follow_the_runs_order_and_shared_names_are_numbered(tmp_path: Path) -> None:
    runs = [
        write_run(tmp_path / "x" / "iba.jsonl", "iba", [case("h/1")]),
        write_run(tmp_path / "ifgm.jsonl", "ifgm", [case("h/1")]),
        write_run(tmp_path / "y" / "iba.jsonl", "iba", [case("h/1", "fail", reason="hit")]),
    ]
    comparison = read_runs(runs)
    assert [run.label for run in comparison.runs] == ["iba", "ifgm", "iba (2)"]
    page = render_markdown(comparison, tmp_path)
    assert header_row(page, "property") == ["property", "case", "level", "iba", "ifgm", "iba (2)"]
    assert case_row(page, "h/1")[3:5] == ["pass", "pass"]
    assert case_row(page, "h/1")[5].startswith("**FAIL")
    html = render_html(comparison, tmp_path)
    assert re.findall(r"<th>(iba|ifgm|iba \(2\))</th>", html) == ["iba", "ifgm", "iba (2)"]


def test_each_verdict_has_its_cell_and_its_reason(tmp_path: Path) -> None:
    ran = write_run(
        tmp_path / "a.jsonl",
        "ifgm",
        [
            case("p/1"),
            case("p/2", "fail", reason="min_clearance=-0.3 ft"),
            case("p/3", "skip", reason="no sensor noise declared"),
            case("p/4", "error", reason="timed out after 5 s"),
        ],
    )
    other = write_run(tmp_path / "b.jsonl", "iba", [case("p/1")])
    comparison = read_runs([ran, other])
    page = render_markdown(comparison, tmp_path)
    cells = {row: case_row(page, row)[3:] for row in ("p/1", "p/2", "p/3", "p/4")}
    assert cells == {
        "p/1": ["pass", "pass"],
        "p/2": ["**FAIL**[^1]", "-"],
        "p/3": ["skip[^2]", "-"],
        "p/4": ["error[^3]", "-"],
    }
    notes = re.findall(r"^\[\^(\d)\]: (.*)$", page, flags=re.MULTILINE)
    assert notes == [
        ("1", r"min\_clearance=-0.3 ft"),
        ("2", "no sensor noise declared"),
        ("3", "timed out after 5 s"),
    ]
    html = render_html(comparison, tmp_path)
    assert '<td class="skip" title="no sensor noise declared">skip</td>' in html
    assert '<td class="error" title="timed out after 5 s">error</td>' in html
    assert '<td class="missing" title="not in this run">-</td>' in html


def test_the_same_reason_is_one_footnote(tmp_path: Path) -> None:
    cases = [case("p/1", "skip", reason="no lidar"), case("p/2", "skip", reason="no lidar")]
    page = render_markdown(read_runs([write_run(tmp_path / "a.jsonl", "x", cases)]), tmp_path)
    assert page.count("skip[^1]") == 2
    assert re.findall(r"^\[\^\d\]:", page, flags=re.MULTILINE) == ["[^1]:"]


def failing_run(tmp_path: Path) -> tuple[Path, Path]:
    """A run in ``runs/`` with two failures: one with a plot, one with only report.md."""
    folder = tmp_path / "runs" / "oracle-failures" / "x"
    for name in ("collision_free__0002", "converges_u__0001"):
        (folder / name).mkdir(parents=True)
        (folder / name / "report.md").write_text("# failed\n")
    (folder / "collision_free__0002" / "world.png").write_bytes(b"\x89PNG")
    run = write_run(
        tmp_path / "runs" / "run.jsonl",
        "ifgm",
        [
            case(
                "collision_free/0002",
                "fail",
                counterexample="oracle-failures/x/collision_free__0002",
            ),
            case("converges_u/0001", "fail", counterexample=str(folder / "converges_u__0001")),
        ],
    )
    return run, folder


def test_failures_link_to_their_plot_relative_to_the_page(tmp_path: Path) -> None:
    run, _ = failing_run(tmp_path)
    out = tmp_path / "site" / "suite"
    md_path, html_path = write_report(read_runs([run]), out, "page")
    page = md_path.read_text()
    links = re.findall(r"\[FAIL\]\(([^)]*)\)", page)
    assert links == [
        "../../runs/oracle-failures/x/collision_free__0002/world.png",
        "../../runs/oracle-failures/x/converges_u__0001/report.md",  # no plot: the report
    ]
    assert all((out / link).is_file() for link in links)
    hrefs = re.findall(r'<a href="([^"]*)">FAIL</a>', html_path.read_text())
    assert hrefs == links
    assert "[run](../../runs/run.jsonl)" in page


def test_link_paths_are_quoted(tmp_path: Path) -> None:
    folder = tmp_path / "a run (1)" / "x y"
    folder.mkdir(parents=True)
    (folder / "world.png").write_bytes(b"\x89PNG")
    run = write_run(
        tmp_path / "a run (1)" / "r.jsonl", "x", [case("p/1", "fail", counterexample="x y")]
    )
    page = render_markdown(read_runs([run]), tmp_path)
    assert "[FAIL](a%20run%20%281%29/x%20y/world.png)" in page


def test_text_from_the_runs_is_escaped(tmp_path: Path) -> None:
    reason = '<script>alert("x")</script> & | *'
    run = write_run(tmp_path / "a.jsonl", "<b>impl</b>", [case("p/1", "fail", reason=reason)])
    comparison = read_runs([run])
    html = render_html(comparison, tmp_path, title="<i>title</i>")
    assert "<script" not in html and "<b>" not in html and "<i>" not in html
    assert 'title="&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; | *"' in html
    assert "<code>&lt;b&gt;impl&lt;/b&gt;</code>" in html
    assert "<title>&lt;i&gt;title&lt;/i&gt;</title>" in html
    assert "http" not in html and "<link" not in html  # standalone: nothing fetched
    page = render_markdown(comparison, tmp_path)
    assert "<script>" not in page
    assert r'[^1]: \<script\>alert("x")\</script\> \& \| \*' in page


def test_broken_variants_get_their_own_tables(tmp_path: Path) -> None:
    good = write_run(tmp_path / "ifgm.jsonl", "ifgm", [case("p/1"), case("p/2", tier="full")])
    caught = write_run(tmp_path / "m1.jsonl", "ifgm", [case("p/1", "fail", reason="off")])
    missed = write_run(tmp_path / "m2.jsonl", "no_brake", [case("p/1")])
    comparison = read_runs([good], broken=[caught, missed])
    assert [run.label for run in comparison.broken] == ["m1", "m2"]
    page = render_markdown(comparison, tmp_path)
    main_part, broken_part = page.split("## Known broken variants: the suite's teeth")
    assert "m1" not in main_part and "no\\_brake" not in main_part
    assert header_row(main_part, "property") == ["property", "case", "level", "ifgm"]
    assert header_row(broken_part, "property") == ["property", "case", "level", "m1", "m2"]
    assert header_row(broken_part, "run")[-1] == "caught"
    assert header_row(broken_part, "[m1](m1.jsonl)")[-1] == "yes"
    assert header_row(broken_part, "[m2](m2.jsonl)")[-1] == "**NO**"
    html = render_html(comparison, tmp_path)
    assert html.count("<h2>Known broken variants: the suite&#x27;s teeth</h2>") == 1
    assert html.index("<th>m2</th>") > html.index("Known broken variants")


def test_without_broken_runs_there_is_no_broken_table(tmp_path: Path) -> None:
    comparison = read_runs([write_run(tmp_path / "a.jsonl", "ifgm", [case("p/1")])])
    assert "Known broken" not in render_markdown(comparison, tmp_path)
    assert "Known broken" not in render_html(comparison, tmp_path)


def test_the_runs_table_has_each_summary(tmp_path: Path) -> None:
    cases = [case("p/1"), case("p/2", "fail"), case("p/3", "skip"), case("p/4", "error")]
    run = write_run(tmp_path / "a.jsonl", "ifgm", cases)
    page = render_markdown(read_runs([run]), tmp_path)
    assert header_row(page, "run") == [
        "run", "implementation", "tier", "cases", "pass", "fail", "skip", "error", "ok",
        "seconds",
    ]  # fmt: skip
    row = header_row(page, "[a](a.jsonl)")
    assert row[1:] == ["`ifgm`", "full", "4", "1", "1", "1", "1", "**NOT OK**", "1.50"]


def write_lines(path: Path, lines: list[Any]) -> Path:
    text = [line if isinstance(line, str) else json.dumps(line) + "\n" for line in lines]
    path.write_text("".join(text))
    return path


GOOD = [case("p/1"), case("p/2", "fail")]


@pytest.mark.parametrize(
    ("lines", "message"),
    [
        ([GOOD[0], "{not json\n", summary_of(GOOD, "x")], r"a\.jsonl, line 2: not JSON"),
        ([GOOD[0], "[1, 2]\n"], r"a\.jsonl, line 2: not a JSON object"),
        ([{**GOOD[0], "verdict": "maybe"}], r'line 1: verdict="maybe", but should be one of'),
        ([{**GOOD[0], "seconds": "1"}], r'line 1: seconds="1", but should be a finite number'),
        (
            [json.dumps(GOOD[0]).replace("0.25", "NaN")],
            r"line 1: seconds=NaN, but should be a finite",
        ),
        ([{k: v for k, v in GOOD[0].items() if k != "id"}], r"line 1: no 'id' field"),
        ([{**GOOD[0], "type": "note"}], r'line 1: type="note", but should be "case" or'),
        ([GOOD[0], GOOD[0]], r"line 2: case id 'p/1' again \(line 1\)"),
        (GOOD, r"a\.jsonl: no summary line"),
        ([], r"a\.jsonl: no summary line"),
        ([*GOOD, summary_of(GOOD, "x"), GOOD[0]], r"a\.jsonl, line 4: a line after the summary"),
        ([GOOD[0], summary_of(GOOD, "x")], r"line 2: cases=2, but should be 1, the file's case"),
        (
            [*GOOD, {**summary_of(GOOD, "x"), "pass": 2, "fail": 0}],
            r"line 3: pass=2, but should be 1, the file's pass verdicts",
        ),
        ([*GOOD, {**summary_of(GOOD, "x"), "ok": "no"}], r'line 3: ok="no", but should be true'),
        ([GOOD[0], case("p/2", suite="v2")], r'line 2: suite="v2", but should be "v1", as on'),
    ],
)
def test_a_malformed_run_file_names_its_file_and_line(
    tmp_path: Path, lines: list[Any], message: str
) -> None:
    path = write_lines(tmp_path / "a.jsonl", lines)
    with pytest.raises(ParameterError, match=message):
        read_runs([path])


def test_runs_of_different_suite_versions_are_refused(tmp_path: Path) -> None:
    one = write_run(tmp_path / "one.jsonl", "ifgm", [case("p/1")])
    two = write_run(tmp_path / "two.jsonl", "iba", [case("p/1", suite="v2")])
    with pytest.raises(
        ParameterError,
        match=r"different suite versions: .*one\.jsonl is 'v1', .*two\.jsonl is 'v2'",
    ):
        read_runs([one], broken=[two])


def test_a_file_that_is_not_utf8_names_its_line(tmp_path: Path) -> None:
    path = tmp_path / "a.jsonl"
    path.write_bytes(json.dumps(case("p/1")).encode() + b"\n\xff\xfe\n")
    with pytest.raises(ParameterError, match=r"a\.jsonl, line 2: not UTF-8"):
        read_runs([path])


def test_write_report_replaces_the_pages_whole(tmp_path: Path) -> None:
    run = write_run(tmp_path / "a.jsonl", "ifgm", [case("p/1")])
    out = tmp_path / "out"
    out.mkdir()
    (out / "suite-report.md").write_text("old")
    written = write_report(read_runs([run]), out, title="Nightly")
    assert written == (out / "suite-report.md", out / "suite-report.html")
    assert written[0].read_text().startswith("# Nightly\n")
    assert written[1].read_text().startswith("<!DOCTYPE html>")
    assert sorted(p.name for p in out.iterdir()) == ["suite-report.html", "suite-report.md"]
    with pytest.raises(ParameterError, match="name='a/b', but should be a file name"):
        write_report(read_runs([run]), out, "a/b")


def test_the_command_writes_both_files_and_says_where(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    run = write_run(tmp_path / "a.jsonl", "ifgm", [case("p/1")])
    broken = write_run(tmp_path / "m.jsonl", "mutant", [case("p/1", "fail")])
    out = tmp_path / "new" / "folder"
    argv = ["report", str(run), "--broken", str(broken), "--out", str(out), "--name", "cmp"]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert err.splitlines() == [f"wrote {out / 'cmp.md'}", f"wrote {out / 'cmp.html'}"]
    assert "mutant" in (out / "cmp.md").read_text().split("Known broken variants")[1]


@pytest.mark.parametrize(
    ("lines", "message"),
    [
        ([case("p/1")], r"a\.jsonl: no summary line"),
        ([case("p/1"), "oops\n"], r"a\.jsonl, line 2: not JSON"),
    ],
)
def test_the_command_reports_bad_input_in_one_line_and_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], lines: list[Any], message: str
) -> None:
    path = write_lines(tmp_path / "a.jsonl", lines)
    assert main(["report", str(path), "--out", str(tmp_path / "out")]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert len(captured.err.splitlines()) == 1
    assert re.match(r"ifgm-ref: error: .*" + message, captured.err)
    assert not (tmp_path / "out").exists()  # nothing made for a bad input


def test_the_command_reports_a_missing_file_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["report", str(tmp_path / "none.jsonl")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("ifgm-ref: error: ") and "none.jsonl" in err
