"""Sphinx configuration: gapath's documentation site (``make docs``).

The site is the Markdown pages of this folder (read by MyST), the README's
pymoo section, BENCHMARKS.md, one page per notebook and an API reference
rendered by autodoc + numpydoc from the docstrings. ``make docs`` builds it
with warnings as errors (``-W``); ``tests/test_docs.py`` does the same.

Two sets of pages are generated when the build starts (both folders are
git-ignored, rewritten on every build):

* ``api/`` -- one page per module of :data:`API_MODULES`, the one list of
  documented modules: a module renamed or added is one line here (a name
  that does not import fails the build, naming the module);
* ``notebooks/`` -- one page per ``notebooks/*.ipynb``, its summary taken
  from the table in ``notebooks/README.md`` (a notebook without a row there
  fails the build).
"""

from __future__ import annotations

import re
import sys
import warnings
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "src"))  # document this checkout's source

#: The documented modules, in the order of the API reference: (section, modules).
API_MODULES = [
    ("Package", ["gapath", "gapath.errors"]),
    (
        "Maps and objectives",
        [
            "gapath.workspace",
            "gapath.generators",
            "gapath.loaders",
            "gapath.grid",
            "gapath.openlist",
            "gapath.monotone",
            "gapath.objectives",
            "gapath.costmap",
        ],
    ),
    (
        "The genetic algorithm",
        [
            "gapath.encodings",
            "gapath.encodings.integer",
            "gapath.encodings.binary",
            "gapath.encodings.mixed",
            "gapath.encodings.absolute",
            "gapath.problems",
            "gapath.operators",
            "gapath.algorithms",
            "gapath.constraints",
            "gapath.front",
            "gapath.metrics",
        ],
    ),
    (
        "Planners",
        [
            "gapath.planners",
            "gapath.planners.astar",
            "gapath.planners.dstar_lite",
            "gapath.planners.exact",
            "gapath.planners.pareto",
            "gapath.planners.weighted_sum",
            "gapath.planners.hybrid_astar",
            "gapath.planners.rrt",
            "gapath.planners.geometry",
            "gapath.planners.registry",
        ],
    ),
    (
        "Dynamic environments",
        [
            "gapath.dynamic",
            "gapath.dynamic.prediction",
            "gapath.dynamic.world",
            "gapath.dynamic.planners",
            "gapath.dynamic.results",
            "gapath.dynamic.simulation",
            "gapath.dynamic.scenarios",
            "gapath.dynamic.plots",
        ],
    ),
    (
        "Experiments",
        [
            "gapath.experiments",
            "gapath.experiments.spec",
            "gapath.experiments.runner",
            "gapath.experiments.store",
            "gapath.experiments.report",
            "gapath.experiments.multirun",
            "gapath.experiments.dask_config",
        ],
    ),
    (
        "The paper studies",
        [
            "gapath.studies",
            "gapath.studies.encodings",
            "gapath.studies.dense",
            "gapath.studies.mars",
            "gapath.studies.dynamic",
        ],
    ),
]

#: Packages whose re-exported names are documented on their modules' pages
#: above: their page documents only what the package itself defines (its
#: ``__all__`` ignored), so no name is documented twice.
OWN_MEMBERS_ONLY = {"gapath.encodings", "gapath.planners", "gapath.experiments", "gapath.dynamic"}

project = "gapath"
author = "the gapath authors"
copyright = "gapath authors, MIT licence"
release = __import__("gapath").__version__

extensions = ["sphinx.ext.autodoc", "numpydoc", "myst_parser"]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build"]
root_doc = "index"

autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
#: Names in signatures imported for type checking only, or documented on more
#: than one page (``gapath.Workspace`` re-exports ``gapath.workspace.Workspace``):
#: where their cross-references go.
autodoc_type_aliases = {
    "Workspace": "gapath.workspace.Workspace",
    "PathFront": "gapath.front.PathFront",
    "SolveResult": "gapath.solver.SolveResult",
}
numpydoc_show_class_members = False  # autodoc documents the members itself
numpydoc_xref_param_type = False
myst_heading_anchors = 3

html_theme = "alabaster"
html_title = f"gapath {release}"
html_static_path: list[str] = []


def _write(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` unless it already holds it (keeps rebuilds incremental)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def _prune(folder: Path, keep: set[str]) -> None:
    """Remove generated pages of ``folder`` that are not in ``keep`` (a module dropped)."""
    for p in folder.glob("*"):
        if p.name not in keep:
            p.unlink()


def write_api_pages() -> None:
    """``api/index.rst`` and one ``api/<module>.rst`` per module of :data:`API_MODULES`."""
    folder = HERE / "api"
    index = [
        "API reference",
        "=============",
        "",
        "Generated from the numpydoc docstrings; the list of modules is",
        "``API_MODULES`` in ``docs/conf.py``.",
        "",
    ]
    keep = {"index.rst"}
    for section, modules in API_MODULES:
        index += [".. toctree::", f"   :caption: {section}", "   :maxdepth: 1", ""]
        for mod in modules:
            index.append(f"   {mod}")
            keep.add(f"{mod}.rst")
            title = f"``{mod}``"
            options = "   :ignore-module-all:\n" if mod in OWN_MEMBERS_ONLY else ""
            _write(folder / f"{mod}.rst", f"{title}\n{'=' * len(title)}\n\n.. automodule:: {mod}\n{options}")
        index.append("")
    _write(folder / "index.rst", "\n".join(index))
    _prune(folder, keep)


def notebook_rows() -> dict[str, tuple[str, str]]:
    """``{file name: (what, quick mode)}`` from the table in ``notebooks/README.md``."""
    rows = {}
    for line in (ROOT / "notebooks/README.md").read_text().splitlines():
        m = re.match(r"\|\s*`([^`]+\.ipynb)`\s*\|(.*)\|(.*)\|\s*$", line)
        if m:
            rows[m.group(1)] = (m.group(2).strip(), m.group(3).strip())
    return rows


def write_notebook_pages() -> None:
    """``notebooks/index.md`` (the notebooks' README) and a page per notebook."""
    folder = HERE / "notebooks"
    rows = notebook_rows()
    notebooks = sorted(p.name for p in (ROOT / "notebooks").glob("*.ipynb"))
    missing = [n for n in notebooks if n not in rows]
    if missing:
        raise RuntimeError(
            f"notebooks/README.md has no table row for {', '.join(missing)}; "
            "add one (| `NAME.ipynb` | what | quick mode |)"
        )
    keep = {"index.md"}
    for name in notebooks:
        stem = name.removesuffix(".ipynb")
        what, quick = (text.rstrip(".") for text in rows[name])
        keep.add(f"{stem}.md")
        _write(
            folder / f"{stem}.md",
            f"# {stem.replace('_', ' ')}\n\n"
            f"Notebook: {{download}}`notebooks/{name} <../../notebooks/{name}>` "
            f"(in the repository's `notebooks/` folder).\n\n"
            f"{what[:1].upper()}{what[1:]}.\n\n"
            f"With `GAPATH_QUICK=1` in the environment: {quick}.\n",
        )
    toc = "\n".join(n.removesuffix(".ipynb") for n in notebooks)
    _write(
        folder / "index.md",
        "# Notebooks\n\n"
        "```{include} ../../notebooks/README.md\n:start-line: 1\n```\n\n"
        f"```{{toctree}}\n:maxdepth: 1\n\n{toc}\n```\n",
    )
    _prune(folder, keep)


def _numpydoc_warnings_to_sphinx() -> None:
    """Report numpydoc's docstring warnings (e.g. an unknown section) as Sphinx
    warnings, so that ``-W`` fails on them too (numpydoc issues them with
    :func:`warnings.warn`, which Sphinx does not count)."""
    from sphinx.util import logging

    logger = logging.getLogger("numpydoc")
    show = warnings.showwarning

    def showwarning(message, category, filename, lineno, file=None, line=None):
        if "numpydoc" in filename:
            logger.warning(str(message))
        else:
            show(message, category, filename, lineno, file, line)

    warnings.showwarning = showwarning
    warnings.filterwarnings("always", category=UserWarning, module=r"numpydoc\..*")


def setup(app):
    write_api_pages()
    write_notebook_pages()
    _numpydoc_warnings_to_sphinx()
    return {"parallel_read_safe": True}
