"""The oracle as a new user meets it (issue 14): ``ifgm-ref oracle`` and ``serve`` options,
what a terminal shows, and a report that always comes back, even when a check crashes."""

from __future__ import annotations

import os
import pty
import select
import shlex
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest
from hypothesis import strategies as st

from ifgm_ref.oracle.check_types import Check, Kind
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.equation_checks import NO_EQUATIONS, NO_EQUATIONS_PROGRAM
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.runner import (
    ABOVE_LEVEL,
    Status,
    check_planner,
    crash,
    run_check,
)
from tests.test_cli import run_cli

GOAL_SEEKER = Path(__file__).resolve().parent.parent / "examples" / "goal_seeker.py"
EQ1 = ["--check", "eq1_gap_midpoint"]


# -- --equations -------------------------------------------------------------------------------


def test_equations_option_runs_the_equation_checks() -> None:
    done = run_cli("oracle", "--planner", "ifgm", *EQ1, "--equations", "ifgm_ref.paper.equations")
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("PASSED              eq1_gap_midpoint           50 examples")


def test_equations_may_be_a_module_attribute(tmp_path: Path) -> None:
    """Given, they are checked instead of the reference's, which a built-in planner gets by
    default (:func:`test_a_built_in_planner_gets_the_reference_equations_by_default`)."""
    (tmp_path / "my_port_eqs.py").write_text(
        "from types import SimpleNamespace\n\n"
        "EQUATIONS = SimpleNamespace(eq1_gap_midpoint=lambda p1, p2: (p1[0], p1[1]))\n"
    )
    done = run_cli(
        "oracle", "--planner", "ifgm", *EQ1, "--equations", "my_port_eqs:EQUATIONS", cwd=tmp_path
    )
    assert done.returncode == 1  # found, and its eq. (1) is wrong
    assert "FAILED              eq1_gap_midpoint" in done.stdout
    assert "but should be" in done.stdout


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("no_such_eqs_xyz", "cannot import 'no_such_eqs_xyz': No module named 'no_such_eqs_xyz'"),
        ("math", "'math' has none of the equation functions eq1_gap_midpoint, eq2_gap_angle"),
        (
            "ifgm_ref.paper.equations:nope",
            "module 'ifgm_ref.paper.equations' has no attribute 'nope'",
        ),
    ],
)
def test_equations_that_cannot_be_loaded_are_a_one_line_error(spec: str, message: str) -> None:
    done = run_cli("oracle", "--planner", "ifgm", *EQ1, "--equations", spec)
    assert done.returncode == 2
    assert len(done.stderr.splitlines()) == 1
    assert done.stderr.startswith(f"ifgm-ref: error: {message}")
    assert done.stdout == ""


@pytest.mark.parametrize("planner", ["ifgm", "fgm"])
def test_a_built_in_planner_gets_the_reference_equations_by_default(planner: str) -> None:
    """Issue 45: a built-in planner's equations are the reference's, checked without
    ``--equations`` rather than reported not applicable seven times."""
    done = run_cli("oracle", "--planner", planner, *EQ1)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("PASSED              eq1_gap_midpoint           50 examples")
    assert NO_EQUATIONS not in done.stdout + done.stderr


def test_without_equations_the_message_says_how_to_give_them() -> None:
    """A planner given as ``module:attribute``, even a built-in one's class, gets no
    equations by default: its module need not hold them."""
    done = run_cli("oracle", "--planner", "ifgm_ref.planners.ifgm:IFGMPlanner", *EQ1)
    assert done.returncode == 0
    assert "--equations MODULE (ifgm-ref oracle)" in NO_EQUATIONS
    assert done.stdout.splitlines()[:2] == [
        "NOT APPLICABLE      eq1_gap_midpoint           0 examples, 0 worlds, 0.0 s",
        f"    {NO_EQUATIONS}",
    ]


def test_a_program_is_pointed_to_the_vectors() -> None:
    done = run_cli("oracle", "--cmd", f"{sys.executable} {GOAL_SEEKER}", *EQ1)
    assert done.returncode == 0, done.stderr
    assert "`ifgm-ref vectors`" in NO_EQUATIONS_PROGRAM
    assert f"    {NO_EQUATIONS_PROGRAM}" in done.stdout.splitlines()


# -- one line per check in a terminal ----------------------------------------------------------


def _in_a_terminal(*args: str) -> str:
    """What a terminal shows of ``ifgm-ref ARGS`` (stdout and stderr on one pseudo-terminal)."""
    leader, follower = pty.openpty()
    with subprocess.Popen(
        [sys.executable, "-m", "ifgm_ref", *args],
        stdin=subprocess.DEVNULL,
        stdout=follower,
        stderr=follower,
    ) as process:
        os.close(follower)
        chunks = []
        while True:
            ready, _, _ = select.select([leader], [], [], 60)
            if not ready:
                break
            try:
                chunk = os.read(leader, 4096)
            except OSError:  # the program exited and closed its end
                break
            if not chunk:
                break
            chunks.append(chunk)
        process.wait(timeout=60)
    os.close(leader)
    return b"".join(chunks).decode().replace("\r\n", "\n")


def test_a_terminal_shows_each_check_once_and_the_summary() -> None:
    args = ["oracle", "--planner", "ifgm", "--equations", "ifgm_ref.paper.equations", "--jobs", "1"]
    args += [*EQ1, "--check", "eq2_gap_angle"]
    screen = _in_a_terminal(*args)
    assert screen.count("eq1_gap_midpoint") == 1, screen
    assert screen.count("eq2_gap_angle") == 1, screen
    assert screen.splitlines()[-1].startswith("ifgm (profile quick): 2 properties checked")
    captured = run_cli(*args)  # a script that captures stdout gets the whole report
    assert captured.stdout.count("PASSED") == 2
    assert captured.stderr.count("PASSED") == 2  # the progress
    assert captured.stdout.splitlines()[-1] == screen.splitlines()[-1]


def test_stdout_and_stderr_into_one_pipe_show_each_check_once() -> None:
    """Issue 45: ``ifgm-ref oracle ... 2>&1 | tail`` printed every check's line twice (the
    progress on stderr, the report on stdout): where both go to one place, stdout gets the
    summary only, as on a terminal."""
    args = [*EQ1, "--check", "eq2_gap_angle", "--check", "reports_unreachable", "--jobs", "1"]
    done = subprocess.run(
        [sys.executable, "-m", "ifgm_ref", "oracle", "--planner", "ifgm", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        timeout=120,
        check=False,
    )
    assert done.returncode == 0, done.stdout
    for check in ("eq1_gap_midpoint", "eq2_gap_angle", "reports_unreachable"):
        assert done.stdout.count(check) == 1, done.stdout
    assert done.stdout.count("it does not promise to report it") == 1, done.stdout
    assert done.stdout.splitlines()[-1].startswith("ifgm (profile quick): 2 properties checked")


# -- the same checks as the pytest plugin -----------------------------------------------------


def test_the_command_line_lists_the_checks_the_plugin_runs(pytester: pytest.Pytester) -> None:
    """Issue 45: at the paper level the plugin has a test for ``agrees_with_reference`` (skipped)
    that ``ifgm-ref oracle`` left out; now it reports every check the plugin has a test for,
    those of the reference level not applicable, saying how to run them."""
    done = run_cli("oracle", "--planner", "straight", "--profile", "brief", "--jobs", "1")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    listed = [line.split()[-7] for line in lines if line[:1].isupper() and " examples, " in line]
    assert listed == list(CHECKS)
    above = lines.index(next(line for line in lines if " agrees_with_reference " in line))
    assert lines[above].startswith("NOT APPLICABLE")
    assert lines[above + 1] == "    " + ABOVE_LEVEL.format(level="reference")
    collected = pytester.runpytest_inprocess(
        "--pyargs", "ifgm_ref.oracle", "--ifgm-impl", "straight", "--collect-only", "-q",
        "-k", "test_property", "-p", "no:cacheprovider",
    )  # fmt: skip
    ids = [line.split("[", 1)[1].rstrip("]") for line in collected.outlines if "[" in line]
    assert ids == listed


def test_the_suites_results_file_may_name_a_new_folder(tmp_path: Path) -> None:
    """``--results out/run.jsonl`` (README) in a fresh checkout: the folder is made before the
    run, as every command's outputs' are, not an error once the cases are chosen."""
    results = tmp_path / "out" / "run.jsonl"
    done = run_cli(
        "oracle", "--suite", "v1", "--tier", "quick", "--planner", "straight", "--promises",
        "ifgm", "--stop-on-failure", "--artifacts", str(tmp_path / "found"), "--results",
        str(results),
    )  # fmt: skip
    assert done.returncode == 1, done.stderr  # straight fails IFGM's first case, and stops
    assert '"verdict": "fail"' in results.read_text()


# -- a check that crashes is an error, and the report comes back -------------------------------


def _crashing_check(crash_it: Callable[[], None]) -> Check:
    def test(impl: Implementation, example: int, rec: object) -> None:
        crash_it()

    return Check(
        "crashes", "never crashes", Kind.EQUATION, lambda impl: st.integers(), test, lambda i: None
    )


def _index_error() -> None:
    [][0]


def _group() -> None:
    """Raise a group of two exceptions, each raised (and so located) first, as in ``checks``."""
    caught: list[Exception] = []
    for fail in (_index_error, lambda: {}["k"]):
        try:
            fail()
        except Exception as err:
            caught.append(err)
    raise ExceptionGroup("two", caught)


@pytest.mark.parametrize(
    ("crash_it", "message"),
    [
        (_index_error, "IndexError: list index out of range at tests/test_oracle_cli.py:"),
        (_group, "ExceptionGroup of 2: IndexError: list index out of range at tests/test_oracle"),
    ],
)
def test_a_check_that_crashes_is_an_error_naming_where(
    crash_it: Callable[[], None], message: str
) -> None:
    impl = Implementation.from_spec("ifgm")
    result = run_check(_crashing_check(crash_it), impl, artifacts=None)
    assert result.status is Status.ERROR
    assert "the check itself crashed" in result.message and message in result.message
    assert "\n" not in result.message


def test_check_planner_reports_a_crashed_check_with_the_summary(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setitem(CHECKS, "crashes", _crashing_check(_index_error))
    report = check_planner("ifgm", checks=["crashes"], artifacts=None)
    assert not report.ok and report["crashes"].status is Status.ERROR
    assert report.text().splitlines()[-1].endswith("1 error")


def test_crash_names_the_innermost_frame() -> None:
    def inner() -> None:
        raise KeyError("k")

    try:
        inner()
    except KeyError as err:
        line = inner.__code__.co_firstlineno + 1
        assert crash(err) == f"KeyError: 'k' at tests/test_oracle_cli.py:{line}"


# -- profiles ----------------------------------------------------------------------------------


def test_the_old_profile_name_default_still_works() -> None:
    report = check_planner("ifgm", profile="default", checks=["eq1_gap_midpoint"])
    assert report.profile == "standard"
    args = ["oracle", "--planner", "ifgm", *EQ1, "--equations", "ifgm_ref.paper.equations"]
    done = run_cli(*args, "--profile", "default")
    assert done.returncode == 0
    assert "ifgm-ref: note: profile 'default' is now called 'standard'" in done.stderr
    assert "200 examples" in done.stdout and "(profile standard)" in done.stdout
    assert "(profile quick)" in run_cli(*args).stdout  # quick is the default


def test_the_plugin_takes_the_old_profile_name(pytester: pytest.Pytester) -> None:
    result = pytester.runpytest_inprocess(
        "--pyargs", "ifgm_ref.oracle", "--ifgm-impl", "ifgm", "--ifgm-profile", "default",
        "--ifgm-equations", "ifgm_ref.paper.equations", "-k", "eq1_gap", "-p", "no:cacheprovider",
    )  # fmt: skip
    result.stdout.fnmatch_lines(["ifgm-ref oracle: profile standard (200 examples per check)*"])
    result.assert_outcomes(passed=1)


# -- a factory that makes no planner -----------------------------------------------------------


@pytest.mark.parametrize(
    "args",
    [
        ["oracle", "--planner", "os:getcwd"],
        ["serve", "--planner", "os:getcwd"],
        ["bench", "--planners", "ifgm,os:getcwd", "--per-class", "1"],
    ],
)
def test_a_factory_that_makes_no_planner_is_a_one_line_error(args: list[str]) -> None:
    done = run_cli(*args)
    assert done.returncode == 2
    assert done.stderr.splitlines() == [
        "ifgm-ref: error: 'os:getcwd' made a str, not a planner: it has no name, reset, step "
        "(see ifgm_ref.core.protocol.Planner)"
    ]


# -- a --cmd program's two timeouts (issue 24) -------------------------------------------------


def _slow_start(folder: Path, seconds: float) -> str:
    """The command line of the goal-seeker example that sleeps ``seconds`` before it starts."""
    script = folder / "slow_start.py"
    script.write_text(
        f"import runpy, sys, time\ntime.sleep({seconds!r})\nsys.argv = [{str(GOAL_SEEKER)!r}]\n"
        f"runpy.run_path({str(GOAL_SEEKER)!r}, run_name='__main__')\n"
    )
    return shlex.join([sys.executable, str(script)])


def test_simulate_waits_the_startup_timeout_for_the_first_reply(tmp_path: Path) -> None:
    done = run_cli("simulate", "free", "--cmd", _slow_start(tmp_path, 2.0), "--timeout", "1")
    assert done.returncode == 0, done.stderr
    assert "goal_reached (reached=True" in done.stdout


def test_simulate_names_the_startup_timeout_that_expired(tmp_path: Path) -> None:
    args = ["--timeout", "10", "--startup-timeout", "1.5"]
    done = run_cli("simulate", "free", "--cmd", _slow_start(tmp_path, 60.0), *args)
    assert done.returncode == 2 and done.stdout == ""
    assert len(done.stderr.splitlines()) == 1
    assert (
        "slow_start.py: no reply within 1.5 s to reset "
        "(the start-up timeout, --startup-timeout; program killed); no stderr output"
    ) in done.stderr


def test_oracle_names_the_startup_timeout_in_one_line(tmp_path: Path) -> None:
    args = ["--check", "converges_open", "--jobs", "1", "--timeout", "10"]
    args += ["--startup-timeout", "1", "--artifacts", str(tmp_path / "found")]
    done = run_cli("oracle", "--cmd", _slow_start(tmp_path, 60.0), *args)
    assert done.returncode == 2 and done.stdout == ""
    assert len(done.stderr.splitlines()) == 1
    assert done.stderr.startswith("ifgm-ref: error: ")
    assert done.stderr.rstrip().endswith(
        "no reply within 1.0 s to reset "
        "(the start-up timeout, --startup-timeout; program killed); no stderr output"
    )


@pytest.mark.parametrize(
    ("program", "message"),
    [
        ("no-such-program-xyz", "cannot start program 'no-such-program-xyz'"),
        ("GARBAGE", "reply to reset is not JSON: 'garbage'"),
    ],
)
def test_a_program_that_cannot_be_checked_is_one_line_not_an_error_per_check(
    tmp_path: Path, program: str, message: str
) -> None:
    """A program that cannot start or answers ``reset`` with garbage: bad input (exit 2), said
    once, not "11 properties checked ... 11 error"."""
    if program == "GARBAGE":
        script = tmp_path / "garbage.py"
        script.write_text("import sys\nfor line in sys.stdin:\n    print('garbage', flush=True)\n")
        program = shlex.join([sys.executable, str(script)])
    done = run_cli("oracle", "--cmd", program, "--artifacts", str(tmp_path / "found"))
    assert done.returncode == 2 and done.stdout == ""
    assert len(done.stderr.splitlines()) == 1 and message in done.stderr


@pytest.mark.parametrize(
    ("command", "option", "value", "message"),
    [
        ("oracle", "--startup-timeout", "0", "must be a finite number > 0, got '0'"),
        ("oracle", "--startup-timeout", "nan", "must be a finite number > 0, got 'nan'"),
        ("oracle", "--timeout", "-1", "must be a finite number > 0, got '-1'"),
        ("simulate", "--startup-timeout", "inf", "must be a finite number > 0, got 'inf'"),
        ("simulate", "--startup-timeout", "soon", "must be a finite number > 0, got 'soon'"),
    ],
)
def test_a_bad_timeout_is_a_one_line_error(
    command: str, option: str, value: str, message: str
) -> None:
    where = ["free"] if command == "simulate" else []
    done = run_cli(command, *where, "--cmd", "nothing-runs", option, value)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.splitlines() == [
        f"ifgm-ref: error: argument {option}: {message} (see ifgm-ref {command} --help)"
    ]


@pytest.mark.parametrize("jobs", ["0", "-2"])
def test_jobs_below_one_is_a_one_line_error_naming_the_option(jobs: str) -> None:
    done = run_cli("oracle", "--planner", "ifgm", "--jobs", jobs)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.splitlines() == [f"ifgm-ref: error: --jobs {jobs}: must be at least 1"]


def test_the_plugin_refuses_a_bad_startup_timeout(pytester: pytest.Pytester) -> None:
    result = pytester.runpytest_inprocess(
        "--pyargs", "ifgm_ref.oracle", "--ifgm-cmd", "nothing-runs",
        "--ifgm-startup-timeout", "0", "-p", "no:cacheprovider",
    )  # fmt: skip
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines(["*`startup_timeout` must be a finite number > 0, got 0.0*"])


def test_the_oracle_leaves_no_hypothesis_folder_where_it_runs(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Hypothesis keeps a cache in ``./.hypothesis`` by default; the oracle points it at the
    user's cache folder instead. (Since the oracle draws without local constants,
    ``ifgm_ref.oracle.stable_draws``, Hypothesis no longer caches the constants it found, so
    this run may write nothing at all: what is pinned is that nothing lands where it runs.)"""
    monkeypatch.delenv("HYPOTHESIS_STORAGE_DIRECTORY", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    work = tmp_path / "work"
    work.mkdir()
    done = run_cli(
        "oracle", "--planner", "ifgm", "--equations", "ifgm_ref.paper.equations", *EQ1, cwd=work
    )
    assert done.returncode == 0, done.stderr
    assert list(work.iterdir()) == []


def test_no_shrink_reports_the_failing_example_as_found(tmp_path: Path) -> None:
    """``--no-shrink`` drops Hypothesis's shrink phase: the failure is the same, found in fewer
    examples than with shrinking (which runs more to simplify it)."""
    counts = {}
    for flags in ((), ("--no-shrink",)):
        done = run_cli(
            "oracle", "--planner", "ifgm_ref.oracle.mutants:PointRobot", "--check",
            "converges_open", "--jobs", "1", "--artifacts", str(tmp_path / "out"), *flags,
        )  # fmt: skip
        assert done.returncode == 1, done.stderr
        line = done.stdout.splitlines()[0]
        assert line.split()[0] == "FAILED", line
        counts[flags] = int(line.split("converges_open")[1].split("examples")[0])
    assert counts[("--no-shrink",)] < counts[()], counts
