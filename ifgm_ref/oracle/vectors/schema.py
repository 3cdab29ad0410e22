"""The schema of the vectors file (``docs/vectors-format.md``), typed both ways.

Every part of the file is a frozen dataclass with ``to_json`` (the JSON value, keys in the
file's order) and ``from_json`` (the JSON value read back, checked, into the same dataclass),
so the file is built and read through one schema:

==========================  =====================================================
file                        dataclass
==========================  =====================================================
the whole document          :class:`VectorsDocument`
``tolerances.<quantity>``   :class:`Quantity`, its two :class:`Tolerance` sets
``equations.<group>``       :class:`GroupRecord`, its :class:`Form` s
``...cases[i]``             :class:`CaseRecord`; an expected error: :class:`Failure`
``traces[i]``               :class:`TraceRecord`, its
                            :class:`~ifgm_ref.core.recording.Recording`
==========================  =====================================================

A trace's ``reset``, ``observe`` and ``command`` objects are the JSON-lines protocol's
messages, built and read by :mod:`ifgm_ref.io.transport.wire`. Floats are written with ``repr``
and read back bit for bit, so ``from_json(x).to_json() == x``. A reader ignores keys it does
not know (adding keys keeps the format version); a missing key or a value of the wrong type
raises :class:`~ifgm_ref.core.errors.ParameterError` naming where it is.

Examples
--------
>>> Tolerance(1e-9).allows(1.0, 1.0 + 1e-10), Tolerance(1e-9).allows(1.0, 1.1)
(True, False)
>>> Form.from_json({"function": "eq2_gap_angle", "args": ["x_g", "y_g"], "quantity": "direction"})
Form(function='eq2_gap_angle', args=('x_g', 'y_g'), quantity='direction')
>>> Form.from_json({"function": "eq2_gap_angle", "args": "x_g", "quantity": "direction"})
Traceback (most recent call last):
...
ifgm_ref.core.errors.ParameterError: vectors form.args: must be an array, got 'x_g'
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ifgm_ref.core.errors import ParameterError, ProtocolError
from ifgm_ref.core.recording import Recording
from ifgm_ref.io.transport.wire import (
    command_message,
    observe_message,
    parse_command,
    parse_observe,
    parse_reset,
    reset_message,
)

__all__ = [
    "FORMAT_NAME",
    "FORMAT_VERSION",
    "PRECISIONS",
    "CaseRecord",
    "Failure",
    "Form",
    "GroupRecord",
    "Output",
    "Quantity",
    "Tolerance",
    "TraceRecord",
    "Value",
    "VectorsDocument",
    "check_format",
    "check_precision",
    "parse_equations",
    "parse_tolerances",
    "parse_traces",
]

#: The ``format.name`` of the file; a reader checks it before anything else.
FORMAT_NAME = "ifgm-ref-vectors"
#: The ``format.version``: raised whenever a key changes meaning or disappears (adding cases,
#: traces or keys a reader may ignore keeps the version).
FORMAT_VERSION = 1
#: The tolerance sets of every quantity: IEEE double, and the looser one for a float32 port.
PRECISIONS = ("double", "float32")

#: An equation's input or output: a number, or a point (a pair of numbers).
Value = float | tuple[float, ...]


def check_precision(precision: str) -> None:
    """Raise :class:`ParameterError` unless ``precision`` is one of :data:`PRECISIONS`."""
    if precision not in PRECISIONS:
        raise ParameterError(
            f"`precision` must be one of {', '.join(PRECISIONS)}, got {precision!r}"
        )


def check_format(document: Mapping[str, Any]) -> None:
    """Raise :class:`ParameterError` unless ``document`` is a vectors file of this version."""
    found = document.get("format")
    expected = {"name": FORMAT_NAME, "version": FORMAT_VERSION}
    if found != expected:
        raise ParameterError(f"vectors format={found!r}, but should be {expected!r}")


# ---- tolerances ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Tolerance:
    """Pass when ``|actual - expected| <= absolute + relative * |expected|``.

    Directions are compared modulo 2 pi:

    >>> Tolerance(1e-9).allows(math.pi, -math.pi, periodic=True)
    True
    """

    absolute: float
    relative: float = 0.0

    def allows(self, expected: float, actual: float, *, periodic: bool = False) -> bool:
        """Whether ``actual`` is within this tolerance of ``expected`` (modulo 2 pi if
        ``periodic``)."""
        if not math.isfinite(actual):
            return False
        difference = actual - expected
        if periodic:
            difference = math.remainder(difference, 2.0 * math.pi)
        return abs(difference) <= self.absolute + self.relative * abs(expected)

    def describe(self, *, periodic: bool = False) -> str:
        """The tolerance as a message fragment.

        >>> Tolerance(1e-9).describe(), Tolerance(1e-9, 1e-6).describe(periodic=True)
        ('tolerance 1e-09', 'tolerance 1e-09 + 1e-06 * |expected|, modulo 2 pi')
        """
        text = f"tolerance {self.absolute!r}"
        if self.relative:
            text += f" + {self.relative!r} * |expected|"
        return text + (", modulo 2 pi" if periodic else "")

    def to_json(self) -> dict[str, float]:
        """``{"abs": ..., "rel": ...}``."""
        return {"abs": self.absolute, "rel": self.relative}

    @classmethod
    def from_json(cls, data: object, where: str) -> Tolerance:
        """Read ``{"abs": ..., "rel": ...}``."""
        return cls(
            _number(_get(data, "abs", where), f"{where}.abs"),
            _number(_get(data, "rel", where), f"{where}.rel"),
        )


@dataclass(frozen=True)
class Quantity:
    """A kind of output, its unit, how it is compared and within what, and why.

    ``periodic`` quantities are directions: the difference is taken modulo 2 pi (into
    ``[-pi, pi]``) before it is compared, so ``pi`` and ``-pi`` agree.
    """

    unit: str
    periodic: bool
    double: Tolerance
    float32: Tolerance
    reason: str

    def tolerance(self, precision: str) -> Tolerance:
        """The tolerance of ``precision`` (``"double"`` or ``"float32"``)."""
        check_precision(precision)
        return self.double if precision == "double" else self.float32

    def to_json(self) -> dict[str, Any]:
        """The quantity as the file's ``tolerances`` entry."""
        return {
            "unit": self.unit,
            "periodic": self.periodic,
            "double": self.double.to_json(),
            "float32": self.float32.to_json(),
            "reason": self.reason,
        }

    @classmethod
    def from_json(cls, data: object, where: str) -> Quantity:
        """Read a ``tolerances`` entry."""
        return cls(
            unit=_text(_get(data, "unit", where), f"{where}.unit"),
            periodic=bool(_get(data, "periodic", where)),
            double=Tolerance.from_json(_get(data, "double", where), f"{where}.double"),
            float32=Tolerance.from_json(_get(data, "float32", where), f"{where}.float32"),
            reason=_text(_get(data, "reason", where), f"{where}.reason"),
        )


# ---- equations -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Form:
    """One function of a group: its name, the case inputs it takes, what it returns."""

    function: str
    args: tuple[str, ...]
    quantity: str

    def to_json(self) -> dict[str, Any]:
        """The form as the file's ``forms`` entry."""
        return {"function": self.function, "args": list(self.args), "quantity": self.quantity}

    @classmethod
    def from_json(cls, data: object, where: str = "form") -> Form:
        """Read a ``forms`` entry."""
        args = _array(_get(data, "args", where), f"{where}.args")
        return cls(
            function=_text(_get(data, "function", where), f"{where}.function"),
            args=tuple(_text(a, f"{where}.args") for a in args),
            quantity=_text(_get(data, "quantity", where), f"{where}.quantity"),
        )


@dataclass(frozen=True)
class Failure:
    """An expected error: the reference raises here (its message, for people).

    >>> Failure("undefined").to_json()
    {'error': 'undefined'}
    """

    message: str

    def to_json(self) -> dict[str, str]:
        """``{"error": message}``."""
        return {"error": self.message}


#: What a form gives on a case: a value, or an expected error.
Output = Value | Failure


@dataclass(frozen=True)
class CaseRecord:
    """One case: its id, inputs by name, each form's output by the form's key (``literal``,
    ``interpreted`` or ``output``), and -- hand-picked ones -- why it is there."""

    id: str
    inputs: Mapping[str, Value]
    outputs: Mapping[str, Output]
    note: str | None = None
    errata: tuple[int, ...] = ()

    def to_json(self) -> dict[str, Any]:
        """The case as the file writes it: id, inputs, outputs, note, errata."""
        entry: dict[str, Any] = {
            "id": self.id,
            "inputs": {name: _value_json(v) for name, v in self.inputs.items()},
        }
        for key, output in self.outputs.items():
            entry[key] = output.to_json() if isinstance(output, Failure) else _value_json(output)
        if self.note is not None:
            entry["note"] = self.note
        if self.errata:
            entry["errata"] = list(self.errata)
        return entry

    @classmethod
    def from_json(cls, data: object, keys: Sequence[str], where: str) -> CaseRecord:
        """Read a case; ``keys`` are its group's form keys."""
        case = _object(data, where)
        case_id = _text(_get(case, "id", where), f"{where}.id")
        where = f"{where} ({case_id})"
        inputs = _object(_get(case, "inputs", where), f"{where}.inputs")
        note = case.get("note")
        return cls(
            id=case_id,
            inputs={k: _value(v, f"{where}.inputs.{k}") for k, v in inputs.items()},
            outputs={key: _output(_get(case, key, where), f"{where}.{key}") for key in keys},
            note=None if note is None else _text(note, f"{where}.note"),
            errata=tuple(
                int(_number(e, f"{where}.errata"))
                for e in _array(case.get("errata", []), f"{where}.errata")
            ),
        )


@dataclass(frozen=True)
class GroupRecord:
    """An equation group: its citation, frame, random seed, forms (by key) and cases."""

    paper: str
    frame: str
    seed: int
    forms: Mapping[str, Form]
    cases: tuple[CaseRecord, ...]

    def to_json(self) -> dict[str, Any]:
        """The group as the file's ``equations`` entry."""
        return {
            "paper": self.paper,
            "frame": self.frame,
            "seed": self.seed,
            "forms": {key: form.to_json() for key, form in self.forms.items()},
            "cases": [case.to_json() for case in self.cases],
        }

    @classmethod
    def from_json(cls, data: object, where: str) -> GroupRecord:
        """Read an ``equations`` entry."""
        raw_forms = _object(_get(data, "forms", where), f"{where}.forms")
        forms = {key: Form.from_json(f, f"{where}.forms.{key}") for key, f in raw_forms.items()}
        cases = _array(_get(data, "cases", where), f"{where}.cases")
        return cls(
            paper=_text(_get(data, "paper", where), f"{where}.paper"),
            frame=_text(_get(data, "frame", where), f"{where}.frame"),
            seed=int(_number(_get(data, "seed", where), f"{where}.seed")),
            forms=forms,
            cases=tuple(
                CaseRecord.from_json(c, list(forms), f"{where}.cases[{i}]")
                for i, c in enumerate(cases)
            ),
        )


# ---- traces ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class TraceRecord:
    """A reference trace: which planner in which world, how it ended, the branches it took
    (in order of first use) and the recorded episode."""

    id: str
    planner: str
    world: str
    note: str
    stop_reason: str
    branches: tuple[str, ...]
    recording: Recording

    def to_json(self) -> dict[str, Any]:
        """The trace as the file writes it; reset and steps as protocol messages."""
        recording = self.recording
        return {
            "id": self.id,
            "planner": self.planner,
            "world": self.world,
            "note": self.note,
            "stop_reason": self.stop_reason,
            "branches": list(self.branches),
            "reset": reset_message(recording.start, recording.goal, recording.params),
            "steps": [
                {"observe": observe_message(obs), "command": command_message(cmd)}
                for obs, cmd in recording.steps
            ],
        }

    @classmethod
    def from_json(cls, data: object, where: str) -> TraceRecord:
        """Read a ``traces`` entry (its messages through :mod:`ifgm_ref.io.transport.wire`)."""
        branches = _array(_get(data, "branches", where), f"{where}.branches")
        return cls(
            id=_text(_get(data, "id", where), f"{where}.id"),
            planner=_text(_get(data, "planner", where), f"{where}.planner"),
            world=_text(_get(data, "world", where), f"{where}.world"),
            note=_text(_get(data, "note", where), f"{where}.note"),
            stop_reason=_text(_get(data, "stop_reason", where), f"{where}.stop_reason"),
            branches=tuple(_text(b, f"{where}.branches") for b in branches),
            recording=_recording(data, where),
        )


def _recording(trace: object, where: str) -> Recording:
    """A trace's ``reset`` and ``steps``; a malformed message is reported where it is."""
    reset_data = _get(trace, "reset", where)
    steps = _array(_get(trace, "steps", where), f"{where}.steps")
    at = f"{where}.reset"
    try:
        reset = parse_reset(reset_data)
        parsed = []
        for i, step in enumerate(steps):
            at = f"{where}.steps[{i}]"
            observation = parse_observe(_get(step, "observe", at))
            parsed.append((observation, parse_command(_get(step, "command", at))))
    except ProtocolError as err:
        raise ParameterError(f"vectors {at}: {err}") from None
    return Recording(reset.start, reset.goal, reset.params, tuple(parsed))


# ---- the document ----------------------------------------------------------------------------


@dataclass(frozen=True)
class VectorsDocument:
    """The whole file: how it was made, units and frames, tolerances, equations, traces."""

    generator: str
    units: Mapping[str, str]
    frames: Mapping[str, str]
    tolerances: Mapping[str, Quantity]
    equations: Mapping[str, GroupRecord]
    traces: tuple[TraceRecord, ...]

    def to_json(self) -> dict[str, Any]:
        """The document as JSON values, keys in the file's order."""
        return {
            "format": {"name": FORMAT_NAME, "version": FORMAT_VERSION},
            "generator": self.generator,
            "units": dict(self.units),
            "frames": dict(self.frames),
            "tolerances": {name: q.to_json() for name, q in self.tolerances.items()},
            "equations": {name: g.to_json() for name, g in self.equations.items()},
            "traces": [trace.to_json() for trace in self.traces],
        }

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> VectorsDocument:
        """Read a whole document (its format checked first)."""
        check_format(data)
        return cls(
            generator=_text(_get(data, "generator", "vectors"), "generator"),
            units=_texts(_get(data, "units", "vectors"), "units"),
            frames=_texts(_get(data, "frames", "vectors"), "frames"),
            tolerances=parse_tolerances(data),
            equations=parse_equations(data),
            traces=parse_traces(data),
        )


def parse_tolerances(document: Mapping[str, Any]) -> dict[str, Quantity]:
    """The ``tolerances`` of a document, by quantity name."""
    raw = _object(_get(document, "tolerances", "vectors"), "tolerances")
    return {name: Quantity.from_json(q, f"tolerances.{name}") for name, q in raw.items()}


def parse_equations(document: Mapping[str, Any]) -> dict[str, GroupRecord]:
    """The ``equations`` of a document, by group name."""
    raw = _object(_get(document, "equations", "vectors"), "equations")
    return {name: GroupRecord.from_json(g, f"equations.{name}") for name, g in raw.items()}


def parse_traces(document: Mapping[str, Any]) -> tuple[TraceRecord, ...]:
    """The ``traces`` of a document, in order."""
    raw = _array(_get(document, "traces", "vectors"), "traces")
    return tuple(TraceRecord.from_json(t, f"traces[{i}]") for i, t in enumerate(raw))


# ---- reading values --------------------------------------------------------------------------


def _get(data: object, key: str, where: str) -> Any:
    if not isinstance(data, Mapping):
        raise ParameterError(f"vectors {where}: must be an object, got {data!r}")
    if key not in data:
        raise ParameterError(f"vectors {where}.{key}: missing")
    return data[key]


def _object(value: object, where: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise ParameterError(f"vectors {where}: must be an object, got {value!r}")
    return value


def _array(value: object, where: str) -> list[Any]:
    if not isinstance(value, list):
        raise ParameterError(f"vectors {where}: must be an array, got {value!r}")
    return value


def _text(value: object, where: str) -> str:
    if not isinstance(value, str):
        raise ParameterError(f"vectors {where}: must be a string, got {value!r}")
    return value


def _texts(value: object, where: str) -> dict[str, str]:
    return {k: _text(v, f"{where}.{k}") for k, v in _object(value, where).items()}


def _number(value: object, where: str = "value") -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ParameterError(f"vectors {where}: must be a number, got {value!r}")
    return float(value)


def _value(value: object, where: str) -> Value:
    """A number, or an array of numbers as a tuple."""
    if isinstance(value, list):
        return tuple(_number(v, where) for v in value)
    return _number(value, where)


def _output(value: object, where: str) -> Output:
    if isinstance(value, Mapping):
        return Failure(_text(_get(value, "error", where), f"{where}.error"))
    return _value(value, where)


def _value_json(value: Value) -> float | list[float]:
    return [float(v) for v in value] if isinstance(value, tuple) else float(value)
