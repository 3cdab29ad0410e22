"""Test-suite settings: Hypothesis profiles, and how many workers ``-n auto`` starts.

``ci`` (the default, and what CI runs) is derandomized, so the same commit gives the same
examples; ``deep`` draws many more examples for long local runs:
``HYPOTHESIS_PROFILE=deep pytest``.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci",
    derandomize=True,
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "deep",
    max_examples=2000,
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


def pytest_xdist_auto_num_workers(config: pytest.Config) -> int:
    """One worker more than the processors: some tests wait on purpose (a program past its
    timeout, a slow start, a signal), and the extra worker keeps every processor busy
    meanwhile (docs/testing.md, "On every core")."""
    usable = os.sched_getaffinity(0) if hasattr(os, "sched_getaffinity") else None
    return (len(usable) if usable else os.cpu_count() or 1) + 1
