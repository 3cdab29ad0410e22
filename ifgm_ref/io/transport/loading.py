"""Find a Python planner by name: a built-in planner name or ``module:attribute``.

``ifgm-ref simulate``, ``ifgm-ref bench``, ``ifgm-ref serve``, the oracle and its pytest
plugin all name a Python planner the same way: either a built-in name (``ifgm``, see
``ifgm-ref planners``) or an import path to a factory, ``package.module:make_planner``, i.e.
any callable that takes no argument and returns a new object with ``name``, ``reset`` and
``step`` (:class:`ifgm_ref.core.protocol.Planner`). A class is such a callable. The oracle names
the equations under test the same way (:func:`resolve`;
:func:`ifgm_ref.oracle.equation_checks.load_equations`).
"""

from __future__ import annotations

import importlib
import os
import sys
from collections.abc import Callable

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.protocol import Planner
from ifgm_ref.planners import PLANNERS


def load_factory(spec: str) -> Callable[[], Planner]:
    """Resolve ``spec`` to a planner factory, or raise :class:`ImplementationError`.

    Examples
    --------
    >>> load_factory("ifgm")().name
    'ifgm'
    >>> load_factory("ifgm_ref.planners.iba:IBAPlanner")().name
    'iba'
    >>> load_factory("no_such_module_xyz:make")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ImplementationError: cannot import 'no_such_module_xyz' (from ...): No ...
    >>> load_factory("bogus")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ImplementationError: 'bogus' is neither a built-in planner (...) nor ...
    """
    if spec in PLANNERS:
        return PLANNERS[spec].factory
    module_name, sep, attribute = spec.partition(":")
    if not sep or not module_name or not attribute:
        known = ", ".join(sorted(PLANNERS))
        raise ImplementationError(
            f"{spec!r} is neither a built-in planner ({known}) nor module:attribute"
        )
    target = resolve(spec)
    if not callable(target):
        raise ImplementationError(f"{spec!r} is not callable, got {type(target).__name__}")
    return target


def resolve(spec: str) -> object:
    """The module ``spec`` names, or the attribute of ``module:attribute`` (dots go deeper).

    The current directory joins the import path if missing, as with ``python -m``. Any
    failure is an :class:`ImplementationError` naming ``spec``.

    Examples
    --------
    >>> resolve("ifgm_ref.planners.iba:IBAPlanner").__name__
    'IBAPlanner'
    >>> resolve("math:pi.real")
    3.141592653589793
    >>> resolve("math:tau_xyz")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ImplementationError: module 'math' has no attribute 'tau_xyz' (from ...)
    """
    module_name, _, attribute = spec.partition(":")
    if os.getcwd() not in sys.path and "" not in sys.path:
        sys.path.insert(0, os.getcwd())  # as ``python -m`` does: modules beside the user
    try:
        module = importlib.import_module(module_name)
    except Exception as err:  # any import-time failure of user code is reported, not raised
        source = "" if spec == module_name else f" (from {spec!r})"
        raise ImplementationError(f"cannot import {module_name!r}{source}: {err}") from err
    target: object = module
    for part in attribute.split(".") if attribute else []:
        try:
            target = getattr(target, part)
        except AttributeError:
            raise ImplementationError(
                f"module {module_name!r} has no attribute {attribute!r} (from {spec!r})"
            ) from None
    return target


def load_planner(spec: str) -> Planner:
    """A new planner from ``spec`` (:func:`load_factory`), checked to be one.

    >>> load_planner("os:getcwd")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ImplementationError: 'os:getcwd' made a str, not a planner: it has no ...
    """
    planner = load_factory(spec)()
    missing = [n for n in ("name", "reset", "step") if not hasattr(planner, n)]
    if missing:
        raise ImplementationError(
            f"{spec!r} made a {type(planner).__name__}, not a planner: it has no "
            f"{', '.join(missing)} (see ifgm_ref.core.protocol.Planner)"
        )
    return planner


def load_planner_factory(spec: str) -> Callable[[], Planner]:
    """:func:`load_factory`, once its factory has made a planner (:func:`load_planner`).

    What the oracle and ``ifgm-ref serve`` use, so that a factory that makes something else
    is one error before anything runs, not a failure in every check.

    >>> load_planner_factory("ifgm")().name
    'ifgm'
    """
    load_planner(spec)
    return load_factory(spec)
