"""Reference agreement: does an implementation take the reference's decisions, step by step?

The paper's properties (:mod:`ifgm_ref.oracle.checks`) hold for any valid reading of the
paper. This second level asks more of a port that follows ours: handed the observations the
reference IFGM saw in an episode, in order and open loop (its answers move nothing), it
answers every step with the reference's command -- the heading within :data:`HEADING_TOL`
and the speed within :data:`SPEED_TOL` (above a float32 port's rounding, below another
ray's or gap's heading), and, where it reports one, the same branch (``dead_end_turn`` is
accepted for the dead end's later phases: :func:`~ifgm_ref.io.bags.read.same_branch`).

A step where the two differ is a **tie** when some decision the reference consulted there,
or in the :data:`LOOKBACK` steps before, lay within its bound (:func:`tie_bound`: :data:`TIE`,
or :data:`POINT_TIE` for the followed point) of flipping
(:func:`~ifgm_ref.planners.ifgm.margins.margins`): a port's rounding may decide it the other
way, and after that the two planners' states are no longer comparable, so the comparison
ends there with the reason recorded. Anywhere else the step is the **first divergence**,
and the check fails with it: the observation, both commands and the margins.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from ifgm_ref.core.errors import present
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.recording import Recording, RecordingPlanner
from ifgm_ref.io.bags.read import same_branch
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.invariance import AnswerError, answer_errors
from ifgm_ref.paper.flowchart import Atoms
from ifgm_ref.planners.ifgm import IFGMPlanner
from ifgm_ref.planners.ifgm.margins import margins
from ifgm_ref.planners.ifgm.readings import Readings
from ifgm_ref.sim.simulator import Run, simulate
from ifgm_ref.sim.world import World

__all__ = [
    "HEADING_TOL",
    "LOOKBACK",
    "POINT_TIE",
    "ROUNDING",
    "SPEED_TOL",
    "TIE",
    "Comparison",
    "ReferenceEpisode",
    "compare",
    "divergence_message",
    "reference_episode",
    "tie_bound",
]

#: A heading answered within this of the reference's agrees (rad, 0.57 degrees): a third of
#: the paper sensor's ray spacing, so that another ray, gap or obstacle is a divergence,
#: while a float32 port following an edge through a cloud of remembered points, where the
#: nearest of two points a hair apart is a coin toss, stays within it (1.8e-3 rad measured).
HEADING_TOL = 0.01
#: A speed within this fraction of the robot's top speed agrees: the speed follows the
#: heading (``v max(0, cos(turn still to make))``), so the heading's tolerance.
SPEED_TOL = HEADING_TOL
#: The most a float32 port's rounding moves a position or range a step sees, in robot radii
#: (1e-5 of a radius for a 1 ft robot 200 ft from the origin; double's is far less).
ROUNDING = 1e-5
#: A decision this near its threshold is a tie a port may decide otherwise (robot radii or
#: radians): a hundred times :data:`ROUNDING`, far below a misread rule.
TIE = 100 * ROUNDING
#: The followed point's bound (``nearest_point``): :data:`ROUNDING` itself. Along a wall the
#: next point that is another choice (more than :data:`HEADING_TOL` away in bearing) lies
#: only ``d HEADING_TOL**2 / 2`` farther, 8e-5 of a radius at the stand-off ``d`` = 1.7 r:
#: under :data:`TIE` every step along a wall would be a tie, and a port that tracks the edge
#: by another rule would be excused (docs/oracle.md, "Ties").
POINT_TIE = ROUNDING
#: A tie this many steps before a divergence still explains it: a side or a followed point
#: chosen the other way shows in the headings a step or two later.
LOOKBACK = 2


@dataclass(frozen=True)
class ReferenceEpisode:
    """The reference IFGM's episode: what it saw and answered, the margins of its decisions
    at every step (:func:`~ifgm_ref.planners.ifgm.margins.margins`), and the run."""

    recording: Recording
    margins: tuple[Mapping[str, float], ...]
    atoms: tuple[Atoms, ...]
    run: Run


def tie_bound(decision: str) -> float:
    """How near its threshold ``decision`` (a name of
    :data:`~ifgm_ref.planners.ifgm.margins.DECISIONS`) must be to count as a tie."""
    return POINT_TIE if decision == "nearest_point" else TIE


class _MarginRecorder(RecordingPlanner):
    """The reference IFGM, recorded, with the margins of each step's decisions."""

    def __init__(self, readings: Readings) -> None:
        self.ifgm = IFGMPlanner(readings)
        super().__init__(self.ifgm)
        self.margins: list[Mapping[str, float]] = []
        self.atoms: list[Atoms] = []

    def step(self, observation: Observation) -> Command:
        before = self.ifgm.state.followed if self.ifgm.state.following else None
        command = super().step(observation)
        seen = present(self.ifgm.last_seen, "the step IFGM has just taken")
        branch = present(self.ifgm.last_branch, "its branch")
        self.margins.append(margins(*seen, branch, apart=HEADING_TOL, followed_before=before))
        self.atoms.append(seen[2].atoms)
        return command


def reference_episode(
    world: World, sim: SimParams, readings: Readings | None = None
) -> ReferenceEpisode:
    """Run the reference IFGM in ``world`` under ``sim`` with ``readings`` of the paper's open
    choices (``None``: ours), recording it and its margins."""
    recorder = _MarginRecorder(Readings() if readings is None else readings)
    run = simulate(world, recorder, sim)
    return ReferenceEpisode(
        recorder.recording(), tuple(recorder.margins), tuple(recorder.atoms), run
    )


@dataclass(frozen=True)
class Comparison:
    """How an implementation's replay compared with the reference's episode.

    ``steps`` were compared and agreed. ``differs`` is the first differing step (``None``
    when every step agreed), with ``why`` it differs; ``tie`` names the decision within its
    :func:`tie_bound` that explains it and its margin, or is ``None`` for a divergence.
    """

    steps: int
    differs: AnswerError | None = None
    why: str = ""
    tie: tuple[str, float] | None = None

    @property
    def diverged(self) -> bool:
        """Whether the implementation took another decision where the reference had no tie."""
        return self.differs is not None and self.tie is None


def compare(impl: Implementation, reference: ReferenceEpisode, where: str) -> Comparison:
    """Replay ``reference`` into a fresh planner of ``impl`` up to the first step that
    differs (see the module docstring); ``where`` names the example in a fault's message."""
    agreed = 0
    params = reference.recording.params
    for error in answer_errors(impl, reference.recording, where):
        why = _difference(error, params)
        if not why:
            agreed += 1
            continue
        window = reference.margins[max(0, error.step - LOOKBACK) : error.step + 1]
        ties = [
            (name, value)
            for found in window
            for name, value in found.items()
            if value <= tie_bound(name)
        ]
        return Comparison(agreed, error, why, min(ties, key=lambda item: item[1], default=None))
    return Comparison(agreed)


def _difference(error: AnswerError, params: EpisodeParams) -> str:
    """What differs between the reference's command and the answer, ``""`` if nothing. An
    answer in velocities (``turn_rate``, as a ROS node's Twist) is compared as the motion of
    one step: the reference's command as the same velocities (:meth:`Command.twist`)."""
    found = []
    heading, speed = error.heading, error.speed
    if error.answered.turn_rate is not None:
        pose = error.observation.pose
        (v, w), (v_ref, w_ref) = (c.twist(pose, params) for c in (error.answered, error.expected))
        heading, speed = abs(w - w_ref) * params.dt, abs(v - v_ref) / params.robot.speed
    if heading > HEADING_TOL:
        found.append(f"heading off by {heading:.3g} rad")
    if speed > SPEED_TOL:
        found.append(f"speed off by {speed:.3g} of the top speed")
    wanted, answered = error.expected.branch, error.answered.branch
    if answered is not None and wanted is not None and not same_branch(answered, wanted):
        found.append(f"branch {answered}, but the reference's is {wanted}")
    if error.answered.stop != error.expected.stop:
        found.append(
            f"stop {error.answered.stop!r}, but the reference's is {error.expected.stop!r}"
        )
    return "; ".join(found)


def divergence_message(reference: ReferenceEpisode, found: Comparison, where: str) -> str:
    """The first divergence, said in full: its first line the verdict, then the reference's
    atoms and nearest margins at that step, and what the planner was handed."""
    error = present(found.differs, "the step that differs")
    k, seen = error.step, error.observation
    want, got = error.expected, error.answered
    near = sorted(reference.margins[k].items(), key=lambda item: item[1])[:4]
    atoms = reference.atoms[k]
    held = [name for name in Atoms.names() if getattr(atoms, name)]
    scan = seen.scan.ranges
    return "\n".join(
        [
            f"step {k} (t={seen.t:.1f} s) of the reference's episode, replayed open loop, was "
            f"answered with heading {got.heading:.6g} rad, speed {got.speed:.6g}, branch "
            f"{got.branch}, but the reference answered heading {want.heading:.6g} rad, speed "
            f"{want.speed:.6g}, branch {want.branch} ({found.why}), with no decision within "
            f"{TIE:g} of a tie (the followed point: {POINT_TIE:g}) [{where}]",
            f"  after {found.steps} agreeing steps; the reference's atoms there: "
            f"{', '.join(held) or 'none'}",
            "  its nearest decisions (margin in radii or rad): "
            + ", ".join(f"{name} {value:.3g}" for name, value in near),
            f"  handed: pose ({seen.pose.x:.6g}, {seen.pose.y:.6g}, {seen.pose.theta:.6g}), "
            f"goal ({seen.goal.x:.6g}, {seen.goal.y:.6g}), {len(scan)} ranges, nearest "
            f"{float(scan.min()):.6g}",
        ]
    )
