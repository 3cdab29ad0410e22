"""The planners, by the names the command line uses.

Planners see only what :class:`ifgm_ref.core.protocol.Observation` carries (pose, goal, scan): no
module in this package imports the world, the sensor or the simulator (section 3 of the paper:
"No priori information or map of the environment is required"); a test enforces it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ifgm_ref.core.errors import PlannerError
from ifgm_ref.core.formulas import Scale
from ifgm_ref.core.protocol import Planner
from ifgm_ref.planners.apf import APFPlanner
from ifgm_ref.planners.bug1 import Bug1Planner
from ifgm_ref.planners.bug2 import Bug2Planner
from ifgm_ref.planners.distbug import DistBugPlanner
from ifgm_ref.planners.dwa import DWAPlanner
from ifgm_ref.planners.fgm import FGMPlanner
from ifgm_ref.planners.iba import IBAPlanner
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.planners.straight import StraightPlanner
from ifgm_ref.planners.tuning import ParamInfo, Tuning, parameter_infos


@dataclass(frozen=True)
class PlannerInfo:
    """A registered planner: its factory, a one-line description and its parameter classes."""

    factory: Callable[[], Planner]
    description: str
    tunings: tuple[type[Tuning], ...] = ()

    @property
    def parameters(self) -> tuple[str, ...]:
        """The parameter names, in declaration order."""
        return tuple(info.name for info in self.infos)

    @property
    def infos(self) -> tuple[ParamInfo, ...]:
        """Every parameter with its formula and unit."""
        return parameter_infos(self.tunings)


PLANNERS: dict[str, PlannerInfo] = {
    "bug1": PlannerInfo(
        Bug1Planner,
        "Bug1 (Lumelsky & Stepanov; section 2.1.1): go round the whole obstacle, leave at the "
        "point nearest the goal",
        Bug1Planner.tunings,
    ),
    "bug2": PlannerInfo(
        Bug2Planner,
        "Bug2 (Lumelsky & Stepanov; section 2.1.2): follow the edge back to the start-goal line, "
        "nearer the goal",
        Bug2Planner.tunings,
    ),
    "distbug": PlannerInfo(
        DistBugPlanner,
        "DistBug (Kamon & Rivlin 1997; section 2.1.3): leave when the free range towards the "
        "goal promises progress",
        DistBugPlanner.tunings,
    ),
    "iba": PlannerInfo(
        IBAPlanner,
        "Intelligent Bug Algorithm (section 4.1): bidirectional edge following, leaving at the "
        "first free path to the goal",
        IBAPlanner.tunings,
    ),
    "fgm": PlannerInfo(
        FGMPlanner,
        "Follow the Gap Method (Sezer & Gokasan 2012; section 2.2): steer through the widest "
        "gap; trapped by U and H shapes",
        FGMPlanner.tunings,
    ),
    "ifgm": PlannerInfo(
        IFGMPlanner,
        "Intelligent Follow the Gap Method (section 4, Figure 3): FGM through wide gaps, IBA "
        "round the rest, 45-degree turns out of dead ends",
        IFGMPlanner.tunings,
    ),
    "apf": PlannerInfo(
        APFPlanner,
        "artificial potential field (Khatib 1986; Table 1): goal attracts, returns repel; "
        "trapped by U, H and symmetric obstacles",
        APFPlanner.tunings,
    ),
    "dwa": PlannerInfo(
        DWAPlanner,
        "BARN's baseline, ROS move_base DWA (Fox, Burgard & Thrun 1997): keeps a costmap of its "
        "own scans, plans on it, scores a dynamic window",
        DWAPlanner.tunings,
    ),
    "straight": PlannerInfo(StraightPlanner, "steer straight at the goal; no avoidance"),
}


def make_planner(name: str) -> Planner:
    """A new planner of the registered ``name``.

    >>> make_planner("straight").name
    'straight'
    """
    try:
        info = PLANNERS[name]
    except KeyError:
        known = ", ".join(sorted(PLANNERS))
        raise PlannerError(f"unknown planner {name!r}; known planners: {known}") from None
    return info.factory()


def parameters_markdown() -> str:
    """``docs/parameters.md``: every planner's parameters, each with its formula, its unit and
    its value for the paper's robot (``ifgm-ref planners --markdown`` prints it)."""
    paper = Scale.paper()
    lines = [
        "# Planner parameters",
        "",
        "Written by `ifgm-ref planners --markdown`; `tests/test_tuning.py` checks it is current.",
        "Every default is a formula in the robot radius `r`, speed `v`, turn rate `w`, time step",
        "`dt`, sensor range `R`, ray spacing `res` and field of view `fov`",
        "(`ifgm_ref/planners/tuning.py`); the last column is its value for the paper's robot",
        "(r 1 ft, v 197/149 ft/s, w pi/2 rad/s, dt 0.1 s, R 15 ft, 76 rays over 135 degrees).",
        "Lengths are in the world's unit: feet for the paper's worlds, metres for BARN's.",
        "",
        "| planner | parameter | default | unit | the paper's robot |",
        "|---|---|---|---|---|",
    ]
    for name, info in PLANNERS.items():
        for param in info.infos:
            lines.append(
                f"| `{name}` | `{param.name}` | `{param.formula}` | {param.unit} "
                f"| {param.value(paper):.6g} |"
            )
    return "\n".join(lines) + "\n"
