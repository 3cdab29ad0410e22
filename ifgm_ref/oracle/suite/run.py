"""Running a suite's cases against an implementation: one verdict per case, no drawing.

Each case runs its check's test on its example (:mod:`.cases`), exactly as the drawn
profiles run it, and gets one of four verdicts:

* ``pass``: the property held, and the case met what the check needs to test anything;
* ``fail``: it broke the property (``reason`` says how; the counterexample is written as the
  drawn profiles write it, :mod:`ifgm_ref.oracle.counterexample`);
* ``skip``: the case does not apply -- the implementation does not promise the property or
  the case's flag (``reason`` says which), or the case met nothing to check (``not
  exercised``, issue 42);
* ``error``: the implementation crashed, hung or answered garbage, or the case could not be
  run at all.

A reference-level case compares with the reference's recorded answers
(:mod:`.recorded`): no reference planner runs. Its episode is rebuilt once per process and
kept (:func:`reference_of`): a process that checks several implementations on the same cases
(the comparison page, the tests) drives the simulator with the recorded commands once.
"""

from __future__ import annotations

import functools
import json
import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.oracle.agreement import ReferenceEpisode
from ifgm_ref.oracle.check_types import CheckFailed, Recorder
from ifgm_ref.oracle.checks import CHECKS, agrees_with
from ifgm_ref.oracle.counterexample import crash, slug, write_evidence
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.suite.cases import Case
from ifgm_ref.oracle.suite.recorded import rebuilt
from ifgm_ref.planners.ifgm.readings import Readings

__all__ = ["VERDICTS", "CaseResult", "reference_of", "run_case", "run_cases", "summary"]

#: The verdicts of a case, as the run file writes them.
VERDICTS = ("pass", "fail", "skip", "error")


@dataclass(frozen=True)
class CaseResult:
    """One case's verdict: its line of the run file (:meth:`to_json`)."""

    case: Case
    verdict: str
    reason: str = ""
    counterexample: Path | None = None
    seconds: float = 0.0

    def to_json(self, suite: str) -> dict[str, Any]:
        """The run file's line for this case."""
        check = CHECKS[self.case.check]
        return {
            "type": "case",
            "suite": suite,
            "id": self.case.id,
            "property": self.case.check,
            "level": str(check.level),
            "tier": self.case.tier,
            "verdict": self.verdict,
            "reason": self.reason,
            "counterexample": None if self.counterexample is None else str(self.counterexample),
            "seconds": round(self.seconds, 3),
        }


def _flag_reason(case: Case, impl: Implementation) -> str | None:
    """Why ``case``'s flags keep it from ``impl`` (``None``: they do not)."""
    promised = impl.promises.converges_in or frozenset({"open"})
    for flag in case.flags:
        kind, _, value = flag.partition(":")
        if kind == "class" and value not in promised:
            return f"its world is of class {value}, in which it does not promise to converge"
    if case.recorded is not None and Readings.declared(impl.promises.readings) != Readings():
        return "its answers were recorded with the reference's readings, not those declared"
    return None


def reference_of(case: Case) -> ReferenceEpisode:
    """The reference's episode of the reference-level ``case``, rebuilt from its recorded
    answers (:func:`~.recorded.rebuilt`) at its first call in this process and kept for the
    next: by the case's content, not its object, so that a suite loaded again finds it."""
    return _rebuilt(_Content(case))


class _Content:
    """A case, equal to another with the same JSON line (:meth:`Case.to_json`)."""

    def __init__(self, case: Case) -> None:
        self.case = case
        self.key = json.dumps(case.to_json(), sort_keys=True)

    def __hash__(self) -> int:
        return hash(self.key)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _Content) and other.key == self.key


#: How many rebuilt episodes a process keeps: a suite's reference level (v1: 39 in its quick
#: tier, about 46 MB in all), with room for a second.
_KEPT = 128


@functools.lru_cache(maxsize=_KEPT)
def _rebuilt(content: _Content) -> ReferenceEpisode:
    case = content.case
    if case.recorded is None:
        raise ValueError(f"{case.id} is not a reference-level case: it records no answers")
    sim = Recorder(sim=case.sim).sim_for(case.example)
    return rebuilt(case.example, sim, case.recorded)


def run_case(case: Case, impl: Implementation, artifacts: Path | None = None) -> CaseResult:
    """Run ``case`` against ``impl``; a failure's counterexample goes under ``artifacts``
    (``IMPLEMENTATION/ID``), none if it is ``None``."""
    check = CHECKS[case.check]
    reason = check.applies(impl) or _flag_reason(case, impl)
    if reason is not None:
        return CaseResult(case, "skip", reason)
    recorder = Recorder(sim=case.sim)
    started = time.perf_counter()
    try:
        if case.recorded is not None:
            agrees_with(impl, case.example, reference_of(case), recorder)
        else:
            check.test(impl, case.example, recorder)
    except CheckFailed as err:
        message = str(err)
        folder = None
        if artifacts is not None and recorder.evidence is not None:
            folder = artifacts / slug(impl.label) / case.id.replace("/", "__")
            write_evidence(folder, recorder.evidence, check, impl, message, sim=case.sim)
        seconds = time.perf_counter() - started
        return CaseResult(case, "fail", message.split("\n")[0], folder, seconds)
    except ImplementationError as err:
        return CaseResult(case, "error", str(err), None, time.perf_counter() - started)
    except Exception as err:  # the oracle's own machinery broke: still a verdict
        why = f"the check itself crashed (a bug in the oracle, not a verdict): {crash(err)}"
        return CaseResult(case, "error", why, None, time.perf_counter() - started)
    seconds = time.perf_counter() - started
    missed = None if check.meets is None else check.meets.missed(recorder)
    if missed is not None:
        return CaseResult(case, "skip", f"not exercised: {missed}", None, seconds)
    return CaseResult(case, "pass", "", None, seconds)


def run_cases(
    cases: Iterable[Case],
    impl: Implementation,
    artifacts: Path | None = None,
    *,
    finished: Callable[[CaseResult], None] | None = None,
) -> Iterator[CaseResult]:
    """Run every case in order, calling ``finished`` with each result as it comes."""
    for case in cases:
        result = run_case(case, impl, artifacts)
        if finished is not None:
            finished(result)
        yield result


def summary(
    results: Iterable[CaseResult], *, suite: str, implementation: str, tier: str
) -> dict[str, Any]:
    """The run file's last line: the counts of each verdict, and whether the run passed
    (every case that applied passed: no ``fail``, no ``error``)."""
    results = list(results)
    counts = {verdict: sum(r.verdict == verdict for r in results) for verdict in VERDICTS}
    return {
        "type": "summary",
        "suite": suite,
        "implementation": implementation,
        "tier": tier,
        "cases": len(results),
        **counts,
        "ok": counts["fail"] == 0 and counts["error"] == 0,
        "seconds": round(sum(r.seconds for r in results), 3),
    }
