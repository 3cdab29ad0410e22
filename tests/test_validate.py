"""The one validator (ifgm_ref.core.validate): its rule, and that the configuration path words every
refusal of a number through it."""

from __future__ import annotations

import ast
import math
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import ParameterError, ProtocolError
from ifgm_ref.core.validate import NON_NEGATIVE, POSITIVE, REAL, Domain, require, violation

PACKAGE = Path(__file__).resolve().parent.parent / "ifgm_ref"

#: Anything a configuration may be handed.
VALUES = st.one_of(
    st.floats(),
    st.integers(min_value=-(10**400), max_value=10**400),
    st.booleans(),
    st.none(),
    st.text(max_size=3),
)


def _fits_a_float(value: int | float) -> bool:
    try:
        float(value)
    except OverflowError:
        return False
    return True


@given(value=VALUES, domain=st.sampled_from(Domain))
def test_a_value_passes_exactly_when_it_is_a_finite_number_in_the_domain(
    value: object, domain: Domain
) -> None:
    number = isinstance(value, int | float) and not isinstance(value, bool)
    finite = number and _fits_a_float(value) and math.isfinite(float(value))  # type: ignore[arg-type]
    inside = (
        finite
        and {
            REAL: True,
            POSITIVE: value > 0,  # type: ignore[operator]
            NON_NEGATIVE: value >= 0,  # type: ignore[operator]
        }[domain]
    )
    why = violation(value, domain)
    assert (why == "") is bool(inside), (value, domain, why)
    if why:
        assert why == f"must be a finite number{' ' + domain if domain else ''}, got {value!r}"


def test_require_names_the_value_and_raises_the_callers_error() -> None:
    assert require("dt", 1, POSITIVE) == 1.0 and type(require("dt", 1)) is float
    with pytest.raises(ParameterError, match=r"^`dt` must be a finite number > 0, got 0$"):
        require("dt", 0, POSITIVE)
    with pytest.raises(ProtocolError, match=r"^`x` must be a finite number, got 'a'$"):
        require("x", "a", error=ProtocolError)


#: The modules that still word a refusal of a number themselves, and why.
OWN_WORDING = {
    # numpy arrays of radii and coordinates, checked whole inside the ray-casting kernel
    "sim/raycast.py",
    # a scan range may also be null (no return): "must be a finite number or null"
    "io/transport/wire.py",
    # equations (1)-(4)'s messages are in the test vectors, whose bytes stay put
    "paper/equations.py",
}

#: The wordings of a refused number.
REFUSALS = ("must be finite", "must be > 0", "must be >= 0", "must be a finite number")


def _strings_outside_docstrings(tree: ast.AST) -> list[str]:
    docstrings = {
        id(node.body[0].value)
        for node in ast.walk(tree)
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef)
        and node.body
        and isinstance(node.body[0], ast.Expr)
        and isinstance(node.body[0].value, ast.Constant)
    }
    return [
        node.value
        for node in ast.walk(tree)
        if isinstance(node, ast.Constant)
        and isinstance(node.value, str)
        and id(node) not in docstrings
    ]


def test_every_refusal_of_a_number_is_worded_by_the_validator() -> None:
    """Issue 29: one validator. No module but :mod:`ifgm_ref.core.validate` (and the listed
    exceptions) writes "must be finite", "must be > 0" and the like itself."""
    found = {
        str(path.relative_to(PACKAGE))
        for path in PACKAGE.rglob("*.py")
        if path.name != "validate.py"
        for text in _strings_outside_docstrings(ast.parse(path.read_text()))
        if any(refusal in text for refusal in REFUSALS)
    }
    assert found == OWN_WORDING
