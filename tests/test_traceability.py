"""The traceability matrix: built from markers, committed current, and with teeth."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from ifgm_ref.core.elements import ELEMENTS, traces
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.paper.traceability import (
    build_matrix,
    marked_c_sources,
    marked_tests,
    render_markdown,
)
from tests.test_cli import run_cli

ROOT = Path(__file__).resolve().parent.parent
MATRIX = ROOT / "docs" / "trace-matrix.md"

#: Elements the reference exists for: each must stay implemented *and* checked.
CORE = [
    "eq1", "eq2", "eq3", "eq4",
    "fig3.move_to_goal", "fig3.both_conditions", "fig3.case1", "fig3.case2", "fig3.case3",
    "fig3.dead_end", "fig3.regenerate", "fig3.partition",
    "iba.leave_free_path", "iba.bidirectional", "d_th", "d_obs", "sensor.fov",
]  # fmt: skip


@pytest.fixture(scope="module")
def matrix() -> dict:
    return build_matrix(ROOT)


def test_committed_matrix_is_what_the_markers_say(matrix: dict) -> None:
    """docs/trace-matrix.md is regenerated from the markers and must be current: an element
    that loses its code, proof or test changes the matrix (run `ifgm-ref trace-matrix`)."""
    assert MATRIX.read_text(encoding="utf-8") == render_markdown(matrix)


def test_core_elements_are_implemented_and_checked(matrix: dict) -> None:
    uncovered = {key: matrix[key].status for key in CORE if matrix[key].status != "covered"}
    assert not uncovered


def test_every_element_has_a_row(matrix: dict) -> None:
    assert list(matrix) == list(ELEMENTS)
    text = render_markdown(matrix)
    assert all(f"| `{key}` |" in text for key in ELEMENTS)


def test_an_unknown_element_is_refused_in_code() -> None:
    with pytest.raises(KeyError, match="unknown paper element 'eq9'"):
        traces("eq9")


def _project(tmp_path: Path, test_source: str) -> Path:
    """A copy of the project folder's layout with one test file of our own."""
    for folder in ("proofs", "notebooks"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "test_marked.py").write_text(test_source)
    return tmp_path


def test_markers_are_read_from_test_sources(tmp_path: Path) -> None:
    """Module-level tests and methods of test classes, string literals only."""
    source = (
        "import pytest\n\n"
        "@pytest.mark.paper('eq1', 'eq2')\ndef test_a():\n    pass\n\n"
        "class TestB:\n    @pytest.mark.paper('d_th')\n    def test_c(self):\n        pass\n"
    )
    root = _project(tmp_path, source)
    found = dict(marked_tests(root / "tests", root))
    assert found == {
        "tests/test_marked.py::test_a": ("eq1", "eq2"),
        "tests/test_marked.py::TestB::test_c": ("d_th",),
    }
    (root / "tests" / "test_marked.py").write_text(
        "import pytest\nKEY = 'eq1'\n\n@pytest.mark.paper(KEY)\ndef test_a():\n    pass\n"
    )
    with pytest.raises(ParameterError, match="string literals only"):
        list(marked_tests(root / "tests", root))


def test_markers_are_read_from_c_sources(tmp_path: Path) -> None:
    """A port's C sources count as code where a comment line says ``paper: key ...``: on
    its own line, or as a line of a block comment; other comments are not markers."""
    src = tmp_path / "examples" / "c" / "src"
    src.mkdir(parents=True)
    (src / "a.c").write_text("/* paper: s3.cheap */\nint a;\n/* the paper: eq1 */\n")
    (src / "b.h").write_text("/* A header.\n * paper: s6.simpler_than_fgm eq4\n */\n")
    (src / "c.c").write_text("/* nothing marked */\n")
    assert dict(marked_c_sources(src, tmp_path)) == {
        "examples/c/src/a.c": ("s3.cheap",),
        "examples/c/src/b.h": ("s6.simpler_than_fgm", "eq4"),
    }


def test_an_unknown_element_is_refused_in_tests(tmp_path: Path) -> None:
    root = _project(
        tmp_path, "import pytest\n\n@pytest.mark.paper('eq5')\ndef test_a():\n    pass\n"
    )
    with pytest.raises(ParameterError, match="unknown paper element 'eq5'"):
        build_matrix(root)


def test_losing_a_test_uncovers_its_element(tmp_path: Path, matrix: dict) -> None:
    """Teeth: without the test folder, every element checked only by tests loses its check."""
    root = _project(tmp_path, "def test_unmarked():\n    pass\n")
    shrunk = build_matrix(root)
    assert shrunk["fig3.case3"].tests == [] and matrix["fig3.case3"].tests
    assert shrunk["fig3.case3"].status != "covered"
    assert render_markdown(shrunk) != render_markdown(matrix)


def test_not_a_project_folder(tmp_path: Path) -> None:
    with pytest.raises(ParameterError, match="not the project folder"):
        build_matrix(tmp_path)


def test_trace_matrix_command(tmp_path: Path) -> None:
    def run(*args: str) -> subprocess.CompletedProcess[str]:
        return run_cli("trace-matrix", "--root", str(ROOT), *args)

    assert run("--check").returncode == 0
    stale = tmp_path / "stale.md"
    stale.write_text("old\n")
    done = run("--check", "--out", str(stale))
    assert done.returncode == 1 and "out of date" in done.stderr
    assert run("--out", str(stale)).returncode == 0
    assert stale.read_text() == MATRIX.read_text()
    fresh = tmp_path / "new" / "matrix.md"  # its folder is made, as every output's is
    assert run("--out", str(fresh)).returncode == 0
    assert fresh.read_text() == MATRIX.read_text()
