"""The documentation site, built once per test run with ``ifgm-ref docs --strict``.

Shared by the site's checks without a browser (``tests/test_site_build.py``: the strict build
and the internal links, in every run) and those in one (``tests/test_site.py``, ``-m
browser``). ``$IFGM_SITE_DIR`` names a site built already, to check it instead.
"""

from __future__ import annotations

import functools
import html.parser
import os
import shutil
import subprocess
import sys
from pathlib import Path
from urllib.parse import unquote, urldefrag, urlsplit

import pytest

from tests.built_once import built_once

ROOT = Path(__file__).resolve().parent.parent
#: How the site's packages are installed.
DOCS_SETUP = 'pip install -e ".[dev]" (it brings the docs extra)'


#: The one warning a build may give, where Graphviz's ``dot`` is missing: the machine's gap,
#: not the site's, which then shows the flowchart as source and says so on the page.
NO_DOT = "WARNING: Graphviz's `dot` is not installed"


def built_site(factory: pytest.TempPathFactory) -> Path:
    """The built site: ``$IFGM_SITE_DIR``, or a fresh strict ``ifgm-ref docs`` build (any
    Sphinx warning fails it, and the caller with Sphinx's last lines), where Graphviz is
    installed; without it, a build whose only warning is :data:`NO_DOT`. The notebooks are
    rendered, not run (``IFGM_DOCS_EXECUTE=off``): ``tests/test_notebooks.py`` runs them."""
    given = os.environ.get("IFGM_SITE_DIR")
    if given:
        assert (Path(given) / "docs" / "index.html").is_file(), f"no site in {given}"
        return Path(given)
    for package in ("sphinx", "myst_nb", "furo"):
        pytest.importorskip(package, reason=f"the docs extra is not installed: {DOCS_SETUP}")
    # The notebooks run in tests/test_notebooks.py: the build renders them without running
    # them again (docs/conf.py), which saves their run time.
    env = dict(os.environ, PYTHONPATH=str(ROOT), IFGM_DOCS_EXECUTE="off")

    strict = shutil.which("dot") is not None

    def build(out: Path) -> None:
        command = [sys.executable, "-m", "ifgm_ref", "docs", "--out", str(out)]
        done = subprocess.run(
            [*command, "--root", str(ROOT), *(["--strict"] if strict else [])],
            capture_output=True,
            text=True,
            timeout=900,
            env=env,
            check=False,
        )
        assert done.returncode == 0, (done.stdout + done.stderr)[-4000:]
        warnings = [line for line in done.stderr.splitlines() if "WARNING: " in line]
        others = [line for line in warnings if NO_DOT not in line]
        assert not others, f"Sphinx warned: {others}"

    return built_once(factory, "site", build)  # one build for every test worker


def page_paths(site: Path) -> list[str]:
    """Every HTML page of the site, not the folders of Sphinx's assets (``_static``, ...)."""
    pages = (path.relative_to(site) for path in site.rglob("*.html"))
    return sorted(p.as_posix() for p in pages if len(p.parts) == 1 or p.parts[0][0] not in "_.")


class _Page(html.parser.HTMLParser):
    """The ids (anchors) and the link targets (``a href``, ``img src``) of a page."""

    def __init__(self) -> None:
        super().__init__()
        self.ids: set[str] = set()
        self.links: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = dict(attrs)
        self.ids.update(v for k, v in attrs if k in ("id", "name") and v)
        target = values.get("href") if tag == "a" else values.get("src") if tag == "img" else None
        if target:
            self.links.append(target)


@functools.cache
def parsed(file: Path) -> _Page:
    """The page at ``file``, parsed (once)."""
    page = _Page()
    page.feed(file.read_text(encoding="utf-8"))
    return page


def broken_link(site: Path, page: str, href: str) -> str | None:
    """Why the link ``href`` of ``page`` (a path in ``site``) is broken, or None if it
    resolves or leaves the site (another scheme, another host)."""
    parts = urlsplit(href)
    if parts.scheme or parts.netloc:
        return None
    url, fragment = urldefrag(href)
    here = site / page
    return _broken(site, here.parent if url else here, url, fragment)


@functools.cache
def _broken(site: Path, base: Path, url: str, fragment: str) -> str | None:
    """:func:`broken_link` of a link to ``url#fragment`` from the folder ``base`` (or, with
    no ``url``, of an anchor on the page ``base``), checked once: the pages of a folder share
    most links (the sidebar's), some 85,000 links in all for a few thousand checks."""
    file = base if not url else (base / unquote(urlsplit(url).path)).resolve()
    if file.is_dir():
        file = file / "index.html"
    if not file.is_relative_to(site.resolve()) or not file.is_file():
        return "no such file in the site"
    if fragment and file.suffix == ".html" and unquote(fragment) not in parsed(file).ids:
        return f"no anchor #{fragment}"
    return None
