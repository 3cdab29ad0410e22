"""Built-in worlds, by name; a built-in name works wherever a world-file path does.

``free`` is the paper's obstacle-free run (section 5.1, Figure 4a): 197 ft from source to
destination, covered in 149 s at the default speed.

The paper's scenarios are **reconstructions**: the paper gives no coordinates and its figures
are not in our copy, only the text of section 5. What the text fixes is kept (197 ft from
source to destination; two of the simple obstacles on the straight line; three symmetric
obstacles across the path, far apart or close together; a U opening towards the source, then
an H); sizes and positions are ours, chosen so that the robot of the default parameters meets
each situation the text describes:

* ``scenario1`` (Figures 4-6): a 8 x 40 ft rectangle and a hexagon of radius 14 ft on the
  line, a disc and a triangle off it;
* ``fig7a``/``fig7c`` (Figure 7, far apart): three discs / squares across the path with gaps of
  4.5 ft, wider than ``d_th`` = 3 ft; ``fig7b``/``fig7d`` (close together): gaps of 1.5 ft,
  narrower than ``d_th`` and than the robot (2 ft);
* ``scenario2`` (Figures 8-9): the U of ``u_trap`` opening towards the source, then the H of
  ``h_block`` with a cavity facing it.

The small demonstration worlds (one box, a post, three posts, a U, an H) are ours; they
exercise the planners on the paper's obstacle families and every branch of Figure 3.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ifgm_ref.core.errors import WorldError
from ifgm_ref.core.params import PAPER_FREE_DISTANCE_FT
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.io.worldfile import load_world
from ifgm_ref.sim.shapes import circle, h_shape, rectangle, regular_polygon, u_shape
from ifgm_ref.sim.world import Bounds, Obstacle, World

#: Start, goal and arena of the demonstration worlds: 60 ft along +x.
_DEMO_START = Pose(0.0, 0.0, 0.0)
_DEMO_GOAL = Point(60.0, 0.0)
_DEMO_BOUNDS = Bounds(-15.0, -35.0, 75.0, 35.0)


@dataclass(frozen=True)
class BuiltinWorld:
    """A named world: a one-line description and a function that builds it."""

    description: str
    build: Callable[[], World]


def _free() -> World:
    return World(
        name="free",
        start=Pose(0.0, 0.0, 0.0),
        goal=Point(PAPER_FREE_DISTANCE_FT, 0.0),
        bounds=Bounds(-20.0, -50.0, PAPER_FREE_DISTANCE_FT + 20.0, 50.0),
    )


def _demo(name: str, *obstacles: object) -> World:
    return World(
        name=name,
        start=_DEMO_START,
        goal=_DEMO_GOAL,
        obstacles=tuple(obstacles),  # type: ignore[arg-type]
        bounds=_DEMO_BOUNDS,
    )


#: The paper's source-to-destination distance (section 5.1) along +x, and its arena.
_PAPER_START = Pose(0.0, 0.0, 0.0)
_PAPER_GOAL = Point(PAPER_FREE_DISTANCE_FT, 0.0)
_PAPER_BOUNDS = Bounds(-20.0, -70.0, PAPER_FREE_DISTANCE_FT + 20.0, 70.0)
#: Figure 7's arena: 80 ft along +x, the three obstacles half way.
_FIG7_GOAL = Point(80.0, 0.0)
_FIG7_BOUNDS = Bounds(-15.0, -40.0, 95.0, 40.0)
#: Figure 7's gaps between neighbouring obstacles, ft: wider than d_th (3 ft) far apart,
#: narrower than the robot (2 ft) close together. (A gap between 2 ft and d_th looks wider
#: than it is from afar -- the visible borders are the tangent points, and the 1.8-degree
#: rays add up to half a foot -- so IFGM would first take it for a Case-1 gap.)
FIG7_GAP_FAR = 4.5
FIG7_GAP_NEAR = 1.5


def _paper(name: str, *obstacles: Obstacle) -> World:
    return World(
        name=name, start=_PAPER_START, goal=_PAPER_GOAL, obstacles=obstacles, bounds=_PAPER_BOUNDS
    )


def _fig7(name: str, size: float, gap: float, shape: Callable[[float], Obstacle]) -> World:
    """Three equal obstacles of width ``size`` centred on x = 40 ft, ``gap`` apart in y."""
    pitch = size + gap
    return World(
        name=name,
        start=_PAPER_START,
        goal=_FIG7_GOAL,
        obstacles=tuple(shape(k * pitch) for k in (-1, 0, 1)),
        bounds=_FIG7_BOUNDS,
    )


def _scenario1() -> World:
    return _paper(
        "scenario1",
        rectangle((60.0, 3.0), 8.0, 40.0),
        regular_polygon((135.0, -3.0), 14.0, 6),
        circle((100.0, 22.0), 5.0),
        regular_polygon((170.0, -20.0), 6.0, 3),
    )


def _scenario2() -> World:
    return _paper(
        "scenario2",
        u_shape((50.0, 0.0), width=24.0, depth=16.0, thickness=1.0, opening=math.pi),
        h_shape((130.0, 0.0), width=20.0, height=24.0, thickness=1.0, orientation=math.pi / 2),
    )


BUILTIN_WORLDS: dict[str, BuiltinWorld] = {
    "free": BuiltinWorld(
        "no obstacle; 197 ft from source to destination (paper section 5.1, Figure 4a)", _free
    ),
    "scenario1": BuiltinWorld(
        "paper Figures 4-6 (reconstruction): simple obstacles, two on the 197 ft line",
        _scenario1,
    ),
    "fig7a": BuiltinWorld(
        "paper Figure 7a (reconstruction): three discs across the path, 4.5 ft gaps (> d_th)",
        lambda: _fig7("fig7a", 8.0, FIG7_GAP_FAR, lambda y: circle((40.0, y), 4.0)),
    ),
    "fig7b": BuiltinWorld(
        "paper Figure 7b (reconstruction): three discs across the path, 1.5 ft gaps (<= d_th)",
        lambda: _fig7("fig7b", 8.0, FIG7_GAP_NEAR, lambda y: circle((40.0, y), 4.0)),
    ),
    "fig7c": BuiltinWorld(
        "paper Figure 7c (reconstruction): three squares across the path, 4.5 ft gaps (> d_th)",
        lambda: _fig7("fig7c", 6.0, FIG7_GAP_FAR, lambda y: rectangle((40.0, y), 6.0, 6.0)),
    ),
    "fig7d": BuiltinWorld(
        "paper Figure 7d (reconstruction): three squares across the path, 1.5 ft gaps (<= d_th)",
        lambda: _fig7("fig7d", 6.0, FIG7_GAP_NEAR, lambda y: rectangle((40.0, y), 6.0, 6.0)),
    ),
    "scenario2": BuiltinWorld(
        "paper Figures 8-9 (reconstruction): a U opening towards the source, then an H",
        _scenario2,
    ),
    "box": BuiltinWorld(
        "demo: one 4 x 10 ft box across the straight line to the goal",
        lambda: _demo("box", rectangle((30.0, 0.0), 4.0, 10.0)),
    ),
    "post": BuiltinWorld(
        "demo: one post (radius 1.5 ft) in the way, 1 ft left of the straight line",
        lambda: _demo("post", circle((30.0, 1.0), 1.5)),
    ),
    "offset_box": BuiltinWorld(
        "demo: a 4 x 8 ft box just left of the straight line, its edge 0.4 ft into the path",
        lambda: _demo("offset_box", rectangle((30.0, 4.4), 4.0, 8.0)),
    ),
    "posts_wide": BuiltinWorld(
        "demo: three posts (radius 2.5 ft) across the line, 4 ft gaps between them",
        lambda: _demo("posts_wide", *(circle((30.0, y), 2.5) for y in (-9.0, 0.0, 9.0))),
    ),
    "posts_narrow": BuiltinWorld(
        "demo: three posts (radius 2.5 ft) across the line, 0.5 ft gaps between them",
        lambda: _demo("posts_narrow", *(circle((30.0, y), 2.5) for y in (-5.5, 0.0, 5.5))),
    ),
    "wall_posts": BuiltinWorld(
        "demo: a 20 ft wall across the line, two posts 2 ft in front of it",
        lambda: _demo(
            "wall_posts",
            rectangle((30.0, 0.0), 2.0, 20.0),
            circle((26.0, -5.0), 1.0),
            circle((26.0, 5.0), 1.0),
        ),
    ),
    "u_trap": BuiltinWorld(
        "demo: a U (24 ft wide, 16 ft deep) opening towards the start, on the straight line",
        lambda: _demo(
            "u_trap",
            u_shape((30.0, 0.0), width=24.0, depth=16.0, thickness=1.0, opening=math.pi),
        ),
    ),
    "h_block": BuiltinWorld(
        "demo: an H (24 ft long walls, 20 ft apart) whose cavity faces the start",
        lambda: _demo(
            "h_block",
            h_shape((30.0, 0.0), width=20.0, height=24.0, thickness=1.0, orientation=math.pi / 2),
        ),
    ),
}


def resolve_world(spec: str | os.PathLike[str]) -> World:
    """The built-in world named ``spec``, or else the world file at that path.

    >>> resolve_world("free").goal
    Point(x=197.0, y=0.0)
    """
    name = os.fspath(spec)
    if name in BUILTIN_WORLDS:
        return BUILTIN_WORLDS[name].build()
    if not Path(name).exists():
        known = ", ".join(BUILTIN_WORLDS)
        raise WorldError(f"{name}: no such world file, and not a built-in world ({known})")
    return load_world(name)
