"""The oracle's equation checks: an implementation's eqs. (1)-(4) against the reference.

Each check draws keyword arguments from the equation's domain
(:func:`ifgm_ref.oracle.domains.inputs`, the same table the test vectors and
``tests/test_equations.py`` draw from), calls the implementation's function of that name and
the reference's, and fails when they differ by more than :data:`EQUATION_TOL` (a point by its
distance, a direction modulo 2 pi). Inputs where the reference raises (the domain's singular
points) are skipped. A program, which exposes no Python functions, checks its equations
against the test vectors instead (``docs/vectors-format.md``).
"""

from __future__ import annotations

import math
from typing import Any

from hypothesis import strategies as st

from ifgm_ref.core.elements import traces
from ifgm_ref.core.errors import IfgmRefError, ImplementationError
from ifgm_ref.io.transport.loading import resolve
from ifgm_ref.oracle.check_types import Check, CheckFailed, Evidence, Kind, Recorder
from ifgm_ref.oracle.domains import inputs
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.paper import equations as reference

__all__ = [
    "EQUATION_TOL",
    "NO_EQUATIONS",
    "NO_EQUATIONS_PROGRAM",
    "equation_checks",
    "load_equations",
]

#: Why the equation checks do not apply to a Python implementation given without equations:
#: how to give them, on the command line, under pytest and in Python.
NO_EQUATIONS = (
    "no equations given: --equations MODULE (ifgm-ref oracle), --ifgm-equations MODULE "
    "(pytest), equations= (check_planner)"
)
#: ... and to a program: it has no Python functions to call.
NO_EQUATIONS_PROGRAM = (
    "a program exposes no Python functions: check its eqs. (1)-(4) against the vectors of "
    "`ifgm-ref vectors` (docs/vectors-format.md)"
)
#: Equation outputs may differ from the reference by this much (ft, or rad modulo 2 pi).
EQUATION_TOL = 1e-9


def _angle_gap(a: float, b: float) -> float:
    return abs(math.remainder(a - b, 2.0 * math.pi))


def _equation_check(
    name: str, sentence: str, examples: st.SearchStrategy[dict[str, Any]], *, angle: bool
) -> Check:
    """A check that ``impl.equations.<name>`` agrees with the reference on drawn inputs."""

    def test(impl: Implementation, kwargs: dict[str, Any], rec: Recorder) -> None:
        rec.examples += 1
        rec.evidence = Evidence(inputs=kwargs)
        try:
            want = getattr(reference, name)(**kwargs)
        except IfgmRefError:  # outside the equation's domain: nothing to compare
            return
        try:
            got = getattr(impl.equations, name)(**kwargs)
        except Exception as err:
            raise CheckFailed(
                f"{name}({_args(kwargs)}) raised {type(err).__name__}: {err}, but should be "
                f"{want!r} [{impl.label}]"
            ) from err
        try:
            if angle:
                error = _angle_gap(float(got), want)
            elif isinstance(want, tuple):
                error = math.dist(tuple(got), want)
            else:
                error = abs(float(got) - want)
        except (TypeError, ValueError) as err:
            raise CheckFailed(
                f"{name}({_args(kwargs)}) = {got!r}, but should be {want!r} [{impl.label}]"
            ) from err
        if not error <= EQUATION_TOL:
            raise CheckFailed(
                f"{name}({_args(kwargs)}) = {got!r}, but should be {want!r} within "
                f"{EQUATION_TOL:g} [{impl.label}]"
            )

    def applies(impl: Implementation) -> str | None:
        if impl.equations is None:
            return NO_EQUATIONS_PROGRAM if impl.is_program else NO_EQUATIONS
        if not callable(getattr(impl.equations, name, None)):
            return f"the equations object has no {name}"
        return None

    return Check(name, sentence, Kind.EQUATION, lambda impl: examples, test, applies)


def _args(kwargs: dict[str, Any]) -> str:
    return ", ".join(f"{k}={v!r}" for k, v in kwargs.items())


_EQ4_LITERAL_ARGS = ("theta_g", "theta_d", "w_g", "w_d", "d_th")

#: The checked functions: name, sentence, the equation whose domain gives the inputs, the
#: arguments taken (``None``: all of the domain's), whether the output is a direction.
_CHECKED: tuple[tuple[str, str, str, tuple[str, ...] | None, bool], ...] = (
    (
        "eq1_gap_midpoint",
        "eq. (1): the gap midpoint is the mean of the two saved obstacle points",
        "eq1_gap_midpoint",
        None,
        False,
    ),
    ("eq2_gap_angle", "eq. (2) as run: theta_g = atan2(y_g, x_g)", "eq2_gap_angle", None, True),
    ("eq2_gap_angle_literal", "eq. (2) as printed: y_g / x_g", "eq2_gap_angle", None, False),
    (
        "eq3_goal_angle",
        "eq. (3) as run: the quadrant-aware bearing of the destination",
        "eq3_goal_angle",
        None,
        True,
    ),
    (
        "eq3_goal_angle_literal",
        "eq. (3) as printed: arctan((y_d - y_c) / (x_d - x_c))",
        "eq3_goal_angle",
        None,
        False,
    ),
    (
        "eq4_final_heading",
        "eq. (4) as run: the weighted mean of gap and goal directions, robot frame",
        "eq4_final_heading",
        None,
        True,
    ),
    (
        "eq4_final_heading_literal",
        "eq. (4) as printed: the weighted mean of the two angles as numbers",
        "eq4_final_heading",
        _EQ4_LITERAL_ARGS,
        False,
    ),
)


@traces("eq1", "eq2", "eq3", "eq4")
def equation_checks() -> list[Check]:
    """The equation checks, one per function of :mod:`ifgm_ref.paper.equations` they cover (FGM's
    two forms are not among them)."""
    return [
        _equation_check(name, sentence, inputs(equation, args), angle=angle)
        for name, sentence, equation, args, angle in _CHECKED
    ]


def load_equations(spec: str) -> object:
    """The equations under test: the module ``spec`` names, or ``module:attribute``.

    It must expose at least one of the functions the oracle's equation checks compare with
    :mod:`ifgm_ref.paper.equations` (``eq1_gap_midpoint`` ... ``eq4_final_heading_literal``, the
    names of the checks), with the reference's signatures.

    >>> load_equations("ifgm_ref.paper.equations").__name__
    'ifgm_ref.paper.equations'
    >>> load_equations("math")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ImplementationError: 'math' has none of the equation functions eq1_gap_...
    """
    target = resolve(spec)
    names = [check.name for check in equation_checks()]
    if not any(callable(getattr(target, name, None)) for name in names):
        raise ImplementationError(
            f"{spec!r} has none of the equation functions {', '.join(names)} "
            "(see ifgm_ref.paper.equations)"
        )
    return target
