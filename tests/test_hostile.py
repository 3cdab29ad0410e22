"""Programs that try to fool the oracle, or break it: each gets a clean verdict (issue 42).

A claimed arrival gets the world's verdict, never the program's. The battery after it
(``tests/hostile/``: a 100 MB line, a line that is not UTF-8, output without end, answers out
of turn, a closed stdout, a process left running, writes to the terminal, sleeps past every
timeout) gets a clean error or verdict, in bounded time and memory, leaving no process behind
and nothing outside the artifacts folder.
"""

from __future__ import annotations

import contextlib
import json
import os
import pty
import select
import shlex
import signal
import subprocess
import sys
import tempfile
import time
import tracemalloc
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.protocol import EpisodeParams, Observation
from ifgm_ref.io.transport.external import ExternalPlanner
from tests.test_cli import run_cli
from tests.test_external import GOAL, SCAN, START

HOSTILE = Path(__file__).resolve().parent / "hostile"


def command(program: str, *args: str) -> str:
    """The ``--cmd`` that runs ``tests/hostile/<program>.py ARGS`` with this Python."""
    return shlex.join([sys.executable, str(HOSTILE / f"{program}.py"), *args])


def test_a_claimed_arrival_fails_simulate_require_goal() -> None:
    done = run_cli("simulate", "free", "--cmd", command("claim_goal"), "--json", "--require-goal")
    result = json.loads(done.stdout)
    assert done.returncode == 1, done.stderr
    assert (result["reached"], result["stop_reason"]) == (False, "invalid_command")
    assert "stop='goal_reached'" in result["detail"]


def test_a_claimed_arrival_fails_the_convergence_checks() -> None:
    checks = ("converges_open", "converges_u", "collision_free")
    args = [arg for check in checks for arg in ("--check", check)]
    done = run_cli("oracle", "--cmd", command("claim_goal"), *args, "--no-shrink")
    verdicts = {line.split()[1]: line.split()[0] for line in done.stdout.splitlines()
                if line.split() and line.split()[0] in ("PASSED", "FAILED")}  # fmt: skip
    assert done.returncode == 1, done.stdout + done.stderr
    assert verdicts["converges_open"] == verdicts["converges_u"] == "FAILED", done.stdout


# --- the battery: each case a clean verdict, in bounded time and memory, leaving nothing -----

#: The longest any case may take, s: a hang guard, not a performance test (each case takes a
#: few seconds: the command line's start, and a timeout where one is the verdict).
HANG_GUARD = 30.0
#: How much more memory than a healthy run a hostile one may take, bytes: far less than the
#: 100 MB, or the endless output, the program writes, which must not be held.
MEMORY_SLACK = 32 << 20
#: Timeouts for the cases a timeout ends, s: small for a quick test, and for a standard-library
#: program's start (tens of ms) still a margin on a loaded machine.
QUICK = ("--timeout", "1", "--startup-timeout", "3")
#: Timeouts for the cases no timeout should end, s: generous, so that load cannot decide them.
PATIENT = ("--timeout", "10", "--startup-timeout", "20")
#: Runs ``argv[2:]`` in a new session whose controlling terminal is ``argv[1]`` (a session
#: leader that opens a terminal, having none, makes it its own).
ATTACH = (
    "import os, sys; os.close(os.open(sys.argv[1], os.O_RDWR)); os.execv(sys.argv[2], sys.argv[2:])"
)
#: What ``tests/hostile/writes_to_tty.py`` writes on a terminal.
NOTE = b"HOSTILE PROGRAM WAS HERE"


@dataclass(frozen=True)
class Ran:
    """How one run of the command line ended."""

    returncode: int
    stdout: str
    stderr: str
    seconds: float
    peak_rss: int  #: bytes: the largest of the command line and every process it waited for


def ifgm_ref(*args: str, cwd: Path, terminal: str | None = None) -> Ran:
    """Run ``ifgm-ref ARGS``: see :func:`run`."""
    return run([sys.executable, "-m", "ifgm_ref", *args], cwd=cwd, terminal=terminal)


def run(argv: list[str], *, cwd: Path, terminal: str | None = None) -> Ran:
    """Run ``argv`` in ``cwd``, in a session of its own (with ``terminal`` as its controlling
    terminal if given), with no input; kill it at twice :data:`HANG_GUARD`."""
    if terminal is not None:
        argv = [sys.executable, "-c", ATTACH, terminal, *argv]
    began = time.monotonic()
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        process = subprocess.Popen(
            argv, stdin=subprocess.DEVNULL, stdout=out, stderr=err, cwd=cwd,
            start_new_session=True,
        )  # fmt: skip
        while True:  # wait4, not wait: it tells the peak memory
            pid, status, usage = os.wait4(process.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() - began > 2 * HANG_GUARD:
                os.killpg(process.pid, signal.SIGKILL)
            time.sleep(0.02)
        process.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        return Ran(
            process.returncode,
            out.read().decode(),
            err.read().decode(),
            time.monotonic() - began,
            usage.ru_maxrss * (1 if sys.platform == "darwin" else 1024),
        )


@pytest.fixture(scope="module")
def healthy_rss(tmp_path_factory: pytest.TempPathFactory) -> int:
    """The peak memory of ``simulate`` with a program that misbehaves in no costly way, bytes."""
    cwd = tmp_path_factory.mktemp("healthy")
    ran = ifgm_ref("simulate", "free", "--cmd", command("claim_goal"), "--json", cwd=cwd)
    assert ran.returncode == 0, ran.stderr
    return ran.peak_rss


@pytest.fixture
def cwd(tmp_path: Path) -> Path:
    """An empty working folder for the command line, which it must leave empty (but for the
    artifacts folder it is told)."""
    folder = tmp_path / "work"
    folder.mkdir()
    return folder


def simulate(program: str, *args: str, cwd: Path, timeouts: tuple[str, ...] = PATIENT) -> Ran:
    """``simulate free`` with ``tests/hostile/<program>.py ARGS``: bounded, leaving nothing."""
    ran = ifgm_ref("simulate", "free", "--cmd", command(program, *args), "--json", *timeouts,
                   cwd=cwd)  # fmt: skip
    assert ran.seconds < HANG_GUARD, ran
    assert os.listdir(cwd) == []
    return ran


def refused(ran: Ran, program: str, *args: str) -> str:
    """The one error ``ran`` ended with, naming the program: a clean message, no traceback."""
    prefix = f"ifgm-ref: error: {command(program, *args)}: "
    assert (ran.returncode, ran.stdout) == (2, ""), ran
    assert ran.stderr.startswith(prefix) and "Traceback" not in ran.stderr, ran.stderr
    return ran.stderr.removeprefix(prefix)


def gone(pid_file: Path) -> bool:
    """Whether every process whose pid ``pid_file`` lists has ended (waiting up to 2 s for it
    to be reaped)."""
    pids = [int(line) for line in pid_file.read_text().split()]
    assert pids
    deadline = time.monotonic() + 2.0
    while True:
        alive = [pid for pid in pids if _alive(pid)]
        if not alive or time.monotonic() > deadline:
            return not alive
        time.sleep(0.05)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with contextlib.suppress(OSError):  # a zombie no one reaped has ended too
        if Path(f"/proc/{pid}/stat").read_text().split(") ")[-1].startswith("Z"):
            return False
    return True


TOO_LONG = "program wrote a line longer than 1048576 bytes in reply to observe at t=0.0 s, "
NOBODY_ASKED = "program wrote a line nobody asked for before observe at t=0.0 s: "
PID_FILE = "PID"  #: stands for a file for the program's pids in the arguments below

# --- through the adapter: every hostile program, each variant ---------------------------------

#: The adapter's timeouts for the programs below, s (the command line's QUICK, the start-up
#: one shorter still: none of these programs is slow to start but where that is the verdict).
TIMEOUT, STARTUP_TIMEOUT = 1.0, 2.0
#: What reporting a failure may take beyond the timeout that expired, s: killing, reaping,
#: draining stderr (and the program's start, on a loaded machine).
REPORT = 3.0
#: Each program, its arguments, how far the session goes (``reset``, ``observe`` -- a reset
#: and a step -- or ``bye``: a reset, a step and a close), and what the adapter raises, after
#: the program's name (None: nothing).
SESSIONS = [
    ("huge_line", [], "observe", TOO_LONG + "read no further (program killed); it began "
                                 '\'{"type": "command", "heading": 0.0, "speed": 1.0, "pad": "xxx'),
    ("endless_output", ["line"], "observe", TOO_LONG + "read no further (program killed); it "
                                           'began \'{"type": "command", "heading": 0.0, "spe'),
    ("endless_output", ["lines"], "observe", NOBODY_ASKED + '\'{"type": "ready"}\''),
    ("not_utf8", [], "observe", "reply to observe at t=0.0 s is not UTF-8 (byte 0xe9 at column "
                                '68): \'{"type": "command", "heading": 0.0, "speed": 1.0, '
                                '"behaviour": "caf\ufffd"}\''),
    ("out_of_order", ["command_first"], "reset", "reply to reset: type 'command', but should be "
                                                 "'ready'; the reply: '{\"type\": \"command\", "
                                                 '"heading": 0.0, "speed": 1.3221476510067114}\''),
    ("out_of_order", ["twice"], "observe", NOBODY_ASKED + '\'{"type": "ready"}\''),
    ("out_of_order", ["ready_again"], "observe", "reply to observe at t=0.0 s: type 'ready', but "
                                                 "should be 'command'; the reply: "
                                                 '\'{"type": "ready"}\''),
    ("closes_stdout", [], "observe", "program closed its stdout before answering observe at "
                                     "t=0.0 s (program killed); no stderr output"),
    ("leaves_a_child", [PID_FILE, "bye"], "bye", None),
    ("leaves_a_child", [PID_FILE, "exit"], "reset", "program exited with status 0 before "
                                                      "answering reset, but what it started held "
                                                      "its stdout open for 2.0 s (the start-up "
                                                      "timeout, --startup-timeout; its process "
                                                      "group killed); no stderr output"),
    ("sleeps", ["reset", PID_FILE], "reset", "no reply within 2.0 s to reset (the start-up "
                                               "timeout, --startup-timeout; program killed); no "
                                               "stderr output"),
    ("sleeps", ["observe", PID_FILE], "observe", "no reply within 1.0 s to observe at t=0.0 s "
                                                   "(the per-reply timeout, --timeout; program "
                                                   "killed); no stderr output"),
    ("sleeps", ["bye", PID_FILE], "bye", "program did not exit within 2.0 s after bye (the "
                                           "start-up timeout, --startup-timeout, which bounds "
                                           "the exit too; program killed); no stderr output"),
]  # fmt: skip


@pytest.mark.parametrize(
    ("program", "args", "until", "verdict"),
    SESSIONS,
    ids=[" ".join([program, *args]) for program, args, _, _ in SESSIONS],
)
def test_the_adapter_gives_each_hostile_program_a_clean_verdict(
    tmp_path: Path, program: str, args: list[str], until: str, verdict: str | None
) -> None:
    """Raised within the timeout that applies (and a few seconds more: the report), holding
    less than 4 MiB (however much the program writes), leaving no process behind."""
    pid_file = tmp_path / "pid"
    argv = [sys.executable, str(HOSTILE / f"{program}.py")]
    argv += [str(pid_file) if arg == PID_FILE else arg for arg in args]
    planner = ExternalPlanner(
        argv, name=program, cwd=tmp_path, timeout=TIMEOUT, startup_timeout=STARTUP_TIMEOUT
    )
    steps: list[Callable[[], object]] = [lambda: planner.reset(START, GOAL, EpisodeParams())]
    if until != "reset":
        steps.append(lambda: planner.step(Observation(0.0, START, GOAL, SCAN)))
    if until == "bye":
        steps.append(planner.close)
    tracemalloc.start()
    began = time.monotonic()
    try:
        for step in steps:
            if step is steps[-1] and args == ["lines"]:
                time.sleep(0.2)  # let its flood of lines reach the pipe
            step()
        raised = None
    except ImplementationError as err:
        raised = str(err)
    finally:
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        planner._kill()
    assert time.monotonic() - began < STARTUP_TIMEOUT + REPORT
    if verdict is None:
        assert raised is None
    else:  # a line too long is quoted to 200 characters: its start is enough here
        assert raised is not None and raised.startswith(f"{program}: {verdict}")
        assert raised == f"{program}: {verdict}" or verdict.startswith(TOO_LONG)
    assert peak < 4 << 20
    if PID_FILE in args:
        assert gone(pid_file)


# --- through the command line: each case once -------------------------------------------------


def test_a_100_mb_line_is_refused_at_1_mib_without_being_held(cwd: Path, healthy_rss: int) -> None:
    ran = simulate("huge_line", cwd=cwd)
    assert refused(ran, "huge_line").startswith(
        TOO_LONG + "read no further (program killed); it began "
        '\'{"type": "command", "heading": 0.0, "speed": 1.0, "pad": "xxxxxxxx'
    )
    assert ran.peak_rss < healthy_rss + MEMORY_SLACK


def test_the_oracle_reports_a_100_mb_line_as_an_error(cwd: Path) -> None:
    ran = oracle("huge_line", cwd=cwd)
    status, check, message = report(ran)
    assert (ran.returncode, status, check) == (1, "ERROR", "converges_open"), ran
    assert message.startswith(f"{command('huge_line')}: {TOO_LONG}read no further"), message
    assert "Traceback" not in ran.stdout + ran.stderr


def test_a_reply_that_is_not_utf8_is_refused(cwd: Path) -> None:
    ran = simulate("not_utf8", cwd=cwd)
    assert refused(ran, "not_utf8") == (
        "reply to observe at t=0.0 s is not UTF-8 (byte 0xe9 at column 68): "
        '\'{"type": "command", "heading": 0.0, "speed": 1.0, "behaviour": "caf\ufffd"}\'\n'
    )


def test_the_oracle_kills_what_a_program_leaves_running(cwd: Path, tmp_path: Path) -> None:
    """Started twice (the oracle's first look at it, then the check), and each time what it
    left running dies with it; the verdict is the world's (driving straight at the goal
    through the open world collides)."""
    pids = tmp_path / "pids"
    ran = oracle("leaves_a_child", str(pids), "bye", cwd=cwd)
    status, check, message = report(ran)
    assert (ran.returncode, status, check) == (1, "FAILED", "converges_open"), ran
    assert message.startswith("stop_reason='collision'"), message
    assert len(pids.read_text().split()) == 2 and gone(pids)


def test_a_program_sleeping_past_every_timeout_is_killed(cwd: Path, tmp_path: Path) -> None:
    pid = tmp_path / "pid"
    ran = simulate("sleeps", "observe", str(pid), cwd=cwd, timeouts=QUICK)
    assert refused(ran, "sleeps", "observe", str(pid)) == (
        "no reply within 1.0 s to observe at t=0.0 s (the per-reply timeout, --timeout; "
        "program killed); no stderr output\n"
    )
    assert gone(pid)


def test_a_program_cannot_write_to_the_terminal(cwd: Path) -> None:
    """Under a terminal of the test's own (a pseudo-terminal), the program, which writes to
    its terminal wherever it can, does when run as such; under the oracle, which starts it in
    a session of its own with no terminal, it cannot, and it is checked as a healthy one."""
    master, slave = pty.openpty()
    terminal = os.ttyname(slave)
    try:
        alone = run([sys.executable, str(HOSTILE / "writes_to_tty.py")], cwd=cwd, terminal=terminal)
        assert (alone.returncode, alone.stderr) == (0, "wrote to the terminal\n")
        assert NOTE in read_terminal(master)  # the control: this test sees such a write
        for file in os.listdir(cwd):
            os.remove(cwd / file)
        ran = ifgm_ref("simulate", "free", "--cmd", command("writes_to_tty"), "--json",
                       *PATIENT, cwd=cwd, terminal=terminal)  # fmt: skip
        assert ran.returncode == 0, ran
        assert json.loads(ran.stdout)["stop_reason"] == "goal_reached"
        assert read_terminal(master) == b""
        assert ran.seconds < HANG_GUARD and os.listdir(cwd) == []
    finally:
        os.close(master)
        os.close(slave)


def read_terminal(master: int) -> bytes:
    """What was written on the pseudo-terminal whose master end is ``master`` (waiting 0.2 s
    for a write in flight)."""
    data = b""
    while select.select([master], [], [], 0.2)[0]:
        try:
            chunk = os.read(master, 1 << 16)
        except OSError:  # no one holds the other end open any more
            break
        if not chunk:
            break
        data += chunk
    return data


def oracle(program: str, *args: str, cwd: Path, timeouts: tuple[str, ...] = PATIENT) -> Ran:
    """``oracle --check converges_open`` on ``tests/hostile/<program>.py ARGS``, with
    ``artifacts`` for artifacts: bounded, writing nothing else."""
    ran = ifgm_ref("oracle", "--cmd", command(program, *args), "--check", "converges_open",
                   "--no-shrink", "--artifacts", "artifacts", *timeouts, cwd=cwd)  # fmt: skip
    assert ran.seconds < HANG_GUARD, ran
    assert set(os.listdir(cwd)) <= {"artifacts"}
    return ran


def report(ran: Ran) -> tuple[str, str, str]:
    """The one check's status, name and message in the oracle's report."""
    first, message = ran.stdout.splitlines()[:2]
    status, check = first.split()[:2]
    return status, check, message.strip()
