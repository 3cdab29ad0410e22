"""The explorer of ``notebooks/05_explore.ipynb`` (``ifgm_ref/apps/explore.py``): its world holds
the U across the start-goal line, every slider reaches the run, bad values are refused."""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import pytest
import shapely
from matplotlib.collections import LineCollection

from ifgm_ref.apps.explore import (
    BRANCH_COLOURS,
    CHANGE_LABEL,
    GATE_GAP,
    PRESETS,
    ExploreSetting,
    branch_changes,
    explore_figure,
    explore_run,
    explore_world,
)
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.paper.flowchart import Branch


@pytest.mark.parametrize(("width", "depth"), [(4.0, 2.0), (24.0, 16.0), (40.0, 30.0)])
def test_explore_world_puts_the_u_across_the_line(width: float, depth: float) -> None:
    world = explore_world(ExploreSetting(u_width=width, u_depth=depth))
    line = shapely.LineString([world.start[:2], (world.goal.x, world.goal.y)])
    gate_near, gate_far, u = (ob.geometry for ob in world.obstacles)
    assert line.intersects(u) and line.intersects(gate_near) and not line.intersects(gate_far)
    assert u.bounds[3] - u.bounds[1] == pytest.approx(width)
    assert u.bounds[2] - u.bounds[0] == pytest.approx(depth)
    # The mouth faces the start: the line meets the U only in its base, 1 ft thick at the back.
    crossing = line.intersection(u).bounds
    assert crossing[0] == pytest.approx(u.bounds[2] - 1.0)
    assert crossing[2] == pytest.approx(u.bounds[2])
    assert shapely.distance(gate_near, gate_far) == pytest.approx(GATE_GAP)


def _branches(d_th: float) -> set[str | None]:
    return {s.branch for s in explore_run(d_th=d_th).run.trace}


def test_d_th_decides_case1_or_case2_at_the_gate() -> None:
    assert 3.0 < GATE_GAP < 5.0
    wide, narrow = _branches(3.0), _branches(5.0)
    assert Branch.CASE1_GAP in wide and Branch.CASE2_NARROW_GAP not in wide
    assert Branch.CASE1_GAP not in narrow and Branch.CASE2_NARROW_GAP in narrow


@pytest.mark.parametrize(
    "change", [{"w_g": 40.0}, {"w_d": 5.0}, {"sensor_range": 6.0}, {"u_width": 12.0}]
)
def test_every_slider_reaches_the_run(change: dict[str, float]) -> None:
    default = explore_run()
    changed = explore_run(**change)
    assert [(s.x, s.y) for s in changed.run.trace] != [(s.x, s.y) for s in default.run.trace]
    if "sensor_range" in change:
        assert changed.world.sensor.range_max == change["sensor_range"]


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"d_th": 2.0}, "robot diameter"),
        ({"w_g": 0.0}, "`w_g` must be a finite number > 0"),
        ({"w_d": math.nan}, "`w_d`"),
        ({"sensor_range": 0.0}, r"`sensor_range` must be in \[4.0, 30.0\]"),
        ({"u_width": 41.0}, "`u_width`"),
        ({"u_depth": 1.0}, "`u_depth`"),
    ],
)
def test_explore_run_refuses_values_out_of_their_domain(
    change: dict[str, float], message: str
) -> None:
    with pytest.raises(ParameterError, match=message):
        explore_run(**change)


def test_plot_explore_colours_by_branch_and_marks_changes() -> None:
    runs = [(name, explore_run(**vars(s))) for name, s in PRESETS.items()]
    fig = explore_figure(runs)
    try:
        ax = fig.axes[0]
        _, run = runs[0]
        drawn = {c.get_label() for c in ax.collections if isinstance(c, LineCollection)}
        taken = {str(s.branch).replace("_", " ") for s in run.run.trace[:-1]}
        assert drawn == taken
        (marks,) = [c for c in ax.collections if c.get_label() == CHANGE_LABEL]
        assert len(marks.get_offsets()) == len(branch_changes(run.run)) > 3
        legend = [t.get_text() for t in fig.legends[0].get_texts()]
        branches = [b.replace("_", " ") for b in BRANCH_COLOURS if b.replace("_", " ") in legend]
        assert legend[-1] == CHANGE_LABEL and legend[-1 - len(branches) : -1] == branches
    finally:
        plt.close(fig)
