"""Plots that show the world (issue 45): a run's plot and animation, and a replay's plot, frame
the world and the path, not the sensor's reach; everything drawn is in the legend; the engine
is named; the animation's titles are sentences.

The frames are checked against extents computed here from the world and the trace, not
against the module's own :func:`~ifgm_ref.sim.plotting.frame`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Sequence
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.artist import Artist
from matplotlib.collections import LineCollection
from matplotlib.colors import to_rgba
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from numpy.typing import NDArray

from ifgm_ref.apps.replay import ReplayReport, replay_log, setting_of
from ifgm_ref.apps.replay_plot import plot_replay
from ifgm_ref.core.recording import RecordingPlanner
from ifgm_ref.io.bags.read import read_log
from ifgm_ref.io.bags.write import write_bag
from ifgm_ref.io.barn import gazebo_task
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners.fgm import FGMPlanner
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.sim.noise import NoiseLevels
from ifgm_ref.sim.plotting import animate_run, plot_run
from ifgm_ref.sim.simulator import Run, simulate
from ifgm_ref.sim.world import Circle, World

#: The most a plot's side may be, as a multiple of the larger side of what it must show:
#: room for the margins and for the widening to the axes' shape, none for a 30 m sensor
#: around a 4.5 x 10 m world.
MOST_SPAN = 2.5


def _extent(points: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    return points.min(axis=0), points.max(axis=0)


def _world_points(world: World, run: Run) -> NDArray[np.float64]:
    """The corners of what a plot of ``run`` must show: bounds, obstacles, start, goal and
    the path."""
    points = [world.start[:2], tuple(world.goal), *((s.x, s.y) for s in run.trace)]
    if world.bounds is not None:
        points += [world.bounds[:2], world.bounds[2:]]
    for ob in world.obstacles:
        if isinstance(ob, Circle):
            points += [
                tuple(np.add(ob.center, ob.radius)),
                tuple(np.subtract(ob.center, ob.radius)),
            ]
        else:
            points += list(ob.vertices)
    return np.array(points, dtype=float)


def _assert_frames(
    limits: tuple[tuple[float, float], tuple[float, float]], points: NDArray[np.float64]
) -> None:
    """The axes' limits hold ``points`` and are no more than :data:`MOST_SPAN` times their
    larger side, on either axis."""
    low, high = _extent(points)
    (x0, x1), (y0, y1) = limits
    assert x0 <= low[0] and high[0] <= x1 and y0 <= low[1] and high[1] <= y1, (limits, low, high)
    side = float((high - low).max())
    assert max(x1 - x0, y1 - y0) <= MOST_SPAN * side, (limits, side)


@pytest.fixture(scope="module")
def barn() -> tuple[World, Run]:
    """BARN's world 5 run by IFGM, with BARN's default sensor: it sees 30 m, 270 degrees."""
    task = gazebo_task("barn:5")
    assert task is not None
    return task.world, simulate(task.world, IFGMPlanner(), task.sim)


def test_a_barn_run_plot_frames_the_world_not_the_30_m_sensor(barn: tuple[World, Run]) -> None:
    world, run = barn
    low, high = _extent(_world_points(world, run))
    assert world.sensor.range_max > 2 * float((high - low).max())  # the case of the issue
    fig = plot_run(world, run.trace, run.result, unit="m")
    fig.canvas.draw()
    ax = fig.axes[0]
    _assert_frames((ax.get_xlim(), ax.get_ylim()), _world_points(world, run))
    assert any(p.get_label() == "field of view" for p in ax.patches)  # drawn, and cut
    plt.close(fig)


def _shown_frames(
    world: World, run: Run, tmp_path: Path, **options: object
) -> list[tuple[tuple[float, float], tuple[float, float], str]]:
    """The limits and title of every frame :func:`animate_run` writes."""
    shown = []
    original = plt.Figure.savefig

    def keep(fig: plt.Figure, *args: object, **kwargs: object) -> None:
        ax = fig.axes[0]
        shown.append((ax.get_xlim(), ax.get_ylim(), ax.get_title()))
        original(fig, *args, **kwargs)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(plt.Figure, "savefig", keep)
        animate_run(world, run.trace, run.result, tmp_path / "a.gif", progress=False, **options)
    return shown


def test_a_barn_animation_frames_the_world_and_its_titles_end_cleanly(
    barn: tuple[World, Run], tmp_path: Path
) -> None:
    """First and last frame frame the world (the rays reach 30 m); no title ends in a comma
    (the last sample has no behaviour: its title gives the stop reason)."""
    world, run = barn
    shown = _shown_frames(world, run, tmp_path, max_frames=3, unit="m")
    assert len(shown) == 3
    for xlim, ylim, title in shown:
        _assert_frames((xlim, ylim), _world_points(world, run))
        assert not title.rstrip().endswith(","), title
    assert shown[-1][2].endswith(f"t = {run.trace[-1].t:.1f} s, {run.result.stop_reason}")


def test_a_paper_world_with_a_long_sensor_is_framed_by_its_bounds() -> None:
    """Whatever the sensor: a 200 ft one in ``u_trap`` leaves the frame at the arena."""
    world = resolve_world("u_trap")
    world = dataclasses.replace(world, sensor=dataclasses.replace(world.sensor, range_max=200.0))
    run = simulate(world, IFGMPlanner())
    fig = plot_run(world, run.trace, run.result)
    fig.canvas.draw()
    ax = fig.axes[0]
    _assert_frames((ax.get_xlim(), ax.get_ylim()), _world_points(world, run))
    plt.close(fig)


def _looks(artist: Artist) -> set[tuple[object, ...]]:
    """How ``artist`` looks, as far as a legend tells it: colours and, for a line, its marker
    and its dashes."""
    if isinstance(artist, Patch):
        return {("patch", artist.get_facecolor(), artist.get_edgecolor())}
    if isinstance(artist, Line2D):
        colour = to_rgba(artist.get_color())
        looks: set[tuple[object, ...]] = {(colour, artist.get_linestyle())}
        if artist.get_marker() not in (None, "None", "", " "):
            looks.add((colour, f"marker {artist.get_marker()}"))
        return looks
    assert isinstance(artist, LineCollection), artist
    return {(tuple(artist.get_colors()[0]), artist.get_linestyle()[0] and "-")}


def _drawn(ax: plt.Axes) -> Iterator[Artist]:
    """What ``ax`` shows: its lines with points, patches and collections."""
    yield from (line for line in ax.lines if len(line.get_xdata()))
    yield from ax.patches
    yield from (c for c in ax.collections if len(c.get_paths()))


def _unexplained(fig: plt.Figure) -> list[str]:
    """The artists of ``fig`` that neither have a legend entry nor look like one that has."""
    (legend,) = fig.legends
    entries = {text.get_text() for text in legend.get_texts()}
    ax = fig.axes[0]
    every = [*ax.lines, *ax.patches, *ax.collections]
    explained = set().union(*(_looks(a) for a in every if a.get_label() in entries))
    return [str(a) for a in _drawn(ax) if not _looks(a) & explained]


@pytest.mark.parametrize("noise", ["none", "odometry=0.02"])
def test_every_line_and_marker_of_a_run_plot_is_in_the_legend(noise: str) -> None:
    """Bounds, the robot at the end, the believed path and the marked step included."""
    world = NoiseLevels.parse(noise).apply(resolve_world("wall_posts"), 1)
    run = simulate(world, IFGMPlanner())
    for colour_by in ("behaviour", "branch"):
        fig = plot_run(world, run.trace, run.result, colour_by=colour_by, mark=5)
        assert _unexplained(fig) == []
        plt.close(fig)


@pytest.mark.parametrize("engine", ["mujoco", "kinematic"])
def test_the_engine_is_named_in_the_plot_and_the_animation(engine: str, tmp_path: Path) -> None:
    """The engine only enters the titles: a kinematic trace stands for either."""
    world = resolve_world("box")
    run = simulate(world, IFGMPlanner())
    fig = plot_run(world, run.trace, run.result, engine=engine)
    assert f"({engine} engine)" in fig.axes[0].get_title()
    plt.close(fig)
    titles = [t for *_, t in _shown_frames(world, run, tmp_path, max_frames=2, engine=engine)]
    assert titles and all(f"({engine} engine)" in t for t in titles)
    fig = plot_run(world, run.trace, run.result)
    assert "engine" not in fig.axes[0].get_title()  # none given, none named
    plt.close(fig)


def _replay(tmp_path: Path, world: World) -> tuple[ReplayReport, Run]:
    """IFGM's run in ``world`` recorded to a bag and replayed by FGM (which differs)."""
    recorder = RecordingPlanner(IFGMPlanner())
    run = simulate(world, recorder)
    bag = tmp_path / "run.mcap"
    write_bag(bag, world, run, recorder.recording(), "ft")
    log = read_log(bag)
    return replay_log(log, FGMPlanner(), setting_of(log)), run


def _legend_texts(fig: plt.Figure) -> Sequence[str]:
    (legend,) = fig.legends
    return [t.get_text() for t in legend.get_texts()]


def test_a_replay_plot_frames_the_path_and_names_the_scan_returns(tmp_path: Path) -> None:
    """With a 60 ft sensor around a 60 x 24 ft trap: the axes hold the path, start, goal and
    the returns drawn, with little blank figure around them; the returns and the logged path
    have legend entries."""
    world = resolve_world("u_trap")
    world = dataclasses.replace(world, sensor=dataclasses.replace(world.sensor, range_max=60.0))
    report, run = _replay(tmp_path, world)
    fig = plot_replay(report)
    fig.canvas.draw()
    ax = fig.axes[0]
    texts = _legend_texts(fig)
    assert any(t.startswith("scan returns") for t in texts) and "logged path" in texts
    (returns,) = [line for line in ax.lines if line.get_label().startswith("scan returns")]
    points = np.vstack([returns.get_xydata(), [(s.x, s.y) for s in run.trace], [world.goal]])
    _assert_frames((ax.get_xlim(), ax.get_ylim()), points)
    axes, legend = ax.get_tightbbox(), fig.legends[0].get_window_extent()
    blank = fig.bbox.height - axes.height - legend.height  # pixels, above, between, below
    assert blank < 0.75 * fig.dpi, blank / fig.dpi
    plt.close(fig)


@pytest.mark.parametrize("engine", ["kinematic", "mujoco"])
def test_a_counterexample_plot_names_the_engine_it_ran_on(
    engine: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The oracle's counterexample plots say the engine, as ``simulate``'s do."""
    from ifgm_ref.core.params import SimParams
    from ifgm_ref.io.scenarios import resolve_world
    from ifgm_ref.oracle.check_types import Evidence
    from ifgm_ref.oracle.checks import CHECKS
    from ifgm_ref.oracle.counterexample import write_evidence
    from ifgm_ref.oracle.implementation import Implementation
    from ifgm_ref.planners import make_planner
    from ifgm_ref.sim import plotting
    from ifgm_ref.sim.simulator import simulate

    titles: list[str] = []
    draw = plotting.plot_run

    def plot_run(*args: object, **kwargs: object) -> plt.Figure:
        figure = draw(*args, **kwargs)  # type: ignore[arg-type]
        titles.append(figure.axes[0].get_title())
        return figure

    monkeypatch.setattr(plotting, "plot_run", plot_run)
    world = resolve_world("post")
    run = simulate(world, make_planner("ifgm"))
    evidence = Evidence([world], [run], 60.0)
    impl = Implementation.from_spec("ifgm")
    sim = SimParams(engine=engine)
    write_evidence(tmp_path, evidence, CHECKS["converges_open"], impl, "x", sim=sim)
    assert titles and f"({engine} engine)" in titles[0]
