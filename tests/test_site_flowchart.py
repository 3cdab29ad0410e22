"""The flowchart page of the documentation site (``docs/_ext/ifgm_site.py``): drawn by
Graphviz when its ``dot`` is installed, and otherwise said so on the page, with the source
shown (it was folded away, and the page looked empty). Needs the ``docs`` extra (Sphinx)."""

from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGE = (ROOT / "docs" / "flowchart.md").read_text()


@pytest.fixture(scope="module")
def site_ext() -> ModuleType:
    pytest.importorskip("sphinx", reason="the docs extra is not installed")
    spec = importlib.util.spec_from_file_location("ifgm_site", ROOT / "docs/_ext/ifgm_site.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["ifgm_site"] = module
    spec.loader.exec_module(module)
    return module


def test_without_graphviz_the_page_says_so_and_shows_the_source(
    site_ext: ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(shutil, "which", lambda name: None)
    page = site_ext._flowchart(PAGE)
    assert site_ext.NO_GRAPHVIZ in page
    assert "<details>" not in page and "flowchart TD" in page
    assert "{graphviz}" not in page


def test_with_graphviz_the_flowchart_is_drawn(
    site_ext: ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(shutil, "which", lambda name: "/usr/bin/dot")
    page = site_ext._flowchart(PAGE)
    assert "```{graphviz}" in page and site_ext.NO_GRAPHVIZ not in page
