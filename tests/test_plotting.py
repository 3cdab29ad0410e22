"""Plots and animations (ifgm_ref.sim.plotting): what they show, checked on the figure objects."""

from __future__ import annotations

import dataclasses
import inspect
import itertools
import math
import re
from collections import Counter
from pathlib import Path

import matplotlib.pyplot as plt
import pytest
from PIL import Image

from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners.fgm import FGMPlanner
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.sim.noise import NoiseLevels
from ifgm_ref.sim.plotting import (
    BELIEVED_LABEL,
    END_LABEL,
    MAX_FRAMES,
    RARE_MARKER,
    RARE_SHARE,
    animate_run,
    draw_path,
    finest_colouring,
    plot_run,
    switch_indices,
)
from ifgm_ref.sim.simulator import simulate


def test_run_plot_colours_the_path_by_behaviour_and_marks_switches() -> None:
    world = resolve_world("u_trap")
    run = simulate(world, IFGMPlanner())
    fig = plot_run(world, run.trace, run.result)
    ax = fig.axes[0]
    labels = {re.sub(r" \(\d+ steps?\)", "", text.get_text()) for text in _legend(fig).get_texts()}
    assert {"move to goal", "obstacle avoidance", "behaviour switch", "field of view"} <= labels
    switches = switch_indices(run.trace)
    assert len(switches) >= 2  # into avoidance and back to move to goal
    assert "goal_reached" in ax.get_title() and ax.get_xlabel() == "x (ft)"
    plt.close(fig)


def test_run_plot_by_branch_names_the_flowchart_branches() -> None:
    world = resolve_world("u_trap")
    run = simulate(world, IFGMPlanner())
    fig = plot_run(world, run.trace, run.result, colour_by="branch")
    labels = {re.sub(r" \(\d+ steps?\)", "", text.get_text()) for text in _legend(fig).get_texts()}
    assert {"dead end turn", "follow edge", "move to goal"} <= labels
    plt.close(fig)


def _legend(fig: plt.Figure) -> plt.Legend:
    (legend,) = fig.legends
    return legend


def test_branch_legend_goes_by_steps_and_rare_branches_are_marked() -> None:
    world = resolve_world("wall_posts")
    run = simulate(world, IFGMPlanner())
    fig = plot_run(world, run.trace, run.result, colour_by="branch")
    steps, drawn = Counter[str](), Counter[str]()
    for a, b in itertools.pairwise(run.trace):
        steps[str(a.branch)] += 1
        drawn[str(a.branch)] += math.dist((a.x, a.y), (b.x, b.y))
    rare = {b for b in steps if drawn[b] < RARE_SHARE * run.result.path_length}
    assert rare and rare != set(steps)  # one-step branches, and long ones
    legend = _legend(fig)
    entries = {  # the path's entries, in order: name -> (steps, marked)
        match[1]: (int(match[2]), handle.get_marker() == RARE_MARKER["marker"])
        for text, handle in zip(legend.get_texts(), legend.legend_handles, strict=True)
        if (match := re.fullmatch(r"(.+) \((\d+) steps?\)", text.get_text()))
    }
    assert [n for n, _ in entries.values()] == sorted(steps.values(), reverse=True)
    assert {name: n for name, (n, _) in entries.items()} == {
        b.replace("_", " "): n for b, n in steps.items()
    }
    assert {name for name, (_, marked) in entries.items() if marked} == {
        b.replace("_", " ") for b in rare
    }
    marked = [
        line.get_xydata()
        for line in fig.axes[0].lines
        if line.get_marker() == RARE_MARKER["marker"]
    ]
    for branch in rare:  # marked where it is first taken
        first = next(s for s in run.trace if s.branch == branch)
        assert any(((xy == (first.x, first.y)).all(1)).any() for xy in marked), branch
    plt.close(fig)


#: A ``--cmd`` program's name as long as a path makes it, for a run's title.
LONG_NAME = "cmd: python3 " + "/home/someone/projects/my_port/build" * 4 + " --verbose"


@pytest.mark.parametrize(
    ("world", "planner", "name"),
    [
        ("wall_posts", IFGMPlanner, None),
        ("scenario2", FGMPlanner, None),
        ("u_trap", FGMPlanner, LONG_NAME),
    ],
)
def test_run_plot_labels_and_legend_lie_within_the_figure(
    world: str, planner: type, name: str | None
) -> None:
    """Labels, title and legend stay within the figure, and the title (wrapped when a
    program's name makes it long) never covers the legend."""
    built = resolve_world(world)
    run = simulate(built, planner(), progress=False)
    result = run.result if name is None else dataclasses.replace(run.result, planner=name)
    fig = plot_run(built, run.trace, result, colour_by="branch")
    fig.canvas.draw()
    figure, axes, legend = fig.bbox, fig.axes[0].get_tightbbox(), _legend(fig).get_window_extent()
    for box in (axes, legend):
        assert figure.x0 <= box.x0 and box.x1 <= figure.x1 and figure.y0 <= box.y0
        assert box.y1 <= figure.y1
    assert not axes.overlaps(legend)
    plt.close(fig)


def test_paper_panels_keep_plain_labels_in_order_of_appearance() -> None:
    world = resolve_world("u_trap")
    run = simulate(world, IFGMPlanner())
    fig, ax = plt.subplots()
    draw_path(ax, run.trace, world.robot.radius, colour_by="branch")
    labels = ax.get_legend_handles_labels()[1]
    seen = list(dict.fromkeys(str(s.branch).replace("_", " ") for s in run.trace[:-1]))
    assert labels == [*seen, "behaviour switch", END_LABEL]
    plt.close(fig)


def test_animation_writes_a_gif_of_at_most_max_frames(tmp_path: Path) -> None:
    """One frame a step up to the cap, then the cap (the default cap is ``MAX_FRAMES``;
    small caps here keep the rendering short)."""
    assert inspect.signature(animate_run).parameters["max_frames"].default == MAX_FRAMES
    world = resolve_world("box")
    run = simulate(world, IFGMPlanner())
    for trace, cap in ((run.trace, 7), (run.trace[:5], 7)):
        path = tmp_path / "run.gif"
        frames = animate_run(world, trace, run.result, path, max_frames=cap, progress=False)
        with Image.open(path) as gif:
            assert gif.n_frames == frames
        assert frames == min(len(trace), cap)


def test_animation_counts_its_frames_on_stderr(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    world = resolve_world("box")
    run = simulate(world, IFGMPlanner())
    capsys.readouterr()
    frames = animate_run(world, run.trace, run.result, tmp_path / "run.gif", max_frames=4)
    assert frames == 4 and capsys.readouterr().err == ""  # not a terminal: no bar by default
    animate_run(world, run.trace, run.result, tmp_path / "run.gif", max_frames=4, progress=True)
    shown = capsys.readouterr().err
    assert "GIF" in shown and "1/4" in shown and "4/4" in shown


def test_run_plot_draws_the_believed_path_only_where_odometry_moved_it() -> None:
    """With odometry noise the plot adds a dashed "believed path (odometry)"
    (``docs/noise.md``); without, none."""
    world = resolve_world("post")
    for levels, drawn in (("odometry=0.02", True), ("none", False)):
        noisy = NoiseLevels.parse(levels).apply(world, 1)
        run = simulate(noisy, IFGMPlanner())
        fig = plot_run(noisy, run.trace, run.result)
        labels = [line.get_label() for line in fig.axes[0].get_lines()]
        assert (BELIEVED_LABEL in labels) is drawn, labels
        plt.close(fig)


def test_a_counterexample_is_coloured_by_branch_only_where_the_planner_reports_one() -> None:
    """The oracle's plots (``finest_colouring``): a ``--cmd`` program that reports no branch
    gets its path coloured by behaviour, not one colour called "none"."""
    run = simulate(resolve_world("post"), IFGMPlanner())
    assert finest_colouring(run.trace) == "branch"
    silent = [dataclasses.replace(s, branch=None) for s in run.trace]
    assert finest_colouring(silent) == "behaviour"
    fig = plot_run(resolve_world("post"), silent, run.result, colour_by=finest_colouring(silent))
    labels = [t.get_text() for t in _legend(fig).get_texts()]
    assert not any(label.startswith("none") for label in labels), labels
    plt.close(fig)


def test_plots_and_animations_label_lengths_in_the_worlds_unit(tmp_path: Path) -> None:
    """ft by default (the paper's worlds), m where ``simulate`` runs a Gazebo or BARN world."""
    world = resolve_world("post")
    run = simulate(world, IFGMPlanner())
    for unit in ("ft", "m"):
        fig = plot_run(world, run.trace, run.result, unit=unit)
        ax = fig.axes[0]
        assert (ax.get_xlabel(), ax.get_ylabel()) == (f"x ({unit})", f"y ({unit})")
        assert ax.get_title().endswith(f" {unit}")
        plt.close(fig)
    shown: list[str] = []
    original = plt.Figure.savefig

    def keep_labels(fig: plt.Figure, *args: object, **kwargs: object) -> None:
        shown.append(fig.axes[0].get_xlabel())
        original(fig, *args, **kwargs)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(plt.Figure, "savefig", keep_labels)
        animate_run(world, run.trace[:3], run.result, tmp_path / "m.gif", unit="m")
    assert shown and set(shown) == {"x (m)"}
