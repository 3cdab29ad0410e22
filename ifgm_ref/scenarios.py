"""Built-in worlds, by name; a built-in name works wherever a world-file path does.

``free`` is the paper's obstacle-free run (section 5.1, Figure 4a): 197 ft from source to
destination, covered in 149 s at the default speed. The small demonstration worlds (one box,
a U opening towards the start, an H) exercise the planners on the paper's obstacle families;
they are ours, not the paper's. The paper's own scenarios are reconstructions added beside
them.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ifgm_ref.errors import WorldError
from ifgm_ref.params import PAPER_FREE_DISTANCE_FT
from ifgm_ref.pose import Point, Pose
from ifgm_ref.shapes import circle, h_shape, rectangle, u_shape
from ifgm_ref.world import Bounds, World
from ifgm_ref.worldfile import load_world

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


BUILTIN_WORLDS: dict[str, BuiltinWorld] = {
    "free": BuiltinWorld(
        "no obstacle; 197 ft from source to destination (paper section 5.1, Figure 4a)", _free
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
