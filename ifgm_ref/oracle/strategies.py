"""The oracle's world classes as Hypothesis strategies: failing worlds shrink.

Each strategy draws the worlds of one generator of :mod:`ifgm_ref.sim.worldgen.classes` through
Hypothesis (:func:`~ifgm_ref.sim.worldgen.draws.strategy`), so that every choice is labelled
and a failing world shrinks towards one simple obstacle straight on the start-goal line. The
benchmark samples the same generators from a seed instead
(:func:`ifgm_ref.sim.worldgen.classes.random_world`).

=========================  ============================================================
strategy                   worlds of (:mod:`ifgm_ref.sim.worldgen.classes`)
=========================  ============================================================
:func:`open_worlds`        ``open_world``: 1-4 simple convex obstacles
:func:`u_worlds`           ``u_world``: a U across the line, half of them the paper's trap
:func:`h_worlds`           ``h_world``: an H across the line, half of them the paper's trap
:func:`symmetric_worlds`   ``symmetric_world``: three equal obstacles (Figure 7)
:func:`mixed_worlds`       ``mixed_world``: two or three features in a row
:func:`enclosed_worlds`    ``enclosed_world``: the goal in a closed box (unsolvable)
:func:`gap_walls`          ``gap_wall``: a wall pierced by one gap, and the gap
:func:`placements`         ``placement``: a rigid motion (rotation and shift)
=========================  ============================================================

>>> from hypothesis import find
>>> find(open_worlds(), lambda world: len(world.obstacles) >= 2).name
'open'
"""

from __future__ import annotations

import functools
from collections.abc import Callable

from hypothesis import strategies as st

from ifgm_ref.core.errors import present
from ifgm_ref.io.barn import gazebo_task
from ifgm_ref.io.scenarios import BUILTIN_WORLDS, resolve_world
from ifgm_ref.sim.world import Polygon, World
from ifgm_ref.sim.worldgen.classes import (
    enclosed_world,
    gap_wall,
    h_world,
    mixed_world,
    open_world,
    placement,
    symmetric_world,
    u_world,
)
from ifgm_ref.sim.worldgen.draws import strategy

WorldClass = Callable[[], st.SearchStrategy[World]]


def open_worlds(*, max_obstacles: int = 4) -> st.SearchStrategy[World]:
    """Strategy of :func:`~ifgm_ref.sim.worldgen.classes.open_world`."""
    return strategy(functools.partial(open_world, max_obstacles=max_obstacles))


def u_worlds(*, max_clutter: int = 0) -> st.SearchStrategy[World]:
    """Strategy of :func:`~ifgm_ref.sim.worldgen.classes.u_world`."""
    return strategy(functools.partial(u_world, max_clutter=max_clutter))


def h_worlds(*, max_clutter: int = 0) -> st.SearchStrategy[World]:
    """Strategy of :func:`~ifgm_ref.sim.worldgen.classes.h_world`."""
    return strategy(functools.partial(h_world, max_clutter=max_clutter))


def symmetric_worlds() -> st.SearchStrategy[World]:
    """Strategy of :func:`~ifgm_ref.sim.worldgen.classes.symmetric_world`."""
    return strategy(symmetric_world)


def mixed_worlds() -> st.SearchStrategy[World]:
    """Strategy of :func:`~ifgm_ref.sim.worldgen.classes.mixed_world`."""
    return strategy(mixed_world)


def enclosed_worlds() -> st.SearchStrategy[World]:
    """Strategy of :func:`~ifgm_ref.sim.worldgen.classes.enclosed_world`."""
    return strategy(enclosed_world)


def gap_walls() -> st.SearchStrategy[tuple[World, Polygon]]:
    """Strategy of :func:`~ifgm_ref.sim.worldgen.classes.gap_wall`."""
    return strategy(gap_wall)


def placements() -> st.SearchStrategy[tuple[float, tuple[float, float]]]:
    """Strategy of :func:`~ifgm_ref.sim.worldgen.classes.placement`."""
    return strategy(placement)


#: The solvable classes (their strategies) by the names checks and reports use, those of
#: :data:`ifgm_ref.sim.worldgen.classes.GENERATORS`.
SOLVABLE_CLASSES: dict[str, WorldClass] = {
    "open": open_worlds,
    "u": u_worlds,
    "h": h_worlds,
    "symmetric": symmetric_worlds,
    "mixed": mixed_worlds,
}


def any_solvable_worlds() -> st.SearchStrategy[World]:
    """A world of any solvable class (open first, so failures shrink towards it)."""
    return st.one_of([make() for make in SOLVABLE_CLASSES.values()])


def builtin_worlds() -> list[World]:
    """The built-in worlds (``ifgm-ref worlds``: the paper's scenarios reconstructed, the U
    and H traps, the Figure 7 variants), in name order: explicit examples of a check."""
    return [resolve_world(name) for name in sorted(BUILTIN_WORLDS)]


#: BARN's worlds replayed by reference agreement: the four kept with the tests
#: (``tests/worlds/barn``), from the bundled set; 245 is one where IFGM needs Bug1's round.
BARN_SAMPLES = (1, 2, 4, 245)


def reference_worlds() -> list[World]:
    """The built-in worlds and :data:`BARN_SAMPLES` (BARN's obstacle fields, with the
    Jackal-sized robot and its LiDAR: :mod:`ifgm_ref.io.barn`): the explicit examples of
    reference agreement, run every time."""
    barn = [present(gazebo_task(f"barn:{n}"), "a BARN task").world for n in BARN_SAMPLES]
    return [*builtin_worlds(), *barn]
