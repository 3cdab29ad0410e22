"""The paper's elements, by key, and the marker that ties code to them.

:data:`ELEMENTS` is the paper's index: every equation, flowchart branch, rule, threshold and
claim a reader may want to find, with its section and the paper's own words (shortened).
Code says which element it implements with the :func:`traces` decorator (proof modules, the
figure functions and planners too); tests say which element they pin with the pytest marker
``@pytest.mark.paper("key", ...)``; notebooks in their metadata (``"paper": [...]``).
``ifgm-ref trace-matrix`` gathers the markers into the traceability matrix
(:mod:`ifgm_ref.paper.traceability`, ``docs/trace-matrix.md``). The list of elements is kept by
hand -- it is the paper, which does not change -- but which of them are covered, and by
what, is read from the markers, never written down.

This module imports nothing of ours: every layer may use it.

>>> @traces("eq4")
... def blend(): ...
>>> blend.__paper__
('eq4',)
>>> traces("eq5")
Traceback (most recent call last):
...
KeyError: "unknown paper element 'eq5'; see ifgm_ref.core.elements.ELEMENTS"
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TypeVar

T = TypeVar("T")


@dataclass(frozen=True)
class Element:
    """One thing the paper says: where (``section``), what kind, and its words."""

    section: str
    kind: str
    text: str


def _e(section: str, kind: str, text: str) -> Element:
    return Element(section, kind, text)


#: Every element of the paper a reader may look for, in the paper's order within each kind.
ELEMENTS: dict[str, Element] = {
    # The equations of section 4, Case-1.
    "eq1": _e("§4 Case-1", "equation", "(1) gap midpoint (x_g, y_g) = ((x1+x2)/2, (y1+y2)/2)"),
    "eq2": _e("§4 Case-1", "equation", "(2) gap centre angle theta_g = y_g / x_g"),
    "eq3": _e("§4 Case-1", "equation", "(3) goal angle theta_d = tan^-1((y_d-y_c)/(x_d-x_c))"),
    "eq4": _e(
        "§4 Case-1",
        "equation",
        "(4) final heading theta_f = (w_g/d_th theta_g + w_d theta_d) / (w_g/d_th + w_d)",
    ),
    # Figure 3 and section 4's text around it.
    "fig3.move_to_goal": _e(
        "§4",
        "flowchart",
        "follow the reference path until the goal is reached or an obstacle is sensed",
    ),
    "fig3.both_conditions": _e(
        "§4, Figure 3",
        "flowchart",
        "after encountering obstacles, FGM steers if max gap > "
        "d_th and nearest obstacle > d_obs, otherwise IBA",
    ),
    "fig3.case1": _e(
        "§4 Case-1", "flowchart", "max gap > d_th: steer through the gap by eqs. (1)-(4)"
    ),
    "fig3.case2": _e(
        "§4 Case-2", "flowchart", "max gap <= d_th, or obstacles on one side only: IBA"
    ),
    "fig3.case3": _e(
        "§4 Case-3",
        "flowchart",
        "while avoiding, an obstacle of more impact is avoided first, recursively",
    ),
    "fig3.dead_end": _e(
        "§4, §5.2",
        "flowchart",
        "stuck in a U or H: turn in 45-degree steps until a free direction (at most 180 degrees)",
    ),
    "fig3.regenerate": _e(
        "§4", "flowchart", "after avoiding, regenerate the reference path to the goal"
    ),
    "fig3.partition": _e(
        "§4, Figure 3",
        "flowchart",
        "the flowchart decides exactly one branch for every percept (our reconstruction)",
    ),
    # IBA, section 4.1.
    "iba.leave_free_path": _e(
        "§4.1", "rule", "leave the edge where an obstacle-free path to the goal is sensed"
    ),
    "iba.bidirectional": _e(
        "§4.1", "rule", "bidirectional edge following, using the sensor's configuration"
    ),
    # Thresholds, sensor, percepts (section 4).
    "d_th": _e("§4", "threshold", "d_th is greater than the robot's operational radius"),
    "d_obs": _e("§4", "threshold", "d_obs depends on the robot's speed, higher when faster"),
    "sensor.fov": _e("§4, Figure 2", "sensor", "135-degree field of view, three 45-degree beams"),
    "percepts.obstacle_array": _e(
        "§4",
        "percepts",
        "obstacle array of (x, y) points, clustered; gaps between consecutive obstacles",
    ),
    # The planners compared (section 2).
    "bug1": _e("§2.1.1", "planner", "Bug-1: go round the whole obstacle, leave nearest the goal"),
    "bug2": _e("§2.1.2", "planner", "Bug-2: leave where the start-goal slope is met again"),
    "distbug": _e("§2.1.3", "planner", "Dist-Bug: leave when the distance to the goal improves"),
    "fgm": _e("§2.2", "planner", "FGM: steer through the maximum gap, blended with the goal"),
    "apf": _e("§2, Table 1", "planner", "APF: goal attracts, obstacles repel"),
    # Section 3's novelty claims.
    "s3.critical_shapes": _e(
        "§3",
        "novelty",
        "avoids simple and critical (U, H) shaped obstacles; IBA escapes local minima",
    ),
    "s3.clear_path": _e("§3", "novelty", "IBA plans keeping a clear path towards the goal"),
    "s3.safe_near_obstacles": _e("§3", "novelty", "safer with several obstacles in close vicinity"),
    "s3.robot_dimensions": _e(
        "§3", "novelty", "incorporates the robot's dimensions by the threshold d_th"
    ),
    "s3.bidirectional": _e("§3", "novelty", "wide field of view permits bidirectional avoidance"),
    "s3.shorter": _e("§3", "novelty", "shorter trajectories, less traversal time"),
    "s3.no_map": _e("§3", "novelty", "no prior information or map: current percepts only"),
    "s3.cheap": _e("§3, §6", "novelty", "computationally inexpensive, fits a microcontroller"),
    "s3.no_subgoals": _e("§3", "novelty", "no sub-goals needed in maze-type environments"),
    # Section 5's results.
    "s5.free_run": _e("§5.1", "result", "197 ft covered in 149 s with no obstacle"),
    "s5.scenario1_times": _e(
        "§5.1, Figure 6", "result", "Scenario 1: Dist-Bug 205 s, IBA 184 s, IFGM 180 s"
    ),
    "s5.iba_beats_distbug": _e(
        "§5.1", "result", "IBA's path is smaller and smoother than Dist-Bug's"
    ),
    "s5.fgm_equals_ifgm": _e(
        "§5.1", "result", "with simple obstacles the results of FGM and IFGM are the same"
    ),
    "s5.ifgm_smoothest": _e(
        "§5.1", "result", "IFGM/FGM's trajectory is the smoothest and shortest"
    ),
    "s5.symmetric": _e(
        "§5.1, Figure 7",
        "result",
        "symmetric obstacles: gap > d_th taken by IFGM, gap < d_th avoided by IBA",
    ),
    "s5.fgm_trapped": _e(
        "§5.2, Figure 8a", "result", "FGM steers into the U and is trapped at its centre"
    ),
    "s5.ifgm_u_h": _e(
        "§5.2, Figure 8b", "result", "IFGM escapes the U by 45-degree turns and passes the H"
    ),
    "s5.scenario2_times": _e("§5.2, Figure 9", "result", "distance-time of FGM and IFGM"),
    # Table 1's limitations, where we implement the algorithm.
    "t1.bug_point_robot": _e("Table 1", "limitation", "Bug: the robot is taken as a point"),
    "t1.bug_long_paths": _e(
        "Table 1", "limitation", "Bug: trajectories sometimes very long, more time"
    ),
    "t1.bug_unidirectional": _e(
        "Table 1", "limitation", "Bug: unidirectional avoidance increases traversal time"
    ),
    "t1.bug_other_obstacles": _e(
        "Table 1", "limitation", "Bug: other obstacles ignored while following an edge"
    ),
    "t1.fgm_u": _e("Table 1", "limitation", "FGM cannot avoid U-shaped obstacles"),
    "t1.fgm_h": _e("Table 1", "limitation", "FGM: H-shaped obstacles are dead ends"),
    "t1.apf_u_h_symmetric": _e(
        "Table 1", "limitation", "APF cannot avoid U, H-shaped and symmetric obstacles"
    ),
    "t1.apf_narrow": _e("Table 1", "limitation", "APF performs poorly in narrow passages"),
    # Section 6.
    "s6.simpler_than_fgm": _e(
        "§6", "claim", "IFGM is computationally simpler than the reported FGM"
    ),
}


def traces(*keys: str) -> Callable[[T], T]:
    """Mark a function, class or method as implementing (or proving, or drawing) the paper
    elements ``keys``; raises ``KeyError`` at import for a key not in :data:`ELEMENTS`."""
    for key in keys:
        if key not in ELEMENTS:
            raise KeyError(f"unknown paper element {key!r}; see ifgm_ref.core.elements.ELEMENTS")

    def mark(obj: T) -> T:
        obj.__paper__ = (*vars(obj).get("__paper__", ()), *keys)  # type: ignore[attr-defined]
        return obj

    return mark
