"""The modules' old names (before issue 44 gave the layers folders) still import, as the new
modules themselves, with a warning naming the new place (:mod:`ifgm_ref.core.moved`)."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

from ifgm_ref.core.moved import MOVED, new_name


@pytest.mark.parametrize("old", sorted(MOVED))
def test_every_old_name_is_its_new_module(old: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delitem(sys.modules, old, raising=False)  # imported once already, it warns no more
    with pytest.warns(DeprecationWarning, match=f"{old} is now {MOVED[old]}"):
        module = importlib.import_module(old)
    assert module is importlib.import_module(MOVED[old])


def test_a_module_of_a_moved_package_follows_it() -> None:
    assert new_name("ifgm_ref.bench.soak") == "ifgm_ref.apps.bench.soak"
    assert new_name("ifgm_ref.planners.fgm") is None  # did not move
    for old in ("ifgm_ref.transport", "ifgm_ref.transport.wire"):
        sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning):
        from ifgm_ref.transport.wire import PROTOCOL_VERSION
    from ifgm_ref.io.transport import wire

    assert sys.modules["ifgm_ref.transport.wire"] is wire  # the module, not a second copy
    assert PROTOCOL_VERSION == wire.PROTOCOL_VERSION


def test_a_name_that_never_was_is_still_missing() -> None:
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("ifgm_ref.no_such_module")


def test_old_names_work_where_users_give_them() -> None:
    """``--ifgm-equations ifgm_ref.equations``, as docs of old told it, in a fresh process."""
    code = (
        "import importlib, ifgm_ref; print(importlib.import_module('ifgm_ref.equations').__name__)"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "ifgm_ref.paper.equations"
