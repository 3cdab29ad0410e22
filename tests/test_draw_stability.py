"""The oracle draws the same examples whatever is installed or imported (issue 43, part 3):
:mod:`ifgm_ref.oracle.stable_draws` keeps Hypothesis's local constants out of its draws."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import NamedTuple

import hypothesis
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.internal.conjecture import providers

import ifgm_ref
from ifgm_ref.oracle.stable_draws import HypothesisChanged, global_constants_only

ROOT = Path(__file__).resolve().parent.parent
#: A constant no module of ours or of Hypothesis holds, ft.
UNUSUAL = 123456.789

#: Draw the quick profile's examples of ``converges_open`` through the oracle's own path
#: (:func:`~ifgm_ref.oracle.runner.run_check`), recording each world instead of simulating it,
#: and judge the reference on the frozen suite's quick tier (its first case of each property:
#: the verdicts, by case id);
#: the modules named on the command line are imported first, as a user's own would be.
DRAW = """
import hashlib, importlib, sys
from dataclasses import replace

for name in sys.argv[1:]:
    importlib.import_module(name)
import ifgm_ref
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.runner import run_check

worlds = []
check = replace(CHECKS["converges_open"], test=lambda impl, world, rec: worlds.append(world))
result = run_check(check, Implementation.from_spec("ifgm"), "quick", artifacts=None)
digest = hashlib.sha256(repr(worlds).encode()).hexdigest()
from ifgm_ref.oracle.suite.run import run_cases
from ifgm_ref.oracle.suite.versions import load_suite
quick = load_suite("v1").tier("quick")
names = dict.fromkeys(c.check for c in quick)
cases = [next(c for c in quick if c.check == name) for name in names]
verdicts = [(r.case.id, r.verdict) for r in run_cases(cases, Implementation.from_spec("ifgm"))]
suite = hashlib.sha256(repr(verdicts).encode()).hexdigest()
print(result.status, len(worlds), digest, ifgm_ref.__file__, len(verdicts), suite)
"""

#: A user's planner module full of constants, in the ranges the world classes draw from.
USER_MODULE = "\n".join(f"C{i} = {0.011 + 0.37 * i!r}" for i in range(200)) + "\n"


class Drawn(NamedTuple):
    """What one run of :data:`DRAW` printed: the check's status, the worlds drawn, their
    SHA-256, the ``ifgm_ref`` package it imported, and the suite cases judged with the
    SHA-256 of their verdicts."""

    status: str
    worlds: int
    digest: str
    package: Path
    cases: int
    verdicts: str


def draw(cwd: Path, *imported: str, path: Path | None = None) -> Drawn:
    """Run :data:`DRAW` in a new interpreter in ``cwd`` (the repository off ``sys.path``),
    with ``path`` as ``PYTHONPATH`` if given."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["HYPOTHESIS_STORAGE_DIRECTORY"] = str(cwd / ".hypothesis")
    if path is not None:
        env["PYTHONPATH"] = str(path)
    done = subprocess.run(
        [sys.executable, "-c", DRAW, *imported],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=cwd,
        env=env,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    status, worlds, digest, package, cases, verdicts = done.stdout.split()
    return Drawn(status, int(worlds), digest, Path(package), int(cases), verdicts)


@pytest.fixture(scope="module")
def wheel_site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A wheel of the package, built from a copy of the sources and installed where pip puts
    it: a folder named ``site-packages``, which Hypothesis takes for installed code."""
    root = tmp_path_factory.mktemp("wheel")
    sources = root / "src"
    sources.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, sources / name)
    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info")
    shutil.copytree(ROOT / "ifgm_ref", sources / "ifgm_ref", ignore=ignore)
    site = root / "lib" / "site-packages"
    pip("wheel", "--no-deps", str(sources), "-w", str(root / "dist"))
    (wheel,) = (root / "dist").glob("ifgm_ref-*.whl")
    pip("install", "--no-deps", "--target", str(site), str(wheel))
    return site


def pip(*args: str) -> None:
    """Run pip in this interpreter; its error output if it fails."""
    command = [sys.executable, "-m", "pip", "--disable-pip-version-check", "-q", *args]
    done = subprocess.run(command, capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr


def drawn_floats(low: float, high: float) -> set[float]:
    """The floats in ``[low, high]`` that 100 derandomized Hypothesis examples draw."""
    seen: set[float] = set()

    @settings(max_examples=100, derandomize=True, database=None)
    @given(st.floats(low, high))
    def collect(x: float) -> None:
        seen.add(x)

    collect()
    return seen


def test_the_local_pool_is_empty_inside_the_block(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "unusual_constants.py").write_text(f"X = {UNUSUAL!r}\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setenv("HYPOTHESIS_STORAGE_DIRECTORY", str(tmp_path / ".hypothesis"))
    __import__("unusual_constants")
    pool = vars(providers.HypothesisProvider)["_local_constants"]
    assert UNUSUAL in drawn_floats(UNUSUAL - 0.5, UNUSUAL + 0.5)  # Hypothesis draws it ...
    with global_constants_only(), global_constants_only():  # nested: harmless
        assert len(providers.HypothesisProvider(None)._local_constants) == 0
        assert UNUSUAL not in drawn_floats(UNUSUAL - 0.5, UNUSUAL + 0.5)  # ... but not here
    assert vars(providers.HypothesisProvider)["_local_constants"] is pool  # put back
    assert UNUSUAL in providers.HypothesisProvider(None)._local_constants.floats


@pytest.mark.parametrize(
    ("owner", "name", "missing"),
    [
        (providers.HypothesisProvider, "_local_constants", "HypothesisProvider._local_constants"),
        (providers, "CONSTANTS_CACHE", "CONSTANTS_CACHE.cache"),
        (providers, "HypothesisProvider", "HypothesisProvider"),
    ],
)
def test_a_hypothesis_without_the_pool_is_refused(
    owner: object, name: str, missing: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delattr(owner, name)
    told = rf"^Hypothesis {re.escape(hypothesis.__version__)} has no {re.escape(missing)}\b"
    with pytest.raises(HypothesisChanged, match=told), global_constants_only():
        pass  # pragma: no cover


def test_a_draw_that_reads_another_pool_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    def reads_elsewhere(self: object, *args: object, **kwargs: object) -> None:
        return None

    monkeypatch.setattr(providers.HypothesisProvider, "_maybe_draw_constant", reads_elsewhere)
    told = "_maybe_draw_constant reading _local_constants"
    with pytest.raises(HypothesisChanged, match=told), global_constants_only():
        pass  # pragma: no cover


def test_same_examples_in_every_install(wheel_site: Path, tmp_path: Path) -> None:
    """An editable install, a wheel and a user module imported first: the same drawn
    examples, and the same verdicts of the frozen suite, case by case."""
    (tmp_path / "my_planner.py").write_text(USER_MODULE)
    editable = draw(tmp_path)
    wheel = draw(tmp_path, path=wheel_site)
    user_first = draw(tmp_path, "my_planner")
    assert editable.package == user_first.package == Path(ifgm_ref.__file__)
    assert wheel.package == wheel_site / "ifgm_ref" / "__init__.py"
    assert editable.worlds == 50 and editable.cases > 10  # the wheel ships the suite's files
    assert wheel == editable._replace(package=wheel.package)
    assert user_first == editable
