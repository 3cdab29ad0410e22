"""One registry per concept (issue 44): a planner's promises are declared with it, and the
oracle holds an implementation to what it declares or is told, never to IFGM's by default;
the engines are one enumeration with one factory each."""

from __future__ import annotations

from pathlib import Path

import pytest

from ifgm_ref.core.errors import ImplementationError, ParameterError
from ifgm_ref.core.params import ENGINES, EngineName, SimParams
from ifgm_ref.oracle.implementation import PROMISES, Implementation, Promises, promises_of
from ifgm_ref.oracle.mutants import MUTANTS
from ifgm_ref.oracle.profiles import Profile
from ifgm_ref.oracle.runner import Status, check_planner
from ifgm_ref.oracle.variants import HeadingWobble
from ifgm_ref.planners import PLANNERS, declared_promises
from ifgm_ref.planners.iba import IBAPlanner
from ifgm_ref.sim.engine import ENGINE_FACTORIES
from tests.test_cli import run_cli

PORT = """\
from ifgm_ref.planners.straight import StraightPlanner


def make():
    return StraightPlanner()
"""


@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_every_registered_planner_declares_its_promises(name: str) -> None:
    """Registered with its promises, the oracle's are built from them, not kept apart."""
    declared = PLANNERS[name].promises
    assert isinstance(declared, Promises)
    assert declared_promises(PLANNERS[name].factory) == declared
    assert PROMISES[name] is declared
    assert Implementation.from_spec(name).promises == PROMISES[name]


def test_dwa_is_held_to_its_own_promises_not_ifgms() -> None:
    """``oracle --planner dwa`` judged DWA against IFGM's promises, reference level included."""
    dwa = Implementation.from_spec("dwa").promises
    assert dwa != promises_of("ifgm")
    assert dwa.reference is None and not dwa.turns_at_dead_ends and not dwa.converges_in
    assert dwa.collision_free and dwa.scale_invariant and dwa.stops_in_time  # measured
    report = check_planner("dwa", level="reference", checks=["agrees_with_reference"])
    (result,) = report.results
    assert result.status is Status.NOT_APPLICABLE, result.message


def test_dwa_declines_rigid_motion_invariance_and_every_other_planner_promises_it() -> None:
    """DWA's costmap is aligned with the world's axes: it fails the check (measured,
    docs/oracle.md) and does not promise it; the check is then not applicable to it."""
    assert {name for name, p in PROMISES.items() if not p.rigid_motion_invariant} == {"dwa"}
    (result,) = check_planner("dwa", checks=["rigid_motion_invariant"], artifacts=None).results
    assert result.status is Status.NOT_APPLICABLE
    assert result.message == "it does not promise rigid-motion invariance"


def test_an_unknown_module_must_be_told_what_it_promises(tmp_path: Path) -> None:
    (tmp_path / "my_port.py").write_text(PORT)
    done = run_cli("oracle", "--planner", "my_port:make", "--check", "collision_free", cwd=tmp_path)
    assert done.returncode == 2
    assert done.stderr.splitlines() == [
        "ifgm-ref: error: my_port:make declares no promises; say what it promises: "
        "--promises ifgm (ifgm-ref oracle), --ifgm-promises ifgm (pytest), "
        'promises="ifgm" (check_planner), a --spec file, or a promises attribute on its factory'
    ]
    told = ["--promises", "straight", "--check", "collision_free"]
    done = run_cli("oracle", "--planner", "my_port:make", *told, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("NOT APPLICABLE      collision_free")  # straight's promises
    with pytest.raises(ImplementationError, match="declares no promises"):
        check_planner(lambda: IBAPlanner(), checks=[])
    assert check_planner(lambda: IBAPlanner(), promises="iba", checks=[]).results == ()


def test_a_spec_file_says_what_an_unknown_module_promises(tmp_path: Path) -> None:
    (tmp_path / "my_port.py").write_text(PORT)
    (tmp_path / "port.toml").write_text('unit = "ft"\n[promises]\nlike = "straight"\n')
    args = ["--planner", "my_port:make", "--spec", "port.toml", "--check", "collision_free"]
    done = run_cli("oracle", *args, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "NOT APPLICABLE      collision_free" in done.stdout  # straight's promises


class _Declares(IBAPlanner):
    """A port that declares, on its class, that it keeps IFGM's promises."""

    promises = "ifgm"


class _DeclaresItsOwn:
    promises = Promises(converges_in=frozenset({"open"}))


class _DeclaresNonsense(IBAPlanner):
    promises = 3


def test_a_factory_declares_its_own_promises() -> None:
    """A ``promises`` attribute (a planner's name or a Promises) wins; a subclass of a
    registered planner keeps its registration's (the oracle's IFGM variants and mutants)."""
    assert declared_promises(_Declares) == PLANNERS["ifgm"].promises
    assert promises_of("ifgm") == Implementation.from_spec(f"{__name__}:_Declares").promises
    assert declared_promises(_DeclaresItsOwn) == Promises(converges_in=frozenset({"open"}))
    assert declared_promises(HeadingWobble) == PLANNERS["ifgm"].promises
    assert all(declared_promises(m) == PLANNERS["ifgm"].promises for m in MUTANTS.values())
    assert declared_promises(lambda: IBAPlanner()) is None
    with pytest.raises(ImplementationError, match="must be a Promises or a planner name"):
        Implementation.from_spec(f"{__name__}:_DeclaresNonsense")


def test_on_fail_is_checked_before_any_check_runs() -> None:
    with pytest.raises(ParameterError, match="on_fail: must be 'raise', 'warn' or None"):
        check_planner("ifgm", on_fail="rasie", checks=["collision_free"])


def test_every_engine_has_a_factory_and_the_body_rule_has_one_place() -> None:
    """Engines are one StrEnum with one registry; a body off the mujoco engine is refused by
    SimParams alone, in the same words wherever it enters."""
    assert set(ENGINE_FACTORIES) == set(EngineName) and ENGINES[0] is EngineName.KINEMATIC
    assert SimParams(engine="mujoco").engine is EngineName.MUJOCO
    message = "`body` applies to the mujoco engine only, got 'paper'"
    with pytest.raises(ParameterError, match=message):
        SimParams(body="paper")
    with pytest.raises(ParameterError, match=message):
        Profile("p", 1, body="paper")
    done = run_cli("simulate", "u_trap", "--body", "paper")
    assert done.returncode == 2
    assert done.stderr == f"ifgm-ref: error: {message}\n"
