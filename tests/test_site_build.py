"""The documentation site builds without a warning and its internal links resolve.

Every run builds the site (``ifgm-ref docs --strict``, about one minute, on one worker
while the others test) and reads every page's links and images with an HTML parser: a link
to a page, a file or an anchor the site lacks fails, as a page moved or a heading renamed
would leave it. ``tests/test_site.py`` (``-m browser``) opens the same pages in Chromium.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from tests.site_build import DOCS_SETUP, ROOT, broken_link, built_site, page_paths, parsed


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return built_site(tmp_path_factory)


def test_the_strict_build_has_every_page(site: Path) -> None:
    """The build warned of nothing (``--strict``: any warning fails it in the fixture) and
    made the pages the README and the docs index promise."""
    pages = page_paths(site)
    expected = ["index.html", "docs/index.html", "docs/bags.html", "docs/errata.html"]
    expected += ["docs/oracle-protocol.html", "docs/_generated/api/index.html"]
    missing = [page for page in expected if page not in pages]
    assert not missing, f"pages={missing}, but should be built [{len(pages)} pages]"
    assert len(pages) > 100


def test_every_internal_link_resolves(site: Path) -> None:
    broken: dict[str, list[str]] = {}
    for page in page_paths(site):
        for href in sorted(set(parsed(site / page).links)):
            reason = broken_link(site, page, href)
            if reason:
                broken.setdefault(page, []).append(f"{href}: {reason}")
    assert not broken, f"broken links={broken}, but should be none"


def test_a_broken_link_is_found(tmp_path: Path) -> None:
    """The link check itself: a missing page, a missing anchor, and what it leaves alone."""
    (tmp_path / "a.html").write_text(
        '<h1 id="top">A</h1><a href="b.html#here">b</a><a href="#top">up</a>'
        '<a href="https://example.org/x">out</a><img src="missing.png">'
    )
    (tmp_path / "b.html").write_text('<p id="there">B</p>')
    links = parsed(tmp_path / "a.html").links
    reasons = {href: broken_link(tmp_path, "a.html", href) for href in links}
    assert reasons == {
        "b.html#here": "no anchor #here",
        "#top": None,
        "https://example.org/x": None,
        "missing.png": "no such file in the site",
    }


#: A toctree as Sphinx renders it for furo's sidebar: seen from no page, then from page B.
_TOCTREE = (
    '<p class="caption" role="heading"><span class="caption-text">Part</span></p>\n<ul>\n'
    '<li class="toctree-l1"><a class="reference internal" href="x.html">X</a></li>\n'
    '<li class="toctree-l1"><a class="reference internal" href="a.html">A</a><ul>\n'
    '<li class="toctree-l2"><a class="reference internal" href="b.html">B</a></li>\n'
    '<li class="toctree-l2"><a class="reference internal" href="c.html">C</a></li>\n'
    "</ul>\n</li>\n</ul>\n"
)
_ON_B = (
    _TOCTREE.replace("<ul>\n<li", '<ul class="current">\n<li')
    .replace(
        '"toctree-l1"><a class="reference internal" href="a',
        '"toctree-l1 current"><a class="reference internal" href="a',
    )
    .replace(
        '"toctree-l2"><a class="reference internal" href="b.html"',
        '"toctree-l2 current"><a class="current reference internal" href="#"',
    )
)


def test_the_sidebar_marks_the_page_as_furo_does() -> None:
    """The build makes furo's sidebar once a folder and marks each page in it
    (``docs/_ext/ifgm_site.py``, ``mark_current``): the same markup as furo's own sidebar
    of the page's toctree, with the installed furo."""
    navigation = pytest.importorskip("furo.navigation", reason=DOCS_SETUP)
    spec = importlib.util.spec_from_file_location("ifgm_site", ROOT / "docs/_ext/ifgm_site.py")
    assert spec is not None and spec.loader is not None
    site_ext = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(site_ext)
    unmarked = navigation.get_navigation_tree(_TOCTREE)
    assert site_ext.mark_current(unmarked, "b.html") == navigation.get_navigation_tree(_ON_B)
    assert site_ext.mark_current(unmarked, "nowhere.html") is None
