"""The formulas run as the code sympy prints for them, without importing sympy
(``ifgm_ref.core.formulas``, its pinned table ``ifgm_ref.core.lambdified``)."""

from __future__ import annotations

import functools
import subprocess
import sys
import textwrap
from collections.abc import Callable

import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.apps.formula_table import TABLE, render
from ifgm_ref.core import formulas
from ifgm_ref.core.formulas import SYMBOL_NAMES, Scale, declared, evaluate, formula_expr
from ifgm_ref.core.lambdified import LAMBDIFIED

#: A positive quantity of a robot, a time step or a sensor, across many orders of magnitude.
quantity = st.floats(min_value=1e-4, max_value=1e4, allow_nan=False, allow_infinity=False)


def test_the_committed_table_is_current() -> None:
    """Every formula of every module is in the table, as the installed sympy prints it; a
    sympy release that prints one otherwise fails here, not silently in a threshold."""
    assert TABLE.read_text(encoding="utf-8") == render(), (
        "ifgm_ref/core/lambdified.py is not current: run python -m ifgm_ref.apps.formula_table"
    )
    assert set(declared()) == set(LAMBDIFIED)
    assert len(LAMBDIFIED) > 30


@functools.cache
def _lambdified(formula: str) -> Callable[..., float]:
    return sympy.lambdify(formulas.SYMBOLS, formula_expr(formula), modules="math")


@given(st.tuples(*[quantity] * len(SYMBOL_NAMES)).map(lambda values: Scale(*values)))
def test_the_table_gives_lambdify_s_value_to_the_bit(scale: Scale) -> None:
    """The pinned code, run in :mod:`math`'s names, is the function sympy.lambdify makes."""
    for formula in LAMBDIFIED:
        assert evaluate(formula, scale) == float(_lambdified(formula)(*scale)), formula


def test_a_formula_not_in_the_table_is_printed_by_sympy() -> None:
    formula = "3*r/7 + v*dt"
    assert formula not in LAMBDIFIED
    scale = Scale.paper()
    assert evaluate(formula, scale) == scale.r * (3 / 7) + scale.dt * scale.v


def test_running_an_episode_imports_no_sympy() -> None:
    """A process that runs a planner in a world pays no sympy import (0.3 s at each start of
    ``ifgm-ref serve``, a ROS node or an oracle worker)."""
    code = textwrap.dedent(
        """
        import sys
        from ifgm_ref.core.params import SimParams
        from ifgm_ref.io.scenarios import resolve_world
        from ifgm_ref.planners import PLANNERS, make_planner
        from ifgm_ref.sim.simulator import simulate
        for name in PLANNERS:
            simulate(resolve_world("post"), make_planner(name), SimParams(max_time=0.3))
        print(sorted(m for m in sys.modules if m.split(".")[0] == "sympy"))
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=False
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_the_sympy_symbols_are_made_at_first_use() -> None:
    symbols = formulas.SYMBOLS
    assert [s.name for s in symbols] == list(SYMBOL_NAMES)
    assert all(s.is_positive for s in symbols)
    with pytest.raises(AttributeError, match="no attribute 'SYMBOLZ'"):
        _ = formulas.SYMBOLZ  # type: ignore[attr-defined]
