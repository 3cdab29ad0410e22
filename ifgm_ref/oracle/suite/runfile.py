"""A run file of the conformance suite, read and checked (``ifgm-ref report`` reads them).

A run file holds one JSON line per case, then one summary line::

    {"type": "case", "suite": "v1", "id": "converges_u/0003", "property": "converges_u",
     "level": "paper", "tier": "quick", "verdict": "fail", "reason": "...",
     "counterexample": "oracle-failures/x/converges_u__0003", "seconds": 0.42}
    {"type": "summary", "suite": "v1", "implementation": "ifgm", "tier": "quick",
     "cases": 1, "pass": 0, "fail": 1, "skip": 0, "error": 0, "ok": false, "seconds": 0.5}

(:mod:`ifgm_ref.oracle.suite.run` writes it). ``counterexample`` is ``null`` or a failure's
evidence folder (``report.md``, ``world.png``, ...), relative to the run file's folder or
absolute. :func:`read_runs` reads and checks the files, and names each run's column by its
file's stem.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from enum import Enum
from pathlib import Path
from typing import Any

from ifgm_ref.core.errors import ParameterError

__all__ = [
    "EVIDENCE_FILES",
    "CaseLine",
    "Comparison",
    "Run",
    "Summary",
    "Verdict",
    "parse_run",
    "read_run",
    "read_runs",
    "unique_labels",
]

#: What a counterexample's link points at: the first of these its folder holds, else the
#: folder itself.
EVIDENCE_FILES = ("world.png", "report.md")


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
class CaseLine:
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
    cases: tuple[CaseLine, ...]
    label: str


@dataclass(frozen=True)
class Comparison:
    """One page's runs, and those of variants broken on purpose: one suite, unique labels."""

    suite: str
    runs: tuple[Run, ...]
    broken: tuple[Run, ...] = ()


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


def _case(record: dict[str, Any], path: Path, where: str) -> CaseLine:
    verdict = _text(record, "verdict", where)
    if verdict not in {v.value for v in Verdict}:
        raise _wrong(where, "verdict", verdict, "one of pass, fail, skip, error")
    folder = _value(record, "counterexample", where)
    if folder is not None and (not isinstance(folder, str) or not folder):
        raise _wrong(where, "counterexample", folder, "null or a folder")
    return CaseLine(
        id=_text(record, "id", where),
        property=_text(record, "property", where),
        level=_text(record, "level", where),
        tier=_text(record, "tier", where),
        verdict=Verdict(verdict),
        reason=_text(record, "reason", where, empty=True),
        counterexample=None if folder is None else path.parent / folder,
        seconds=_seconds(record, where),
    )


def _summary(record: dict[str, Any], where: str, cases: Sequence[CaseLine]) -> Summary:
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
    ifgm_ref.core.errors.ParameterError: runs/a.jsonl: no summary line: the run stopped before ...
    """
    path = Path(path)
    numbered = ((n, line) for n, line in enumerate(lines, start=1) if line.strip())
    cases: list[CaseLine] = []
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
    ``broken``, runs of variants broken on purpose (:func:`read_run`); label each run (its
    column) with its file's stem, numbered where two runs of either group share it
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
    labels = unique_labels([run.path.stem for run in every])
    every = [replace(run, label=label) for run, label in zip(every, labels, strict=True)]
    return Comparison(every[0].suite, tuple(every[: len(paths)]), tuple(every[len(paths) :]))
