"""Build the vectors: evaluate the equation cases, run the reference traces, write the file.

Everything is deterministic -- explicit seeds, noise-free simulations, no dates, no machine
facts -- so rebuilding gives the same bytes (another platform's math library may move a last
bit, far inside every tolerance); floats are written with ``repr`` and read back bit for bit.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.outputs import written
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.core.recording import RecordingPlanner
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.oracle.vectors.cases import (
    GROUPS,
    RANDOM_CASES,
    TRACES,
    Case,
    EquationGroup,
    TraceSpec,
)
from ifgm_ref.oracle.vectors.schema import (
    CaseRecord,
    Failure,
    Form,
    GroupRecord,
    Output,
    TraceRecord,
    Value,
    VectorsDocument,
)
from ifgm_ref.oracle.vectors.tolerances import QUANTITIES
from ifgm_ref.paper import equations as reference
from ifgm_ref.planners import PLANNERS, make_planner
from ifgm_ref.planners.tuning import episode_values
from ifgm_ref.sim.simulator import episode_params, simulate

__all__ = [
    "VectorsSummary",
    "build_document",
    "build_vectors",
    "dumps_vectors",
    "summarize",
    "write_vectors",
]

#: How to make the file again, written into it.
GENERATOR = "ifgm-ref vectors --out FILE.json (ifgm_ref.oracle.vectors.build_vectors)"
#: The file's units and frames.
UNITS = {"length": "ft", "angle": "rad", "time": "s", "speed": "ft/s"}
FRAMES = {
    "robot": "REP-103 robot frame: x forward along the heading, y to the left, angles "
    "counter-clockwise from the heading; eq. (1) and (2) inputs and outputs, FGM's "
    "border angles, scan ray angles",
    "world": "REP-103 world frame: x east, y north, angles counter-clockwise from +x; "
    "eq. (3) positions and angle, trace poses, goals and command headings",
}


# ---- equations -------------------------------------------------------------------------------


def _evaluate(function: Callable[..., Any], form: Form, inputs: Mapping[str, Any]) -> Output:
    """The reference output of ``form`` on ``inputs``, or the error it raises."""
    try:
        value = function(**{name: inputs[name] for name in form.args})
    except ParameterError as err:
        return Failure(str(err))
    if isinstance(value, tuple):
        return tuple(float(v) for v in value)
    return float(value)


def _input(value: Any) -> Value:
    return tuple(float(v) for v in value) if isinstance(value, tuple | list) else float(value)


def _group_record(group: EquationGroup) -> GroupRecord:
    """The group's hand-picked cases, then its random ones, evaluated by the reference."""
    rng = np.random.default_rng(group.seed)
    cases = list(group.cases) + [
        Case(f"random-{i:02d}", group.draw(rng)) for i in range(RANDOM_CASES)
    ]
    records = tuple(
        CaseRecord(
            id=case.id,
            inputs={name: _input(case.inputs[name]) for name in group.inputs},
            outputs={
                key: _evaluate(getattr(reference, form.function), form, case.inputs)
                for key, form in group.forms
            },
            note=case.note,
            errata=case.errata,
        )
        for case in cases
    )
    return GroupRecord(group.paper, group.frame, group.seed, dict(group.forms), records)


# ---- traces ----------------------------------------------------------------------------------


def _effective_params(planner_name: str, episode: EpisodeParams) -> dict[str, float]:
    """Every parameter of the planner with the value it takes at reset (derived ones too)."""
    return episode_values(PLANNERS[planner_name].tunings, episode)


def _trace_record(spec: TraceSpec) -> TraceRecord:
    """Run ``spec``'s planner from its start, recording every step."""
    world = dataclasses.replace(resolve_world(spec.world), start=spec.start)
    sim = SimParams()
    sim = SimParams(dt=sim.dt, max_time=spec.steps * sim.dt, goal_tolerance=sim.goal_tolerance)
    params = _effective_params(spec.planner, episode_params(world, sim))
    recorder = RecordingPlanner(make_planner(spec.planner))
    run = simulate(world, recorder, sim, params=params)
    recording = recorder.recording()
    branches = (str(c.branch) for _, c in recording.steps if c.branch is not None)
    return TraceRecord(
        id=spec.id,
        planner=spec.planner,
        world=spec.world,
        note=spec.note,
        stop_reason=run.result.stop_reason,
        branches=tuple(dict.fromkeys(branches)),
        recording=recording,
    )


# ---- the file --------------------------------------------------------------------------------


def build_document() -> VectorsDocument:
    """Build the test vectors as a typed document (:func:`build_vectors` as JSON)."""
    return VectorsDocument(
        generator=GENERATOR,
        units=UNITS,
        frames=FRAMES,
        tolerances=QUANTITIES,
        equations={group.name: _group_record(group) for group in GROUPS},
        traces=tuple(_trace_record(spec) for spec in TRACES),
    )


def build_vectors() -> dict[str, Any]:
    """Build the test vectors (deterministic and JSON-ready: no NaN or infinity).

    Returns
    -------
    dict
        The document ``docs/vectors-format.md`` specifies: ``format``, ``units``, ``frames``,
        ``tolerances``, ``equations`` (by group) and ``traces``.

    Examples
    --------
    >>> vectors = build_vectors()
    >>> vectors["format"]
    {'name': 'ifgm-ref-vectors', 'version': 1}
    >>> case = vectors["equations"]["eq3_goal_angle"]["cases"][1]
    >>> case["id"], case["inputs"]
    ('q2-behind', {'current': [0.0, 0.0], 'destination': [-1.0, 1.0]})
    >>> case["literal"], case["interpreted"]
    (-0.7853981633974483, 2.356194490192345)
    >>> vectors["equations"]["eq2_gap_angle"]["cases"][8]["literal"]  # doctest: +ELLIPSIS
    {'error': 'eq. (2) as printed is undefined for x_g == 0 (division by zero); got ...'}
    """
    vectors = build_document().to_json()
    _check_json_ready(vectors, "vectors")
    return vectors


def _check_json_ready(value: Any, where: str) -> None:
    """Raise ``AssertionError`` on anything JSON cannot carry exactly (NaN, inf, tuples...)."""
    if isinstance(value, dict):
        for key, item in value.items():
            assert isinstance(key, str), f"{where}: key {key!r} is not a string"
            _check_json_ready(item, f"{where}.{key}")
    elif isinstance(value, list):
        for i, item in enumerate(value):
            _check_json_ready(item, f"{where}[{i}]")
    elif isinstance(value, float):
        assert math.isfinite(value), f"{where}={value!r}, but should be finite"
    else:
        assert value is None or type(value) in (str, int, bool), (
            f"{where}: {type(value).__name__} {value!r}, but should be a JSON value"
        )


def dumps_vectors(vectors: Mapping[str, Any]) -> str:
    """Write ``vectors`` as JSON: one space of indent per level, arrays of plain values on one
    line (a scan's ranges, a point), keys in insertion order, a final newline.

    >>> print(dumps_vectors({"a": [1.0, None], "b": {"c": [{"d": "e"}]}}), end="")
    {
     "a": [1.0, null],
     "b": {
      "c": [
       {
        "d": "e"
       }
      ]
     }
    }
    """
    return _dumps(vectors, 0) + "\n"


def _dumps(value: Any, level: int) -> str:
    pad, inner = " " * level, " " * (level + 1)
    if isinstance(value, Mapping) and value:
        items = (f"{inner}{json.dumps(k)}: {_dumps(v, level + 1)}" for k, v in value.items())
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list) and any(isinstance(v, Mapping | list) for v in value):
        items = (f"{inner}{_dumps(v, level + 1)}" for v in value)
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return json.dumps(value, allow_nan=False)


def write_vectors(path: str | os.PathLike[str]) -> dict[str, Any]:
    """Build the vectors, write them to ``path`` (:func:`dumps_vectors`) and return them."""
    vectors = build_vectors()
    with written(path, announce=False) as partial:  # the command says it in its summary
        partial.write_text(dumps_vectors(vectors), encoding="utf-8")
    return vectors


@dataclass(frozen=True)
class VectorsSummary:
    """How much a vectors document holds."""

    groups: int
    cases: int
    traces: int
    steps: int
    branches: tuple[str, ...]

    def __str__(self) -> str:
        return (
            f"{self.cases} equation cases in {self.groups} groups, {self.traces} traces of "
            f"{self.steps} steps covering {len(self.branches)} branches"
        )


def summarize(vectors: Mapping[str, Any] | VectorsDocument) -> VectorsSummary:
    """Count the groups, cases, traces, steps and distinct branches of ``vectors``."""
    document = (
        vectors if isinstance(vectors, VectorsDocument) else VectorsDocument.from_json(vectors)
    )
    groups, traces = document.equations, document.traces
    return VectorsSummary(
        groups=len(groups),
        cases=sum(len(group.cases) for group in groups.values()),
        traces=len(traces),
        steps=sum(len(trace.recording.steps) for trace in traces),
        branches=tuple(dict.fromkeys(b for trace in traces for b in trace.branches)),
    )
