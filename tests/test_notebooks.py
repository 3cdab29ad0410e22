"""Every notebook runs top to bottom, headless, in a fresh kernel (nbclient).

Outputs are not compared (they change with matplotlib versions); the notebooks assert the
numbers they show, so a failing claim fails here.
"""

from __future__ import annotations

from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

NOTEBOOKS = sorted((Path(__file__).resolve().parent.parent / "notebooks").glob("*.ipynb"))


def test_there_are_notebooks() -> None:
    assert NOTEBOOKS


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_notebook_executes(path: Path) -> None:
    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(
        notebook,
        timeout=300,
        kernel_name="python3",
        resources={"metadata": {"path": str(path.parent)}},
    )
    client.execute()
    errors = [
        output
        for cell in notebook.cells
        for output in cell.get("outputs", [])
        if output.get("output_type") == "error"
    ]
    assert not errors


#: The cell tags with which MyST-NB leaves a cell's source off the documentation site.
HIDDEN_ON_THE_SITE = {"remove-input", "remove-cell"}


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_the_set_up_cell_is_hidden_on_the_site(path: Path) -> None:
    """The first code cell finds the project root and puts it on ``sys.path``: machinery, not
    the paper, so the site leaves its source off and the reader meets the paper first (issue
    45). It still runs, in Jupyter and in the site's build."""
    notebook = nbformat.read(path, as_version=4)
    setup = next(cell for cell in notebook.cells if cell.cell_type == "code")
    assert "sys.path" in setup.source
    assert HIDDEN_ON_THE_SITE & set(setup.metadata.get("tags", [])), setup.metadata
