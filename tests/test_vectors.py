"""The test vectors (``ifgm_ref.oracle.vectors``, ``docs/vectors-format.md``).

The file must be deterministic and JSON-clean; the reference must pass its own vectors; broken
equations and broken planners must be caught, with messages that name the equation or trace
and the case or step; and a float32 evaluation of the equations -- what a microcontroller port
computes -- must pass within the file's float32 tolerances (and fail the double ones), which
is the evidence that those tolerances are neither too tight nor pointless.
"""

from __future__ import annotations

import copy
import functools
import json
import math
import types
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.pose import Pose
from ifgm_ref.core.protocol import Command, Observation
from ifgm_ref.io.transport.wire import observe_message, parse_observe
from ifgm_ref.oracle.vectors import (
    FORMAT_NAME,
    FORMAT_VERSION,
    PRECISIONS,
    QUANTITIES,
    RANDOM_CASES,
    build_vectors,
    check_vectors,
    dumps_vectors,
    replay_traces,
    summarize,
    write_vectors,
)
from ifgm_ref.paper import equations
from ifgm_ref.paper.flowchart import Branch
from ifgm_ref.paper.percepts.clusters import Gap
from ifgm_ref.planners import IBAPlanner, IFGMPlanner
from tests.test_cli import run_cli

#: Errata rows (docs/errata.md) that touch equations (1)-(4) and FGM's gap centre angle.
EQUATION_ERRATA = frozenset({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 13})
#: The file must stay small enough to vendor into a port's repository.
MAX_BYTES = 1_000_000


@functools.cache
def _built() -> dict[str, Any]:
    return build_vectors()


def vectors() -> dict[str, Any]:
    """A private copy of the vectors (built once per session)."""
    return copy.deepcopy(_built())


def _cases() -> list[tuple[str, str, dict[str, Any]]]:
    """Every ``(group, form key, case)`` of the vectors."""
    return [
        (name, key, case)
        for name, group in _built()["equations"].items()
        for key in group["forms"]
        for case in group["cases"]
    ]


def _numbers(value: Any) -> list[Any]:
    """Every number anywhere inside ``value``."""
    if isinstance(value, dict):
        return [n for item in value.values() for n in _numbers(item)]
    if isinstance(value, list):
        return [n for item in value for n in _numbers(item)]
    if isinstance(value, float | int) and not isinstance(value, bool):
        return [value]
    return []


# ---- the file --------------------------------------------------------------------------------


def test_build_is_deterministic() -> None:
    first, second = build_vectors(), build_vectors()
    assert first == second
    assert dumps_vectors(first) == dumps_vectors(second)


def test_every_number_is_finite_and_the_file_round_trips_through_json() -> None:
    text = dumps_vectors(vectors())
    assert text.endswith("}\n")
    numbers = _numbers(vectors())
    assert numbers, "no numbers at all"
    bad = [n for n in numbers if not math.isfinite(n)]
    assert not bad, f"non-finite numbers: {bad[:5]}"

    def reject(constant: str) -> None:
        raise AssertionError(f"the file holds {constant}")

    assert json.loads(text, parse_constant=reject) == vectors()


def test_file_size_is_reasonable() -> None:
    size = len(dumps_vectors(vectors()).encode())
    assert size < MAX_BYTES, f"file size={size} bytes, but should be < {MAX_BYTES}"


def test_top_level_keys_and_format() -> None:
    v = vectors()
    assert list(v) == [
        "format",
        "generator",
        "units",
        "frames",
        "tolerances",
        "equations",
        "traces",
    ]
    assert v["format"] == {"name": FORMAT_NAME, "version": FORMAT_VERSION}
    assert v["units"] == {"length": "ft", "angle": "rad", "time": "s", "speed": "ft/s"}
    assert set(v["frames"]) == {"robot", "world"}
    assert set(v["tolerances"]) == set(QUANTITIES)
    for name, quantity in v["tolerances"].items():
        for precision in PRECISIONS:
            assert set(quantity[precision]) == {"abs", "rel"}, name
        assert quantity["float32"]["abs"] >= quantity["double"]["abs"], name
        assert quantity["reason"], name


def test_every_equation_function_has_cases_under_a_uniform_schema() -> None:
    forms = {
        form["function"]: key
        for group in vectors()["equations"].values()
        for key, form in group["forms"].items()
    }
    assert set(forms) == set(equations.__all__)
    for name, group in vectors()["equations"].items():
        keys = set(group["forms"])
        assert keys in ({"output"}, {"literal", "interpreted"}), name
        assert sum(c["id"].startswith("random-") for c in group["cases"]) == RANDOM_CASES
        ids = [c["id"] for c in group["cases"]]
        assert len(ids) == len(set(ids)), f"duplicate case ids in {name}"
        for case in group["cases"]:
            assert set(case) - {"note", "errata"} == {"id", "inputs"} | keys, case["id"]
            args = {a for form in group["forms"].values() for a in form["args"]}
            assert set(case["inputs"]) == args, case["id"]


def test_cases_exercise_every_errata_row_on_the_equations() -> None:
    covered = {
        row
        for group in vectors()["equations"].values()
        for case in group["cases"]
        for row in case.get("errata", ())
    }
    assert covered >= EQUATION_ERRATA, f"errata rows without a case: {EQUATION_ERRATA - covered}"


def test_literal_division_by_zero_is_the_exact_parameter_error_message() -> None:
    groups = vectors()["equations"]
    eq2 = {c["id"]: c for c in groups["eq2_gap_angle"]["cases"]}
    eq3 = {c["id"]: c for c in groups["eq3_goal_angle"]["cases"]}
    assert eq2["x_g-zero-left"]["literal"] == {
        "error": "eq. (2) as printed is undefined for x_g == 0 (division by zero); "
        "got (x_g, y_g) = (0.0, 1.0)"
    }
    assert eq2["x_g-zero-left"]["interpreted"] == math.pi / 2
    assert eq3["vertical-up"]["literal"] == {
        "error": "eq. (3) as printed is undefined for x_d == x_c (division by zero); "
        "got current=(1.0, 2.0), destination=(1.0, 7.0)"
    }
    assert eq3["q3-behind"]["literal"] == pytest.approx(math.pi / 4)
    assert eq3["q3-behind"]["interpreted"] == pytest.approx(-3 * math.pi / 4)


@given(data=st.data())
def test_stored_outputs_are_the_reference_outputs(data: st.DataObject) -> None:
    """Every case's stored output is, bit for bit, the reference function on its inputs."""
    name, key, case = data.draw(st.sampled_from(_cases()), label="case")
    form = _built()["equations"][name]["forms"][key]
    function = getattr(equations, form["function"])
    inputs = {a: tuple(v) if isinstance(v, list) else v for a, v in case["inputs"].items()}
    try:
        value = function(**{a: inputs[a] for a in form["args"]})
    except ParameterError as err:
        assert case[key] == {"error": str(err)}
        return
    expected = list(value) if isinstance(value, tuple) else value
    assert case[key] == expected, f"{form['function']} [case {case['id']}]"


# ---- checking equations ----------------------------------------------------------------------


def test_reference_equations_pass_their_vectors() -> None:
    skipped: list[str] = []
    assert check_vectors(vectors(), equations, skipped=skipped) == []
    assert skipped == []


def test_vectors_read_back_from_a_file_check_the_same(tmp_path: Path) -> None:
    path = tmp_path / "vectors.json"
    written = write_vectors(path)
    loaded = json.loads(path.read_text())
    assert loaded == written
    assert check_vectors(loaded, equations) == []


def _blind_eq3(current: tuple[float, float], destination: tuple[float, float]) -> float:
    return math.atan((destination[1] - current[1]) / (destination[0] - current[0]))


def _swapped_eq4(
    theta_g: float, theta_d: float, *, w_g: float, w_d: float, d_th: float, heading: float
) -> float:
    """Eq. (4) with the gap's weight on the goal and the goal's on the gap."""
    return equations.eq4_final_heading(
        theta_g, theta_d, w_g=w_d * d_th, w_d=w_g / d_th, d_th=d_th, heading=heading
    )


BROKEN: dict[str, tuple[dict[str, Callable[..., Any]], str, str]] = {
    "eq3 quadrant-blind atan": ({"eq3_goal_angle": _blind_eq3}, "eq3_goal_angle(", "q2-behind"),
    "eq2 sign flipped": (
        {"eq2_gap_angle": lambda x_g, y_g: -equations.eq2_gap_angle(x_g, y_g)},
        "eq2_gap_angle(",
        "q1-ahead-left",
    ),
    "eq4 weights swapped": (
        {"eq4_final_heading": _swapped_eq4},
        "eq4_final_heading(",
        "default-weights",
    ),
    "eq1 not halved": (
        {"eq1_gap_midpoint": lambda p1, p2: (p1[0] + p2[0], p1[1] + p2[1])},
        "eq1_gap_midpoint(",
        "doc-example",
    ),
    "eq2 literal as atan": (
        {"eq2_gap_angle_literal": lambda x_g, y_g: math.atan(y_g / x_g)},
        "eq2_gap_angle_literal(",
        "q1-ahead-left",
    ),
}


@pytest.mark.parametrize("broken", list(BROKEN))
def test_broken_equations_are_rejected_naming_equation_and_case(broken: str) -> None:
    functions, call, case = BROKEN[broken]
    reference = {name: getattr(equations, name) for name in equations.__all__}
    implementation = types.SimpleNamespace(**{**reference, **functions})
    problems = check_vectors(vectors(), implementation)
    assert problems, f"{broken} passed the vectors"
    assert all(p.startswith(call) for p in problems), problems
    assert any(p.endswith(f"[case {case}]") for p in problems), problems
    assert all(", but should be " in p or ", but should fail: " in p for p in problems)


def test_an_implementation_that_never_fails_is_told_which_error_it_missed() -> None:
    lenient = types.SimpleNamespace(eq2_gap_angle_literal=lambda x_g, y_g: 0.0)
    problems = check_vectors(vectors(), lenient, skipped=[])
    message = next(p for p in problems if p.endswith("[case x_g-zero-left]"))
    assert message.startswith("eq2_gap_angle_literal(x_g=0.0, y_g=1.0) = 0.0, but should fail: ")
    assert "division by zero" in message


def test_nan_and_any_exception_count_as_the_expected_error() -> None:
    def nan_or_raise(x_g: float, y_g: float) -> float:
        if x_g == 0 and y_g == 0:
            raise ZeroDivisionError("no direction")
        return math.nan if x_g == 0 else equations.eq2_gap_angle_literal(x_g, y_g)

    port = types.SimpleNamespace(eq2_gap_angle_literal=nan_or_raise)
    assert check_vectors(vectors(), port, skipped=[]) == []


def test_missing_functions_are_skipped_and_reported() -> None:
    partial = types.SimpleNamespace(eq1_gap_midpoint=equations.eq1_gap_midpoint)
    skipped: list[str] = []
    assert check_vectors(vectors(), partial, skipped=skipped) == []
    assert sorted(skipped) == sorted(set(equations.__all__) - {"eq1_gap_midpoint"})
    with pytest.warns(UserWarning, match="skipped 8 function"):
        check_vectors(vectors(), partial)


def test_wrong_format_or_precision_is_rejected() -> None:
    v = vectors()
    v["format"] = {"name": FORMAT_NAME, "version": FORMAT_VERSION + 1}
    with pytest.raises(ParameterError, match="vectors format="):
        check_vectors(v, equations)
    with pytest.raises(ParameterError, match="`precision` must be one of double, float32"):
        check_vectors(vectors(), equations, precision="half")


@given(data=st.data())
def test_an_output_off_by_more_than_the_tolerance_is_rejected(data: st.DataObject) -> None:
    """Shifting one numeric output by k times its tolerance fails for k > 1, passes for k < 1."""
    numeric = [c for c in _cases() if not isinstance(c[2][c[1]], dict)]
    name, key, case = data.draw(st.sampled_from(numeric), label="case")
    precision = data.draw(st.sampled_from(PRECISIONS), label="precision")
    factor = data.draw(
        st.one_of(st.floats(0.0, 0.9), st.floats(1.1, 100.0)), label="shift / tolerance"
    )
    sign = data.draw(st.sampled_from([-1.0, 1.0]), label="sign")
    v = vectors()
    group = v["equations"][name]
    form = group["forms"][key]
    expected = case[key]
    first = expected[0] if isinstance(expected, list) else expected
    bounds = v["tolerances"][form["quantity"]][precision]
    shift = sign * factor * (bounds["abs"] + bounds["rel"] * abs(first))
    shifted = first + shift
    if shifted - first != shift and not math.isclose(shifted - first, shift, rel_tol=1e-3):
        return  # the shift is below the output's ulp: nothing to test
    answer = [shifted, *expected[1:]] if isinstance(expected, list) else shifted
    v["equations"] = {name: {**group, "forms": {key: form}, "cases": [case]}}
    port = types.SimpleNamespace(**{form["function"]: lambda **_: answer})
    problems = check_vectors(v, port, precision=precision)
    assert len(problems) == (1 if factor > 1 else 0), problems


# ---- a float32 port --------------------------------------------------------------------------

F32 = np.float32
PI32 = F32(np.pi)


def _wrap32(angle: np.float32) -> np.float32:
    if -PI32 <= angle < PI32:
        return angle
    return F32((angle + PI32) % (F32(2.0) * PI32) - PI32)


def _mean32(
    theta_g: float, theta_d: float, gap: np.float32, goal: np.float32, heading: float
) -> np.float32:
    h = F32(heading)
    relative_g, relative_d = _wrap32(F32(theta_g) - h), _wrap32(F32(theta_d) - h)
    return _wrap32(h + (gap * relative_g + goal * relative_d) / (gap + goal))


def _float32(reference: Callable[..., Any], compute: Callable[..., Any]) -> Callable[..., Any]:
    """``compute`` in float32, after the reference's own domain checks (which raise)."""

    def port(*args: Any, **kwargs: Any) -> Any:
        reference(*args, **kwargs)
        return compute(*args, **kwargs)

    return port


def _fgm32(d1: float, phi1: float, d2: float, phi2: float) -> np.float32:
    d1_, d2_, phi1_ = F32(d1), F32(d2), F32(phi1)
    c = np.cos(phi1_ + F32(phi2))
    ratio = (d1_ + d2_ * c) / np.sqrt(d1_ * d1_ + d2_ * d2_ + F32(2.0) * d1_ * d2_ * c)
    return np.arccos(np.clip(ratio, F32(-1.0), F32(1.0))) - phi1_


FLOAT32 = types.SimpleNamespace(
    eq1_gap_midpoint=_float32(
        equations.eq1_gap_midpoint,
        lambda p1, p2: (
            (F32(p1[0]) + F32(p2[0])) * F32(0.5),
            (F32(p1[1]) + F32(p2[1])) * F32(0.5),
        ),
    ),
    eq2_gap_angle_literal=_float32(
        equations.eq2_gap_angle_literal, lambda x_g, y_g: F32(y_g) / F32(x_g)
    ),
    eq2_gap_angle=_float32(
        equations.eq2_gap_angle, lambda x_g, y_g: np.arctan2(F32(y_g), F32(x_g))
    ),
    fgm_gap_centre_angle=_float32(equations.fgm_gap_centre_angle, _fgm32),
    eq3_goal_angle_literal=_float32(
        equations.eq3_goal_angle_literal,
        lambda current, destination: np.arctan(
            (F32(destination[1]) - F32(current[1])) / (F32(destination[0]) - F32(current[0]))
        ),
    ),
    eq3_goal_angle=_float32(
        equations.eq3_goal_angle,
        lambda current, destination: np.arctan2(
            F32(destination[1]) - F32(current[1]), F32(destination[0]) - F32(current[0])
        ),
    ),
    eq4_final_heading_literal=_float32(
        equations.eq4_final_heading_literal,
        lambda theta_g, theta_d, *, w_g, w_d, d_th: (
            (F32(w_g) / F32(d_th) * F32(theta_g) + F32(w_d) * F32(theta_d))
            / (F32(w_g) / F32(d_th) + F32(w_d))
        ),
    ),
    eq4_final_heading=_float32(
        equations.eq4_final_heading,
        lambda theta_g, theta_d, *, w_g, w_d, d_th, heading: _mean32(
            theta_g, theta_d, F32(w_g) / F32(d_th), F32(w_d), heading
        ),
    ),
    eq4_final_heading_fgm=_float32(
        equations.eq4_final_heading_fgm,
        lambda theta_g, theta_d, *, alpha, beta, d_min, heading: _mean32(
            theta_g, theta_d, F32(alpha) / F32(d_min), F32(beta), heading
        ),
    ),
)


def test_a_float32_port_passes_the_float32_tolerances() -> None:
    assert check_vectors(vectors(), FLOAT32, precision="float32", skipped=[]) == []


def test_a_float32_port_fails_the_double_tolerances() -> None:
    """The double tolerances are tight enough to tell float32 from double."""
    problems = check_vectors(vectors(), FLOAT32, precision="double", skipped=[])
    assert len(problems) > 20


# ---- traces ----------------------------------------------------------------------------------


def test_the_format_page_lists_the_traces_as_the_file_holds_them() -> None:
    """docs/vectors-format.md's table of traces: id, planner, world, start, steps, stop and
    branches, row for row (it had gone stale once: starts and branch lists)."""
    page = (Path(__file__).resolve().parent.parent / "docs" / "vectors-format.md").read_text()
    rows = [
        [cell.strip().strip("`") for cell in line.strip("|").split("|")]
        for line in page.splitlines()
        if line.startswith("| `") and line.count("|") == 8
    ]
    listed = [
        (t["id"], t["planner"], t["world"], t["reset"]["start"], len(t["steps"]),
         t["stop_reason"], t["branches"])
        for t in vectors()["traces"]
    ]  # fmt: skip
    assert [
        (i, planner, world, [float(x) for x in start.strip("()").split(",")], int(steps), stop,
         branches.split(", "))
        for i, planner, world, start, steps, stop, branches in rows
    ] == [
        (i, planner, world, [round(x, 2) for x in start], steps, stop, branches)
        for i, planner, world, start, steps, stop, branches in listed
    ]  # fmt: skip


def test_traces_cover_every_branch_of_figure_3() -> None:
    v = vectors()
    taken = {
        step["command"]["branch"]
        for trace in v["traces"]
        if trace["planner"] == "ifgm"
        for step in trace["steps"]
    }
    assert taken == {str(b) for b in Branch}
    assert len(summarize(v).branches) >= 3
    for trace in v["traces"]:
        in_steps = list(dict.fromkeys(s["command"]["branch"] for s in trace["steps"]))
        assert trace["branches"] == in_steps, trace["id"]
        assert len(trace["branches"]) >= 2, trace["id"]
        assert 20 <= len(trace["steps"]) <= 90, trace["id"]


def test_trace_observations_are_protocol_messages() -> None:
    for trace in vectors()["traces"]:
        assert trace["reset"]["type"] == "reset"
        assert trace["reset"]["start"] == trace["steps"][0]["observe"]["pose"]
        for step in trace["steps"]:
            message = step["observe"]
            assert observe_message(parse_observe(message)) == message
            assert set(step["command"]) == {"type", "heading", "speed", "behaviour", "branch"}


@pytest.mark.parametrize("factory", [IFGMPlanner, IBAPlanner])
def test_reference_planners_replay_their_traces(factory: Callable[[], Any]) -> None:
    assert replay_traces(vectors(), factory) == []
    assert replay_traces(vectors(), factory, precision="float32") == []


class NegatedHeading(IFGMPlanner):
    """Steers to the mirror image of IFGM's heading about the robot's own heading."""

    def step(self, observation: Observation) -> Command:
        command = super().step(observation)
        theta = observation.pose.theta
        return Command(2.0 * theta - command.heading, command.speed, branch=command.branch)


class FlippedGapAngle(IFGMPlanner):
    """Case-1 with the sign of eq. (2) flipped: the gap mirrored about the heading."""

    def gap_heading(self, pose: Pose, gap: Gap) -> float:
        x_g, y_g = equations.eq1_gap_midpoint(gap.right, gap.left)
        return equations.eq4_final_heading(
            pose.theta - equations.eq2_gap_angle(x_g, y_g),
            equations.eq3_goal_angle(pose.position, self.goal),
            w_g=self.ifgm.w_g,
            w_d=self.ifgm.w_d,
            d_th=self.d_th,
            heading=pose.theta,
        )


def test_a_mirrored_heading_is_caught_with_trace_step_and_branch() -> None:
    problems = replay_traces(vectors(), NegatedHeading)
    assert problems
    assert all(p.startswith("heading=") and "[trace " in p and " step " in p for p in problems)
    assert any("[trace fig7a-ifgm step 0, t=0.0 s, branch case1_gap]" in p for p in problems)


def test_a_flipped_gap_angle_is_caught_in_case1() -> None:
    problems = replay_traces(vectors(), FlippedGapAngle)
    assert len(problems) == 1, problems
    assert problems[0].startswith("heading=")
    assert problems[0].endswith("[trace fig7a-ifgm step 0, t=0.0 s, branch case1_gap]")


def test_a_crashing_planner_is_reported_not_raised() -> None:
    class Crashing(IBAPlanner):
        def step(self, observation: Observation) -> Command:
            raise RuntimeError("boom")

    problems = replay_traces(vectors(), Crashing)
    assert problems == [
        "step() raised RuntimeError: boom [trace post-iba step 0, t=0.0 s, branch move_to_goal]"
    ]


def test_replay_for_a_planner_without_traces_says_so() -> None:
    assert replay_traces(vectors(), IBAPlanner, planner="bug1") == [
        "no trace is for planner 'bug1', but traces exist for: iba, ifgm"
    ]


# ---- command line ----------------------------------------------------------------------------


def test_cli_writes_the_vectors_and_a_one_line_summary(tmp_path: Path) -> None:
    out = tmp_path / "vectors.json"
    done = run_cli("vectors", "--out", str(out))
    assert done.returncode == 0, done.stderr
    assert done.stdout == ""
    lines = done.stderr.splitlines()
    assert len(lines) == 1, done.stderr
    summary = summarize(vectors())
    size = out.stat().st_size
    assert lines[0] == f"wrote {summary} to {out} ({size} bytes)"
    assert f"{summary.cases} equation cases" in lines[0]
    assert f"{summary.traces} traces" in lines[0]
    assert out.read_text() == dumps_vectors(vectors())


def test_cli_vectors_requires_out() -> None:
    done = run_cli("vectors")
    assert done.returncode == 2
    assert "--out" in done.stderr
