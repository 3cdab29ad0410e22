"""The page comparing runs of the conformance suite, Markdown and HTML (``ifgm-ref report``).

A run file holds one JSON line per case, then one summary line::

    {"type": "case", "suite": "v1", "id": "converges_u/0003", "property": "converges_u",
     "level": "paper", "tier": "quick", "verdict": "fail", "reason": "...",
     "counterexample": "oracle-failures/x/converges_u__0003", "seconds": 0.42}
    {"type": "summary", "suite": "v1", "implementation": "ifgm", "tier": "quick",
     "cases": 1, "pass": 0, "fail": 1, "skip": 0, "error": 0, "ok": false, "seconds": 0.5}

``counterexample`` is ``null`` or a failure's evidence folder (``report.md``, ``world.png``,
...), relative to the run file's folder or absolute. :func:`read_runs` reads and checks the
files; :func:`render_markdown` and :func:`render_html` build the page, touching no file;
:func:`write_report` writes ``NAME.md`` and ``NAME.html``, each whole or not at all. The page:
a table of the runs, then the cases as rows, grouped by property and by tier (quick first), a
column per run, each cell the verdict (``FAIL`` linked to the counterexample's plot) with its
reason; then the same for runs of variants broken on purpose: one the suite passes is a fault
it cannot see, and the page says so.
"""

from __future__ import annotations

import json
import math
import os
import secrets
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from enum import Enum
from html import escape
from pathlib import Path
from typing import Any
from urllib.parse import quote

from ifgm_ref.errors import ParameterError

#: The tiers in the order the page shows them; any other tier follows them, by name.
TIERS = ("quick", "full")
#: What a counterexample's link points at: the first of these its folder holds, else the
#: folder itself.
EVIDENCE_FILES = ("world.png", "report.md")
#: The cell of a case that a run does not hold (a quick run beside a full one).
MISSING = "-"
LEGEND = (
    "pass: the case held. FAIL: it did not; the cell links to its counterexample (the "
    "plot, world.png, else report.md). skip: not checked. error: the program crashed, hung "
    f"or answered garbage. {MISSING}: not in that run."
)
BROKEN_HEADING = "Known broken variants: the suite's teeth"
BROKEN_NOTE = (
    "Variants broken on purpose: each should fail some case. One the suite passes "
    "(caught: NO) is a fault the suite cannot see."
)
#: The page's style, inline: the page needs no other file and no network.
CSS = """
body { font-family: system-ui, sans-serif; margin: 2em; color: #222; }
table { border-collapse: collapse; margin: 1em 0; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; }
th { background: #f3f3f3; } tr.group th { background: #e4e8f0; } td[title] { cursor: help; }
td.number { text-align: right; } td.bad, td.fail { color: #a00; font-weight: bold; }
td.pass { background: #e6f4e6; } td.fail { background: #f9d6d5; }
td.skip { color: #666; } td.error { background: #fde8c8; } td.missing { color: #999; }
"""


class Verdict(Enum):
    """A case's verdict: ``pass``, ``fail``, ``skip`` (its reason says why) or ``error`` (the
    program crashed, hung or answered garbage; its reason says how)."""

    PASS = "pass"
    FAIL = "fail"
    SKIP = "skip"
    ERROR = "error"

    @property
    def cell(self) -> str:
        """The verdict as the page shows it: ``pass``, ``FAIL``, ``skip`` or ``error``."""
        return "FAIL" if self is Verdict.FAIL else self.value


@dataclass(frozen=True)
class CaseResult:
    """One case line. ``counterexample``: its folder, joined to the run file's folder;
    ``evidence``: the file its link points at (:data:`EVIDENCE_FILES`), which
    :func:`read_run` looks for (``None`` before)."""

    id: str
    property: str
    level: str
    tier: str
    verdict: Verdict
    reason: str
    counterexample: Path | None
    seconds: float
    evidence: Path | None = None


@dataclass(frozen=True)
class Summary:
    """The summary line of a run file: who ran, which tier, the counts and the time, s."""

    implementation: str
    tier: str
    cases: int
    passed: int
    failed: int
    skipped: int
    errors: int
    ok: bool
    seconds: float


@dataclass(frozen=True)
class Run:
    """One run file, its cases in file order; ``label`` names its column (:func:`read_runs`)."""

    path: Path
    suite: str
    summary: Summary
    cases: tuple[CaseResult, ...]
    label: str


@dataclass(frozen=True)
class Comparison:
    """One page's runs, and those of variants broken on purpose: one suite, unique labels."""

    suite: str
    runs: tuple[Run, ...]
    broken: tuple[Run, ...] = ()


@dataclass(frozen=True)
class Group:
    """Rows of a case table: the ids of the cases of one property and tier."""

    property: str
    tier: str
    case_ids: tuple[str, ...]


def _wrong(where: str, key: str, value: object, expected: str) -> ParameterError:
    shown = json.dumps(value)
    shown = shown if len(shown) <= 60 else shown[:57] + "..."
    return ParameterError(f"{where}: {key}={shown}, but should be {expected}")


def _value(record: dict[str, Any], key: str, where: str) -> Any:
    if key not in record:
        raise ParameterError(f"{where}: no {key!r} field")
    return record[key]


def _text(record: dict[str, Any], key: str, where: str, *, empty: bool = False) -> str:
    value = _value(record, key, where)
    if not isinstance(value, str) or not (value or empty):
        raise _wrong(where, key, value, "a string" if empty else "a non-empty string")
    return value


def _count(record: dict[str, Any], key: str, where: str) -> int:
    value = _value(record, key, where)
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise _wrong(where, key, value, "an integer >= 0")
    return value


def _seconds(record: dict[str, Any], where: str) -> float:
    value = _value(record, "seconds", where)
    if isinstance(value, bool) or not isinstance(value, int | float) or not 0 <= value < math.inf:
        raise _wrong(where, "seconds", value, "a finite number >= 0")
    return float(value)


def _record(line: str, where: str) -> dict[str, Any]:
    try:
        record = json.loads(line)
    except json.JSONDecodeError as err:
        raise ParameterError(f"{where}: not JSON ({err.msg}, column {err.colno})") from None
    if not isinstance(record, dict):
        raise ParameterError(f"{where}: not a JSON object")
    if (kind := _value(record, "type", where)) not in ("case", "summary"):
        raise _wrong(where, "type", kind, '"case" or "summary"')
    return record


def _case(record: dict[str, Any], path: Path, where: str) -> CaseResult:
    verdict = _text(record, "verdict", where)
    if verdict not in {v.value for v in Verdict}:
        raise _wrong(where, "verdict", verdict, "one of pass, fail, skip, error")
    folder = _value(record, "counterexample", where)
    if folder is not None and (not isinstance(folder, str) or not folder):
        raise _wrong(where, "counterexample", folder, "null or a folder")
    return CaseResult(
        id=_text(record, "id", where),
        property=_text(record, "property", where),
        level=_text(record, "level", where),
        tier=_text(record, "tier", where),
        verdict=Verdict(verdict),
        reason=_text(record, "reason", where, empty=True),
        counterexample=None if folder is None else path.parent / folder,
        seconds=_seconds(record, where),
    )


def _summary(record: dict[str, Any], where: str, cases: Sequence[CaseResult]) -> Summary:
    if not isinstance(ok := _value(record, "ok", where), bool):
        raise _wrong(where, "ok", ok, "true or false")
    keys = ("cases", *(v.value for v in Verdict))
    stated = [_count(record, key, where) for key in keys]
    held = [len(cases), *(sum(case.verdict is v for case in cases) for v in Verdict)]
    for key, says, found in zip(keys, stated, held, strict=True):
        if says != found:
            what = "case lines" if key == "cases" else f"{key} verdicts"
            raise _wrong(where, key, says, f"{found}, the file's {what}")
    total, passed, failed, skipped, errors = stated
    name, tier = _text(record, "implementation", where), _text(record, "tier", where)
    return Summary(name, tier, total, passed, failed, skipped, errors, ok, _seconds(record, where))


def parse_run(lines: Iterable[str], path: str | Path) -> Run:
    """Parse the lines of the run file ``path``: case lines, then one summary line.

    Blank lines are ignored. Relative counterexample folders are joined to ``path``'s folder
    (no file is read). The run's label is its summary's implementation.

    Raises
    ------
    ParameterError
        Naming ``path`` and the line: a line that is not a JSON case or summary record with
        every field of its type, a repeated case id, another suite version than the first
        line's, a summary whose counts are not those of the case lines, a line after it;
        naming ``path``: no summary.

    Examples
    --------
    >>> case = ('{"type": "case", "suite": "v1", "id": "a/1", "property": "a", '
    ...         '"level": "paper", "tier": "quick", "verdict": "fail", "reason": "hit", '
    ...         '"counterexample": "failures/a__1", "seconds": 1}')
    >>> summary = ('{"type": "summary", "suite": "v1", "implementation": "ifgm", '
    ...            '"tier": "quick", "cases": 1, "pass": 0, "fail": 1, "skip": 0, '
    ...            '"error": 0, "ok": false, "seconds": 1.5}')
    >>> run = parse_run([case, "", summary], "runs/a.jsonl")
    >>> run.label, run.cases[0].verdict, run.cases[0].counterexample.as_posix()
    ('ifgm', <Verdict.FAIL: 'fail'>, 'runs/failures/a__1')
    >>> parse_run([case], "runs/a.jsonl")
    Traceback (most recent call last):
    ...
    ifgm_ref.errors.ParameterError: runs/a.jsonl: no summary line: the run stopped before ...
    """
    path = Path(path)
    numbered = ((n, line) for n, line in enumerate(lines, start=1) if line.strip())
    cases: list[CaseResult] = []
    seen: dict[str, int] = {}
    first: tuple[str, int] | None = None  # the suite version and the line that set it
    for number, line in numbered:
        where = f"{path}, line {number}"
        record = _record(line, where)
        suite = _text(record, "suite", where)
        first = first or (suite, number)
        if suite != first[0]:
            raise _wrong(where, "suite", suite, f'"{first[0]}", as on line {first[1]}')
        if record["type"] == "summary":
            summary = _summary(record, where, cases)
            if (after := next(numbered, None)) is not None:
                raise ParameterError(f"{path}, line {after[0]}: a line after the summary")
            return Run(path, suite, summary, tuple(cases), summary.implementation)
        case = _case(record, path, where)
        if case.id in seen:
            raise ParameterError(f"{where}: case id {case.id!r} again (line {seen[case.id]})")
        seen[case.id] = number
        cases.append(case)
    stopped = f"the run stopped before its end? ({len(cases)} case lines)"
    raise ParameterError(f"{path}: no summary line: {stopped}")


def read_run(path: str | Path) -> Run:
    """Read and check the run file ``path`` (:func:`parse_run`), and find each
    counterexample's evidence: its ``world.png``, else its ``report.md``, else its folder.

    Raises
    ------
    ParameterError
        For what :func:`parse_run` refuses, or a line that is not UTF-8 text.
    OSError
        For a file that cannot be read.
    """
    path = Path(path)
    data = path.read_bytes()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        line = data.count(b"\n", 0, err.start) + 1
        raise ParameterError(f"{path}, line {line}: not UTF-8 text ({err.reason})") from None
    run = parse_run(text.splitlines(), path)
    cases = []
    for case in run.cases:
        if (folder := case.counterexample) is not None:
            files = [folder / name for name in EVIDENCE_FILES if (folder / name).is_file()]
            case = replace(case, evidence=files[0] if files else folder)
        cases.append(case)
    return replace(run, cases=tuple(cases))


def unique_labels(names: Sequence[str]) -> list[str]:
    """``names``, the second and later of a name numbered so that no two are the same.

    >>> unique_labels(["ifgm", "iba", "ifgm", "ifgm"])
    ['ifgm', 'iba', 'ifgm (2)', 'ifgm (3)']
    >>> unique_labels(["ifgm", "ifgm", "ifgm (2)"])
    ['ifgm', 'ifgm (2)', 'ifgm (2) (2)']
    """
    labels: list[str] = []
    for name in names:
        label, k = name, 1
        while label in labels:
            k += 1
            label = f"{name} ({k})"
        labels.append(label)
    return labels


def read_runs(paths: Sequence[str | Path], broken: Sequence[str | Path] = ()) -> Comparison:
    """Read the run files ``paths`` to compare, in the order of the page's columns, and
    ``broken``, runs of variants broken on purpose (:func:`read_run`); label each run with
    its implementation, numbered where two runs of either group share it
    (:func:`unique_labels`).

    Raises
    ------
    ParameterError
        With no ``paths``, for a file :func:`read_run` refuses, or for runs of different
        suite versions (naming a file of each).
    """
    if not paths:
        raise ParameterError("no run file to report on: name at least one")
    every = [read_run(path) for path in [*paths, *broken]]
    for run in every[1:]:
        if run.suite != every[0].suite:
            raise ParameterError(
                f"runs of different suite versions: {every[0].path} is {every[0].suite!r}, "
                f"{run.path} is {run.suite!r}"
            )
    labels = unique_labels([run.summary.implementation for run in every])
    every = [replace(run, label=label) for run, label in zip(every, labels, strict=True)]
    return Comparison(every[0].suite, tuple(every[: len(paths)]), tuple(every[len(paths) :]))


def case_groups(runs: Sequence[Run]) -> tuple[Group, ...]:
    """The rows of a case table: every case id of ``runs``, grouped by property (in the order
    the properties first appear) and within one by tier (:data:`TIERS` first, in that order,
    then the others by name), sorted by id within a group.

    >>> def run(*cases):
    ...     made = [CaseResult(i, p, "paper", t, Verdict.PASS, "", None, 0.0) for i, p, t in cases]
    ...     return Run(Path("r.jsonl"), "v1", Summary("x", "full", 2, 2, 0, 0, 0, True, 0.0),
    ...                tuple(made), "x")
    >>> for group in case_groups([run(("u/2", "u", "full"), ("h/1", "h", "quick")),
    ...                           run(("u/1", "u", "quick"), ("u/3", "u", "full"))]):
    ...     print(group.property, group.tier, group.case_ids)
    u quick ('u/1',)
    u full ('u/2', 'u/3')
    h quick ('h/1',)
    """
    order: dict[str, int] = {}
    found: dict[tuple[str, str], set[str]] = {}
    for run in runs:
        for case in run.cases:
            order.setdefault(case.property, len(order))
            found.setdefault((case.property, case.tier), set()).add(case.id)
    ranks = {tier: (k, "") for k, tier in enumerate(TIERS)}
    keys = sorted(found, key=lambda k: (order[k[0]], ranks.get(k[1], (len(TIERS), k[1]))))
    return tuple(Group(prop, tier, tuple(sorted(found[prop, tier]))) for prop, tier in keys)


@dataclass(frozen=True)
class _Cell:
    """A verdict cell: its text, class (the verdict, or ``missing``), reason and link."""

    text: str
    kind: str
    reason: str = ""
    link: str | None = None


def _href(target: Path, out: Path) -> str:
    """The URL of ``target`` from a page in the folder ``out``: relative, quoted."""
    relative = os.path.relpath(os.path.abspath(target), os.path.abspath(out))
    return quote(Path(relative).as_posix())


def _cell(case: CaseResult | None, out: Path) -> _Cell:
    if case is None:
        return _Cell(MISSING, "missing", "not in this run")
    evidence = case.evidence or case.counterexample
    link = None if evidence is None else _href(evidence, out)
    return _Cell(case.verdict.cell, case.verdict.value, case.reason, link)


#: A row of a case table: the case id, its level, a cell per run.
_Row = tuple[str, str, list[_Cell]]


def _case_tables(runs: Sequence[Run], out: Path) -> list[tuple[Group, list[_Row]]]:
    """The rows of the case tables of ``runs``, group by group (:func:`case_groups`)."""
    by_id = [{case.id: case for case in run.cases} for run in runs]
    tables = []
    for group in case_groups(runs):
        rows = []
        for case_id in group.case_ids:
            level = next(cases[case_id].level for cases in by_id if case_id in cases)
            rows.append((case_id, level, [_cell(cases.get(case_id), out) for cases in by_id]))
        tables.append((group, rows))
    return tables


#: The columns of a table of runs; one of broken variants adds ``caught``.
RUN_COLUMNS = ("implementation", "run file", "tier", "cases", *(v.value for v in Verdict))
RUN_COLUMNS += ("ok", "seconds")
#: Fields shown in bold red: the run failed, or the suite did not catch a broken variant.
ALARMS = ("NOT OK", "NO")


def _run_fields(run: Run, *, broken: bool) -> list[str]:
    """The counts, ok and seconds of a row of a table of runs (and whether the suite caught
    a broken variant: it did if the run is not ok)."""
    s = run.summary
    fields = [str(n) for n in (s.cases, s.passed, s.failed, s.skipped, s.errors)]
    fields += ["ok" if s.ok else "NOT OK", f"{s.seconds:.2f}"]
    return [*fields, "NO" if s.ok else "yes"] if broken else fields


#: What Markdown could take for markup in text: each is shown backslash-escaped.
MARKDOWN_SPECIAL = frozenset("\\`*_[]<>|&#!~$")


def markdown_text(text: str) -> str:
    """``text`` as literal Markdown on one line: runs of white space made one space, every
    character that could be markup backslash-escaped (a table's ``|`` included).

    >>> print(markdown_text("x<script>|*y*\\n z"))
    x\\<script\\>\\|\\*y\\* z
    """
    return "".join("\\" + c if c in MARKDOWN_SPECIAL else c for c in " ".join(text.split()))


def _md_table(header: Sequence[str], rows: Iterable[Sequence[str]]) -> list[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return lines + ["| " + " | ".join(row) + " |" for row in rows]


def _md_runs(runs: Sequence[Run], out: Path, *, broken: bool) -> list[str]:
    rows = []
    for run in runs:
        link = f"[{markdown_text(run.path.name)}]({_href(run.path, out)})"
        fields = [f"**{f}**" if f in ALARMS else f for f in _run_fields(run, broken=broken)]
        rows.append([markdown_text(run.label), link, markdown_text(run.summary.tier), *fields])
    return [*_md_table((*RUN_COLUMNS, "caught") if broken else RUN_COLUMNS, rows), ""]


def _md_cell(cell: _Cell, notes: dict[str, int]) -> str:
    """The cell's Markdown: its reason a footnote, numbered in ``notes`` (one a reason)."""
    text = f"[{cell.text}]({cell.link})" if cell.link else cell.text
    text = f"**{text}**" if cell.kind == Verdict.FAIL.value else text
    if cell.kind == "missing" or not cell.reason:
        return text
    return text + f"[^{notes.setdefault(cell.reason, len(notes) + 1)}]"


def _md_cases(runs: Sequence[Run], out: Path, notes: dict[str, int]) -> list[str]:
    header = ["case", "level", *(markdown_text(run.label) for run in runs)]
    lines = []
    for group, rows in _case_tables(runs, out):
        lines += [f"### {markdown_text(group.property)}, {markdown_text(group.tier)}", ""]
        table = [
            [markdown_text(case_id), markdown_text(level), *(_md_cell(c, notes) for c in cells)]
            for case_id, level, cells in rows
        ]
        lines += [*_md_table(header, table), ""]
    return lines


def render_markdown(comparison: Comparison, out: str | Path, title: str | None = None) -> str:
    """The comparison page of ``comparison`` (:func:`read_runs`) as Markdown (GitHub's:
    tables, footnotes), to be written in the folder ``out``, which its links to run files and
    counterexamples are relative to; ``title`` defaults to "Conformance suite" and the
    suite version.

    The page: a table of the runs, tables of the cases by property and tier, the same for
    the broken variants if any, then the verdicts' reasons as footnotes, one for each
    distinct reason. All text from the runs is escaped (:func:`markdown_text`).
    """
    out, notes = Path(out), dict[str, int]()
    title = title or f"Conformance suite {comparison.suite}"
    lines = [f"# {markdown_text(title)}", "", markdown_text(LEGEND), ""]
    lines += ["## Runs", "", *_md_runs(comparison.runs, out, broken=False), "## Cases", ""]
    lines += _md_cases(comparison.runs, out, notes)
    if comparison.broken:
        lines += [f"## {BROKEN_HEADING}", "", markdown_text(BROKEN_NOTE), ""]
        lines += [*_md_runs(comparison.broken, out, broken=True)]
        lines += _md_cases(comparison.broken, out, notes)
    lines += [f"[^{n}]: {markdown_text(reason)}" for reason, n in notes.items()]
    return "\n".join(lines) + "\n"


def _html_table(header: Sequence[str], body: list[str]) -> list[str]:
    head = "".join(f"<th>{escape(name)}</th>" for name in header)
    return ["<table>", f"<thead><tr>{head}</tr></thead>", "<tbody>", *body, "</tbody>", "</table>"]


def _html_runs(runs: Sequence[Run], out: Path, *, broken: bool) -> list[str]:
    body = []
    for run in runs:
        link = f'<a href="{escape(_href(run.path, out))}">{escape(run.path.name)}</a>'
        row = [f"<td>{cell}</td>" for cell in (escape(run.label), link, escape(run.summary.tier))]
        for field in _run_fields(run, broken=broken):
            row.append(f'<td class="{"bad" if field in ALARMS else "number"}">{escape(field)}</td>')
        body.append(f"<tr>{''.join(row)}</tr>")
    return _html_table((*RUN_COLUMNS, "caught") if broken else RUN_COLUMNS, body)


def _html_cell(cell: _Cell) -> str:
    title = f' title="{escape(cell.reason)}"' if cell.reason else ""
    text = f'<a href="{escape(cell.link)}">{cell.text}</a>' if cell.link else cell.text
    return f'<td class="{cell.kind}"{title}>{text}</td>'


def _html_cases(runs: Sequence[Run], out: Path) -> list[str]:
    body = []
    for group, rows in _case_tables(runs, out):
        heading = escape(f"{group.property}, {group.tier}")
        body.append(f'<tr class="group"><th colspan="{len(runs) + 2}">{heading}</th></tr>')
        for case_id, level, cells in rows:
            row = [f"<td>{escape(case_id)}</td><td>{escape(level)}</td>", *map(_html_cell, cells)]
            body.append(f"<tr>{''.join(row)}</tr>")
    return _html_table(["case", "level", *(run.label for run in runs)], body)


def render_html(comparison: Comparison, out: str | Path, title: str | None = None) -> str:
    """The comparison page as one standalone HTML file: inline style, no script, nothing
    fetched. Parameters and parts as :func:`render_markdown`'s; a verdict's reason is its
    cell's tooltip. All text from the runs is escaped.

    >>> page = render_html(Comparison("v1", ()), ".", title="<b>&</b>")
    >>> "<title>&lt;b&gt;&amp;&lt;/b&gt;</title>" in page, "<script" in page
    (True, False)
    """
    out, heading = Path(out), escape(title or f"Conformance suite {comparison.suite}")
    parts = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">']
    parts += [f"<title>{heading}</title>", f"<style>{CSS}</style>", "</head>", "<body>"]
    parts += [f"<h1>{heading}</h1>", f"<p>{escape(LEGEND)}</p>", "<h2>Runs</h2>"]
    parts += [*_html_runs(comparison.runs, out, broken=False), "<h2>Cases</h2>"]
    parts += _html_cases(comparison.runs, out)
    if comparison.broken:
        parts += [f"<h2>{escape(BROKEN_HEADING)}</h2>", f"<p>{escape(BROKEN_NOTE)}</p>"]
        parts += _html_runs(comparison.broken, out, broken=True)
        parts += _html_cases(comparison.broken, out)
    return "\n".join([*parts, "</body>", "</html>"]) + "\n"


def _write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` whole or not at all: to a new file beside it (with the
    usual permissions, not a temporary file's owner-only ones), then renamed over it."""
    scratch = path.with_name(f".{path.name}.{secrets.token_hex(4)}.tmp")
    try:
        with scratch.open("x", encoding="utf-8") as file:
            file.write(text)
        os.replace(scratch, path)
    finally:
        scratch.unlink(missing_ok=True)


def write_report(
    comparison: Comparison, out: str | Path = ".", name: str = "suite-report",
    title: str | None = None,
) -> tuple[Path, Path]:  # fmt: skip
    """Write the page of ``comparison`` as ``out/NAME.md`` and ``out/NAME.html``
    (:func:`render_markdown`, :func:`render_html`), each atomically, making the folder
    ``out`` if missing; return the two paths.

    Raises
    ------
    ParameterError
        For a ``name`` that is empty, ``.``, ``..`` or holds a folder.
    OSError
        For a file that cannot be written: a page already there is then left as it was.
    """
    if name in ("", ".", "..") or "/" in name or os.sep in name:
        raise ParameterError(f"name={name!r}, but should be a file name without a folder")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    written = (out / f"{name}.md", out / f"{name}.html")
    _write_atomic(written[0], render_markdown(comparison, out, title))
    _write_atomic(written[1], render_html(comparison, out, title))
    return written
