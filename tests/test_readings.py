"""Readings as options (issue 26, item 3; ifgm_ref.planners.ifgm.readings): the reference IFGM
runs each reading the errata table leaves open, a port declares the one it takes, and
reference agreement compares it with the reference running that reading -- or says that
the reference cannot run it."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from ifgm_ref.core.errors import ImplementationError, ParameterError
from ifgm_ref.core.params import SimParams
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.oracle.agreement import compare, divergence_message, reference_episode
from ifgm_ref.oracle.implementation import Implementation, Promises, promises_of
from ifgm_ref.oracle.runner import check_planner
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.planners.ifgm.readings import (
    OPEN_READINGS,
    Readings,
    parse_readings,
    unrunnable,
)
from ifgm_ref.sim.convergence import time_bound
from ifgm_ref.sim.world import World
from ifgm_ref.sim.worldgen.classes import random_world
from tests.test_cli import run_cli

#: For each reading other than ours, a world (built-in, or class-seed drawn) where it changes
#: the reference's run away from a tie. Most built-in worlds meet symmetric obstacles
#: head-on on the line, where the side to go round and the widest of two gaps are exact
#: ties, and a port's other reading shows first at a tie there (``u_trap``, ``fig7a``).
WHERE_IT_SHOWS = {
    ("dead_end_side", "left"): "posts_narrow",
    ("dead_end_side", "right"): "wall_posts",
    ("gap_points", "means"): "mixed-0",
    ("gap_choice", "widest"): "mixed-0",
    ("leaving_rule", "free_path"): "mixed-0",
}


def _world(name: str) -> World:
    kind, _, seed = name.partition("-")
    return random_world(kind, int(seed)) if seed else resolve_world(name)


def _port(choices: dict[str, str], declared: bool) -> Implementation:
    """The reference running ``choices``, as a port that declares them or does not."""
    readings = Readings.declared(choices)
    promises = promises_of("ifgm")
    impl = Implementation(lambda: IFGMPlanner(readings), "port", promises)
    if declared:
        impl.declare_readings(choices)
    return impl


def test_every_reading_the_reference_runs_is_listed_and_shows_somewhere() -> None:
    """Every reading other than ours has a world where it changes the run (an option that
    changed nothing would be a name only), and ours is the default."""
    others = {(n, v) for n, reading in OPEN_READINGS.items() for v in reading.values[1:]}
    assert others == set(WHERE_IT_SHOWS)
    assert Readings.declared({}) == Readings()
    for name, reading in OPEN_READINGS.items():
        assert str(getattr(Readings(), name)) == reading.values[0]


@pytest.mark.parametrize(("choice", "world_name"), sorted(WHERE_IT_SHOWS.items()))
def test_a_port_declaring_its_reading_agrees_and_one_that_does_not_diverges(
    choice: tuple[str, str], world_name: str
) -> None:
    """Undeclared, the other reading is a divergence (no tie explains it); declared, the
    reference runs it too and every step agrees."""
    name, value = choice
    world = _world(world_name)
    sim = SimParams(max_time=time_bound(world))
    ours = reference_episode(world, sim)
    found = compare(_port({name: value}, declared=False), ours, world_name)
    assert found.diverged, found
    theirs = reference_episode(world, sim, Readings.declared({name: value}))
    assert theirs.run.trace != ours.run.trace
    found = compare(_port({name: value}, declared=True), theirs, world_name)
    assert found.differs is None, divergence_message(theirs, found, world_name)
    assert found.steps == len(theirs.recording.steps)


def test_a_program_serving_a_reading_agrees_with_the_reference_running_it() -> None:
    """``ifgm-ref serve --reading`` runs the reading over the protocol, step for step."""
    world = resolve_world("u_trap")
    readings = Readings.declared({"dead_end_side": "right"})
    reference = reference_episode(world, SimParams(max_time=time_bound(world)), readings)
    command = f"{sys.executable} -m ifgm_ref serve --planner ifgm --reading dead_end_side=right"
    impl = Implementation.from_command(command, promises=promises_of("ifgm"))
    try:
        found = compare(impl, reference, "u_trap")
    finally:
        impl.close()
    assert found.differs is None and found.steps == len(reference.recording.steps)


def test_a_reading_the_reference_cannot_run_is_said_not_failed() -> None:
    declared = {"dead_end_side": "random"}
    assert unrunnable(declared) == (
        "the reference cannot run dead_end_side=random; it runs: freer, left, right"
    )
    impl = Implementation.from_spec("ifgm")
    impl.declare_readings(declared)
    report = check_planner(
        impl, level="reference", checks=["agrees_with_reference"], artifacts=None
    )
    (result,) = report.results
    assert result.status == "not applicable", result
    assert result.message == unrunnable(declared)
    with pytest.raises(ParameterError, match="cannot run dead_end_side=random"):
        Readings.declared(declared)


def test_an_unknown_name_is_a_mistake_said_at_once() -> None:
    with pytest.raises(ImplementationError, match="no open reading named dead_end_turn"):
        Promises(readings={"dead_end_turn": "left"})
    with pytest.raises(ParameterError, match="a reading is NAME=VALUE"):
        parse_readings(["dead_end_side:left"])


def test_the_command_line_takes_readings_and_refuses_them_where_they_cannot_apply(
    tmp_path: Path,
) -> None:
    done = run_cli("serve", "--planner", "fgm", "--reading", "gap_points=means")
    assert done.returncode == 2 and "--reading runs with --planner ifgm only" in done.stderr
    done = run_cli("oracle", "--planner", "ifgm", "--reading", "gap_point=means")
    assert done.returncode == 2 and "no open reading named gap_point" in done.stderr
    done = run_cli(
        "oracle", "--planner", "ifgm", "--level", "reference", "--check",
        "agrees_with_reference", "--reading", "leaving_rule=shortest", "--artifacts", str(tmp_path),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "the reference cannot run leaving_rule=shortest" in done.stdout
