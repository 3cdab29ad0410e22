"""The oracle as a pytest plugin (registered under the ``pytest11`` entry point).

Run the whole suite against a Python planner, one test id per property::

    pytest --pyargs ifgm_ref.oracle --ifgm-impl mypkg.module:make_planner

or against a program in any language that speaks the JSON-lines protocol
(``docs/oracle-protocol.md``)::

    pytest --pyargs ifgm_ref.oracle --ifgm-cmd "./my_planner --flag"

or, one test id per case id, the frozen cases of a suite version instead of drawn examples
(:mod:`ifgm_ref.oracle.suite`)::

    pytest --pyargs ifgm_ref.oracle --ifgm-cmd "./my_planner" --ifgm-suite v1 --ifgm-tier quick

pytest is not in the base install: the ``oracle`` extra brings it (``python3 -m pip install -e
".[oracle]"``), and ``python3 -m pytest`` runs the pytest of the Python that has ``ifgm_ref``
(a bare ``pytest`` may be another Python's, which does not know the ``--ifgm-*`` options). A
built-in planner given by name is checked with the reference's equations unless
``--ifgm-equations`` names others, as ``ifgm-ref oracle --planner`` is.

The pytest header names the implementation, the profile and the promises (and, in a
robustness run, ``--ifgm-profile robust`` or ``--ifgm-noise``, the noise levels checked and
promised; with ``--ifgm-engine mujoco``, the engine); a missing or unimportable
implementation stops the run with a usage error before any test runs; the terminal summary
says how much was checked.
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path
from typing import Any

import pytest

from ifgm_ref.core.errors import IfgmRefError
from ifgm_ref.core.params import ENGINES
from ifgm_ref.io.transport.external import STARTUP_TIMEOUT, TIMEOUT
from ifgm_ref.oracle.check_types import Kind, Level, levels_up_to
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.equation_checks import load_equations
from ifgm_ref.oracle.implementation import (
    PROMISES,
    Implementation,
    Promises,
    default_equations,
)
from ifgm_ref.oracle.profiles import (
    PROFILE_ALIASES,
    PROFILES,
    Profile,
    engine_tag,
    noise_tags,
    on_engine,
    profile_named,
    with_noise,
)
from ifgm_ref.oracle.runner import CheckResult, run_check, tally, verdicts
from ifgm_ref.oracle.specification import (
    Specification,
    declared,
    load_specification,
    refuse_options,
)
from ifgm_ref.oracle.suite.cases import TIERS, Case
from ifgm_ref.oracle.suite.run import CaseResult, run_case
from ifgm_ref.oracle.suite.versions import load_suite
from ifgm_ref.planners.ifgm.readings import parse_readings
from ifgm_ref.sim.physics.bodies import BODIES

#: The test module whose items need an implementation.
SUITE = "test_conformance.py"


def pytest_addoption(parser: pytest.Parser) -> None:
    """The ``--ifgm-*`` options."""
    group = parser.getgroup("ifgm-ref oracle", "ifgm-ref oracle (pytest --pyargs ifgm_ref.oracle)")
    group.addoption(
        "--ifgm-impl",
        metavar="SPEC",
        help="the Python planner under test: a built-in name or module:attribute (a factory)",
    )
    group.addoption(
        "--ifgm-cmd",
        metavar="COMMAND",
        help="a program under test, speaking the JSON-lines protocol (docs/oracle-protocol.md)",
    )
    group.addoption(
        "--ifgm-profile",
        default="quick",
        choices=[*PROFILES, *PROFILE_ALIASES],
        help="examples per check: quick 50 (default), standard 200, thorough 1000, brief 10; "
        "robust: 50 under the noise levels the implementation promises ('default' is the old "
        "name of standard)",
    )
    group.addoption(
        "--ifgm-noise",
        metavar="KIND=LEVEL,...",
        help="check under these noise levels, in any profile (docs/oracle.md, 'Robustness')",
    )
    group.addoption(
        "--ifgm-promises",
        metavar="PLANNER",
        help="check what this built-in planner promises (default: what the planner declares)",
    )
    group.addoption(
        "--ifgm-spec",
        metavar="FILE.toml",
        help="the implementation's declared specification (as ifgm-ref oracle --spec): its "
        "promises, level, readings, goal tolerance, dt, sensor and robot; not with "
        "--ifgm-promises, --ifgm-level or --ifgm-reading",
    )
    group.addoption(
        "--ifgm-equations",
        metavar="MODULE",
        help="a module (or module:attribute) exposing eq1_gap_midpoint ... eq4_final_heading "
        "to check eqs. (1)-(4) (default: ifgm_ref.paper.equations for a built-in --ifgm-impl, none "
        "for any other)",
    )
    group.addoption(
        "--ifgm-xfails",
        metavar="FILE",
        help="expected failures: one check name per line, '# reason' after it",
    )
    group.addoption(
        "--ifgm-artifacts",
        default="oracle-failures",
        metavar="DIR",
        help="where counterexamples are written (default oracle-failures)",
    )
    _add_suite_options(group)
    _add_level_options(group)
    _add_engine_options(group)
    _add_timeout_options(group)


def _add_suite_options(group: pytest.OptionGroup) -> None:
    """``--ifgm-suite`` and ``--ifgm-tier``: frozen cases instead of drawn examples."""
    group.addoption(
        "--ifgm-suite",
        metavar="VERSION",
        help="run the frozen cases of this suite version, one test id per case id "
        "(test_case[converges_u/0003]), instead of drawing the simulation checks' examples",
    )
    group.addoption(
        "--ifgm-tier",
        default="full",
        choices=TIERS,
        help="with --ifgm-suite: the quick tier's cases only, or every case (default)",
    )


def _add_level_options(group: pytest.OptionGroup) -> None:
    """``--ifgm-level`` and the readings the implementation declares, ``--ifgm-reading``."""
    group.addoption(
        "--ifgm-level",
        choices=[str(level) for level in Level],
        help="paper (default): the paper's properties; reference: those and agreement with "
        "the reference IFGM step by step (agrees_with_reference)",
    )
    group.addoption(
        "--ifgm-reading",
        action="append",
        metavar="NAME=VALUE",
        help="the implementation's reading of one of the paper's open choices, where it is not "
        "ours (repeatable; as ifgm-ref oracle --reading)",
    )


def _add_engine_options(group: pytest.OptionGroup) -> None:
    """``--ifgm-engine`` and ``--ifgm-body``: what senses and moves the robot of every episode
    (docs/oracle.md, "On the physical robot")."""
    group.addoption(
        "--ifgm-engine",
        default=ENGINES[0],
        choices=ENGINES,
        help="what moves the robot: kinematic (default) or mujoco, a robot with mass "
        "(docs/oracle.md, 'On the physical robot')",
    )
    group.addoption(
        "--ifgm-body",
        choices=sorted(BODIES),
        help="with --ifgm-engine mujoco: the robot's body (default: the robot's own)",
    )


def _add_timeout_options(group: pytest.OptionGroup) -> None:
    """``--ifgm-timeout`` and ``--ifgm-startup-timeout``: how long a program may take to reply
    (:class:`~ifgm_ref.io.transport.external.ExternalPlanner`); checked when the session starts."""
    group.addoption(
        "--ifgm-timeout",
        type=float,
        default=TIMEOUT,
        metavar="SECONDS",
        help=f"per-reply timeout for --ifgm-cmd programs (default {TIMEOUT:g} s)",
    )
    group.addoption(
        "--ifgm-startup-timeout",
        type=float,
        default=None,
        metavar="SECONDS",
        help="timeout for an --ifgm-cmd program's first reply, start-up included, and its "
        f"exit (default {STARTUP_TIMEOUT:g} s, or --ifgm-timeout if longer)",
    )


class OracleSession:
    """The implementation under test and the results gathered in this pytest session."""

    def __init__(self, config: pytest.Config) -> None:
        self.config = config
        self.results: list[CheckResult] = []
        self.case_results: list[CaseResult] = []
        self.expected = _expected_failures(config.getoption("ifgm_xfails"))
        self.profile = _profile(config)
        level = config.getoption("ifgm_level") or Level.PAPER
        self.implementation = _implementation(config)
        self.spec = _specification(config)
        if self.spec is not None:  # its promises, level, robot, sensor, dt and goal tolerance
            held = declared(self.spec, self.implementation, self.profile)
            self.implementation, self.profile, level = held[:3]
        self.level = level
        self.levels = levels_up_to(level)

    def run_case(self, case: Case) -> CaseResult:
        """Run one suite case against the implementation under test."""
        result = run_case(case, self.implementation, Path(self.config.getoption("ifgm_artifacts")))
        self.case_results.append(result)
        return result

    def run(self, check: str) -> CheckResult:
        """Run ``check`` against the implementation under test."""
        result = run_check(
            CHECKS[check],
            self.implementation,
            self.profile,
            artifacts=self.config.getoption("ifgm_artifacts"),
            expected_failure=self.expected.get(check),
            level=self.level,  # a check above it is not applicable, as in the CLI's report
        )
        self.results.append(result)
        return result

    def close(self) -> None:
        """Stop an external program (``--ifgm-cmd``)."""
        self.implementation.close()


def _expected_failures(path: str | None) -> dict[str, str]:
    if path is None:
        return {}
    expected: dict[str, str] = {}
    for number, line in enumerate(Path(path).read_text().splitlines(), start=1):
        name, _, reason = line.partition("#")
        name = name.strip()
        if not name:
            continue
        if name not in CHECKS:
            raise pytest.UsageError(f"{path}:{number}: no check named {name!r}")
        expected[name] = reason.strip() or "listed in " + path
    return expected


def _implementation(config: pytest.Config) -> Implementation:
    spec, cmd = config.getoption("ifgm_impl"), config.getoption("ifgm_cmd")
    if (spec is None) == (cmd is None):
        raise pytest.UsageError(
            "the ifgm-ref oracle needs exactly one implementation to check: "
            "--ifgm-impl module:factory (or a built-in planner name) or --ifgm-cmd 'PROGRAM'"
        )
    promises = config.getoption("ifgm_promises")
    if config.getoption("ifgm_spec") is not None:
        promises = Promises()  # the file declares them (an option besides is refused)
    equations: object | None = None
    try:
        given = _equations(config)
        if given is not None:
            equations = load_equations(given)
        if spec is not None:
            impl = Implementation.from_spec(spec, promises=promises, equations=equations)
        else:
            impl = Implementation.from_command(
                cmd,
                timeout=config.getoption("ifgm_timeout"),
                startup_timeout=config.getoption("ifgm_startup_timeout"),
                promises=promises,
                equations=equations,
            )
        impl.declare_readings(parse_readings(config.getoption("ifgm_reading") or []))
        return impl
    except IfgmRefError as err:
        raise pytest.UsageError(f"ifgm-ref oracle: cannot load the implementation: {err}") from err


def _equations(config: pytest.Config) -> str | None:
    """The equations to check: ``--ifgm-equations``, or for a built-in ``--ifgm-impl`` the
    reference's (:func:`~ifgm_ref.oracle.implementation.default_equations`), as
    ``ifgm-ref oracle`` does; ``None``: none."""
    given: str | None = config.getoption("ifgm_equations")
    spec = config.getoption("ifgm_impl")
    if not given and spec is not None:
        return default_equations(spec)
    return given or None


def _specification(config: pytest.Config) -> Specification | None:
    """The specification of ``--ifgm-spec``, if given; an option that declares what the file
    declares is refused (:func:`~ifgm_ref.oracle.specification.refuse_options`)."""
    path = config.getoption("ifgm_spec")
    if path is None:
        return None
    try:
        spec = load_specification(path)
        given = ("ifgm_promises", "ifgm_level", "ifgm_reading")
        options = {"--" + name.replace("_", "-"): config.getoption(name) for name in given}
        refuse_options(spec.source, options)
    except IfgmRefError as err:
        raise pytest.UsageError(f"ifgm-ref oracle: --ifgm-spec: {err}") from err
    return spec


def _profile(config: pytest.Config) -> Profile:
    """The profile of ``--ifgm-profile``, with the levels of ``--ifgm-noise`` if given, on the
    engine of ``--ifgm-engine`` and ``--ifgm-body``."""
    try:
        profile = with_noise(config.getoption("ifgm_profile"), config.getoption("ifgm_noise"))
    except IfgmRefError as err:
        raise pytest.UsageError(f"ifgm-ref oracle: --ifgm-noise: {err}") from err
    engine, body = config.getoption("ifgm_engine"), config.getoption("ifgm_body")
    try:
        return on_engine(profile, engine, body)
    except IfgmRefError as err:
        raise pytest.UsageError(f"ifgm-ref oracle: --ifgm-engine {engine}: {err}") from err


def _suite_requested(items: list[pytest.Item]) -> bool:
    return any(item.path.name == SUITE for item in items)


def suite_cases(config: pytest.Config) -> list[Case]:
    """The cases of ``--ifgm-suite`` in ``--ifgm-tier`` (none without the option)."""
    version = config.getoption("ifgm_suite")
    if version is None:
        return []
    try:
        return load_suite(version).tier(config.getoption("ifgm_tier"))
    except IfgmRefError as err:
        raise pytest.UsageError(f"ifgm-ref oracle: --ifgm-suite {version}: {err}") from err


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    """One test per case of ``--ifgm-suite`` (``test_case[ID]``); without it, the drawn
    checks (``test_property[CHECK]``), with it, only those the suite does not hold."""
    if metafunc.definition.path.name != SUITE:
        return
    if "case" in metafunc.fixturenames:
        cases = suite_cases(metafunc.config)
        metafunc.parametrize("case", cases, ids=[case.id for case in cases])
    if "check" in metafunc.fixturenames:
        suite = metafunc.config.getoption("ifgm_suite") is not None
        checks = [n for n, c in CHECKS.items() if not (suite and c.kind is Kind.SIMULATION)]
        metafunc.parametrize("check", checks)


_KEY = pytest.StashKey[OracleSession]()


def pytest_collection_modifyitems(
    session: pytest.Session, config: pytest.Config, items: list[pytest.Item]
) -> None:
    """Load the implementation (loudly) as soon as the suite is collected."""
    if _suite_requested(items) and _KEY not in config.stash:
        config.stash[_KEY] = OracleSession(config)


@pytest.fixture(scope="session")
def ifgm_oracle(request: pytest.FixtureRequest) -> Any:
    """The :class:`OracleSession` of this run."""
    oracle = request.config.stash[_KEY]
    yield oracle
    oracle.close()


def pytest_report_header(config: pytest.Config) -> list[str]:
    """Name the implementation under test and the profile, "to catch typos"."""
    spec, cmd = config.getoption("ifgm_impl"), config.getoption("ifgm_cmd")
    if spec is None and cmd is None:
        return []
    try:
        profile = _profile(config)
    except pytest.UsageError:  # said once the suite is collected
        profile = profile_named(config.getoption("ifgm_profile"))
    promises = config.getoption("ifgm_promises") or (spec if spec in PROMISES else None)
    declared_in = _declared_in(config)
    promised = PROMISES.get(promises or ("ifgm" if cmd else ""), Promises())
    if declared_in is not None:
        promises, promised = f"declared in {declared_in.source}", declared_in.promises
    lines = [
        f"ifgm-ref oracle: implementation {spec or 'cmd: ' + cmd}",
        f"ifgm-ref oracle: profile {profile.name} ({profile.max_examples} examples per check), "
        f"promises {promises or 'declared by the planner'}, equations {_equations(config)}, "
        f"artifacts {config.getoption('ifgm_artifacts')}",
    ]
    checked, noise = noise_tags(profile, promised)
    if checked is not None:
        lines.append(f"ifgm-ref oracle: noise {checked} checked, {noise} promised")
    if profile.physical:
        lines.append(f"ifgm-ref oracle: engine {engine_tag(profile)}")
    if declared_in is not None:
        lines += [f"ifgm-ref oracle: {line}" for line in declared_in.held_to().splitlines()]
    return lines


def _declared_in(config: pytest.Config) -> Specification | None:
    """The specification of ``--ifgm-spec`` for the header (``None``: none, or a bad one,
    which is said once the suite is collected)."""
    try:
        return _specification(config)
    except pytest.UsageError:
        return None


def pytest_terminal_summary(terminalreporter: Any, exitstatus: int, config: pytest.Config) -> None:
    """Say how much was checked."""
    if _KEY not in config.stash:
        return
    cases = config.stash[_KEY].case_results
    if cases:
        terminalreporter.write_sep("-", f"ifgm-ref oracle: suite {config.getoption('ifgm_suite')}")
        counts = Counter(result.verdict for result in cases)
        terminalreporter.write_line(", ".join(f"{n} {v}" for v, n in counts.items()) + " cases")
    results = config.stash[_KEY].results
    if not results:
        return
    terminalreporter.write_sep("-", "ifgm-ref oracle")
    for result in results:
        terminalreporter.write_line(result.line())
    label = config.stash[_KEY].implementation.label
    terminalreporter.write_line(f"{label}: {tally(results)}: {verdicts(results)}")
