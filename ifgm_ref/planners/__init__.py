"""The planners, by the names the command line uses.

Planners see only what :class:`ifgm_ref.core.protocol.Observation` carries (pose, goal, scan): no
module in this package imports the world, the sensor or the simulator (section 3 of the paper:
"No priori information or map of the environment is required"); a test enforces it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

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
from ifgm_ref.planners.promises import REFERENCE_NOISE_LEVELS, Promises
from ifgm_ref.planners.straight import StraightPlanner
from ifgm_ref.planners.tuning import ParamInfo, Tuning, parameter_infos


@dataclass(frozen=True)
class PlannerInfo:
    """A registered planner: its factory, a one-line description, what it promises (declared
    with it, so that no planner is without: :class:`~ifgm_ref.planners.promises.Promises`) and its
    parameter classes."""

    factory: Callable[[], Planner]
    description: str
    promises: Promises
    tunings: tuple[type[Tuning], ...] = ()

    @property
    def parameters(self) -> tuple[str, ...]:
        """The parameter names, in declaration order."""
        return tuple(info.name for info in self.infos)

    @property
    def infos(self) -> tuple[ParamInfo, ...]:
        """Every parameter with its formula and unit."""
        return parameter_infos(self.tunings)


#: The Bug family's promises (Table 1): convergence in every solvable class, "goal
#: unreachable" reported, obstacles gone round rather than gaps taken. Bug1 and Bug2 miss too
#: often under noise at any level tried, so they promise none (``docs/oracle.md``,
#: "Robustness"); DistBug and IBA keep their promises under the reference levels.
BOUNDARY = Promises(reports_unreachable=True, passes_wide_gaps=False, stops_in_time=True)
ROBUST_BOUNDARY = replace(BOUNDARY, noise=REFERENCE_NOISE_LEVELS)
#: DWA's promises, what it kept under ``ifgm-ref oracle --planner dwa --profile brief``
#: (``docs/oracle.md``, "What DWA promises, measured"): collision-freedom, scale invariance and
#: stopping in time (its dynamic window keeps within the robot's braking); no convergence (it
#: stalls even in open worlds, turning in place beside a post), no Case-1 gap, no "goal
#: unreachable", no IFGM dead end, no noise levels, and no rigid-motion invariance (its
#: costmap's cells are aligned with the world's axes: a rotated problem rasterizes otherwise).
DWA_PROMISES = Promises(
    converges_in=frozenset(),
    passes_wide_gaps=False,
    rigid_motion_invariant=False,
    stops_in_time=True,
)

#: Every planner by its command-line name, with what it promises (paper Table 1 and section
#: 5; FGM steers at the *widest* gap, which beside a wall is the open space past its end; IFGM
#: has no "goal unreachable" exit).
PLANNERS: dict[str, PlannerInfo] = {
    "bug1": PlannerInfo(
        Bug1Planner,
        "Bug1 (Lumelsky & Stepanov; section 2.1.1): go round the whole obstacle, leave at the "
        "point nearest the goal",
        BOUNDARY,
        Bug1Planner.tunings,
    ),
    "bug2": PlannerInfo(
        Bug2Planner,
        "Bug2 (Lumelsky & Stepanov; section 2.1.2): follow the edge back to the start-goal line, "
        "nearer the goal",
        BOUNDARY,
        Bug2Planner.tunings,
    ),
    "distbug": PlannerInfo(
        DistBugPlanner,
        "DistBug (Kamon & Rivlin 1997; section 2.1.3): leave when the free range towards the "
        "goal promises progress",
        ROBUST_BOUNDARY,
        DistBugPlanner.tunings,
    ),
    "iba": PlannerInfo(
        IBAPlanner,
        "Intelligent Bug Algorithm (section 4.1): bidirectional edge following, leaving at the "
        "first free path to the goal",
        ROBUST_BOUNDARY,
        IBAPlanner.tunings,
    ),
    "fgm": PlannerInfo(
        FGMPlanner,
        "Follow the Gap Method (Sezer & Gokasan 2012; section 2.2): steer through the widest "
        "gap; trapped by U and H shapes",
        Promises(
            converges_in=frozenset({"open", "symmetric"}),
            passes_wide_gaps=False,
            noise=REFERENCE_NOISE_LEVELS,
            stops_in_time=True,
        ),
        FGMPlanner.tunings,
    ),
    "ifgm": PlannerInfo(
        IFGMPlanner,
        "Intelligent Follow the Gap Method (section 4, Figure 3): FGM through wide gaps, IBA "
        "round the rest, 45-degree turns out of dead ends",
        Promises(
            noise=REFERENCE_NOISE_LEVELS,
            turns_at_dead_ends=True,
            reference="ifgm",
            stops_in_time=True,
        ),
        IFGMPlanner.tunings,
    ),
    "apf": PlannerInfo(
        APFPlanner,
        "artificial potential field (Khatib 1986; Table 1): goal attracts, returns repel; "
        "trapped by U, H and symmetric obstacles",
        Promises(converges_in=frozenset({"open"}), passes_wide_gaps=False, stops_in_time=True),
        APFPlanner.tunings,
    ),
    "dwa": PlannerInfo(
        DWAPlanner,
        "BARN's baseline, ROS move_base DWA (Fox, Burgard & Thrun 1997): keeps a costmap of its "
        "own scans, plans on it, scores a dynamic window",
        DWA_PROMISES,
        DWAPlanner.tunings,
    ),
    "straight": PlannerInfo(
        StraightPlanner,
        "steer straight at the goal; no avoidance",
        Promises(converges_in=frozenset(), collision_free=False, passes_wide_gaps=False),
    ),
}


def declared_promises(factory: object) -> Promises | None:
    """What the planner factory ``factory`` declares it promises, or ``None`` if nothing.

    A factory declares it with a ``promises`` attribute (on a class: for every instance and
    subclass), either a :class:`~ifgm_ref.planners.promises.Promises` or the name of a registered
    planner whose promises it keeps. A registered planner's class declares the promises it is
    registered with, and so does any subclass of it (the oracle's IFGM variants and mutants,
    a port built on the reference): the registration nearest in its method resolution order.

    >>> declared_promises(IFGMPlanner) == PLANNERS["ifgm"].promises
    True
    >>> class Port(IBAPlanner):
    ...     promises = "ifgm"
    >>> declared_promises(Port) == PLANNERS["ifgm"].promises
    True
    >>> declared_promises(lambda: StraightPlanner()) is None
    True
    """
    promises = getattr(factory, "promises", None)
    if isinstance(promises, Promises):
        return promises
    if isinstance(promises, str):
        return promises_named(promises)
    if promises is not None:
        raise PlannerError(
            f"{factory!r}.promises: must be a Promises or a planner name, got {promises!r}"
        )
    registered = {info.factory: info.promises for info in PLANNERS.values()}
    for base in factory.__mro__ if isinstance(factory, type) else ():
        if base in registered:
            return registered[base]
    return None


def promises_named(name: str) -> Promises:
    """What the registered planner ``name`` promises.

    >>> promises_named("apf").converges_in
    frozenset({'open'})
    """
    return _info(name).promises


def make_planner(name: str) -> Planner:
    """A new planner of the registered ``name``.

    >>> make_planner("straight").name
    'straight'
    """
    return _info(name).factory()


def _info(name: str) -> PlannerInfo:
    try:
        return PLANNERS[name]
    except KeyError:
        known = ", ".join(sorted(PLANNERS))
        raise PlannerError(f"unknown planner {name!r}; known planners: {known}") from None


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
