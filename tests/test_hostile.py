"""Programs that try to fool the oracle: each gets a clean verdict from the world, never from
what it claims (issue 42)."""

from __future__ import annotations

import json
import shlex
import sys
from pathlib import Path

from tests.test_cli import run_cli

HOSTILE = Path(__file__).resolve().parent / "hostile"


def command(program: str) -> str:
    """The ``--cmd`` that runs ``tests/hostile/<program>.py`` with this Python."""
    return shlex.join([sys.executable, str(HOSTILE / f"{program}.py")])


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
