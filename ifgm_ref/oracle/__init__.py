"""The oracle: property checks that any IFGM, IBA, FGM or Bug implementation can be run against.

Its whole Python face: :func:`check` runs every check an implementation's :class:`Promises`
make apply, as hard as a :class:`Profile` says, and returns a :class:`Report` of one
:class:`CheckResult` (a :class:`Status`, a message, the examples and worlds run) per check.
A planner is a factory (a class will do), a built-in planner's name, or ``module:attribute``;
a program in another language is ``"cmd: ./my_planner"`` (``docs/oracle.md``).

A planner that promises to converge in open worlds only, under a profile of two examples a
check:

>>> from ifgm_ref.oracle import Profile, Promises, check
>>> from ifgm_ref.planners.ifgm import IFGMPlanner
>>> tiny = Profile("tiny", max_examples=2)
>>> open_only = Promises(converges_in=frozenset({"open"}))
>>> report = check(IFGMPlanner, profile=tiny, promises=open_only,
...                checks=["collision_free", "converges_open"], artifacts=None)
>>> report.ok, [result.status.value for result in report.results]
(True, ['passed', 'passed'])

A planner that drives straight at the goal, promised collision-free, fails on the first world
(shrunk to the simplest that still fails); the message says what should have been:

>>> from ifgm_ref.planners.straight import StraightPlanner
>>> report = check(StraightPlanner, profile=tiny, promises=open_only,
...                checks=["collision_free"], artifacts=None)
>>> report.ok
False
>>> print(report["collision_free"].message)  # doctest: +ELLIPSIS
min_clearance=-0.128 ft at t=3.4 s, but should be >= 0 [...StraightPlanner in open world ...]

Importing this package is cheap (the pytest plugin imports it in every pytest session): the
names above load their modules, and Hypothesis, when first used. The rest of the oracle
(its checks, strategies, the suite, the test vectors, what each module is for) is
``docs/oracle-modules.md``.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # annotations only: importing the package loads none of the oracle
    from collections.abc import Callable, Iterable, Mapping
    from pathlib import Path
    from typing import Any

    from ifgm_ref.core.protocol import Planner
    from ifgm_ref.oracle.implementation import Implementation
    from ifgm_ref.oracle.profiles import Profile
    from ifgm_ref.oracle.runner import CheckResult, Report, Status
    from ifgm_ref.planners.promises import Promises

__all__ = ["CheckResult", "Profile", "Promises", "Report", "Status", "check"]

#: Each name of the face, and the module that defines it (loaded when the name is first used).
_HOMES = {
    "CheckResult": "ifgm_ref.oracle.runner",
    "Profile": "ifgm_ref.oracle.profiles",
    "Promises": "ifgm_ref.planners.promises",
    "Report": "ifgm_ref.oracle.runner",
    "Status": "ifgm_ref.oracle.runner",
}


def __getattr__(name: str) -> Any:
    """Load a name of the face from its module on first use (PEP 562)."""
    if name not in _HOMES:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(importlib.import_module(_HOMES[name]), name)


def __dir__() -> list[str]:
    return sorted([*globals(), *_HOMES])


def check(
    planner: Callable[[], Planner] | Implementation | str,
    *,
    profile: Profile | str = "quick",
    promises: Promises | str | None = None,
    checks: Iterable[str] | None = None,
    expected_failed_checks: Mapping[str, str] | None = None,
    artifacts: str | Path | None = "oracle-failures",
    on_fail: str | None = None,
    level: str | None = None,
    spec: str | Path | None = None,
) -> Report:
    """Check a planner implementation against every property it promises: the arguments an
    implementer needs of :func:`~ifgm_ref.oracle.runner.check_planner` (which takes more).

    Parameters
    ----------
    planner : callable, Implementation or str
        A factory returning a new planner (a class will do), or a built-in name, or
        ``module:attribute``, or ``"cmd: ./my_planner"`` (a program speaking the JSON-lines
        protocol, ``docs/oracle-protocol.md``).
    profile : {"quick", "standard", "thorough", "robust", "brief"} or Profile, default "quick"
        How hard to look: examples per check (50, 200, 1000; ``robust``: 50 under the noise
        the planner promises; ``brief``: 10).
    promises : Promises or str, optional
        What it promises (the checks that apply), or a built-in planner's name (default: what
        the planner declares, a built-in's own; a program's, IFGM's; anything else must say).
    checks : iterable of str, optional
        Run only these checks (default: every one that applies).
    expected_failed_checks : mapping of str to str, optional
        ``{check: reason}``: checks known to fail, reported as expected failures.
    artifacts : path or None, default "oracle-failures"
        Where a failure's counterexample is written (world file, trace, plot, ``report.md``
        with the ``ifgm-ref simulate`` command that replays it); ``None``: nowhere.
    on_fail : {None, "raise", "warn"}, default None
        Raise :class:`AssertionError`, or warn, when a check failed or errored.
    level : {"paper", "reference"}, default "paper"
        The paper's properties, or also ``agrees_with_reference``.
    spec : path, optional
        Its declared specification (TOML: promises, level, robot, sensor, dt, goal tolerance).

    Returns
    -------
    Report
        One :class:`CheckResult` per check (``report["collision_free"]``), ``report.ok``, and
        ``report.text()``: a line per check, then a summary.
    """
    from ifgm_ref.oracle.runner import check_planner

    return check_planner(
        planner,
        profile=profile,
        promises=promises,
        checks=checks,
        expected_failed_checks=expected_failed_checks,
        artifacts=artifacts,
        on_fail=on_fail,
        level=level,
        spec=spec,
    )
