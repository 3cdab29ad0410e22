"""The page comparing runs of the conformance suite, Markdown and HTML (``ifgm-ref report``).

:func:`~ifgm_ref.oracle.suite.runfile.read_runs` reads and checks the run files;
:func:`render_markdown` and :func:`render_html` build the page, touching no file;
:func:`write_report` writes ``NAME.md`` and ``NAME.html``, each whole or not at all. The page:
a table of the runs (each a column named by its file's stem, the implementation beside it),
then the cases as rows, tier by tier (quick first), grouped by property, a column per run,
each cell the verdict (``FAIL`` linked to the counterexample's plot) with its reason; then the
same for runs of variants broken on purpose: one the suite passes is a fault it cannot see,
and the page says so.
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from html import escape
from pathlib import Path
from urllib.parse import quote

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.oracle.suite.cases import TIERS
from ifgm_ref.oracle.suite.runfile import CaseLine, Comparison, Run, Verdict

__all__ = ["case_groups", "render_html", "render_markdown", "write_report"]

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


@dataclass(frozen=True)
class Group:
    """Rows of a case table: the ids of the cases of one property and tier."""

    property: str
    tier: str
    case_ids: tuple[str, ...]


def case_groups(runs: Sequence[Run]) -> tuple[Group, ...]:
    """The rows of a case table: every case id of ``runs``, grouped by property (in the order
    the properties first appear) and within one by tier (:data:`TIERS` first, in that order,
    then the others by name), sorted by id within a group.

    >>> from ifgm_ref.oracle.suite.runfile import Summary
    >>> def run(*cases):
    ...     made = [CaseLine(i, p, "paper", t, Verdict.PASS, "", None, 0.0) for i, p, t in cases]
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


def _cell(case: CaseLine | None, out: Path) -> _Cell:
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
RUN_COLUMNS = ("run", "implementation", "tier", "cases", *(v.value for v in Verdict))
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


def markdown_code(text: str) -> str:
    """``text`` as an inline code span in a table cell (as typed: ``--`` stays two dashes).

    >>> print(markdown_code("serve --planner `x` | y"))
    `serve --planner 'x' \\| y`
    """
    return "`" + " ".join(text.split()).replace("`", "'").replace("|", "\\|") + "`"


def _md_runs(runs: Sequence[Run], out: Path, *, broken: bool) -> list[str]:
    rows = []
    for run in runs:
        link = f"[{markdown_text(run.label)}]({_href(run.path, out)})"
        fields = [f"**{f}**" if f in ALARMS else f for f in _run_fields(run, broken=broken)]
        what = markdown_code(run.summary.implementation)
        rows.append([link, what, markdown_text(run.summary.tier), *fields])
    return [*_md_table((*RUN_COLUMNS, "caught") if broken else RUN_COLUMNS, rows), ""]


def _md_cell(cell: _Cell, notes: dict[str, int]) -> str:
    """The cell's Markdown: its reason a footnote, numbered in ``notes`` (one a reason)."""
    text = f"[{cell.text}]({cell.link})" if cell.link else cell.text
    text = f"**{text}**" if cell.kind == Verdict.FAIL.value else text
    if cell.kind == "missing" or not cell.reason:
        return text
    return text + f"[^{notes.setdefault(cell.reason, len(notes) + 1)}]"


def _md_cases(runs: Sequence[Run], out: Path, notes: dict[str, int]) -> list[str]:
    """One table a tier, its rows grouped by property (named on a group's first row)."""
    header = ["property", "case", "level", *(markdown_text(run.label) for run in runs)]
    tables: dict[str, list[list[str]]] = {}
    for group, rows in _case_tables(runs, out):
        table = tables.setdefault(group.tier, [])
        for k, (case_id, level, cells) in enumerate(rows):
            name = "" if k else markdown_text(group.property)
            cases = [markdown_text(case_id), markdown_text(level)]
            table.append([name, *cases, *(_md_cell(c, notes) for c in cells)])
    lines = []
    for tier, table in tables.items():
        lines += [f"### The {markdown_text(tier)} tier", "", *_md_table(header, table), ""]
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
        link = f'<a href="{escape(_href(run.path, out))}">{escape(run.label)}</a>'
        what = f"<code>{escape(run.summary.implementation)}</code>"
        row = [f"<td>{cell}</td>" for cell in (link, what, escape(run.summary.tier))]
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
