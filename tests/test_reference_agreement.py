"""The reference level of the oracle (ifgm_ref.oracle.agreement, issue 26): the reference and
its faithful ports agree with it step by step, every broken variant diverges at the step
where it first differs, and a tie ends the comparison only where a decision was on its
threshold."""

from __future__ import annotations

import functools
import math
import sys
from dataclasses import replace

import numpy as np
import pytest

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.io.scenarios import BUILTIN_WORLDS, resolve_world
from ifgm_ref.oracle import agreement
from ifgm_ref.oracle.agreement import (
    HEADING_TOL,
    Comparison,
    ReferenceEpisode,
    compare,
    divergence_message,
    reference_episode,
)
from ifgm_ref.oracle.braking import with_dynamics
from ifgm_ref.oracle.checks import checks_at
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.mutants import MUTANTS
from ifgm_ref.oracle.runner import check_planner
from ifgm_ref.oracle.strategies import BARN_SAMPLES, SOLVABLE_CLASSES, reference_worlds
from ifgm_ref.oracle.variants import VARIANTS
from ifgm_ref.planners.ifgm.margins import DECISIONS, _tracking_margin
from ifgm_ref.planners.ifgm.planner import IFGMPlanner, nearest_remembered
from ifgm_ref.planners.sight import BoundaryParams, Episode, Sight
from ifgm_ref.sim.convergence import time_bound
from ifgm_ref.sim.worldgen.classes import random_world

#: Worlds that take IFGM through every branch of Figure 3 between them.
WORLDS = ("u_trap", "h_block", "fig7a", "post", "wall_posts", "offset_box", "scenario1")


#: Worlds drawn with explicit seeds, three of each class: goals in every direction.
DRAWN = tuple(f"{kind}-{seed}" for kind in SOLVABLE_CLASSES for seed in range(3))
#: Drawn worlds whose robot brakes in one radius from top speed and responds within half a
#: step (the oracle's ``stops_in_time`` dynamics): where the braking governor acts.
BRAKED = tuple(f"{name}-braked" for name in DRAWN[:: len(DRAWN) // 3])


@functools.cache
def episode(name: str) -> ReferenceEpisode:
    params = SimParams()
    if name in BRAKED:
        kind, seed = name.removesuffix("-braked").rsplit("-", 1)
        world = with_dynamics(random_world(kind, int(seed)), 1.0, 1.0, 0.5, params.dt)
    elif name in DRAWN:
        kind, seed = name.rsplit("-", 1)
        world = random_world(kind, int(seed))
    else:
        world = resolve_world(name)
    return reference_episode(world, replace(params, max_time=time_bound(world)))


def _compare(spec: str, name: str) -> Comparison:
    return compare(Implementation.from_spec(spec, promises="ifgm"), episode(name), name)


@pytest.mark.parametrize("spec", ["ifgm", *(f"ifgm_ref.oracle.variants:{v}" for v in
                                            ("Float32", "OppositeTies", "Twist"))])  # fmt: skip
def test_the_reference_and_its_faithful_variants_agree_with_it(spec: str) -> None:
    """Issue 26: the reference, a float32 port, the other choice at exact ties and velocity
    commands never diverge; the reference itself agrees at every step, with no tie."""
    for name in WORLDS:
        found = _compare(spec, name)
        assert not found.diverged, divergence_message(episode(name), found, name)
        if spec == "ifgm":
            assert found.differs is None and found.steps == len(episode(name).recording.steps)


def test_a_tie_the_other_way_ends_the_comparison_where_a_decision_was_on_its_threshold() -> None:
    """Between two posts on the line, mirrored, the other of two equal gaps is taken: a tie
    (equal widths, margin 0), not a divergence; with no tolerance for ties it would be one."""
    found = _compare("ifgm_ref.oracle.variants:OppositeTies", "posts_wide")
    assert found.tie is not None and found.tie[1] <= agreement.TIE, found
    assert found.tie[0] in DECISIONS
    assert found.differs is not None and found.differs.heading > HEADING_TOL


def test_without_the_tie_tolerance_the_same_flip_is_a_divergence(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(agreement, "TIE", -1.0)
    assert _compare("ifgm_ref.oracle.variants:OppositeTies", "posts_wide").diverged


@pytest.mark.parametrize("mutant", sorted(MUTANTS))
def test_every_broken_variant_diverges_at_the_first_step_that_differs(mutant: str) -> None:
    """Each broken variant of ``oracle/mutants.py`` diverges in a built-in or a drawn world
    (one whose robot brakes, for the governor's mutant); the step named is the first whose
    answer differs beyond the tolerances (every earlier one agreed)."""
    spec = f"ifgm_ref.oracle.mutants:{MUTANTS[mutant].__name__}"
    for name in (*BRAKED, *sorted(BUILTIN_WORLDS), *DRAWN):
        found = _compare(spec, name)
        if found.diverged:
            break
    else:
        pytest.fail(f"{mutant} agreed with the reference in every world")
    assert found.differs is not None
    assert found.steps == found.differs.step
    message = divergence_message(episode(name), found, name)
    assert message.startswith(f"step {found.differs.step} ")
    assert "no decision within" in message.split("\n")[0]


def test_the_followed_points_margin_is_that_of_tracking_it_from_the_last_one() -> None:
    """The followed point ``A`` was tracked from ``before``: of the points within ``jump`` of
    it, ``B`` (elsewhere in bearing) is the next choice; ``C``, nearer the robot than ``A``
    but just beyond ``jump`` from ``before``, is nearer still to being chosen; ``A``'s
    neighbour a hair away in bearing is no other choice at all."""
    before, a, b, c = Point(2.0, 1.0), Point(2.0, 1.1), Point(2.0, 1.3), Point(1.45, 1.0)
    neighbour = Point(2.0005, 1.1)
    episode = Episode.of(Point(10.0, 0.0), EpisodeParams(), BoundaryParams.paper())
    pose = Pose(0.0, 0.0, 0.0)

    def margin(*points: Point) -> float:
        sight = Sight(pose, episode, np.array(points, dtype=float), 0.0)
        return _tracking_margin(sight, a, before, 0.5, HEADING_TOL)

    assert margin(a, neighbour, b) == pytest.approx(math.hypot(*b) - math.hypot(*a))
    assert margin(a, neighbour, b, c) == pytest.approx(0.05)
    assert margin(a, neighbour) == math.inf


class _Untracked(IFGMPlanner):
    """Follows whichever remembered point is nearest, rather than the point tracked along its
    edge: mutants #48 and #53 of ``benchmarks/bench_mutation.py``, a valid reading of the
    paper that is not the reference's."""

    def _track(self, sight: Sight, followed: Point | None) -> Point | None:
        return nearest_remembered(sight, None, self.ifgm.jump)


def test_an_edge_followed_by_another_rule_diverges_though_every_wall_step_is_near_a_tie(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Along a wall the next point that is another choice lies only ``d delta**2 / 2``
    farther: under :data:`~agreement.TIE` every step would be a tie and excuse a port that
    tracks the edge otherwise. The followed point's own bound, the rounding, does not."""
    impl = Implementation(_Untracked, "untracked", promises_of("ifgm"))
    found = compare(impl, episode("fig7b"), "fig7b")
    assert found.diverged and found.differs is not None, found
    window = episode("fig7b").margins[found.differs.step - agreement.LOOKBACK :][:3]
    assert 0.0 < min(m.get("nearest_point", math.inf) for m in window) <= agreement.TIE
    monkeypatch.setattr(agreement, "POINT_TIE", agreement.TIE)
    again = compare(impl, episode("fig7b"), "fig7b")
    assert again.tie is not None and again.tie[0] == "nearest_point", again


@pytest.mark.parametrize("posing", ["fgm", "iba"])
def test_other_planners_posing_as_ifgm_diverge(posing: str) -> None:
    assert any(_compare(posing, name).diverged for name in WORLDS)


def test_a_wobble_of_a_degree_fails_at_the_first_step() -> None:
    """The heading-wobble variant passes the paper's properties (a degree of heading noise is
    a valid robot), but a degree is above :data:`HEADING_TOL`: step by step it is not the
    reference's answer, and the reference level says so at step 0."""
    found = _compare(f"ifgm_ref.oracle.variants:{VARIANTS['heading_wobble'].__name__}", "post")
    assert found.diverged and found.steps == 0


def test_the_levels_choose_the_checks() -> None:
    assert "agrees_with_reference" not in checks_at("paper")
    assert set(checks_at("reference")) == {*checks_at("paper"), "agrees_with_reference"}
    with pytest.raises(ImplementationError, match="unknown level 'strict'"):
        check_planner("ifgm", level="strict", artifacts=None)


def test_it_applies_only_to_what_follows_the_reference_ifgm() -> None:
    report = check_planner(
        "iba", checks=["agrees_with_reference"], artifacts=None, level="reference"
    )
    assert report.results[0].message.startswith("it does not claim to follow")


def test_every_decision_is_measured_somewhere_and_never_negative() -> None:
    """The margins of the reference's episodes in :data:`WORLDS`: each name is one of
    :data:`DECISIONS`, each value >= 0, and every decision is measured at some step."""
    seen: set[str] = set()
    for name in WORLDS:
        for found in episode(name).margins:
            assert set(found) <= set(DECISIONS) and min(found.values()) >= 0.0, found
            seen.update(found)
    assert seen == set(DECISIONS)


def test_barn_samples_are_replayed_every_time_and_the_reference_agrees_on_them() -> None:
    """Item 1's BARN samples: BARN's obstacle fields, with the Jackal-sized robot and its
    270-degree LiDAR, are explicit examples of the check, and the reference (as a program:
    ``ifgm-ref serve``) agrees with itself on every step of them."""
    worlds = {world.name: world for world in reference_worlds()}
    barn = [f"barn-{n:03d}" for n in BARN_SAMPLES]
    assert set(barn) <= set(worlds) and set(BUILTIN_WORLDS) <= set(worlds)
    impl = Implementation.from_command(f"{sys.executable} -m ifgm_ref serve --planner ifgm")
    try:
        for name in barn:
            world = worlds[name]
            assert world.sensor.fov > math.radians(135)
            reference = reference_episode(world, SimParams(max_time=time_bound(world)))
            assert reference.run.result.reached, name
            found = compare(impl, reference, name)
            assert found.differs is None and found.steps == len(reference.recording.steps)
    finally:
        impl.close()
