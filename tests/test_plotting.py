"""Plots and animations (ifgm_ref.plotting): what they show, checked on the figure objects."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
from PIL import Image

from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.plotting import MAX_FRAMES, animate_run, plot_run, switch_indices
from ifgm_ref.scenarios import resolve_world
from ifgm_ref.simulator import simulate


def test_run_plot_colours_the_path_by_behaviour_and_marks_switches() -> None:
    world = resolve_world("u_trap")
    run = simulate(world, IFGMPlanner())
    fig = plot_run(world, run.trace, run.result)
    ax = fig.axes[0]
    labels = {text.get_text() for text in ax.get_legend().get_texts()}
    assert {"move to goal", "obstacle avoidance", "behaviour switch", "field of view"} <= labels
    switches = switch_indices(run.trace)
    assert len(switches) >= 2  # into avoidance and back to move to goal
    assert "goal_reached" in ax.get_title() and ax.get_xlabel() == "x (ft)"
    plt.close(fig)


def test_run_plot_by_branch_names_the_flowchart_branches() -> None:
    world = resolve_world("u_trap")
    run = simulate(world, IFGMPlanner())
    fig = plot_run(world, run.trace, run.result, colour_by="branch")
    labels = {text.get_text() for text in fig.axes[0].get_legend().get_texts()}
    assert {"dead end turn", "follow edge", "move to goal"} <= labels
    plt.close(fig)


def test_animation_writes_a_gif_of_at_most_max_frames(tmp_path: Path) -> None:
    world = resolve_world("box")
    run = simulate(world, IFGMPlanner())
    path = tmp_path / "run.gif"
    frames = animate_run(world, run.trace, run.result, path)
    with Image.open(path) as gif:
        assert gif.n_frames == frames
    assert frames == min(len(run.trace), MAX_FRAMES)
