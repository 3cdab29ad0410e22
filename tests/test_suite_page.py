"""The committed page of the conformance suite's runs (docs/suite-report.md) cannot go stale.

``benchmarks/suite_runs.py`` runs the suite against every implementation, writes the run
files into ``docs/suite/`` (the known-broken ones into ``docs/suite/broken/``, with the plot
of each one's first failure under ``docs/suite/counterexamples/``) and renders the page with
``ifgm-ref report``. Here: the committed page is what ``ifgm-ref report`` renders from the
committed runs, every link of it resolves to a committed file, and the committed run of the
reference has the verdicts a fresh run of the reference gets on the same tier (its seconds
differ from run to run: verdicts only).
"""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path
from urllib.parse import unquote

from ifgm_ref.apps.cli import main
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.suite.run import run_cases
from ifgm_ref.oracle.suite.versions import load_suite

DOCS = Path(__file__).resolve().parent.parent / "docs"
PAGE = DOCS / "suite-report.md"
RUNS = DOCS / "suite"
#: The reference's run, in process: ``--planner ifgm --level reference``.
REFERENCE_RUN = RUNS / "ifgm.jsonl"


def _title(page: str) -> str:
    """The page's title, as given to ``--title``: its first line without the ``# `` and the
    Markdown escapes."""
    return re.sub(r"\\(.)", r"\1", page.splitlines()[0].removeprefix("# "))


def test_the_committed_page_is_what_the_committed_runs_render(tmp_path: Path) -> None:
    """``ifgm-ref report docs/suite/*.jsonl --broken docs/suite/broken/*.jsonl`` (the shell's
    order: by name), rendered from a copy of ``docs/suite/`` beside the new page, so that its
    links are those of the committed one."""
    committed = PAGE.read_text()
    shutil.copytree(RUNS, tmp_path / "suite")
    runs = sorted((tmp_path / "suite").glob("*.jsonl"))
    broken = sorted((tmp_path / "suite" / "broken").glob("*.jsonl"))
    assert runs and broken
    argv = ["report", *map(str, runs), *(a for p in broken for a in ("--broken", str(p)))]
    argv += ["--out", str(tmp_path), "--name", "suite-report", "--title", _title(committed)]
    assert main(argv) == 0
    assert (tmp_path / "suite-report.md").read_text() == committed


def test_every_link_of_the_page_is_a_committed_file() -> None:
    """The run files and the counterexamples' plots the page links to are there (the site
    copies each as a download); no plot is committed that the page does not show."""
    targets = {unquote(t) for t in re.findall(r"(?<!\\)\]\(([^)#\s]+)\)", PAGE.read_text())}
    assert targets
    for target in targets:
        assert (DOCS / target).is_file(), target
    plots = {p.relative_to(DOCS).as_posix() for p in (RUNS / "counterexamples").rglob("*")}
    folders = {p for p in plots if (DOCS / p).is_dir()}
    assert plots - folders == {t for t in targets if t.endswith(".png")}
    assert all(p.endswith("/world.png") for p in plots - folders)


def test_the_committed_reference_run_has_a_fresh_run_s_verdicts() -> None:
    """The reference IFGM in process at the reference level, on the committed run's suite
    version and tier (about 10 s for v1's quick tier): every case passes but those only IBA
    promises (reports_unreachable), skipped, and the committed run says the same."""
    lines = [json.loads(line) for line in REFERENCE_RUN.read_text().splitlines()]
    summary = lines[-1]
    assert summary["type"] == "summary" and summary["implementation"] == "ifgm"
    suite = load_suite(summary["suite"])
    impl = Implementation.from_spec("ifgm")
    fresh = [(r.case.id, r.verdict) for r in run_cases(suite.tier(summary["tier"]), impl)]
    assert [(line["id"], line["verdict"]) for line in lines[:-1]] == fresh
    unreachable = {v for i, v in fresh if i.startswith("reports_unreachable/")}
    assert unreachable == {"skip"}
    assert {v for i, v in fresh if not i.startswith("reports_unreachable/")} == {"pass"}
