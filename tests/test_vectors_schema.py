"""The schema of the vectors file (``ifgm_ref.oracle.vectors.schema``).

One schema both ways: the typed document written to JSON is the file byte for byte, the file
read back through the schema writes the same JSON, a malformed file is rejected with the place
of the fault, and the typed document checks implementations as the JSON does.
"""

from __future__ import annotations

import functools
import json
import math
import types
from typing import Any

import pytest

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.oracle.vectors import (
    VectorsDocument,
    build_document,
    build_vectors,
    check_vectors,
    dumps_vectors,
    replay_traces,
)
from ifgm_ref.paper import equations
from ifgm_ref.planners import IBAPlanner


@functools.cache
def _built() -> str:
    return json.dumps(build_vectors())


def vectors() -> dict[str, Any]:
    """A private copy of the vectors (built once)."""
    loaded: dict[str, Any] = json.loads(_built())
    return loaded


def _blind_eq3(current: tuple[float, float], destination: tuple[float, float]) -> float:
    return math.atan((destination[1] - current[1]) / (destination[0] - current[0]))


def test_the_schema_reads_back_what_it_writes() -> None:
    """One schema both ways: the typed document written to JSON is the file, and the file
    read back through the schema writes the same JSON (through a JSON text too)."""
    text = dumps_vectors(vectors())
    document = VectorsDocument.from_json(json.loads(text))
    assert document.to_json() == vectors()
    assert dumps_vectors(document.to_json()) == text
    assert dumps_vectors(build_document().to_json()) == text
    first = document.equations["eq1_gap_midpoint"].cases[0]
    assert first.inputs == {"p1": (4.0, -1.0), "p2": (2.0, 3.0)}
    assert first.outputs == {"output": (3.0, 1.0)}
    assert first.errata == (1,)


@pytest.mark.parametrize(
    ("path", "value", "message"),
    [
        (
            ("equations", "eq3_goal_angle", "cases", 1, "inputs", "current"),
            "origin",
            r"eq3_goal_angle\.cases\[1\] \(q2-behind\)\.inputs\.current: must be a number",
        ),
        (
            ("equations", "eq2_gap_angle", "forms", "literal", "args"),
            "x_g",
            r"equations\.eq2_gap_angle\.forms\.literal\.args: must be an array",
        ),
        (
            ("tolerances", "heading", "double", "abs"),
            None,
            r"tolerances\.heading\.double\.abs: must be a number, got None",
        ),
        (
            ("traces", 0, "steps", 2, "command", "heading"),
            "north",
            r"traces\[0\]\.steps\[2\]: command\.heading: must be a finite number",
        ),
    ],
)
def test_a_malformed_file_is_rejected_saying_where(
    path: tuple[Any, ...], value: Any, message: str
) -> None:
    v = vectors()
    container = v
    for key in path[:-1]:
        container = container[key]
    container[path[-1]] = value
    with pytest.raises(ParameterError, match=message):
        VectorsDocument.from_json(v)


def test_the_typed_document_checks_like_the_json() -> None:
    document = build_document()
    assert check_vectors(document, equations) == []
    assert replay_traces(document, IBAPlanner) == []
    blind = types.SimpleNamespace(eq3_goal_angle=_blind_eq3)
    assert check_vectors(document, blind, skipped=[]) == check_vectors(vectors(), blind, skipped=[])
