"""Sphinx configuration of the documentation site (``ifgm-ref docs --out site``).

Why Sphinx with MyST-NB: it is the scientific-Python standard (numpy, scipy, matplotlib,
shapely), it builds the API reference from the numpydoc docstrings (autodoc + napoleon), it
reads the existing Markdown pages unchanged (MyST), and MyST-NB executes the notebooks at build
time, so the committed notebooks stay without outputs and the site always shows fresh ones.

The source folder is the project folder itself, narrowed by ``include_patterns``, so the
relative links of README.md and docs/*.md resolve on the site as they do on a code host. The
proof, API and test pages are generated at build time into ``docs/_generated/``
(gitignored) by ``docs/_ext/ifgm_site.py``, which also links the traceability matrix's cells
and draws the flowchart. Nothing is fetched from a CDN: MathJax is served from the site
(sphinx-mathjax-offline) and the flowchart is an SVG drawn at build time.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), str(ROOT / "docs" / "_ext")]

project = "ifgm-ref"
author = "the ifgm-ref authors"
copyright = "the ifgm-ref authors, MIT licence"
release = "0.1.0"

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",
    "ifgm_site",
]

root_doc = "docs/index"
include_patterns = [
    "README.md",
    "docs/*.md",
    "docs/_generated/**/*.md",
    "notebooks/*.ipynb",
    "paper_figs/reproduction.md",
    "benchmarks/README.md",
    "examples/c/README.md",
]
exclude_patterns = ["site/**", "build/**", "**/.ipynb_checkpoints"]

# ---- MyST and MyST-NB -------------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 4
# Anchors as a code host makes them, so that links such as oracle.md#world-classes-... work
# on the site as in the repository.
myst_heading_slug_func = "github"
# Execute every notebook at build time (they are committed without outputs), in its own folder.
# The test suite's build sets IFGM_DOCS_EXECUTE=off: tests/test_notebooks.py runs them already.
nb_execution_mode = os.environ.get("IFGM_DOCS_EXECUTE", "force")
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_execution_show_tb = True
# Markdown that a cell displays (the proofs in 00_equations) is MyST, with its $$ math.
nb_render_markdown_format = "myst"
# No widget JavaScript from a CDN.
nb_ipywidgets_js: dict[str, dict[str, str]] = {}

# ---- API reference ----------------------------------------------------------------------
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_preserve_defaults = True
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
# The module docstrings cite the paper under "Reference": a rubric, like "References".
napoleon_custom_sections = [("Reference", "References")]

# ---- HTML -------------------------------------------------------------------------------
html_theme = "furo"
html_title = "ifgm-ref"
html_static_path = ["_static"]
html_css_files = ["site.css"]
# The site's root page, /index.html, sends the reader on to docs/index.html.
html_extra_path = ["_root"]
html_favicon = "_root/favicon.svg"
html_copy_source = False
html_show_sourcelink = False
# myst.header: the notebooks' headings start below level 1 in places. ref.python: a short name
# in a docstring's type (``x``, ``VectorsDocument``) that several classes define is left
# unlinked rather than linked to one of them.
suppress_warnings = ["myst.header", "ref.python"]
