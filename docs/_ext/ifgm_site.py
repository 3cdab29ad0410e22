"""The Sphinx extension of the documentation site: generated pages and linked citations.

At the start of a build (``config-inited``) it writes, into ``docs/_generated/`` (gitignored):

- ``proofs/KEY.md``, one page per proof module of ``proofs/``: the sympy derivation built
  (so every claim is checked again by the build) and rendered as MyST with LaTeX math, each
  claim with a label (:func:`proofs._util.claim_anchor`);
- ``api/MODULE.md``, one ``automodule`` page per module of ``ifgm_ref`` (but the modules of
  the ROS shim packages, :data:`API_SHIMS`, listed on their package's page), and an index;
- ``tests/MODULE.md``, one page per test module of ``tests/``: each test's docstring and
  source, with a label, and an index.

While Sphinx reads a Markdown page (``source-read``), it turns the inline-code citations of
the traceability matrix, the errata and the other pages into links: ``ifgm_ref.a.b`` to the
API page, ``ifgm_ref/a/b.py`` to its module, ``proofs.eq4:name`` to the claim,
``proofs.eq4.derivation`` to the proof page, ``notebooks/X.ipynb`` to the executed notebook,
``tests/test_x.py::test_y`` to the test on its module's page. And it replaces
the Mermaid block of ``docs/flowchart.md`` by a Graphviz drawing of the same graph (an SVG
made at build time, so no Mermaid JavaScript is fetched), with the Mermaid source below it.

And it keeps the build quick: each page's saved doctree without Sphinx's environment
(:func:`adopt_nested_nodes`), furo's navigation sidebar made once a folder and the page
marked in it (:func:`quick_navigation`, :func:`mark_navigation`).
"""

from __future__ import annotations

import ast
import importlib
import pkgutil
import posixpath
import re
import shutil
import textwrap
from pathlib import Path
from typing import Any

from sphinx.application import Sphinx
from sphinx.config import Config
from sphinx.util import logging

LOG = logging.getLogger(__name__)

#: The proof modules (``proofs/KEY.py``) and the function that builds each derivation.
PROOFS = {
    "eq1": "derivation",
    "eq2": "derivation",
    "eq3": "derivation",
    "eq4": "derivation",
    "flowchart": "derivation",
    "scale": "derivation",
    "braking": "derivation",
}
#: Modules of ifgm_ref left out of the API reference: entry points and a pytest test module.
API_SKIP = ("__main__", "ifgm_ref.oracle.test_conformance")
#: Packages of ifgm_ref on one page each, their modules listed there, not a page a module:
#: the stand-ins for ROS's packages that a ROS node imports (``ifgm_ref/io/ros/process.py``).
API_SHIMS = ("ifgm_ref.io.ros.shims", "ifgm_ref.io.ros.shims2")
GENERATED = "docs/_generated"


# ---- generated pages ----------------------------------------------------------------------


def _write(path: Path, text: str, written: set[Path]) -> None:
    """Write ``text`` to ``path`` unless it is there already (keeps Sphinx's cache valid)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.is_file() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")
    written.add(path)


def _proof_page(key: str) -> str:
    module = importlib.import_module(f"proofs.{key}")
    derivation = getattr(module, PROOFS[key])()
    body = derivation.to_markdown(level=1, anchors=True)
    title, _, rest = body.partition("\n\n")
    proved = sum(c.kind == "proved" for c in derivation.claims)
    note = (
        f"*Source: `proofs/{key}.py`; in a terminal: `python -m proofs.{key}`. This page was "
        f"built by running the derivation: its {proved} **[proved]** claim(s) were reduced by "
        "sympy to exactly 0 or True during the build, and the build fails if one is not. "
        "**[numeric spot check]** claims are regression tests at sample points, not proofs.*"
    )
    return f"({_proof_label(key)})=\n{title}\n\n{note}\n\n{rest}\n"


def _proof_label(key: str) -> str:
    return f"proof-page-{key}"


def _proof_index() -> str:
    entries = "\n".join(f"{key}" for key in PROOFS)
    return (
        "# Proofs\n\n"
        "The sympy derivations of `proofs/`, run when this site was built and rendered as "
        "math. A claim cited as `proofs.eq4:convex_combination` in the errata or the "
        "traceability matrix links to its place here.\n\n"
        f"```{{toctree}}\n:maxdepth: 1\n\n{entries}\n```\n"
    )


def _api_modules() -> list[str]:
    """Every module of ``ifgm_ref`` with a page, found in its folders (none imported): not
    those of :data:`API_SKIP`, nor the modules inside a package of :data:`API_SHIMS`."""
    import ifgm_ref

    names: list[str] = []

    def walk(package: str, folder: Path) -> None:
        names.append(package)
        if package in API_SHIMS:
            return
        for info in pkgutil.iter_modules([str(folder)]):
            name = f"{package}.{info.name}"
            if info.name == API_SKIP[0] or name in API_SKIP:
                continue
            if info.ispkg:
                walk(name, folder / info.name)
            else:
                names.append(name)

    walk("ifgm_ref", Path(ifgm_ref.__file__).parent)
    return sorted(names)


def _api_page(name: str) -> str:
    page = f"# `{name}`\n\n```{{eval-rst}}\n.. automodule:: {name}\n```\n"
    return page + (_shim_modules(name) if name in API_SHIMS else "")


def _shim_modules(package: str) -> str:
    """The modules of the shim package ``package``, each with its docstring's first
    paragraph, read from the files (nothing imported)."""
    import ifgm_ref

    folder = Path(ifgm_ref.__file__).parent.joinpath(*package.split(".")[1:])
    entries = []
    for path in sorted(folder.rglob("*.py")):
        parts = path.relative_to(folder).with_suffix("").parts
        parts = parts[:-1] if parts[-1] == "__init__" else parts
        if parts:
            doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
            first = " ".join(doc.split("\n\n")[0].split())
            entries.append(f"``{'.'.join(parts)}``\n   {first}")
    return (
        "\nIts modules are what a ROS node imports in place of ROS's own packages: the node "
        "runs with this folder first on its `PYTHONPATH` ([how nodes are run]"
        "(../../ros-nodes.md#how-nodes-are-run)). They are listed here with their docstrings, "
        "not given a page each, for they hold next to no code of their own: a message "
        "module's classes are made when it is imported, from rosbags' message definitions "
        "(`ifgm_ref/io/ros/messages.py`), and the others re-export the stand-in documented on "
        "the pages of `ifgm_ref.io.ros` or, as their docstrings say, accept what it does not "
        "act on.\n\n```{eval-rst}\n" + "\n\n".join(entries) + "\n```\n"
    )


def _api_index(names: list[str]) -> str:
    groups: dict[str, list[str]] = {}
    for name in names:
        parts = name.split(".")
        group = ".".join(parts[:2]) if len(parts) > 2 else "ifgm_ref"
        groups.setdefault(group, []).append(name)
    tocs = "\n".join(
        f"```{{toctree}}\n:maxdepth: 1\n:caption: {group}\n\n" + "\n".join(members) + "\n```\n"
        for group, members in sorted(groups.items())
    )
    return (
        "# API reference\n\n"
        "Every module of `ifgm_ref`, from its docstrings (numpydoc; sphinx.ext.autodoc and "
        "napoleon), but the modules of the stand-in ROS packages a ROS node imports, "
        "listed on their package's page (`ifgm_ref/io/ros/shims/`, `ifgm_ref/io/ros/shims2/`). "
        "The module docstrings open with the paper's reference and map each "
        "parameter to its symbol.\n\n" + tocs
    )


def _test_label(module: str, test: str | None = None) -> str:
    """The label of a test module's page, or of one test on it."""
    return f"tests-{module}" + (f"-{test}" if test else "")


def _test_page(path: Path) -> str:
    """The page of the test module at ``path``: its docstring, then each test's docstring
    and source (``literalinclude``, so the page shows the code that runs)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    module = path.stem
    intro = (ast.get_docstring(tree) or "").split("\n\n")[0]
    parts = [f"({_test_label(module)})=", f"# `tests/{path.name}`", "", intro, ""]
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and node.name.startswith("test_"):
            doc = ast.get_docstring(node) or ""
            first = min([node.lineno, *(d.lineno for d in node.decorator_list)])
            parts += [
                f"({_test_label(module, node.name)})=",
                f"## `{node.name}`",
                "",
                doc,
                "",
                f"```{{literalinclude}} ../../../tests/{path.name}",
                f":lines: {first}-{node.end_lineno}",  # by line: Sphinx's own parser can fail
                ":language: python",
                "```",
                "",
            ]
    return "\n".join(parts)


def _test_index(modules: list[str]) -> str:
    entries = "\n".join(modules)
    return (
        "# Tests\n\n"
        "The test modules of `tests/`, each test with its docstring and its source. A test "
        "cited in the traceability matrix or the errata (as tests/test_x.py::test_y) links "
        "to its place here. `python3 -m pytest` runs them all.\n\n"
        f"```{{toctree}}\n:maxdepth: 1\n\n{entries}\n```\n"
    )


def keep_notebook_outputs_in_the_site(app: Sphinx, config: Config) -> None:
    """Have MyST-NB write the executed notebooks in ``OUT/.jupyter_execute`` (config-inited).

    MyST-NB writes them beside the output folder (``OUT/../jupyter_execute``), which for
    ``--out site`` is the project folder. Its folder name is a module constant joined to that
    parent, so an absolute path moves it; a MyST-NB without the constant keeps its default.
    """
    import myst_nb.sphinx_ext

    if hasattr(myst_nb.sphinx_ext, "OUTPUT_FOLDER"):
        myst_nb.sphinx_ext.OUTPUT_FOLDER = str(Path(app.outdir) / ".jupyter_execute")


def generate(app: Sphinx, config: Config) -> None:
    """Write the proof and API pages into ``docs/_generated`` (config-inited)."""
    out = Path(app.srcdir) / GENERATED
    written: set[Path] = set()
    for key in PROOFS:
        _write(out / "proofs" / f"{key}.md", _proof_page(key), written)
    _write(out / "proofs" / "index.md", _proof_index(), written)
    names = _api_modules()
    for name in names:
        _write(out / "api" / f"{name}.md", _api_page(name), written)
    _write(out / "api" / "index.md", _api_index(names), written)
    tests = sorted((Path(app.srcdir) / "tests").glob("test_*.py"))
    for path in tests:
        _write(out / "tests" / f"{path.stem}.md", _test_page(path), written)
    _write(out / "tests" / "index.md", _test_index([p.stem for p in tests]), written)
    for stale in out.rglob("*.md"):
        if stale not in written:
            stale.unlink()


# ---- citations as links -------------------------------------------------------------------

_CODE = re.compile(r"(?<![`\w])`([^`\n]+)`(?!`)")
_PYTHON_NAME = re.compile(r"ifgm_ref(\.[A-Za-z_]\w*)+|ifgm_ref")
_PYTHON_FILE = re.compile(r"ifgm_ref(/[a-z_]\w*)*(\.py|/)")
_CLAIM = re.compile(r"proofs\.(\w+):(\w+)")
_PROOF = re.compile(r"proofs\.(\w+)\.(\w+)")
_NOTEBOOK = re.compile(r"notebooks/([\w.-]+)\.ipynb")
_TEST = re.compile(r"tests/(test_\w+)\.py(?:::(test_\w+))?")


def _link(code: str) -> str | None:
    """The MyST role that links the inline code ``code``, or None to leave it as it is."""
    from proofs._util import claim_anchor

    if _PYTHON_NAME.fullmatch(code):
        return f"{{py:obj}}`{code}`"
    if _PYTHON_FILE.fullmatch(code):
        module = code.removesuffix(".py").removesuffix("/").replace("/", ".")
        module = module.removesuffix(".__init__")
        return f"{{py:mod}}`{code} <{module}>`"
    if (m := _CLAIM.fullmatch(code)) and m.group(1) in PROOFS:
        return f"{{ref}}`{code} <{claim_anchor(m.group(1), m.group(2))}>`"
    if (m := _PROOF.fullmatch(code)) and m.group(1) in PROOFS:
        return f"{{ref}}`{code} <{_proof_label(m.group(1))}>`"
    if m := _NOTEBOOK.fullmatch(code):
        return f"{{doc}}`{code} </notebooks/{m.group(1)}>`"
    if m := _TEST.fullmatch(code):
        return f"{{ref}}`{code} <{_test_label(m.group(1), m.group(2))}>`"
    return None


def link_citations(text: str) -> str:
    """Turn the citations in inline code outside fenced blocks and headings into links.

    >>> link_citations("see `proofs.eq4:convex_combination` and `x`")
    'see {ref}`proofs.eq4:convex_combination <proof-eq4-convex-combination>` and `x`'
    """
    lines, fence = [], ""
    for line in text.split("\n"):
        stripped = line.lstrip()
        if fence:
            fence = "" if stripped.startswith(fence) else fence
        elif stripped.startswith(("```", "~~~")):
            fence = stripped[:3]
        elif not stripped.startswith("#"):  # headings keep their code (and their anchors)
            line = _CODE.sub(lambda m: _link(m.group(1)) or m.group(0), line)
        lines.append(line)
    return "\n".join(lines)


# ---- the flowchart ------------------------------------------------------------------------

_MERMAID = re.compile(r"```mermaid\n(.*?)```\n", re.DOTALL)
_NODE = r'(\w+)(?:\(\["(.*?)"\]\)|\{"(.*?)"\}|\["(.*?)"\])?'
_EDGE = re.compile(rf"^\s*{_NODE}\s*(?:--\s*(.*?)\s*)?-->\s*{_NODE}\s*$")


def _dot_label(text: str, width: int = 16) -> str:
    return "\\n".join(textwrap.wrap(text, width)).replace('"', '\\"')


def mermaid_to_dot(source: str) -> str:
    """The Graphviz graph of a Mermaid ``flowchart TD`` of the forms the flowchart page uses.

    Nodes ``A(["stadium"])``, ``A{"decision"}``, ``A["box"]`` or a bare id; edges ``A --> B``
    and ``A -- label --> B``; one per line.

    >>> print(mermaid_to_dot('flowchart TD\\n  A{"x?"} -- yes --> B["do"]'))  # doctest: +ELLIPSIS
    digraph flowchart {
    ...
      A [label="x?", shape=diamond...];
      B [label="do", shape=box...];
      A -> B [label=" yes "];
    }
    """
    shapes = ("box, style=rounded", 'diamond, style=filled, fillcolor="#eef3fb"', "box")
    nodes: dict[str, str] = {}
    edges: list[str] = []
    for line in source.splitlines()[1:]:
        m = _EDGE.match(line)
        if not m:
            if line.strip():
                raise ValueError(f"flowchart line not understood: {line!r}")
            continue
        groups = m.groups()
        for ident, labels in ((groups[0], groups[1:4]), (groups[5], groups[6:9])):
            for shape, label in zip(shapes, labels, strict=True):
                if label is not None:
                    nodes[ident] = f'label="{_dot_label(label)}", shape={shape}'
            nodes.setdefault(ident, f'label="{ident}", shape=box')
        label = f' [label=" {groups[4]} "]' if groups[4] else ""
        edges.append(f"  {groups[0]} -> {groups[5]}{label};")
    head = [
        "digraph flowchart {",
        '  graph [rankdir=TB, nodesep=0.15, ranksep=0.3, fontname="sans-serif"];',
        '  node [fontname="sans-serif", fontsize=10, margin="0.08,0.04"];',
        '  edge [fontname="sans-serif", fontsize=9];',
    ]
    body = [f"  {ident} [{attrs}];" for ident, attrs in nodes.items()]
    return "\n".join([*head, *body, *edges, "}"])


#: What the flowchart page says where the drawing would be when Graphviz is missing.
NO_GRAPHVIZ = (
    ":::{note}\nGraphviz's `dot` was not installed when this site was built, so Figure 3 is "
    "shown as its Mermaid source below, not drawn. Install Graphviz (`apt-get install "
    "graphviz`, or `bash .ci/browser-setup`) and rebuild the site to draw it.\n:::\n\n"
)


def _flowchart(text: str) -> str:
    def replace(m: re.Match[str]) -> str:
        source = m.group(1)
        shown = (
            "<details>\n<summary>The Mermaid source</summary>\n\n"
            f"```text\n{source}```\n\n</details>\n"
        )
        if shutil.which("dot") is None:
            LOG.warning("Graphviz's `dot` is not installed: the flowchart is shown as source only")
            return NO_GRAPHVIZ + f"```text\n{source}```\n"
        dot = mermaid_to_dot(source)
        return (
            "```{graphviz}\n:align: center\n"
            ":alt: The reconstructed Figure 3 flowchart\n\n"
            f"{dot}\n```\n\n{shown}"
        )

    return _MERMAID.sub(replace, text)


def rewrite_source(app: Sphinx, docname: str, source: list[str]) -> None:
    """Link citations and draw the flowchart while Sphinx reads a Markdown page."""
    if not str(app.env.doc2path(docname)).endswith(".md"):
        return
    text = source[0]
    if docname == "docs/flowchart":
        text = _flowchart(text)
    source[0] = link_citations(text)


# ---- the saved doctrees ------------------------------------------------------------------


def adopt_nested_nodes(app: Sphinx, doctree: Any) -> None:
    """Make the page's own document the document of every node on it (doctree-read).

    MyST parses an ``eval-rst`` block (each API page's ``automodule``) into a document of
    its own, which shares the page's settings, Sphinx's environment among them, and moves
    the nodes over without their link to it. Sphinx saves each page's doctree with the
    environment cut off its own settings, but through those nodes the pickle took the whole
    environment as it stood: 95 MB of doctrees, growing page by page, read back at writing.
    """
    for node in doctree.findall():
        if node._document not in (None, doctree):
            node.document = doctree


# ---- the navigation sidebar ---------------------------------------------------------------

#: How furo asks for the site's whole toctree, the navigation sidebar of every page.
FURO_NAVIGATION: dict[str, Any] = {
    "collapse": False,
    "titles_only": True,
    "maxdepth": -1,
    "includehidden": True,
}
#: The sidebar's links and lists, and where a page's own link is (furo's markup).
_NAV_TAG = re.compile(r"<(/?)(ul|li)\b([^>]*)>")
_NAV_LINK = '<a class="reference internal" href="{}">'
_NAV_CHECKBOX = re.compile(r'<input aria-label="[^"]*"(?= class="toctree-checkbox")')
#: Sphinx's toctree of the whole site seen from a page of each folder, marked for no page.
_NAV_UNMARKED: dict[str, str] = {}


def forget_navigation(app: Sphinx, env: Any) -> list[str]:
    """Forget the sidebars of the last build once the pages are read (env-updated)."""
    _NAV_UNMARKED.clear()
    return []


def _unmarked_navigation(app: Sphinx, folder: str) -> str:
    """Sphinx's toctree of the whole site (as furo asks for it) from a page in ``folder``
    that is none of the site's: links relative to the folder, no page marked current."""
    from sphinx.environment.adapters.toctree import global_toctree_for_doc

    if folder not in _NAV_UNMARKED:
        nowhere = posixpath.join(folder, "<navigation>")
        builder: Any = app.builder
        tree = global_toctree_for_doc(
            app.env, nowhere, builder, tags=builder.tags, **FURO_NAVIGATION
        )
        _NAV_UNMARKED[folder] = builder.render_partial(tree)["fragment"]
    return _NAV_UNMARKED[folder]


def mark_current(navigation: str, href: str) -> str | None:
    """furo's navigation tree ``navigation`` with the page linked as ``href`` marked as
    furo marks the page it is on: its link ``#`` and current, its item and those around it
    current (and open), its item the current page. None if that link is not there once,
    or the markup is not furo's as known.

    >>> unmarked = (
    ...     '<ul>\\n<li class="toctree-l1 has-children"><a class="reference internal" '
    ...     'href="a.html">A</a><input aria-label="Toggle A" class="toctree-checkbox" '
    ...     'id="c1"/><ul>\\n<li class="toctree-l2"><a class="reference internal" '
    ...     'href="b.html">B</a></li>\\n</ul>\\n</li>\\n</ul>'
    ... )
    >>> print(mark_current(unmarked, "b.html").replace("\\n", ""))  # doctest: +NORMALIZE_WHITESPACE
    <ul class="current"><li class="toctree-l1 current has-children"><a class="reference
    internal" href="a.html">A</a><input aria-label="Toggle A" checked="" class="toctree-checkbox"
    id="c1"/><ul class="current"><li class="toctree-l2 current current-page"><a class="current
    reference internal" href="#">B</a></li></ul></li></ul>
    """
    link = _NAV_LINK.format(href)
    at = navigation.find(link)
    if at < 0 or navigation.find(link, at + 1) >= 0:
        return None
    around: list[re.Match[str]] = []  # the lists and items the link is in, outermost first
    for tag in _NAV_TAG.finditer(navigation, 0, at):
        if not tag.group(1):
            around.append(tag)
        elif not around or around.pop().group(2) != tag.group(2):
            return None
    edits = [(at, at + len(link), '<a class="current reference internal" href="#">')]
    items = [tag for tag in around if tag.group(2) == "li"]
    for tag in around:
        attributes = tag.group(3)
        if tag.group(2) == "ul":
            if attributes:
                return None
            edits.append((tag.start(), tag.end(), '<ul class="current">'))
            continue
        classes = re.fullmatch(r' class="(toctree-l\d+)( has-children)?"', attributes)
        if not classes:
            return None
        page = " current-page" if tag is items[-1] else ""
        marked = f'<li class="{classes.group(1)} current{classes.group(2) or ""}{page}">'
        edits.append((tag.start(), tag.end(), marked))
        if classes.group(2):  # its checkbox, after its link, opens it
            checkbox = _NAV_CHECKBOX.search(navigation, tag.end())
            if not checkbox or navigation.find("<ul", tag.end(), checkbox.start()) >= 0:
                return None
            edits.append((checkbox.end(), checkbox.end(), ' checked=""'))
    for start, end, text in sorted(edits, reverse=True):
        navigation = navigation[:start] + text + navigation[end:]
    return navigation


def quick_navigation(
    app: Sphinx, pagename: str, templatename: str, context: dict[str, Any], doctree: Any
) -> None:
    """Give furo the navigation sidebar of the page's folder, marked for no page
    (html-page-context, before furo's handler); :func:`mark_navigation` marks the page.

    furo asks every page for the whole site's toctree and makes its sidebar of it: Sphinx
    copies every page's table of contents (every section, every documented object) for each
    of the ~300 pages, and furo parses the result again: most of the build's writing time.
    The tree differs from page to page only by the folder its links are relative to and by
    the page marked current, so it is made once a folder (furo caches its sidebar by the
    toctree) and the page marked in it, as furo would have marked it.
    """
    toctree = context.get("toctree")
    if toctree is None or app.builder.name != "html" or app.config.html_theme != "furo":
        return
    folder = posixpath.dirname(pagename)

    def toctree_of_the_folder(**kwargs: Any) -> str:
        if kwargs != FURO_NAVIGATION:
            return str(toctree(**kwargs))
        context["ifgm_navigation"] = (toctree, folder)
        return _unmarked_navigation(app, folder)

    context["toctree"] = toctree_of_the_folder


def mark_navigation(
    app: Sphinx, pagename: str, templatename: str, context: dict[str, Any], doctree: Any
) -> None:
    """Mark the page in the sidebar furo made of its folder's unmarked toctree
    (html-page-context, after furo's handler); where it cannot, furo's own sidebar."""
    if "ifgm_navigation" not in context:
        return
    toctree, folder = context.pop("ifgm_navigation")
    context["toctree"] = toctree
    builder: Any = app.builder
    href = builder.get_relative_uri(posixpath.join(folder, "<navigation>"), pagename)
    marked = mark_current(context["furo_navigation_tree"], href)
    if marked is None and any(pagename in docs for docs in app.env.toctree_includes.values()):
        from furo.navigation import get_navigation_tree  # type: ignore[import-untyped]

        marked = get_navigation_tree(toctree(**FURO_NAVIGATION))
    if marked is not None:
        context["furo_navigation_tree"] = marked


def setup(app: Sphinx) -> dict[str, Any]:
    """Register the extension."""
    app.setup_extension("sphinx.ext.graphviz")
    app.config.graphviz_output_format = "svg"
    app.connect("config-inited", generate)
    app.connect("config-inited", keep_notebook_outputs_in_the_site)
    app.connect("source-read", rewrite_source)
    app.connect("doctree-read", adopt_nested_nodes)
    app.connect("env-updated", forget_navigation)
    app.connect("html-page-context", quick_navigation, priority=400)
    app.connect("html-page-context", mark_navigation, priority=600)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
