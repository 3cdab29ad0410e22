"""The oracle's conformance suite: one test per property (drawn examples), or one per case of
a frozen suite version (``--ifgm-suite``), run against the implementation named by
``--ifgm-impl`` or ``--ifgm-cmd`` (see :mod:`ifgm_ref.oracle.pytest_plugin`)::

    pytest --pyargs ifgm_ref.oracle --ifgm-impl mypkg.module:make_planner
"""

from __future__ import annotations

import pytest

from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.pytest_plugin import OracleSession
from ifgm_ref.oracle.runner import Status
from ifgm_ref.oracle.suite.cases import Case


def test_property(check: str, ifgm_oracle: OracleSession) -> None:
    """The implementation under test has the property ``check`` (its sentence in the id's
    docstring: ``ifgm_ref.oracle.checks.CHECKS[check].sentence``)."""
    __tracebackhide__ = True
    result = ifgm_oracle.run(check)  # one of a level above the session's: not applicable
    if result.status is Status.NOT_APPLICABLE:
        pytest.skip(f"{check}: {result.message}")
    if result.status is Status.NOT_EXERCISED:
        pytest.skip(f"{check} not exercised: {result.message}")
    if result.status is Status.EXPECTED_FAILURE:
        pytest.xfail(result.message)
    if not result.ok:
        where = ""
        if result.artifacts is not None:
            where = f"\ncounterexample and replay: {result.artifacts}/report.md"
        pytest.fail(
            f"{check} ({CHECKS[check].sentence}) {result.status}: {result.message}{where}",
            pytrace=False,
        )


def test_case(case: Case, ifgm_oracle: OracleSession) -> None:
    """The implementation under test passes the suite's case ``case`` (``--ifgm-suite``)."""
    __tracebackhide__ = True
    check = CHECKS[case.check]
    if check.level not in ifgm_oracle.levels:
        pytest.skip(f"{case.id}: the {check.level} level (--ifgm-level reference)")
    result = ifgm_oracle.run_case(case)
    if result.verdict == "skip":
        pytest.skip(f"{case.id}: {result.reason}")
    if result.verdict != "pass":
        where = (
            "" if result.counterexample is None else f"\ncounterexample: {result.counterexample}"
        )
        pytest.fail(
            f"{case.id} ({check.sentence}) {result.verdict}: {result.reason}{where}", pytrace=False
        )
