"""Check an implementation against the vectors: its equations, and its planner on the traces.

:func:`check_vectors` runs any object with the equation functions' names against the equation
cases; :func:`replay_traces` steps a planner through the reference traces
(:func:`ifgm_ref.core.recording.replay`). Both read the document through its schema
(:mod:`ifgm_ref.oracle.vectors.schema`) and answer a list of mismatches in the oracle's
``quantity = actual, but should be expected [where]`` style.
"""

from __future__ import annotations

import math
import numbers
import warnings
from collections.abc import Callable, Mapping
from typing import Any

from ifgm_ref.core.protocol import Command, Planner
from ifgm_ref.core.recording import replay
from ifgm_ref.io.bags.read import same_branch
from ifgm_ref.oracle.vectors.schema import (
    CaseRecord,
    Failure,
    Form,
    GroupRecord,
    Output,
    Quantity,
    Tolerance,
    TraceRecord,
    VectorsDocument,
    check_format,
    check_precision,
    parse_equations,
    parse_tolerances,
    parse_traces,
)

__all__ = ["check_vectors", "replay_traces"]

#: The trace command fields compared, each by the file's quantity of that name.
COMPARED = ("heading", "speed")


def _values(value: Any) -> list[float] | None:
    """An implementation's output as a list of floats, or ``None`` if it is not numeric.

    A number (any real: ``float``, ``int``, ``numpy.float32``...) is a list of one; a
    sequence of numbers (a point) is itself.

    >>> import numpy as np
    >>> _values(np.float32(0.5)), _values((1, 2.5)), _values("1.0"), _values(True)
    ([0.5], [1.0, 2.5], None, None)
    """
    if _is_real(value):
        return [float(value)]
    if isinstance(value, str | bytes):
        return None
    try:
        items = list(value)
    except TypeError:
        return None
    return [float(v) for v in items] if all(map(_is_real, items)) else None


def _is_real(value: Any) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _shown(output: Output) -> Any:
    """An expected output as the file writes it (a point as a list)."""
    return list(output) if isinstance(output, tuple) else output


# ---- equations -------------------------------------------------------------------------------


def _compare_case(
    function: Callable[..., Any],
    form: Form,
    case: CaseRecord,
    expected: Output,
    quantity: Quantity,
    precision: str,
) -> str | None:
    """One mismatch message, or ``None`` when the implementation agrees on this case."""
    shown = ", ".join(f"{name}={case.inputs[name]!r}" for name in form.args)
    call = f"{form.function}({shown})"
    where = f"[case {case.id}]"
    try:
        actual = function(**{name: case.inputs[name] for name in form.args})
    except Exception as err:
        if isinstance(expected, Failure):
            return None  # any exception is the error the vector asks for
        return (
            f"{call} raised {type(err).__name__}: {err}, but should be {_shown(expected)!r} {where}"
        )
    values = _values(actual)
    if isinstance(expected, Failure):
        if values is not None and not all(map(math.isfinite, values)):
            return None  # NaN or inf is an error signal too
        return f"{call} = {actual!r}, but should fail: {expected.message} {where}"
    tolerance, periodic = quantity.tolerance(precision), quantity.periodic
    wanted = list(expected) if isinstance(expected, tuple) else [expected]
    if (
        values is not None
        and len(values) == len(wanted)
        and all(
            tolerance.allows(e, a, periodic=periodic) for e, a in zip(wanted, values, strict=True)
        )
    ):
        return None
    return (
        f"{call} = {actual!r}, but should be {_shown(expected)!r} "
        f"({tolerance.describe(periodic=periodic)}) {where}"
    )


def _equation_parts(
    vectors: Mapping[str, Any] | VectorsDocument, precision: str
) -> tuple[Mapping[str, Quantity], Mapping[str, GroupRecord]]:
    """The tolerances and equation groups of ``vectors`` (format, then precision, checked)."""
    if isinstance(vectors, VectorsDocument):
        check_precision(precision)
        return vectors.tolerances, vectors.equations
    check_format(vectors)
    check_precision(precision)
    return parse_tolerances(vectors), parse_equations(vectors)


def check_vectors(
    vectors: Mapping[str, Any] | VectorsDocument,
    equations: object,
    *,
    precision: str = "double",
    skipped: list[str] | None = None,
) -> list[str]:
    """Check an implementation's equation functions against the vectors.

    Parameters
    ----------
    vectors : dict or VectorsDocument
        A vectors document (:func:`~ifgm_ref.oracle.vectors.build_vectors`, the JSON file read
        back, or :func:`~ifgm_ref.oracle.vectors.build_document`).
    equations : object
        Anything with attributes named like the reference functions (a module, a namespace,
        an instance): ``eq1_gap_midpoint``, ``eq2_gap_angle``, ``eq2_gap_angle_literal``, ...
        Each is called with the case inputs as keyword arguments (points as tuples).
    precision : {"double", "float32"}, default "double"
        Which tolerance set of the file to apply.
    skipped : list, optional
        If given, the names of the functions ``equations`` lacks are appended to it; if not,
        a :class:`UserWarning` names them. A missing function is skipped, not failed.

    Returns
    -------
    list of str
        One message per mismatching case: ``call = actual, but should be expected (tolerance)
        [case id]``. Where the vector holds an error, any exception -- or a NaN or infinite
        result -- counts as the error; the message text is the reference's, for people.

    Examples
    --------
    >>> import types
    >>> from ifgm_ref.paper import equations
    >>> from ifgm_ref.oracle.vectors import build_vectors
    >>> vectors = build_vectors()
    >>> check_vectors(vectors, equations)
    []
    >>> blind = types.SimpleNamespace(
    ...     eq3_goal_angle=lambda current, destination: math.atan(
    ...         (destination[1] - current[1]) / (destination[0] - current[0])))
    >>> names = []
    >>> problems = check_vectors(vectors, blind, skipped=names)
    >>> print(problems[0].replace(", but", ",\\n but"))
    eq3_goal_angle(current=(0.0, 0.0), destination=(-1.0, 1.0)) = -0.7853981633974483,
     but should be 2.356194490192345 (tolerance 1e-09, modulo 2 pi) [case q2-behind]
    >>> len(names)
    8
    """
    tolerances, groups = _equation_parts(vectors, precision)
    missing: list[str] = []
    problems = [
        problem
        for group in groups.values()
        for problem in _check_group(group, equations, tolerances, precision, missing)
    ]
    _report_missing(missing, skipped)
    return problems


def _report_missing(missing: list[str], skipped: list[str] | None) -> None:
    """Append ``missing`` to ``skipped``, or warn the caller of :func:`check_vectors`."""
    if skipped is not None:
        skipped.extend(missing)
    elif missing:
        warnings.warn(
            f"check_vectors skipped {len(missing)} function(s) the implementation lacks: "
            + ", ".join(missing),
            stacklevel=3,
        )


def _check_group(
    group: GroupRecord,
    equations: object,
    tolerances: Mapping[str, Quantity],
    precision: str,
    missing: list[str],
) -> list[str]:
    """The mismatches of every form of ``group``; the functions ``equations`` lacks are
    appended to ``missing``."""
    problems: list[str] = []
    for key, form in group.forms.items():
        function = getattr(equations, form.function, None)
        if function is None:
            missing.append(form.function)
            continue
        quantity = tolerances[form.quantity]
        for case in group.cases:
            problem = _compare_case(function, form, case, case.outputs[key], quantity, precision)
            if problem is not None:
                problems.append(problem)
    return problems


# ---- traces ----------------------------------------------------------------------------------


def _command_mismatch(
    command: Command, expected: Command, compared: list[tuple[str, Tolerance, bool]], where: str
) -> str | None:
    """What ``command`` gets wrong against the recorded ``expected``, or ``None``."""
    for name, tolerance, periodic in compared:
        actual = getattr(command, name, None)
        values = _values(actual)
        wanted = getattr(expected, name)
        if (
            values is None
            or len(values) != 1
            or not tolerance.allows(wanted, values[0], periodic=periodic)
        ):
            return (
                f"{name}={actual!r}, but should be {wanted!r} "
                f"({tolerance.describe(periodic=periodic)}) {where}"
            )
    branch = getattr(command, "branch", None)
    if (
        branch is not None
        and expected.branch is not None
        and not same_branch(str(branch), expected.branch)
    ):
        return f"branch={str(branch)!r}, but should be {expected.branch!r} {where}"
    return None


def _trace_parts(
    vectors: Mapping[str, Any] | VectorsDocument, precision: str
) -> tuple[Mapping[str, Quantity], tuple[TraceRecord, ...]]:
    """The tolerances and traces of ``vectors`` (format, then precision, checked)."""
    if isinstance(vectors, VectorsDocument):
        check_precision(precision)
        return vectors.tolerances, vectors.traces
    check_format(vectors)
    check_precision(precision)
    return parse_tolerances(vectors), parse_traces(vectors)


def _replayed(
    trace: TraceRecord, planner: Planner, precision: str, tolerances: Mapping[str, Quantity]
) -> str | None:
    """The first mismatch of ``planner`` on ``trace``, or ``None``."""
    compared = [
        (name, tolerances[name].tolerance(precision), tolerances[name].periodic)
        for name in COMPARED
    ]
    try:
        steps = replay(trace.recording, planner)
    except Exception as err:
        return f"reset() raised {type(err).__name__}: {err} [trace {trace.id}]"
    for i, (observation, expected) in enumerate(trace.recording.steps):
        where = f"[trace {trace.id} step {i}, t={observation.t!r} s, branch {expected.branch}]"
        try:
            command = next(steps).command
        except Exception as err:
            return f"step() raised {type(err).__name__}: {err} {where}"
        problem = _command_mismatch(command, expected, compared, where)
        if problem is not None:
            return problem
    return None


def replay_traces(
    vectors: Mapping[str, Any] | VectorsDocument,
    factory: Callable[[], Planner],
    *,
    planner: str | None = None,
    precision: str = "double",
) -> list[str]:
    """Step fresh planners from ``factory`` through the reference traces; report mismatches.

    Each trace's planner is reset with the trace's ``reset`` message and fed its recorded
    observations in order (open loop: the planner's commands do not move anything); every
    command is compared with the recorded one -- heading modulo 2 pi and speed within the
    file's ``heading`` and ``speed`` tolerances, and the branch when the planner reports one.

    Parameters
    ----------
    vectors : dict or VectorsDocument
        A vectors document.
    factory : callable
        Makes a new planner (:class:`~ifgm_ref.core.protocol.Planner`); called once per trace.
    planner : str, optional
        Which traces to replay, by their ``planner`` name; default: the new planner's ``name``.
    precision : {"double", "float32"}, default "double"
        Which tolerance set of the file to apply.

    Returns
    -------
    list of str
        The first mismatch of each trace that has one, with its step, time and reference
        branch; a single message if no trace is for ``planner``.

    Examples
    --------
    >>> from ifgm_ref.planners import IBAPlanner
    >>> from ifgm_ref.oracle.vectors import build_vectors
    >>> vectors = build_vectors()
    >>> replay_traces(vectors, IBAPlanner)
    []
    >>> replay_traces(vectors, IBAPlanner, planner="bug3")
    ["no trace is for planner 'bug3', but traces exist for: iba, ifgm"]
    """
    tolerances, all_traces = _trace_parts(vectors, precision)
    name = planner if planner is not None else factory().name
    traces = [t for t in all_traces if t.planner == name]
    if not traces:
        known = ", ".join(sorted({t.planner for t in all_traces}))
        return [f"no trace is for planner {name!r}, but traces exist for: {known}"]
    problems = []
    for trace in traces:
        problem = _replayed(trace, factory(), precision, tolerances)
        if problem is not None:
            problems.append(problem)
    return problems
