"""Draw the oracle's examples from Hypothesis's global constants only, never from local ones.

Contract: inside :func:`global_constants_only`, every Hypothesis draw in this thread sees an
empty pool of *local* constants, so a seed gives the same examples whatever is installed or
imported: an editable install of this package, a wheel in ``site-packages``, or a user's own
planner module imported first. :func:`~ifgm_ref.oracle.runner.run_check` draws every check
inside it, so ``ifgm-ref oracle``, :func:`~ifgm_ref.oracle.runner.check_planner` and the
pytest plugin all get the same examples.

Why: since 6.131, Hypothesis's default provider
(``hypothesis/internal/conjecture/providers.py``) now and then (0.05 of the draws of an
integer, a string or bytes, 0.15 of a float's) draws a constant instead, half the time one it
found in the source of the *local* modules in ``sys.modules``: those outside
``site-packages`` and the standard library. Which modules are
local depends on how this package was installed and on what the caller imported first, so the
examples of one seed did too (the reference-agreement check drew 41,230 reference steps
from the command line and 41,257 from the Python API, ``docs/oracle.md``). Hypothesis has no
setting that turns the local constants off: the opt-out asked for in its issue #4365 (closed
by a speed fix, without one) and #4627 (open) does not exist. Its *global* constants (the
boundary values it always tries) stay: they depend on Hypothesis's version only.

How: the pool a draw reads, ``HypothesisProvider._local_constants``, is replaced by an empty
one for the duration, and the cache of permitted constants (``CONSTANTS_CACHE``, one a
thread) is cleared on the way in and out. It is scoped rather than set once at import because
the pytest plugin loads in every pytest session where this package is installed: the user's
own Hypothesis tests keep their local constants. Nested uses are harmless (only the outermost
restores). A Hypothesis that no longer has what is replaced raises
:class:`HypothesisChanged`, naming its version and what is missing (every check of the
oracle's report is then an error that says so): silently drawing from local constants again
would make the examples depend on the install once more.

>>> from hypothesis.internal.conjecture.providers import HypothesisProvider
>>> with global_constants_only():
...     len(HypothesisProvider(None)._local_constants)
0
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import hypothesis
from hypothesis.version import __version_info__ as HYPOTHESIS_VERSION

from ifgm_ref.core.errors import IfgmRefError

__all__ = ["FIRST_WITH_LOCAL_CONSTANTS", "HypothesisChanged", "global_constants_only"]

#: The first Hypothesis that draws local constants (6.131.0); before it there is nothing to
#: replace and every draw is already the same in every install.
FIRST_WITH_LOCAL_CONSTANTS = (6, 131, 0)
#: Where the pool lives, and the names replaced or checked there.
PROVIDERS = "hypothesis.internal.conjecture.providers"
POOL = "_local_constants"


class HypothesisChanged(IfgmRefError, RuntimeError):
    """The installed Hypothesis no longer has the local-constants pool this module empties."""


@contextmanager
def global_constants_only() -> Iterator[None]:
    """Draw from Hypothesis's global constants only while in the block (this thread's cache).

    Raises
    ------
    HypothesisChanged
        When this Hypothesis (6.131 or later) has no ``HypothesisProvider._local_constants``
        that its constant draws read, or no ``CONSTANTS_CACHE`` to clear.
    """
    if HYPOTHESIS_VERSION < FIRST_WITH_LOCAL_CONSTANTS:
        yield
        return
    provider, cache = _pool()
    original = vars(provider)[POOL]
    if original is _EMPTY_POOL:  # an outer block holds it
        yield
        return
    cache.clear()  # permitted constants computed from the local pool before
    setattr(provider, POOL, _EMPTY_POOL)
    try:
        yield
    finally:
        setattr(provider, POOL, original)
        cache.clear()  # those computed from the empty pool


def _no_local_constants(provider: object) -> Any:
    """The local pool of every provider in the block: empty (a new one each, never shared)."""
    return importlib.import_module(PROVIDERS).Constants()


#: What replaces the pool: a property, so no provider caches a pool of its own over it.
_EMPTY_POOL = property(_no_local_constants)


def _pool() -> tuple[type, Any]:
    """The provider class whose pool is replaced and its thread's cache of permitted
    constants; :class:`HypothesisChanged` naming what this Hypothesis lacks."""
    providers = importlib.import_module(PROVIDERS)
    provider = getattr(providers, "HypothesisProvider", None)
    draw = getattr(provider, "_maybe_draw_constant", None)
    cache = getattr(getattr(providers, "CONSTANTS_CACHE", None), "cache", None)
    missing = [
        what
        for what, absent in (
            ("HypothesisProvider", provider is None),
            (f"HypothesisProvider.{POOL}", provider is not None and POOL not in vars(provider)),
            (
                f"HypothesisProvider._maybe_draw_constant reading {POOL}",
                POOL not in getattr(getattr(draw, "__code__", None), "co_names", ()),
            ),
            ("CONSTANTS_CACHE.cache", not hasattr(cache, "clear")),
            ("Constants", not callable(getattr(providers, "Constants", None))),
        )
        if absent
    ]
    if missing or provider is None:
        raise HypothesisChanged(
            f"Hypothesis {hypothesis.__version__} has no {', '.join(missing)} in {PROVIDERS}: "
            "ifgm_ref.oracle.stable_draws cannot keep the oracle's draws from its local "
            "constants, and the examples would depend on the install; use a Hypothesis it "
            "knows (6.155.2 is tested) or update the module"
        )
    return provider, cache
