"""Every planner against the paper's claims: all arrive in easy worlds; in U and H shapes
IBA and IFGM arrive while FGM and APF are trapped (Table 1, section 5.2), never colliding."""

from __future__ import annotations

import pytest

from ifgm_ref.core.params import SimParams
from ifgm_ref.core.protocol import Planner
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import PLANNERS, make_planner
from ifgm_ref.sim.simulator import StopReason, simulate

#: The paper's planners. ``dwa``, BARN's baseline (it keeps a map, which the paper's methods do
#: not), is checked in tests/test_dwa.py, on BARN's worlds and on a built-in one.
AVOIDING = [name for name in PLANNERS if name not in ("straight", "dwa")]
#: Trapped means: stalled short of the goal, not collided, within this long (twice the
#: slowest arrival of IBA or IFGM in these worlds, about 70 s).
TRAP_TIME = SimParams(max_time=300.0)


def test_the_command_line_names_are_the_issue_s() -> None:
    assert set(AVOIDING) == {"bug1", "bug2", "distbug", "iba", "fgm", "ifgm", "apf"}
    assert set(PLANNERS) == {*AVOIDING, "straight", "dwa"}


@pytest.mark.parametrize("name", list(PLANNERS))
def test_every_planner_implements_the_protocol(name: str) -> None:
    planner = make_planner(name)
    assert isinstance(planner, Planner) and planner.name == name


@pytest.mark.parametrize("world", ["free", "post"])
@pytest.mark.parametrize("name", AVOIDING)
def test_every_planner_arrives_in_an_empty_world_and_past_one_obstacle(
    name: str, world: str
) -> None:
    result = simulate(resolve_world(world), make_planner(name)).result
    assert result.reached, (
        f"stop_reason={result.stop_reason}, but should be goal_reached [{name} in {world}]"
    )
    assert not result.collided and result.min_clearance > 0.0


@pytest.mark.paper("s3.critical_shapes", "s5.ifgm_u_h")
@pytest.mark.parametrize("world", ["u_trap", "h_block"])
@pytest.mark.parametrize("name", ["iba", "ifgm", "bug1", "bug2", "distbug"])
def test_boundary_followers_get_out_of_u_and_h(name: str, world: str) -> None:
    result = simulate(resolve_world(world), make_planner(name)).result
    assert result.reached and result.min_clearance > 0.0, f"{name} in {world}: {result}"


@pytest.mark.paper("t1.fgm_u", "t1.fgm_h", "t1.apf_u_h_symmetric")
@pytest.mark.parametrize("world", ["u_trap", "h_block"])
@pytest.mark.parametrize("name", ["fgm", "apf"])
def test_fgm_and_apf_are_trapped_in_u_and_h(name: str, world: str) -> None:
    """The documented failure: no collision, no arrival; the robot stalls (no progress)."""
    result = simulate(resolve_world(world), make_planner(name), TRAP_TIME).result
    assert result.stop_reason == StopReason.STALLED, f"{name} in {world}: {result}"
    assert not result.collided and result.min_clearance > 0.0


@pytest.mark.parametrize("name", AVOIDING)
def test_same_world_same_trace(name: str) -> None:
    world = resolve_world("wall_posts")
    sim = SimParams(max_time=60.0)
    assert (
        simulate(world, make_planner(name), sim).trace
        == simulate(world, make_planner(name), sim).trace
    )
