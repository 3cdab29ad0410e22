"""Choosing the quick tier by measurement: the kill matrix, and a greedy set cover over it.

Every known-broken implementation (the mutants of :mod:`ifgm_ref.oracle.mutants`, and the
built-in planners that do not keep IFGM's promises, held to them) runs every case of the
full tier; the **kill matrix** records which cases each fails. The quick tier is then the
smallest set found greedily that still kills every implementation the full tier kills: every
case of the reference level and one case per property first, then, while some killed implementation
survives, the case that kills the most survivors (ties: the cheaper, then the first id).
Killing each known one once does not kill an unseen one as well: each must be killed
``times`` times, the fewest for which, leaving each known implementation out of the choice
in turn, the tier still kills :data:`HELD_OUT_TARGET` of them (:func:`quick_tier`).
Greedy set cover is within a factor ``ln n`` of the smallest cover, and with a dozen broken
implementations it is small; docs/oracle.md gives the measured sizes and times.

Why those first. A property the quick tier never exercised would let a port break it unseen,
so each gets its cheapest case. The reference level's cases compare a port's every answer with
recorded ones, no reference running, so they cost little (the 39 of v1 about 8 s in all), and
the mutants that outlived a cover of the paper level's properties were, every one, killed only
by them (docs/oracle.md): a cover that picks among them by the kills of known mutants misses
the next unseen one that changes a single decision on a single world. The matrix
also takes the kills of implementations run elsewhere (:func:`kills_in_runs`, the mutation
benchmark's mutants): :func:`retier` chooses the quick tier again with them.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Callable, Iterable, Mapping
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import replace
from pathlib import Path

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.oracle.check_types import Level
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.mutants import MUTANTS
from ifgm_ref.oracle.suite.cases import Case, read_cases, write_cases
from ifgm_ref.oracle.suite.run import run_case
from ifgm_ref.planners import make_planner

__all__ = [
    "BROKEN_PLANNERS",
    "broken_implementations",
    "held_out_kills",
    "kill_matrix",
    "kills_in_runs",
    "quick_cover",
    "quick_tier",
    "retier",
    "with_tiers",
]

#: The share of broken implementations an unseen one stands for: the quick tier must kill
#: this share of the known ones when each is left out of its choice in turn (issue 43's
#: target for unseen mutants: 95 % of the full tier's kills).
HELD_OUT_TARGET = 0.95
#: The most times a cover kills each implementation.
MOST_TIMES = 5
#: Built-in planners that break IFGM's promises (they never claimed them): held to them,
#: they are broken implementations the suite must reject.
BROKEN_PLANNERS = ("fgm", "apf", "bug2", "straight")


def broken_implementations() -> dict[str, Implementation]:
    """Every known-broken implementation by name: ``mutant:NAME`` and ``planner:NAME``."""
    ifgm = promises_of("ifgm")
    found = {
        f"mutant:{name}": Implementation.from_spec(f"ifgm_ref.oracle.mutants:{cls.__name__}")
        for name, cls in MUTANTS.items()
    }
    for name in BROKEN_PLANNERS:
        factory = functools.partial(make_planner, name)
        found[f"planner:{name}"] = Implementation(factory, f"{name} (ifgm's promises)", ifgm)
    return found


def _killed(cases: list[Case], impl: Implementation) -> list[str]:
    """The ids of the cases ``impl`` fails or errs on (in a worker process)."""
    return [c.id for c in cases if run_case(c, impl).verdict in ("fail", "error")]


def kill_matrix(
    cases: list[Case],
    impls: Mapping[str, Implementation],
    progress: Callable[[str], None] = lambda line: None,
    *,
    jobs: int = 1,
) -> dict[str, list[str]]:
    """The ids of the cases each implementation fails (or errs on), by implementation, in
    ``jobs`` worker processes."""
    matrix: dict[str, list[str]] = {}
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(_killed, cases, impl): name for name, impl in impls.items()}
        for future in as_completed(futures):
            name = futures[future]
            matrix[name] = future.result()
            progress(f"{name}: killed by {len(matrix[name])} of {len(cases)} cases")
    return {name: matrix[name] for name in impls}


def quick_cover(
    cases: list[Case],
    matrix: Mapping[str, list[str]],
    seconds: Mapping[str, float],
    times: int = 1,
) -> list[str]:
    """The quick tier's case ids (module docstring): every reference-level case and one per
    property, then a greedy cover of ``matrix`` in which each implementation is killed
    ``times`` times (or by every case that kills it, if fewer); ``seconds`` is each case's
    cost (the reference's time on it).

    >>> cases = [Case(f"p/{k}", "p", None) for k in range(3)] + [Case("q/1", "q", None)]
    >>> seconds = {"p/0": 1.0, "p/1": 1.0, "p/2": 2.0, "q/1": 1.0}
    >>> quick_cover(cases, {"a": ["p/1", "p/2"], "b": ["p/2"]}, seconds)
    ['p/0', 'q/1', 'p/2']
    >>> quick_cover(cases, {"a": ["p/1", "p/2"], "b": ["p/2"]}, seconds, times=2)
    ['p/0', 'q/1', 'p/2', 'p/1']
    >>> cases.append(Case("agrees_with_reference/0001", "agrees_with_reference", None))
    >>> quick_cover(cases, {}, {**seconds, "agrees_with_reference/0001": 3.0})
    ['agrees_with_reference/0001', 'p/0', 'q/1']
    """
    chosen = [c.id for c in cases if c.check in CHECKS and CHECKS[c.check].level is Level.REFERENCE]
    for check in dict.fromkeys(c.check for c in cases if c.id not in chosen):
        own = [c.id for c in cases if c.check == check]
        chosen.append(min(own, key=lambda i: (seconds[i], own.index(i))))
    order = [c.id for c in cases]
    wanted = {name: min(times, len(killed)) for name, killed in matrix.items() if killed}

    def short(name: str) -> bool:
        return len(set(matrix[name]) & set(chosen)) < wanted[name]

    while alive := [name for name in wanted if short(name)]:
        gains = {i: sum(i in matrix[name] for name in alive) for i in order if i not in chosen}
        chosen.append(max(gains, key=lambda i: (gains[i], -seconds[i], -order.index(i))))
    return chosen


def held_out_kills(
    cases: list[Case], matrix: Mapping[str, list[str]], seconds: Mapping[str, float], times: int
) -> tuple[int, int]:
    """Leave one out: of the implementations ``matrix`` kills, how many the cover chosen
    without each one (:func:`quick_cover`, ``times``) still kills, and how many there are."""
    killed = [name for name, ids in matrix.items() if ids]
    caught = 0
    for name in killed:
        others = {other: ids for other, ids in matrix.items() if other != name}
        caught += bool(set(matrix[name]) & set(quick_cover(cases, others, seconds, times)))
    return caught, len(killed)


def quick_tier(
    cases: list[Case], matrix: Mapping[str, list[str]], seconds: Mapping[str, float]
) -> tuple[list[str], int, tuple[int, int]]:
    """The quick tier: :func:`quick_cover` with the fewest ``times`` (1 to
    :data:`MOST_TIMES`) whose leave-one-out kills (:func:`held_out_kills`) reach
    :data:`HELD_OUT_TARGET` of the implementations; the ids, ``times`` and those kills."""
    for times in range(1, MOST_TIMES + 1):
        caught, killed = held_out_kills(cases, matrix, seconds, times)
        if caught >= HELD_OUT_TARGET * killed or times == MOST_TIMES:
            return quick_cover(cases, matrix, seconds, times), times, (caught, killed)
    raise AssertionError("unreachable")  # pragma: no cover


def with_tiers(cases: list[Case], quick: list[str]) -> list[Case]:
    """``cases`` with the ``quick`` ones in the quick tier, the rest in the full one."""
    return [replace(c, tier="quick" if c.id in quick else "full") for c in cases]


def kills_in_runs(paths: Iterable[Path]) -> dict[str, list[str]]:
    """The ids of the cases each run file's implementation failed or erred on, by the file's
    stem (``ifgm-ref oracle --suite ... --results FILE``, every case run)."""
    found = {}
    for path in paths:
        lines = [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
        if not lines or lines[-1].get("type") != "summary":
            raise ImplementationError(f"{path}: not a finished suite run (no summary line)")
        killed = [line["id"] for line in lines if line.get("verdict") in ("fail", "error")]
        found[f"run:{path.stem}"] = killed
    return found


def retier(folder: Path, extra: Mapping[str, list[str]]) -> list[str]:
    """Choose the quick tier of the version in ``folder`` again, from its kill matrix and the
    ``extra`` implementations' kills (:func:`kills_in_runs`); rewrite its case files' tiers
    and its ``kill-matrix.json``, and say so in its changelog; return the quick ids. Only
    before the version is released."""
    path = folder / "kill-matrix.json"
    kills = json.loads(path.read_text())
    matrix = {**kills["killed"], **extra}
    manifest = json.loads((folder / "manifest.json").read_text())
    files = {name: read_cases(folder / f"{name}.jsonl") for name in manifest["properties"]}
    cases = [case for _, found in files.values() for case in found]
    quick, times, held_out = quick_tier(cases, matrix, kills["reference_seconds"])
    for name, (header, found) in files.items():
        write_cases(folder / f"{name}.jsonl", header, with_tiers(found, quick))
    chosen = {"quick": quick, "times": times, "held_out": held_out, "killed": matrix}
    path.write_text(json.dumps({**kills, **chosen}, indent=1) + "\n")
    runs = sum(name.startswith("run:") for name in matrix)
    with (folder / "CHANGELOG.md").open("a") as log:
        log.write(
            f"- quick tier chosen again: {len(quick)} cases, from {len(matrix)} broken "
            f"implementations ({runs} of them runs made elsewhere), `times` {times}, "
            f"{held_out[0]} of {held_out[1]} killed when left out of the choice\n"
        )
    return quick
