"""The documentation site, opened page by page in a real browser (headless Chromium).

Run with ``pytest -m browser`` after ``bash .ci/browser-setup`` (Debian's ``chromium`` and
``chromium-driver``, Graphviz, and the ``browser`` extra). The tests use the run's strict
site build (``tests/site_build.py``, about two minutes on 2 cores), or the build in
``$IFGM_SITE_DIR`` if that is set; they serve it on localhost from a thread and open every
page. Screenshots of the landing page and of a notebook page are written to
``$IFGM_SITE_ARTIFACTS`` (default ``site-artifacts/``, gitignored) and their paths printed.

The strict build and the internal links are checked in every run, CI's included, without a
browser (``tests/test_site_build.py``). These tests are marked ``browser`` and left out of
``python3 -m pytest`` and CI: CI would have to install Chromium (36 Debian packages with
``--no-install-recommends``, about a minute) and open the site's pages (measured: 122 s for
the browser tests on 2 cores), on top of a run that with the site build takes about six of
its ten minutes, on machines whose package mirror is not ours to count on. Without
Chromium, its driver or selenium they skip and say what to install.
"""

from __future__ import annotations

import functools
import os
import shutil
import threading
from collections.abc import Iterator
from dataclasses import dataclass, field
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

import pytest

from tests.site_build import built_site, page_paths

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parent.parent
SETUP = "run `bash .ci/browser-setup` (Debian's chromium and chromium-driver, selenium)"
#: The page that proves the math renders, and the pages whose screenshots are kept.
PROOF_PAGES = "docs/_generated/proofs/"
SCREENSHOTS = {
    "landing.png": "docs/index.html",
    "notebook.png": "notebooks/01_scenario1_figures4-6.html",
}
#: How long a page may take to load and typeset its math, in seconds.
PAGE_TIMEOUT_S = 60


@dataclass
class Page:
    """What the browser saw on one page of the site."""

    path: str
    console_errors: list[str] = field(default_factory=list)
    broken_images: list[str] = field(default_factory=list)
    foreign_requests: list[str] = field(default_factory=list)
    math_elements: int = 0
    math_errors: int = 0
    raw_display_math: bool = False


# ---- the site, its server and the browser --------------------------------------------------


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The built site: ``$IFGM_SITE_DIR``, or the run's strict ``ifgm-ref docs`` build."""
    return built_site(tmp_path_factory)


@pytest.fixture(scope="module")
def base_url(site: Path) -> Iterator[str]:
    """The site served on localhost by a thread of this process."""

    class Quiet(SimpleHTTPRequestHandler):
        def log_message(self, format: str, *args: Any) -> None:
            pass

    handler = functools.partial(Quiet, directory=str(site))
    server = ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


@pytest.fixture(scope="module")
def driver() -> Iterator[Any]:
    """Headless Chromium through Debian's chromedriver, keeping the console log."""
    webdriver = pytest.importorskip("selenium.webdriver", reason=f"no selenium: {SETUP}")
    browser, chromedriver = shutil.which("chromium"), shutil.which("chromedriver")
    if browser is None or chromedriver is None:
        pytest.skip(f"chromium or chromedriver is not installed: {SETUP}")
    options = webdriver.ChromeOptions()
    options.binary_location = browser
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1280,900"):
        options.add_argument(argument)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = webdriver.ChromeService(executable_path=chromedriver)
    chrome = webdriver.Chrome(options=options, service=service)
    chrome.set_page_load_timeout(PAGE_TIMEOUT_S)
    chrome.set_script_timeout(PAGE_TIMEOUT_S)
    try:
        yield chrome
    finally:
        chrome.quit()


# ---- visiting every page -------------------------------------------------------------------

#: Wait for MathJax (where the page loads it) to finish typesetting, then report the page.
_INSPECT = """
const done = arguments[arguments.length - 1];
const ready = (window.MathJax && MathJax.startup && MathJax.startup.promise)
    || Promise.resolve();
ready.then(() => {
  const images = [...document.images]
    .filter(img => !img.complete || img.naturalWidth === 0)
    .map(img => img.currentSrc || img.src);
  const origin = location.origin;
  const foreign = performance.getEntriesByType('resource').map(e => e.name)
    .filter(name => !name.startsWith(origin) && !name.startsWith('data:'));
  const article = document.querySelector('article') || document.body;
  const prose = article.cloneNode(true);  // the text outside code: code may show a $$
  prose.querySelectorAll('pre, code').forEach(e => e.remove());
  done({
    images, foreign,
    math: document.querySelectorAll('mjx-container').length,
    mathErrors: document.querySelectorAll('mjx-merror').length,
    rawMath: prose.textContent.includes('$$'),
  });
}, err => done({error: String(err)}));
"""


def _visit(driver: Any, base_url: str, path: str) -> Page:
    driver.get(base_url + path)
    seen = driver.execute_async_script(_INSPECT)
    page = Page(path)
    assert "error" not in seen, f"{path}: {seen.get('error')}"
    page.console_errors = [
        entry["message"] for entry in driver.get_log("browser") if entry["level"] == "SEVERE"
    ]
    page.broken_images = seen["images"]
    page.foreign_requests = seen["foreign"]
    page.math_elements = seen["math"]
    page.math_errors = seen["mathErrors"]
    page.raw_display_math = seen["rawMath"]
    return page


def _artifacts() -> Path:
    folder = Path(os.environ.get("IFGM_SITE_ARTIFACTS", ROOT / "site-artifacts"))
    folder.mkdir(parents=True, exist_ok=True)
    return folder


@pytest.fixture(scope="module")
def pages(driver: Any, site: Path, base_url: str) -> dict[str, Page]:
    """Every page of the site as the browser saw it; screenshots taken on the way.

    The driver comes first, so that without Chromium the tests skip before building the site.
    """
    shots = {path: name for name, path in SCREENSHOTS.items()}
    seen: dict[str, Page] = {}
    for path in page_paths(site):
        seen[path] = _visit(driver, base_url, path)
        if path in shots:
            # The first figure in view (the landing page's, a notebook's first plot); at
            # once, as the theme scrolls smoothly.
            driver.execute_script(
                "const img = document.querySelector('article img');"
                "const box = img && img.getBoundingClientRect();"
                "if (box && box.bottom > innerHeight)"
                "  scrollTo({top: scrollY + box.top - 40, behavior: 'instant'});"
            )
            target = _artifacts() / shots[path]
            driver.save_screenshot(str(target))
            print(f"screenshot of {path}: {target}")
    return seen


# ---- the checks ----------------------------------------------------------------------------


def _problems(pages: dict[str, Page], attribute: str) -> dict[str, Any]:
    """The pages whose ``attribute`` is not empty, with its value."""
    return {path: found for path, page in pages.items() if (found := getattr(page, attribute))}


def test_the_site_has_its_pages(pages: dict[str, Page]) -> None:
    expected = ["index.html", "docs/index.html", "docs/trace-matrix.html", "docs/errata.html"]
    expected += ["docs/flowchart.html", "docs/_generated/api/index.html", *SCREENSHOTS.values()]
    expected += [f"{PROOF_PAGES}{key}.html" for key in ("eq1", "eq2", "eq3", "eq4")]
    missing = [path for path in expected if path not in pages]
    assert not missing, f"pages={missing}, but should be built [{sorted(pages)[:10]}...]"


def test_every_page_loads_without_console_errors(pages: dict[str, Page]) -> None:
    problems = _problems(pages, "console_errors")
    assert not problems, f"console errors={problems}, but should be none"


def test_every_image_loads(pages: dict[str, Page]) -> None:
    problems = _problems(pages, "broken_images")
    assert not problems, f"images with naturalWidth 0={problems}, but should be none"


def test_nothing_is_fetched_from_another_site(pages: dict[str, Page]) -> None:
    problems = _problems(pages, "foreign_requests")
    assert not problems, f"requests off the site={problems}, but should be none (no CDN)"


def test_math_renders_on_the_proof_pages(pages: dict[str, Page]) -> None:
    proofs = {p: page for p, page in pages.items() if p.startswith(PROOF_PAGES)}
    proofs.pop(f"{PROOF_PAGES}index.html")
    assert len(proofs) >= 4
    unrendered = {p: page.math_elements for p, page in proofs.items() if page.math_elements < 3}
    assert not unrendered, f"mjx-container counts={unrendered}, but should be >= 3 each"
    raw = [p for p, page in pages.items() if page.raw_display_math]
    assert not raw, f"pages with a raw $$ left={raw}, but should be none"
    errors = _problems(pages, "math_errors")
    assert not errors, f"MathJax errors={errors}, but should be none"


def test_screenshots_are_saved(pages: dict[str, Page]) -> None:
    for name in SCREENSHOTS:
        shot = _artifacts() / name
        assert shot.is_file() and shot.stat().st_size > 10_000, f"{shot} is missing or blank"
