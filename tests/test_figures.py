"""The paper's figures and reproduction table (ifgm_ref.apps.figures) and the reconstructed
scenarios' facts (ifgm_ref.io.scenarios)."""

from __future__ import annotations

import io
import math
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
import pytest
import shapely
from matplotlib.patches import Circle as CirclePatch

from ifgm_ref.apps.figures import (
    FIGURES,
    reproduction_rows,
    stable_svg_ids,
    table_csv,
    table_markdown,
    write_all,
)
from ifgm_ref.core.params import PAPER_FREE_DISTANCE_FT, PAPER_FREE_TIME_S, RobotParams, SimParams
from ifgm_ref.core.pose import Point, Pose, distance
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.io.scenarios import FIG7_GAP_FAR, FIG7_GAP_NEAR, resolve_world
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import Circle, Obstacle

PAPER_FIGS = Path(__file__).resolve().parent.parent / "paper_figs"


@pytest.mark.paper(
    "s5.scenario1_times",
    "s5.iba_beats_distbug",
    "s5.fgm_equals_ifgm",
    "s5.ifgm_smoothest",
    "s5.scenario2_times",
)
def test_committed_reproduction_table_is_what_the_code_computes() -> None:
    rows = reproduction_rows()
    assert (PAPER_FIGS / "reproduction.csv").read_text() == table_csv(rows)
    assert (PAPER_FIGS / "reproduction.md").read_text() == table_markdown(rows)


def test_figures_command_writes_every_figure_and_the_table(tmp_path: Path) -> None:
    written = {p.name for p in write_all(tmp_path, progress=False)}
    expected = {f"{stem}{suffix}" for stem in FIGURES for suffix in (".png", ".svg")}
    assert written == expected | {"reproduction.md", "reproduction.csv"}
    assert all((tmp_path / name).stat().st_size > 1000 for name in expected)


def test_scenario1_is_197_ft_with_two_obstacles_on_the_line() -> None:
    world = resolve_world("scenario1")
    assert distance(world.start, world.goal) == PAPER_FREE_DISTANCE_FT
    line = shapely.LineString([world.start[:2], world.goal])
    on_line = [ob for ob in world.obstacles if _geometry(ob).intersects(line)]
    assert len(on_line) == 2 and len(world.obstacles) > 2


@pytest.mark.paper("s5.free_run", "fig3.move_to_goal")
def test_the_free_run_takes_149_seconds() -> None:
    assert PAPER_FREE_DISTANCE_FT / RobotParams().speed == PAPER_FREE_TIME_S
    result = simulate(resolve_world("free"), IFGMPlanner()).result
    early = SimParams().goal_tolerance / RobotParams().speed  # stops 0.5 ft short of the goal
    assert PAPER_FREE_TIME_S - early - SimParams().dt <= result.time_s <= PAPER_FREE_TIME_S


def test_the_u_of_scenario2_opens_towards_the_source() -> None:
    world = resolve_world("scenario2")
    u = _geometry(world.obstacles[0])
    cx, cy = u.centroid.x, u.centroid.y
    hull = shapely.convex_hull(u)
    inside = shapely.Point(hull.centroid.x, hull.centroid.y)
    assert hull.contains(inside) and not u.contains(inside)
    towards_source = shapely.LineString([(inside.x, inside.y), (world.start.x, inside.y)])
    away = shapely.LineString([(inside.x, inside.y), (world.goal.x, inside.y)])
    assert not towards_source.intersects(u), "the cavity should be open towards the source"
    assert away.intersects(u), "the base wall should face the destination"
    assert world.start.x < cx < world.obstacles[1].geometry.centroid.x < world.goal.x
    assert math.isclose(cy, 0.0, abs_tol=1e-9)


@pytest.mark.paper("s5.symmetric")
def test_figure7_gaps_are_on_the_documented_sides_of_d_th() -> None:
    planner = IFGMPlanner()
    planner.reset(Pose(0.0, 0.0, 0.0), Point(80.0, 0.0), EpisodeParams())
    diameter = 2.0 * RobotParams().radius
    for name, gap in (
        ("fig7a", FIG7_GAP_FAR),
        ("fig7b", FIG7_GAP_NEAR),
        ("fig7c", FIG7_GAP_FAR),
        ("fig7d", FIG7_GAP_NEAR),
    ):
        shapes = [_geometry(ob) for ob in resolve_world(name).obstacles]
        gaps = [shapes[i].distance(shapes[i + 1]) for i in range(2)]
        assert all(math.isclose(g, gap, rel_tol=1e-3) for g in gaps), (name, gaps)
    assert FIG7_GAP_FAR > planner.d_th >= FIG7_GAP_NEAR
    assert diameter > FIG7_GAP_NEAR


def _geometry(obstacle: Obstacle) -> shapely.Geometry:
    if isinstance(obstacle, Circle):  # the exact disc is needed for distances: buffer finely
        return shapely.Point(obstacle.center).buffer(obstacle.radius, quad_segs=256)
    return obstacle.geometry


def _clipped_figure_svg(salt: str) -> str:
    """A small figure with clip paths and markers, as SVG, its ids hashed with ``salt``."""
    fig, ax = plt.subplots()
    ax.plot([0.0, 1.0, 2.0], [0.0, 1.0, 0.5], marker="o")
    ax.add_patch(CirclePatch((1.0, 0.5), 0.3))
    text = io.StringIO()
    with matplotlib.rc_context({"svg.hashsalt": salt}):
        fig.savefig(text, format="svg", metadata={"Date": None})
    plt.close(fig)
    return text.getvalue()


def test_svg_ids_do_not_depend_on_what_matplotlib_hashed() -> None:
    # Another salt stands for another numpy: both change every hashed id and nothing else.
    one, other = _clipped_figure_svg("one"), _clipped_figure_svg("other")
    assert one != other and 'clip-path="url(#p' in one
    stable = stable_svg_ids(one)
    assert stable == stable_svg_ids(other)
    assert 'clip-path="url(#p1)"' in stable and 'xlink:href="#m1"' in stable


def test_committed_svgs_have_numbered_ids() -> None:
    for path in sorted(PAPER_FIGS.glob("fig*.svg")):
        text = path.read_text(encoding="utf-8")
        assert 'clip-path="url(#p1)"' in text, path.name
        assert stable_svg_ids(text) == text, path.name
