"""The equations' input domains (``ifgm_ref.oracle.domains``), and that their users share them.

The domains are defined once; the oracle's equation checks draw from them, the vectors'
random cases from their ``vectors`` sub-ranges, ``tests/test_equations.py`` through
:func:`~ifgm_ref.oracle.domains.floats`. These tests pin that the table matches the
functions' signatures, that every sub-range lies in its domain, that the vectors file holds
what the table says, and that the reference accepts the domain bar its stated singular points.
"""

from __future__ import annotations

import inspect
import math
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.oracle.check_types import Kind
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.domains import DOMAINS, Argument, Interval, floats, inputs
from ifgm_ref.oracle.vectors import build_vectors
from ifgm_ref.paper import equations

NAMES = list(DOMAINS)


def _values(argument: Argument, value: Any) -> list[float]:
    return list(value) if argument.point else [value]


@pytest.mark.parametrize("name", NAMES)
def test_domain_arguments_are_the_function_parameters(name: str) -> None:
    parameters = list(inspect.signature(getattr(equations, name)).parameters)
    assert [a.name for a in DOMAINS[name].arguments] == parameters


@pytest.mark.parametrize("name", NAMES)
def test_every_vectors_range_lies_in_its_domain(name: str) -> None:
    for argument in DOMAINS[name].arguments:
        inner, outer = argument.vectors, argument.domain
        assert outer.low <= inner.low < inner.high <= outer.high, argument.name


def test_every_random_vector_input_lies_in_its_ranges() -> None:
    groups = build_vectors()["equations"]
    for name, domain in DOMAINS.items():
        cases = [c for c in groups[name]["cases"] if c["id"].startswith("random-")]
        assert cases, name
        for case in cases:
            for argument in domain.arguments:
                for value in _values(argument, case["inputs"][argument.name]):
                    assert argument.vectors.contains(value), (name, case["id"], argument.name)
                    assert argument.domain.contains(value), (name, case["id"], argument.name)


@given(data=st.data())
def test_floats_stay_in_their_interval(data: st.DataObject) -> None:
    low = data.draw(st.floats(-1e3, 1e3), label="low")
    high = data.draw(st.floats(low, 1e3).filter(lambda h: h > low), label="high")
    smallest = data.draw(st.sampled_from([0.0, 1e-9, 1e-3]), label="smallest")
    interval = Interval(low, high, smallest)
    if smallest > 0 and not (high >= smallest or low <= -smallest or low <= 0.0 <= high):
        return  # no float of the interval is 0 or at least `smallest` in size
    value = data.draw(floats(interval), label="value")
    assert interval.contains(value), f"{value=}, but should be in {interval}"


@pytest.mark.parametrize("name", [n for n, c in CHECKS.items() if c.kind is Kind.EQUATION])
@given(data=st.data())
def test_the_oracle_draws_equation_inputs_from_the_domain(name: str, data: st.DataObject) -> None:
    kwargs = data.draw(CHECKS[name].strategy(None), label="inputs")  # type: ignore[arg-type]
    domain = DOMAINS[name.removesuffix("_literal")]
    assert list(kwargs) == list(inspect.signature(getattr(equations, name)).parameters)
    for key, value in kwargs.items():
        argument = domain.argument(key)
        assert all(argument.domain.contains(v) for v in _values(argument, value)), key


@pytest.mark.parametrize("name", NAMES)
@given(data=st.data())
def test_the_reference_accepts_its_domain_bar_the_singular_points(
    name: str, data: st.DataObject
) -> None:
    """Every function returns finite numbers on its domain, or raises ParameterError on one of
    the singular points its domain names."""
    for function in (name, f"{name}_literal"):
        if not hasattr(equations, function):
            continue
        parameters = tuple(inspect.signature(getattr(equations, function)).parameters)
        kwargs = data.draw(inputs(name, parameters), label=function)
        try:
            result = getattr(equations, function)(**kwargs)
        except ParameterError:
            assert _singular(name, function, kwargs), f"{function}({kwargs}) raised"
            continue
        assert all(map(math.isfinite, result if isinstance(result, tuple) else [result]))


def _singular(name: str, function: str, kwargs: dict[str, Any]) -> bool:
    """Whether ``kwargs`` is a singular point of the domain of ``name``, as it says."""
    if name == "eq2_gap_angle":
        return kwargs["x_g"] == 0 and (function.endswith("_literal") or kwargs["y_g"] == 0)
    if name == "eq3_goal_angle":
        (x_c, y_c), (x_d, y_d) = kwargs["current"], kwargs["destination"]
        return x_d == x_c and (function.endswith("_literal") or y_d == y_c)
    if name == "fgm_gap_centre_angle":
        return kwargs["phi1"] + kwargs["phi2"] < 0
    if name.startswith("eq4"):
        weights = [v for k, v in kwargs.items() if k in ("w_g", "w_d", "alpha", "beta")]
        return all(w == 0 for w in weights)
    return False
