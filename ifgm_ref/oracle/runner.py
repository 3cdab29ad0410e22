"""Run the oracle's checks against one implementation and report, scikit-learn style.

:func:`check_planner` runs every check that applies to the implementation (its
:class:`~ifgm_ref.oracle.implementation.Promises`) under a profile and returns one
:class:`CheckResult` per check: passed, failed, expected failure (listed in
``expected_failed_checks`` with a reason), unexpectedly passed, not applicable, or error (the
implementation crashed, hung or answered garbage: it could not be checked). A failure leaves a
folder under ``artifacts``: the shrunk counterexample as a world file, the trace (CSV), a
plot, and a ``report.md`` that says how to replay it with ``ifgm-ref simulate``. Under noise
(the ``robust`` profile, or ``noise=``) the same checks run on noisy worlds, and those about
convergence count successes instead (:mod:`ifgm_ref.oracle.robust`). A profile on another
engine (:func:`~ifgm_ref.oracle.profiles.on_engine`) runs every simulation there: the robot
with mass of ``mujoco`` (``docs/oracle.md``, "On the physical robot").
"""

from __future__ import annotations

import functools
import sys
import time
from collections import Counter
from collections.abc import Callable, Iterable, Mapping
from concurrent.futures import as_completed
from dataclasses import dataclass, field, replace
from enum import StrEnum
from pathlib import Path
from typing import Any

from hypothesis import example, given, seed
from hypothesis.errors import Flaky

from ifgm_ref.core.errors import ImplementationError, ParameterError
from ifgm_ref.core.protocol import Planner
from ifgm_ref.oracle.check_types import (
    Check,
    CheckFailed,
    Kind,
    Level,
    Recorder,
    levels_up_to,
)
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.counterexample import crash, slug, write_evidence
from ifgm_ref.oracle.implementation import Implementation, Promises, promises_for
from ifgm_ref.oracle.profiles import (
    Profile,
    engine_tag,
    noise_tags,
    profile_named,
    with_noise,
)
from ifgm_ref.oracle.robust import noisy_examples, run_statistical, with_world
from ifgm_ref.oracle.specification import Specification, declared, in_feet
from ifgm_ref.oracle.stable_draws import global_constants_only
from ifgm_ref.oracle.workers import worker_pool
from ifgm_ref.sim.noise import NoiseLevels


class Status(StrEnum):
    """The verdict of one check."""

    PASSED = "passed"
    #: It found no fault, but met nothing it checks (:class:`~.check_types.Meets`): counted
    #: apart from the passes, and not a failure of the run.
    NOT_EXERCISED = "not exercised"
    FAILED = "failed"
    EXPECTED_FAILURE = "expected failure"
    UNEXPECTED_PASS = "unexpectedly passed"
    NOT_APPLICABLE = "not applicable"
    ERROR = "error"


#: Why a check of a level above the run's does not apply: how to run at its level, on the
#: command line, under pytest and in Python (``{level}``: the check's level).
ABOVE_LEVEL = (
    "the {level} level: --level {level} (ifgm-ref oracle), --ifgm-level {level} (pytest), "
    'level="{level}" (check_planner)'
)


@dataclass(frozen=True)
class CheckResult:
    """The outcome of one check.

    ``examples`` counts the examples run (shrinking included), ``worlds`` the distinct worlds
    simulated; ``message`` says what failed, or why the check did not apply (or, for a
    statistical check that passed, its tally: :mod:`ifgm_ref.oracle.robust`); ``artifacts`` is
    the folder holding the counterexample of a failure.
    """

    check: str
    status: Status
    examples: int = 0
    worlds: int = 0
    seconds: float = 0.0
    message: str = ""
    artifacts: Path | None = None

    @property
    def ok(self) -> bool:
        """Whether this verdict lets the run pass."""
        return self.status in (
            Status.PASSED,
            Status.NOT_EXERCISED,
            Status.EXPECTED_FAILURE,
            Status.NOT_APPLICABLE,
        )

    def line(self) -> str:
        """One line for a terminal."""
        counts = f"{self.examples} examples, {self.worlds} worlds, {self.seconds:.1f} s"
        text = f"{self.status.upper():<19} {self.check:<26} {counts}"
        if self.message:
            text += f"\n    {self.message}"
        if self.artifacts is not None:
            text += f"\n    counterexample: {self.artifacts}"
        return text


@dataclass(frozen=True)
class Report:
    """Every check's result for one implementation under one profile.

    A robustness run also says which noise levels it checked (``noise``, as
    :meth:`~ifgm_ref.sim.noise.NoiseLevels.tags` writes them: ``"none"`` when the implementation
    promised none) and which the implementation promises (``promised``); ``noise`` is ``None``
    for a noise-free run. ``engine`` names the engine the simulations ran on, and its body if
    one was chosen (:func:`engine_tag`). ``held_to`` says what a declared specification held
    the implementation to (:meth:`~.specification.Specification.held_to`; ``""``: none).
    """

    implementation: str
    profile: str
    results: tuple[CheckResult, ...] = field(default_factory=tuple)
    noise: str | None = None
    promised: str = "none"
    engine: str = "kinematic"
    held_to: str = ""

    @property
    def ok(self) -> bool:
        """Whether every check passed, failed as expected or did not apply."""
        return all(r.ok for r in self.results)

    def __getitem__(self, check: str) -> CheckResult:
        for result in self.results:
            if result.check == check:
                return result
        raise KeyError(check)

    def summary(self) -> str:
        """How much was checked and what came of it, in one line."""
        how = f"profile {self.profile}"
        if self.engine != "kinematic":
            how += f", engine {self.engine}"
        if self.noise is not None:
            how += f", noise {self.noise} checked, {self.promised} promised"
        return f"{self.implementation} ({how}): {tally(self.results)}: {verdicts(self.results)}"

    def text(self) -> str:
        """What a specification held it to (if any), every result's line, then the summary."""
        held = [self.held_to] if self.held_to else []
        return "\n".join([*held, *(r.line() for r in self.results), self.summary()])


def tally(results: Iterable[CheckResult]) -> str:
    """How much the checks that applied checked, in words.

    >>> tally([CheckResult("deterministic", Status.PASSED, 1, 1)])
    '1 property checked, 1 example, 1 world'
    >>> tally([CheckResult("a", Status.PASSED, 50, 50), CheckResult("b", Status.FAILED, 2, 2)])
    '2 properties checked, 52 examples, 52 worlds'
    """
    ran = [r for r in results if r.status is not Status.NOT_APPLICABLE]
    examples, worlds = sum(r.examples for r in ran), sum(r.worlds for r in ran)
    return (
        f"{_counted(len(ran), 'property', 'properties')} checked, "
        f"{_counted(examples, 'example')}, {_counted(worlds, 'world')}"
    )


def verdicts(results: Iterable[CheckResult]) -> str:
    """How many checks got each verdict, in the order met; those that met nothing to check
    ("not exercised") are counted apart from the passes.

    >>> verdicts([CheckResult("a", Status.PASSED), CheckResult("b", Status.NOT_EXERCISED),
    ...           CheckResult("c", Status.PASSED)])
    '2 passed, 1 not exercised'
    """
    counts = Counter(r.status for r in results)
    return ", ".join(f"{n} {status}" for status, n in counts.items())


def _counted(n: int, one: str, many: str | None = None) -> str:
    return f"{n} {one if n == 1 else many or one + 's'}"


def run_check(
    check: Check,
    impl: Implementation,
    profile: Profile | str = "quick",
    *,
    artifacts: str | Path | None = "oracle-failures",
    expected_failure: str | None = None,
    progress: Callable[[int], None] | None = None,
    level: Level | str | None = None,
) -> CheckResult:
    """Run one check against ``impl``; see :func:`check_planner`.

    A check of a level above ``level`` (:func:`~.check_types.levels_up_to`) is not applicable
    and does not run (:data:`ABOVE_LEVEL`); ``level=None`` runs a check of any level.
    """
    profile = profile_named(profile) if isinstance(profile, str) else profile
    levels = profile.levels(impl.promises) if check.kind is Kind.SIMULATION else None
    reason = (
        _level_reason(check, level) or check.applies(impl) or _noise_reason(check, profile, levels)
    )
    if reason is not None:
        return CheckResult(check.name, Status.NOT_APPLICABLE, message=reason)
    recorder = Recorder(sim=profile.sim(), robot=profile.robot, sensor=profile.sensor)
    explore = _explorer(check, impl, profile, levels, recorder, progress)
    started = time.perf_counter()
    failure: Exception | None = None
    try:
        with global_constants_only():  # the same examples in any install (stable_draws)
            explore()
    except (CheckFailed, Flaky) as err:
        failure = err
    except ImplementationError as err:
        return _error(check, recorder, started, str(err))
    except Exception as err:  # the oracle's own machinery broke: still a verdict, and a summary
        why = f"the check itself crashed (a bug in the oracle, not a verdict): {crash(err)}"
        return _error(check, recorder, started, why)
    seconds = time.perf_counter() - started
    common = (check.name, recorder.examples, len(recorder.worlds), seconds)
    if failure is None:
        missed = None if check.meets is None else check.meets.missed(recorder)
        if missed is not None:
            return _result(*common, Status.NOT_EXERCISED, missed)
        if expected_failure is not None:
            return _result(*common, Status.UNEXPECTED_PASS, f"expected to fail: {expected_failure}")
        return _result(*common, Status.PASSED, recorder.summary)
    message = str(failure).split("\n")[0]
    told = str(failure)  # the report file gets every line, the result the first
    if isinstance(failure, Flaky):
        told = message = f"nondeterministic: a failing example passed when replayed ({message})"
    folder = None
    if artifacts is not None and recorder.evidence is not None:
        folder = Path(artifacts) / slug(impl.label) / check.name
        write_evidence(folder, recorder.evidence, check, impl, told, sim=recorder.sim)
    if expected_failure is not None:
        message = f"{message} (expected: {expected_failure})"
        return _result(*common, Status.EXPECTED_FAILURE, message, folder)
    return _result(*common, Status.FAILED, message, folder)


def _error(check: Check, recorder: Recorder, started: float, message: str) -> CheckResult:
    """The verdict ``error`` of ``check``, with what it had run since ``started``."""
    seconds = time.perf_counter() - started
    return CheckResult(
        check.name, Status.ERROR, recorder.examples, len(recorder.worlds), seconds, message
    )


def _level_reason(check: Check, level: Level | str | None) -> str | None:
    """Why ``check`` does not apply in a run at ``level``: it belongs to a level above it
    (``None`` when it applies, and when ``level`` is ``None``).

    >>> _level_reason(CHECKS["agrees_with_reference"], "paper")[:36]
    'the reference level: --level referen'
    >>> _level_reason(CHECKS["agrees_with_reference"], "reference") is None
    True
    """
    if level is None or check.level in levels_up_to(level):
        return None
    return ABOVE_LEVEL.format(level=check.level)


def _noise_reason(check: Check, profile: Profile, levels: NoiseLevels | None) -> str | None:
    """Why simulation ``check`` does not apply in ``profile``'s robustness run: no noise
    ``levels`` to check at (``None`` when it applies, and in a noise-free run)."""
    if check.kind is Kind.SIMULATION and profile.is_robustness_run and levels is None:
        return "it promises no noise levels (Promises.noise); give some to check: --noise"
    return None


def _explorer(
    check: Check,
    impl: Implementation,
    profile: Profile,
    levels: NoiseLevels | None,
    recorder: Recorder,
    progress: Callable[[int], None] | None,
) -> Callable[[], None]:
    """What runs ``check``'s examples: Hypothesis (noisy examples at ``levels``, if any), or
    for a statistical check under noise, its seeded sample counted
    (:func:`~ifgm_ref.oracle.robust.run_statistical`)."""
    if levels is not None and check.sample is not None:
        first = profile.seed or 0
        n = profile.max_examples
        return functools.partial(run_statistical, check, impl, levels, n, first, recorder, progress)
    examples = check.strategy(impl)
    changed = (bool(profile.robot) or profile.sensor is not None) and check.kind is Kind.SIMULATION
    if changed:
        examples = examples.map(lambda drawn: with_world(drawn, recorder.robot_of))
    if levels is not None:
        examples = noisy_examples(examples, levels)

    @profile.settings()
    @given(examples)
    def prop(example: Any) -> None:
        check.test(impl, example, recorder)
        if progress is not None:
            progress(1)

    if levels is None and check.explicit is not None:
        for given_first in reversed(check.explicit()):
            if changed and in_feet(given_first):  # BARN's samples keep their robot, in metres
                given_first = with_world(given_first, recorder.robot_of)
            prop = example(given_first)(prop)
    return prop if profile.seed is None else seed(profile.seed)(prop)


def _pooled_check(
    name: str,
    impl: Implementation,
    profile: Profile | str,
    artifacts: str | Path | None,
    expected_failure: str | None,
) -> CheckResult:
    """Run one check in a worker process (checks are looked up by name: they hold lambdas)."""
    try:
        return run_check(
            CHECKS[name], impl, profile, artifacts=artifacts, expected_failure=expected_failure
        )
    finally:
        impl.close()


def _run_pooled(
    names: list[str],
    impl: Implementation,
    profile: Profile | str,
    artifacts: str | Path | None,
    expected: Mapping[str, str],
    jobs: int,
    finished: Callable[[CheckResult], CheckResult],
    stop_on_failure: bool,
    meanwhile: Callable[[], bool],
) -> dict[str, CheckResult]:
    """Run simulation checks in ``jobs`` worker processes (the platform's default start),
    and ``meanwhile`` here while they run; ``meanwhile`` returns ``False`` to stop them
    (a failure under ``stop_on_failure``)."""
    shipped = replace(impl, equations=None)  # modules do not pickle; equation checks run here
    done: dict[str, CheckResult] = {}
    # The reference level's check is the longest (two runs of every built-in world): first.
    first = sorted(names, key=lambda name: CHECKS[name].level is not Level.REFERENCE)
    with worker_pool(jobs) as pool:
        futures = {
            pool.submit(_pooled_check, n, shipped, profile, artifacts, expected.get(n)): n
            for n in first
        }
        if not meanwhile():
            for future in futures:
                future.cancel()
            return done
        for future in as_completed(futures):
            try:
                result = future.result()
            except Exception as err:  # the worker died (or its result did not unpickle)
                message = f"the worker process running it failed: {crash(err)}"
                result = CheckResult(futures[future], Status.ERROR, message=message)
            result = finished(result)
            done[futures[future]] = result
            if stop_on_failure and not result.ok:
                for other in futures:
                    other.cancel()
                break
    return done


def _result(
    check: str,
    examples: int,
    worlds: int,
    seconds: float,
    status: Status,
    message: str,
    folder: Path | None = None,
) -> CheckResult:
    return CheckResult(check, status, examples, worlds, seconds, message, folder)


def _implementation(
    planner: Callable[[], Planner] | Implementation | str,
    promises: Promises | str | None,
    equations: object | None,
) -> Implementation:
    if isinstance(planner, Implementation):
        return planner
    if isinstance(planner, str):
        return Implementation.from_spec(planner, promises=promises, equations=equations)
    name = getattr(planner, "__qualname__", None) or repr(planner)
    label = f"{getattr(planner, '__module__', '')}:{name}".lstrip(":")
    return Implementation(planner, label, promises_for(planner, label, promises), equations)


def check_planner(
    planner: Callable[[], Planner] | Implementation | str,
    *,
    profile: Profile | str = "quick",
    promises: Promises | str | None = None,
    equations: object | None = None,
    expected_failed_checks: Mapping[str, str] | None = None,
    checks: Iterable[str] | None = None,
    artifacts: str | Path | None = "oracle-failures",
    on_fail: str | None = None,
    progress: bool = False,
    stop_on_failure: bool = False,
    jobs: int = 1,
    noise: NoiseLevels | str | None = None,
    level: Level | str | None = None,
    spec: Specification | str | Path | None = None,
) -> Report:
    """Check a planner implementation against every property it promises.

    Parameters
    ----------
    planner : callable, Implementation or str
        A factory returning a new planner (a class will do), an :class:`Implementation`, or a
        spec: a built-in name or ``module:attribute``.
    profile : {"quick", "standard", "thorough", "robust", "brief"} or Profile, default "quick"
        Examples per check (50, 200, 1000; robust: 50 under the promised noise).
    promises : Promises or str, optional
        What it promises, or a built-in planner's name (default: what the planner declares).
    equations : object, optional
        A module or object exposing ``eq1_gap_midpoint`` ... to check eqs. (1)-(4).
    expected_failed_checks, checks : mapping of str to str, iterable of str, optional
        ``{check: reason}``: checks known to fail ("expected failure"); run only ``checks``.
    artifacts : path or None, default "oracle-failures"
        Where counterexamples are written (``None``: nowhere).
    on_fail : {None, "raise", "warn"}, default None
        Raise :class:`AssertionError` or warn when a check failed or errored.
    progress, stop_on_failure : bool, default False
        Print each result on stderr as it comes; stop at the first check that fails or errors.
    jobs : int, default 1
        Run the simulation checks in this many processes (same verdicts); the factory pickles.
    noise : NoiseLevels or str, optional
        Check under these noise levels (``"range=0.02"``, :mod:`~.robust`), not those promised.
    level : {"paper", "reference"}, default "paper"
        The paper's properties, or also ``agrees_with_reference``; a check above it is listed
        not applicable, saying how to run it (:data:`ABOVE_LEVEL`), as the pytest plugin does.
    spec : Specification or path, optional
        Its declared specification (TOML: promises, level, robot, sensor, dt, goal tolerance).

    Returns
    -------
    Report
        One :class:`CheckResult` per check, the noise levels checked, and a summary.
    """
    impl, profile, level, held_to = _declared(planner, promises, equations, profile, level, spec)
    expected = dict(expected_failed_checks or {})
    names, profile = _arguments(checks, expected, with_noise(profile, noise), jobs, level, on_fail)
    run = (names, impl, profile, artifacts, expected, jobs, progress, stop_on_failure, level)
    report = replace(_report(impl, profile, _run_checks(*run)), held_to=held_to)
    _act_on(report, on_fail)
    return report


def _declared(
    planner: Callable[[], Planner] | Implementation | str,
    promises: Promises | str | None,
    equations: object | None,
    profile: Profile | str,
    level: Level | str | None,
    spec: Specification | str | Path | None,
) -> tuple[Implementation, Profile | str, Level | str, str]:
    """The implementation, profile and level :func:`check_planner` runs, held to ``spec`` if
    given (:func:`~.specification.declared`), and what that holds it to (``""``: nothing)."""
    if spec is None:
        return _implementation(planner, promises, equations), profile, level or Level.PAPER, ""
    told = promises if promises is not None else Promises()  # the file's replace them
    return declared(spec, _implementation(planner, told, equations), profile, promises, level)


def _report(impl: Implementation, profile: Profile, done: tuple[CheckResult, ...]) -> Report:
    """The report of the results ``done``: the noise levels and the engine they ran under."""
    tags = noise_tags(profile, impl.promises)
    return Report(impl.label, profile.name, done, *tags, engine=engine_tag(profile))


def _arguments(
    checks: Iterable[str] | None,
    expected: Mapping[str, str],
    profile: Profile,
    jobs: int,
    level: Level | str,
    on_fail: str | None,
) -> tuple[list[str], Profile]:
    """Validate :func:`check_planner`'s arguments; return the names of the checks to run and
    the profile."""
    levels_up_to(level)  # an unknown level is refused
    if on_fail not in (None, "raise", "warn"):
        raise ParameterError(f"on_fail: must be 'raise', 'warn' or None, got {on_fail!r}")
    names = list(CHECKS) if checks is None else list(checks)
    unknown = [n for n in [*names, *expected] if n not in CHECKS]
    if unknown:
        raise ImplementationError(f"unknown check(s) {unknown}; known: {', '.join(CHECKS)}")
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ImplementationError(f"`jobs` must be an integer >= 1, got {jobs!r}")
    return names, profile


def _run_checks(
    names: list[str],
    impl: Implementation,
    profile: Profile,
    artifacts: str | Path | None,
    expected: Mapping[str, str],
    jobs: int,
    progress: bool,
    stop_on_failure: bool,
    level: Level | str,
) -> tuple[CheckResult, ...]:
    """Run the checks ``names`` on ``impl`` at ``level``: the simulation checks of that level in
    ``jobs`` worker processes when ``jobs > 1``, the others (all, when ``jobs == 1``) here, in
    order, while the workers run; return the results in the order of ``names`` (see
    :func:`check_planner`)."""

    def finished(result: CheckResult) -> CheckResult:
        if progress:
            print(result.line(), file=sys.stderr, flush=True)
        return result

    levels = levels_up_to(level)
    pooled = [n for n in names if CHECKS[n].kind is Kind.SIMULATION and CHECKS[n].level in levels]
    pooled = pooled if jobs > 1 else []
    done: dict[str, CheckResult] = {}

    def run_here() -> bool:
        """Run the checks not pooled; ``False`` if one failed and that stops the run."""
        for name in names:
            if name in pooled:
                continue
            result = run_check(
                CHECKS[name],
                impl,
                profile,
                artifacts=artifacts,
                expected_failure=expected.get(name),
                level=level,
            )
            done[name] = finished(result)
            if stop_on_failure and not result.ok:
                return False
        return True

    if pooled:
        done.update(
            _run_pooled(
                pooled, impl, profile, artifacts, expected, jobs, finished, stop_on_failure,
                run_here,
            )
        )  # fmt: skip
    else:
        run_here()
    return tuple(done[n] for n in names if n in done)


def _act_on(report: Report, on_fail: str | None) -> None:
    """Raise :class:`AssertionError` (``on_fail="raise"``) or warn (``"warn"``, pointing at
    :func:`check_planner`'s caller) when ``report`` is not ok."""
    if not report.ok and on_fail is not None:
        if on_fail == "raise":
            raise AssertionError(report.text())
        import warnings

        warnings.warn(report.text(), stacklevel=3)


__all__ = [
    "ABOVE_LEVEL",
    "CheckResult",
    "Report",
    "Status",
    "check_planner",
    "crash",
    "run_check",
    "tally",
    "verdicts",
    "write_evidence",
]
