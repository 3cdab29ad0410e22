"""A suite case and its file format: one JSON object per line, one file per property.

A case is one example of one check of :data:`ifgm_ref.oracle.checks.CHECKS`, written down:
its id (``converges_u/0017``: the property and a number that is never reused), the example
the check's test takes (worlds as world files, ``docs/world-format.md``; tuples as lists),
the engine settings, the flags it depends on, the reference's verdict and its tier. The
reference level's cases (``agrees_with_reference``) also carry the reference's recorded
answers (:mod:`.recorded`). ``docs/oracle.md``, "The conformance suite", specifies the file.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.params import SimParams
from ifgm_ref.io.worldfile import world_from_dict, world_to_dict
from ifgm_ref.sim.world import Polygon, World

__all__ = [
    "TIERS",
    "Case",
    "decode_example",
    "encode_example",
    "read_cases",
    "write_cases",
]

#: The tiers, smallest first: a run of a tier runs its cases and those of the tiers before it.
TIERS = ("quick", "full")


@dataclass(frozen=True)
class Case:
    """One frozen example of one check.

    ``example`` is what the check's test takes (:func:`decode_example` of the file's
    ``example``); ``flags`` what it depends on beyond the check's own promise (``"class:u"``:
    drawn from the U worlds, run only for an implementation that converges in them);
    ``expected`` the reference's verdict (``"pass"``); ``recorded`` the reference's answers,
    for the reference level's cases.
    """

    id: str
    check: str
    example: Any
    tier: str = "full"
    flags: tuple[str, ...] = ()
    expected: str = "pass"
    sim: SimParams = field(default_factory=SimParams)
    recorded: Mapping[str, Any] | None = None

    def to_json(self) -> dict[str, Any]:
        """The case as its line of the file (a JSON-ready dict)."""
        line: dict[str, Any] = {
            "id": self.id,
            "property": self.check,
            "tier": self.tier,
            "flags": list(self.flags),
            "expected": self.expected,
            "sim": {
                "engine": self.sim.engine,
                "dt": self.sim.dt,
                "goal_tolerance": self.sim.goal_tolerance,
            },
            "example": encode_example(self.example),
        }
        if self.recorded is not None:
            line["recorded"] = self.recorded
        return line

    @classmethod
    def from_json(cls, line: Mapping[str, Any]) -> Case:
        """The case a line of the file holds (:meth:`to_json`)."""
        sim = line["sim"]
        return cls(
            id=line["id"],
            check=line["property"],
            example=decode_example(line["example"]),
            tier=line["tier"],
            flags=tuple(line["flags"]),
            expected=line["expected"],
            sim=SimParams(engine=sim["engine"], dt=sim["dt"], goal_tolerance=sim["goal_tolerance"]),
            recorded=line.get("recorded"),
        )


def encode_example(value: Any) -> Any:
    """``value`` as JSON: a world as its world file under ``"world"``, a polygon's vertices
    under ``"polygon"``, a tuple as a list, a number as itself.

    >>> encode_example((0.5, (1.0, -2.0)))
    [0.5, [1.0, -2.0]]
    """
    if isinstance(value, World):
        return {"world": world_to_dict(value)}
    if isinstance(value, Polygon):
        return {"polygon": [list(v) for v in value.vertices]}
    if isinstance(value, tuple | list):
        return [encode_example(v) for v in value]
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise ImplementationError(f"a suite case cannot hold {type(value).__name__} {value!r}")
    return value


def decode_example(value: Any) -> Any:
    """The example :func:`encode_example` wrote (lists become tuples).

    >>> decode_example([0.5, [1.0, -2.0]])
    (0.5, (1.0, -2.0))
    """
    if isinstance(value, dict):
        if "world" in value:
            return world_from_dict(value["world"], source="a suite case")
        return Polygon(value["polygon"])
    if isinstance(value, list):
        return tuple(decode_example(v) for v in value)
    return value


def write_cases(path: Path, header: Mapping[str, Any], cases: Iterable[Case]) -> None:
    """Write ``header`` (the suite, the protocol version, the property) then ``cases`` to
    ``path``, one line each, atomically (a reader never sees half a file)."""
    lines = [header, *(case.to_json() for case in cases)]
    text = "".join(json.dumps(line, separators=(",", ":")) + "\n" for line in lines)
    partial = path.with_name(path.name + ".partial")
    partial.write_text(text)
    partial.replace(path)


def read_cases(path: Path) -> tuple[dict[str, Any], list[Case]]:
    """The header and the cases of the file at ``path``; a line that is neither is an
    :class:`ImplementationError` naming the file and line."""
    with path.open() as lines:
        header: dict[str, Any] = {}
        cases = []
        for number, line in enumerate(lines, 1):
            try:
                if number == 1:
                    header = dict(json.loads(line))
                    if not isinstance(header["protocol"], int):
                        raise TypeError("its protocol is not a number")
                else:
                    cases.append(Case.from_json(json.loads(line)))
            except (ValueError, KeyError, TypeError) as err:
                what = "a case file's header" if number == 1 else "a suite case"
                raise ImplementationError(f"{path}:{number}: not {what} ({err!r})") from err
    return header, cases
