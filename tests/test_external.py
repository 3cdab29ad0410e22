"""Planners across a process boundary: ``ifgm-ref serve`` and :class:`ExternalPlanner`.

Through the wire a planner must behave bit for bit as in process, and a program that
misbehaves must be reported clearly and within the timeout, never hang the oracle.
"""

from __future__ import annotations

import dataclasses
import io
import math
import os
import pickle
import subprocess
import sys
import textwrap
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from ifgm_ref.apps.cli import main
from ifgm_ref.core.errors import ImplementationError, ParameterError
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.io.transport.external import ExternalFactory, ExternalPlanner
from ifgm_ref.io.transport.serve import serve
from ifgm_ref.io.transport.wire import bye_message, encode, observe_message, reset_message
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.planners.straight import StraightPlanner
from ifgm_ref.sim.simulator import Run, simulate

ROOT = Path(__file__).resolve().parent.parent
GOAL_SEEKER = ROOT / "examples" / "goal_seeker.py"
SERVE_IFGM = [sys.executable, "-m", "ifgm_ref", "serve", "--planner", "ifgm"]
#: The misbehaving programs' timeout, s: long enough for a Python start, short for a test.
TIMEOUT = 1.5
#: What a failure report may take beyond the timeout, s (killing, reaping, draining stderr).
SLACK = 2.0

START, GOAL = Pose(0.0, 0.0, 0.0), Point(10.0, 0.0)
SCAN = LaserScan(-0.5, 0.5, 0.5, 0.0, 15.0, [3.0, float("inf"), 4.0])


def observation(t: float = 0.0) -> Observation:
    return Observation(t, START, GOAL, SCAN)


# --- the same trajectory through the wire ---------------------------------------------------


@pytest.fixture(scope="module")
def served_runs() -> Iterator[dict[str, tuple[Run, int | None]]]:
    """u_trap then fig7a, both through one ``serve`` process (two episodes, one program)."""
    runs = {}
    with ExternalPlanner(SERVE_IFGM, name="ifgm") as planner:
        for name in ("u_trap", "fig7a"):
            run = simulate(resolve_world(name), planner)
            runs[name] = (run, planner.pid)
    yield runs


@pytest.mark.parametrize("world", ["u_trap", "fig7a"])
def test_serve_gives_the_in_process_trajectory_bit_for_bit(
    served_runs: dict[str, tuple[Run, int | None]], world: str
) -> None:
    served, _ = served_runs[world]
    local = simulate(resolve_world(world), IFGMPlanner())
    assert served.result == local.result and served.result.reached
    assert len(served.trace) == len(local.trace)
    for ours, theirs in zip(served.trace, local.trace, strict=True):
        for field in dataclasses.fields(ours):
            a, b = getattr(ours, field.name), getattr(theirs, field.name)
            where = (ours.t, field.name, a, b)
            if isinstance(b, float):  # to the bit: hex tells 0.0 from -0.0
                assert isinstance(a, float) and a.hex() == b.hex(), where
            else:  # a Behaviour or Branch enum travels as its string value
                assert a == b and (a is None) == (b is None), where


def test_episodes_share_one_program(served_runs: dict[str, tuple[Run, int | None]]) -> None:
    (_, first), (_, second) = served_runs["u_trap"], served_runs["fig7a"]
    assert first == second and first is not None


# --- a misbehaving program is reported, quickly ---------------------------------------------

PROGRAMS = {
    "exits_after_reset": """
        sys.stdin.readline()
        print("about to fail", file=sys.stderr)
        sys.exit(3)
    """,
    "hangs_after_ready": """
        sys.stdin.readline()
        send('{"type": "ready"}')
        time.sleep(60)
    """,
    "prints_garbage": """
        sys.stdin.readline()
        send('{"type": "ready"}')
        sys.stdin.readline()
        send("hello")
    """,
    "sends_nan": """
        sys.stdin.readline()
        send('{"type": "ready"}')
        sys.stdin.readline()
        send('{"type": "command", "heading": NaN, "speed": 1.0}')
    """,
    "wrong_type": """
        sys.stdin.readline()
        send('{"type": "ready"}')
        sys.stdin.readline()
        send('{"type": "ready"}')
    """,
    "no_speed": """
        sys.stdin.readline()
        send('{"type": "ready"}')
        sys.stdin.readline()
        send('{"type": "command", "heading": 0.5}')
    """,
    "bad_exit_at_bye": """
        for line in sys.stdin:
            kind = json.loads(line)["type"]
            if kind == "bye":
                print("bye?", file=sys.stderr)
                sys.exit(4)
            send('{"type": "ready"}' if kind == "reset" else
                 '{"type": "command", "heading": 0.0, "speed": 1.0}')
    """,
    "says_ready_twice": """
        sys.stdin.readline()
        send('{"type": "ready"}\\n{"type": "ready"}')
        time.sleep(60)
    """,
    "never_reads": """
        send('{"type": "ready"}')
        time.sleep(60)
    """,
    # Healthy, but slow to start and to exit (as an interpreter loading its imports and
    # tearing them down on a loaded machine): argv[1] s before reading, argv[2] after bye.
    "slow_to_start_and_exit": """
        time.sleep(float(sys.argv[1]))
        for line in sys.stdin:
            kind = json.loads(line)["type"]
            if kind == "bye":
                break
            send('{"type": "ready"}' if kind == "reset" else
                 '{"type": "command", "heading": 0.0, "speed": 1.0}')
        time.sleep(float(sys.argv[2]))
    """,
    "slow_second_ready": """
        sys.stdin.readline()
        send('{"type": "ready"}')
        sys.stdin.readline()
        time.sleep(60)
    """,
}
#: Makes an :class:`ExternalPlanner` for the named program of :data:`PROGRAMS`.
MakeProgram = Callable[..., ExternalPlanner]
PRELUDE = """
import json, sys, time

def send(text):
    sys.stdout.write(text + "\\n")
    sys.stdout.flush()
"""


@pytest.fixture
def program(tmp_path: Path) -> Iterator[MakeProgram]:
    """Make an :class:`ExternalPlanner` for one of :data:`PROGRAMS`; kill what it started."""
    made: list[ExternalPlanner] = []

    def make(name: str, *args: str, **kwargs: object) -> ExternalPlanner:
        path = tmp_path / f"{name}.py"
        path.write_text(PRELUDE + textwrap.dedent(PROGRAMS[name]))
        kwargs.setdefault("timeout", TIMEOUT)
        planner = ExternalPlanner([sys.executable, str(path), *args], **kwargs)
        made.append(planner)
        return planner

    yield make
    for planner in made:
        planner._kill()


def expect_failure(
    call: Callable[[], object], *phrases: str, within: float = TIMEOUT
) -> ImplementationError:
    """Run ``call``; it must raise ImplementationError within ``within`` s (and the slack for
    the report), its message holding ``phrases``."""
    began = time.monotonic()
    with pytest.raises(ImplementationError) as info:
        call()
    assert time.monotonic() - began < within + SLACK
    for phrase in phrases:
        assert phrase in str(info.value)
    return info.value


def test_program_exiting_is_reported_with_its_status_and_stderr(program: MakeProgram) -> None:
    planner = program("exits_after_reset")
    error = expect_failure(
        lambda: planner.reset(START, GOAL, EpisodeParams()),
        "program exited with status 3 before answering reset",
        "last stderr:\n    about to fail",
    )
    assert planner.failure is error and planner.pid is None


def test_hanging_program_is_killed_at_the_timeout(program: MakeProgram) -> None:
    planner = program("hangs_after_ready")
    planner.reset(START, GOAL, EpisodeParams())
    pid = planner.pid
    assert pid is not None
    error = expect_failure(
        lambda: planner.step(observation()),
        "no reply within 1.5 s to observe at t=0.0 s "
        "(the per-reply timeout, --timeout; program killed)",
    )
    assert not _alive(pid)
    # Broken for good: the same error at once, without waiting on the program again.
    began = time.monotonic()
    for call in (
        lambda: planner.step(observation(0.1)),
        lambda: planner.reset(START, GOAL, EpisodeParams()),
    ):
        with pytest.raises(ImplementationError) as info:
            call()
        assert info.value is error
    assert time.monotonic() - began < 0.1
    planner.close()  # nothing left to close; the failure was raised already


@pytest.mark.parametrize(
    ("name", "phrases"),
    [
        ("prints_garbage", ["reply to observe at t=0.0 s is not JSON: 'hello'"]),
        (
            "sends_nan",
            [
                "reply to observe at t=0.0 s contains NaN: "
                '\'{"type": "command", "heading": NaN, "speed": 1.0}\''
            ],
        ),
        (
            "wrong_type",
            [
                "reply to observe at t=0.0 s: type 'ready', but should be 'command'",
                'the reply: \'{"type": "ready"}\'',
            ],
        ),
        ("no_speed", ["reply to observe at t=0.0 s: command.speed: missing"]),
    ],
)
def test_bad_reply_is_quoted(program: MakeProgram, name: str, phrases: list[str]) -> None:
    planner = program(name)
    planner.reset(START, GOAL, EpisodeParams())
    expect_failure(lambda: planner.step(observation()), *phrases)
    assert planner.pid is None  # killed


def test_non_zero_exit_at_bye_is_a_failure(program: MakeProgram) -> None:
    planner = program("bad_exit_at_bye")
    planner.reset(START, GOAL, EpisodeParams())
    assert planner.step(observation()) == Command(0.0, 1.0)
    expect_failure(planner.close, "program exited with status 4 after bye", "bye?")


def test_context_manager_closes_and_checks_the_exit(program: MakeProgram) -> None:
    def session() -> None:
        with program("bad_exit_at_bye") as planner:
            planner.reset(START, GOAL, EpisodeParams())

    expect_failure(session, "exited with status 4 after bye")


def test_unasked_output_is_caught(program: MakeProgram) -> None:
    planner = program("says_ready_twice")
    planner.reset(START, GOAL, EpisodeParams())
    time.sleep(0.2)  # let the second line arrive
    expect_failure(
        lambda: planner.step(observation()),
        'program wrote a line nobody asked for before observe at t=0.0 s: \'{"type": "ready"}\'',
    )


def test_program_that_never_reads_cannot_block_the_oracle(program: MakeProgram) -> None:
    """Writes go through a thread: a full stdin pipe ends in the timeout, not a hang."""
    planner = program("never_reads")
    planner.reset(START, GOAL, EpisodeParams())
    big = LaserScan(-0.5, 0.5, 1.0 / 9999, 0.0, 15.0, [1.0] * 10000)  # ~50 kB a message
    expect_failure(
        lambda: [planner.step(Observation(0.0, START, GOAL, big)) for _ in range(10)],
        "no reply within 1.5 s",
    )


# --- the start-up timeout ---------------------------------------------------------------------

#: The start-up timeout of the tests that start or exit slowly, s: over twice their delay.
STARTUP = 3 * TIMEOUT


def test_first_reply_gets_the_startup_timeout(program: MakeProgram) -> None:
    """A start longer than the per-reply timeout, within the start-up one, is not a failure."""
    planner = program("slow_to_start_and_exit", str(TIMEOUT + 0.5), "0", startup_timeout=STARTUP)
    planner.reset(START, GOAL, EpisodeParams())  # waited longer than TIMEOUT for its ready
    assert planner.step(observation()) == Command(0.0, 1.0)
    planner.reset(START, GOAL, EpisodeParams())
    planner.close()
    assert planner.failure is None


def test_a_start_past_the_startup_timeout_names_it(program: MakeProgram) -> None:
    planner = program("slow_to_start_and_exit", "60", "0", startup_timeout=STARTUP)
    expect_failure(
        lambda: planner.reset(START, GOAL, EpisodeParams()),
        f"no reply within {STARTUP!r} s to reset "
        "(the start-up timeout, --startup-timeout; program killed)",
        within=STARTUP,
    )
    assert planner.pid is None


def test_every_start_of_the_program_gets_the_startup_timeout(program: MakeProgram) -> None:
    planner = program("slow_to_start_and_exit", str(TIMEOUT + 0.5), "0", startup_timeout=STARTUP)
    for _ in range(2):  # a reset after close starts the program again
        planner.reset(START, GOAL, EpisodeParams())
        planner.close()
    assert planner.failure is None


def test_the_exit_after_bye_gets_the_startup_timeout(program: MakeProgram) -> None:
    """Tearing a program down is as load-bound as starting it: the exit is not a reply."""
    planner = program("slow_to_start_and_exit", "0", str(TIMEOUT + 0.5), startup_timeout=STARTUP)
    planner.reset(START, GOAL, EpisodeParams())
    planner.close()  # waited longer than TIMEOUT for the exit
    assert planner.failure is None and planner.pid is None


def test_an_exit_past_the_startup_timeout_names_it(program: MakeProgram) -> None:
    planner = program("slow_to_start_and_exit", "0", "60", startup_timeout=STARTUP)
    planner.reset(START, GOAL, EpisodeParams())
    expect_failure(
        planner.close,
        f"program did not exit within {STARTUP!r} s after bye (the start-up timeout, "
        "--startup-timeout, which bounds the exit too; program killed)",
        within=STARTUP,
    )


def test_a_later_reset_gets_the_per_reply_timeout(program: MakeProgram) -> None:
    planner = program("slow_second_ready", startup_timeout=STARTUP)
    planner.reset(START, GOAL, EpisodeParams())
    expect_failure(
        lambda: planner.reset(START, GOAL, EpisodeParams()),
        "no reply within 1.5 s to reset (the per-reply timeout, --timeout; program killed)",
    )


@pytest.mark.parametrize(
    ("timeout", "startup_timeout", "expected"),
    [(10.0, None, 60.0), (100.0, None, 100.0), (10.0, 2.0, 2.0), (1, 30, 30.0)],
)
def test_startup_timeout_defaults_to_60_s_or_the_per_reply_one(
    timeout: float, startup_timeout: float | None, expected: float
) -> None:
    planner = ExternalPlanner("x", timeout=timeout, startup_timeout=startup_timeout)
    factory = ExternalFactory("x", timeout=timeout, startup_timeout=startup_timeout)
    impl = Implementation.from_command("x", timeout=timeout, startup_timeout=startup_timeout)
    made = pickle.loads(pickle.dumps(factory))()  # as a worker process gets it
    assert isinstance(impl.factory, ExternalFactory)
    for each in (planner, factory, made, impl.factory):
        assert (each.timeout, each.startup_timeout) == (float(timeout), expected)


def test_program_that_cannot_start_is_reported(tmp_path: Path) -> None:
    planner = ExternalPlanner([str(tmp_path / "nothing-here")], timeout=TIMEOUT)
    expect_failure(lambda: planner.reset(START, GOAL, EpisodeParams()), "cannot start program")


def test_step_before_reset_is_reported() -> None:
    with pytest.raises(ImplementationError, match="reset\\(\\) was not called"):
        ExternalPlanner("true").step(observation())


def test_stderr_is_copied_to_the_log(program: MakeProgram) -> None:
    log = io.StringIO()
    planner = program("exits_after_reset", log=log)
    expect_failure(lambda: planner.reset(START, GOAL, EpisodeParams()), "status 3")
    assert log.getvalue() == "about to fail\n"


def test_adapter_is_a_planner_with_argv_and_repr() -> None:
    planner = ExternalPlanner("python3 'my planner.py' --fast", timeout=2)
    assert isinstance(planner, Planner)
    assert planner.argv == ("python3", "my planner.py", "--fast")
    assert planner.name == "python3 'my planner.py' --fast"
    assert repr(planner) == (
        "ExternalPlanner(['python3', 'my planner.py', '--fast'], timeout=2.0, "
        "startup_timeout=60.0, name=\"python3 'my planner.py' --fast\") <not running>"
    )
    planner.close()  # never started: nothing to do


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"command": ""}, "`command` must be a non-empty"),
        ({"command": ["x"], "timeout": 0}, "`timeout` must be a finite number > 0, got 0"),
        ({"command": ["x"], "timeout": math.inf}, "`timeout` must be a finite .* got inf"),
        ({"command": ["x"], "timeout": True}, "`timeout` must be a finite .* got True"),
        ({"command": ["x"], "startup_timeout": -1.0}, "`startup_timeout` must be .* got -1.0"),
        ({"command": ["x"], "startup_timeout": math.nan}, "`startup_timeout` must .* got nan"),
        ({"command": ["x"], "startup_timeout": "60"}, "`startup_timeout` must .* got '60'"),
    ],
)
def test_adapter_arguments_are_checked(kwargs: dict[str, object], message: str) -> None:
    command = kwargs.pop("command")
    with pytest.raises(ParameterError, match=message):
        ExternalPlanner(command, **kwargs)  # type: ignore[arg-type]
    if kwargs:  # a factory and an implementation refuse it at once, not in a worker
        with pytest.raises(ParameterError, match=message):
            ExternalFactory(command, **kwargs)  # type: ignore[arg-type]
        with pytest.raises(ParameterError, match=message):
            Implementation.from_command(command, **kwargs)  # type: ignore[arg-type]


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


# --- the example program ----------------------------------------------------------------------


@pytest.mark.parametrize("world", ["free", "post"])
def test_goal_seeker_example_reaches_the_goal(world: str) -> None:
    with ExternalPlanner([sys.executable, str(GOAL_SEEKER)], name="goal_seeker") as planner:
        result = simulate(resolve_world(world), planner).result
    assert result.reached and not result.collided, result


def test_close_ends_the_program_and_a_reset_starts_it_again() -> None:
    planner = ExternalPlanner([sys.executable, str(GOAL_SEEKER)], timeout=10.0)
    planner.reset(START, GOAL, EpisodeParams())
    first = planner.pid
    assert first is not None and "running as pid" in repr(planner)
    planner.close()
    assert planner.pid is None and not _alive(first) and planner.failure is None
    planner.reset(START, GOAL, EpisodeParams())
    assert planner.pid not in (None, first)
    assert isinstance(planner.step(observation()), Command)
    planner.close()


def test_goal_seeker_example_uses_only_the_standard_library() -> None:
    text = GOAL_SEEKER.read_text()
    assert "ifgm_ref" not in text.split('"""', 2)[2]


# --- the serve side ---------------------------------------------------------------------------


def session(*messages: dict[str, object] | str) -> io.StringIO:
    lines = [m if isinstance(m, str) else encode(m) for m in messages]
    return io.StringIO("".join(line + "\n" for line in lines))


RESET = reset_message(START, GOAL, EpisodeParams())
OBSERVE = observe_message(observation())


def run_serve(stdin: io.StringIO, factory: object = StraightPlanner) -> tuple[int, str, str]:
    stdout, stderr = io.StringIO(), io.StringIO()
    status = serve(factory, stdin, stdout, stderr)  # type: ignore[arg-type]
    return status, stdout.getvalue(), stderr.getvalue()


def test_serve_answers_each_message_on_one_line() -> None:
    status, out, err = run_serve(session(RESET, OBSERVE, RESET, OBSERVE, bye_message()))
    assert status == 0 and err == ""
    replies = out.splitlines()
    assert replies[0] == replies[2] == '{"type": "ready"}'
    assert (
        replies[1]
        == replies[3]
        == (
            '{"type": "command", "heading": 0.0, "speed": 1.3221476510067114, '
            '"behaviour": "move_to_goal"}'
        )
    )


def test_serve_builds_a_fresh_planner_at_every_reset() -> None:
    built: list[StraightPlanner] = []

    def factory() -> StraightPlanner:
        built.append(StraightPlanner())
        return built[-1]

    assert run_serve(session(RESET, RESET, bye_message()), factory)[0] == 0
    assert len(built) == 2 and built[0] is not built[1]


@pytest.mark.parametrize(
    ("lines", "message"),
    [
        (["hello"], "line 1 is not JSON: 'hello'"),
        ([RESET, '{"type": "observe", "t": NaN}'], "line 2 contains NaN"),
        ([OBSERVE], "line 1 (observe): observe before the first reset"),
        ([RESET, {"type": "command"}], "line 2 (command): type 'command', but should be"),
        ([{"type": "hello"}], "line 1.type: 'hello', but should be one of"),
        ([{**RESET, "dt": -1}], "line 1 (reset): reset.dt: must be a finite number > 0, got -1"),
        ([RESET, {**OBSERVE, "pose": [0, 0]}], "line 2 (observe): observe.pose: must be an array"),
        ([RESET, OBSERVE], "end of input after 2 line(s), before bye"),
        ([{**RESET, "params": {"d_th": -1.0}}], "line 1 (reset): `d_th` must be"),
    ],
)
def test_serve_rejects_bad_input_with_one_line_and_status_2(
    lines: list[dict[str, object] | str], message: str
) -> None:
    status, _, err = run_serve(session(*lines), IFGMPlanner)
    assert status == 2
    assert err.count("\n") == 1 and err.startswith("ifgm-ref serve: error: ")
    assert message in err


class _Crashing(StraightPlanner):
    def step(self, observation: Observation) -> Command:
        print("thinking...")  # must not reach the protocol's stdout
        raise RuntimeError("boom")


class _Talkative(StraightPlanner):
    def step(self, observation: Observation) -> Command:
        print("thinking...")
        return super().step(observation)


def test_serve_reports_a_crashing_planner_with_status_1() -> None:
    status, out, err = run_serve(session(RESET, OBSERVE, bye_message()), _Crashing)
    assert status == 1 and out == '{"type": "ready"}\n'
    assert "Traceback" in err and "thinking..." in err
    assert err.splitlines()[-1] == (
        "ifgm-ref serve: error: line 2: _Crashing.step raised RuntimeError: boom"
    )


def test_serve_keeps_planner_prints_out_of_the_protocol() -> None:
    status, out, err = run_serve(session(RESET, OBSERVE, bye_message()), _Talkative)
    assert status == 0 and err == "thinking...\n"
    assert len(out.splitlines()) == 2


def test_serve_reports_a_command_json_cannot_carry() -> None:
    class NaNPlanner(StraightPlanner):
        def step(self, observation: Observation) -> Command:
            return Command(float("nan"), 1.0)

    status, _, err = run_serve(session(RESET, OBSERVE, bye_message()), NaNPlanner)
    assert status == 1
    assert "step() returned Command(heading=nan" in err and "which JSON cannot carry" in err


def test_serve_command_line_malformed_input(monkeypatch: pytest.MonkeyPatch) -> None:
    stdout, stderr = io.StringIO(), io.StringIO()
    monkeypatch.setattr(sys, "stdin", io.StringIO('{"type": "reset"\n'))
    monkeypatch.setattr(sys, "stdout", stdout)
    monkeypatch.setattr(sys, "stderr", stderr)
    assert main(["serve", "--planner", "ifgm"]) == 2
    assert stdout.getvalue() == ""
    assert stderr.getvalue().startswith("ifgm-ref serve: error: line 1 is not JSON: ")
    assert stderr.getvalue().count("\n") == 1


@pytest.mark.parametrize(
    ("planner", "message"),
    [
        ("bogus", "'bogus' is neither a built-in planner"),
        ("no_such_module_xyz:make", "cannot import 'no_such_module_xyz'"),
    ],
)
def test_serve_command_line_unknown_planner_is_one_line_and_exit_2(
    planner: str, message: str
) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "ifgm_ref", "serve", "--planner", planner],
        input="",
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.startswith("ifgm-ref: error: ") and done.stderr.count("\n") == 1
    assert message in done.stderr


def test_serve_command_line_loads_module_attribute() -> None:
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "ifgm_ref",
            "serve",
            "--planner",
            "ifgm_ref.planners.iba:IBAPlanner",
        ],
        input=encode(RESET) + "\n" + encode(bye_message()) + "\n",
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert (done.returncode, done.stdout, done.stderr) == (0, '{"type": "ready"}\n', "")


def test_the_documented_example_session_is_what_serve_answers() -> None:
    text = (ROOT / "docs" / "oracle-protocol.md").read_text()
    example = text.split("## Example", 1)[1].split("```text\n", 1)[1].split("```", 1)[0]
    lines = example.splitlines()
    sent = [line[2:] for line in lines if line.startswith("> ")]
    documented = [line[2:] for line in lines if line.startswith("< ")]
    assert len(sent) == 4 and len(documented) == 3
    status, out, err = run_serve(io.StringIO("".join(s + "\n" for s in sent)), IFGMPlanner)
    assert (status, err) == (0, "")
    assert out.splitlines() == documented
