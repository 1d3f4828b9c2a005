"""The documentation site (``make docs``) builds with warnings as errors and
holds what it promises: a page per documented module with every public name,
the README's pymoo example, a page and a download per notebook, the guides.

The build needs the docs tools (``pip install -e '.[docs]'``). ``make test``
installs them and sets ``GAPATH_REQUIRE_DOCS=1``, under which their absence
is a failure; a bare ``pytest`` in an environment without them skips this
module, saying so.
"""

from __future__ import annotations

import html
import importlib
import importlib.util
import os
import re
import runpy
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
TOOLS = ("sphinx", "numpydoc", "myst_parser")


def _require_tools() -> None:
    missing = [t for t in TOOLS if importlib.util.find_spec(t) is None]
    if not missing:
        return
    msg = (
        f"the docs tools are not installed ({', '.join(missing)}); "
        "install them with: pip install -c constraints.txt -e '.[docs]'"
    )
    if os.environ.get("GAPATH_REQUIRE_DOCS") == "1":
        pytest.fail(f"{msg} (GAPATH_REQUIRE_DOCS=1, as make test sets it, requires them)", pytrace=False)
    pytest.skip(f"{msg}; make test installs them and sets GAPATH_REQUIRE_DOCS=1")


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The site built as ``make docs`` builds it (``-W``), into a temporary folder."""
    _require_tools()
    out = tmp_path_factory.mktemp("docs")
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "sphinx",
            "-W",
            "--keep-going",
            "-q",
            "-b",
            "html",
            "-d",
            str(out / "doctrees"),
            str(DOCS),
            str(out / "html"),
        ],
        capture_output=True,
        text=True,
        timeout=1200,
        cwd=ROOT,
    )
    assert proc.returncode == 0 and "WARNING" not in proc.stderr, (
        f"sphinx-build -W failed (exit {proc.returncode}):\n{proc.stderr}"
    )
    return out / "html"


@pytest.fixture(scope="module")
def conf() -> dict:
    """The names defined by ``docs/conf.py`` (``API_MODULES``, ...)."""
    path = list(sys.path)
    try:
        return runpy.run_path(str(DOCS / "conf.py"))
    finally:
        sys.path[:] = path  # conf.py puts src/ first


def _text(page: Path) -> str:
    """The visible text of an HTML page, whitespace collapsed."""
    s = re.sub(r"(?s)<(script|style|head)\b.*?</\1>", " ", page.read_text())
    return " ".join(html.unescape(re.sub(r"<[^>]+>", "", s)).split())


def test_every_api_module_has_a_page_and_every_public_name_an_entry(site, conf):
    modules = [m for _, mods in conf["API_MODULES"] for m in mods]
    assert len(modules) == len(set(modules)), "a module listed twice in API_MODULES"
    index = (site / "api/index.html").read_text()
    pages = {}
    for mod in modules:
        page = site / "api" / f"{mod}.html"
        assert page.exists(), f"no API page for {mod}"
        assert f'href="{mod}.html"' in index, f"{mod} missing from the API index"
        pages[mod] = page.read_text()
        assert f'id="module-{mod}"' in pages[mod], f"{mod}: automodule rendered nothing"
    entries = set(re.findall(r'<dt class="sig sig-object py" id="([^"]+)"', "".join(pages.values())))
    for mod in modules:
        module = importlib.import_module(mod)
        undocumented = []
        for name in getattr(module, "__all__", []):
            obj = getattr(module, name)
            # on this page, or where it is defined (a re-export of a documented module)
            home = f"{getattr(obj, '__module__', mod)}.{getattr(obj, '__qualname__', name)}"
            # data (no __module__) re-exported by a package: documented on a submodule's page
            homes = {f"{mod}.{name}", home} | {
                e
                for e in entries
                if e.startswith(f"{mod}.") and e.endswith(f".{name}") and not hasattr(obj, "__module__")
            }
            if name != "__version__" and not homes & entries:
                undocumented.append(name)
        assert not undocumented, (
            f"{mod}: public names without an entry in the API reference (no docstring?): {undocumented}"
        )


def test_pymoo_page_is_the_readme_section(site):
    readme = (ROOT / "README.md").read_text()
    section = readme.split("## Use it from pymoo", 1)[1].split("\n## ", 1)[0]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    page = _text(site / "pymoo.html")
    for line in filter(None, (ln.strip() for ln in code.splitlines())):
        assert " ".join(line.split()) in page, f"README line missing from pymoo.html: {line}"


def test_every_notebook_has_a_page_with_a_download(site):
    notebooks = sorted((ROOT / "notebooks").glob("*.ipynb"))
    assert notebooks
    index = (site / "notebooks/index.html").read_text()
    for nb in notebooks:
        page = site / "notebooks" / f"{nb.stem}.html"
        assert page.exists(), f"no page for {nb.name}"
        assert f'href="{nb.stem}.html"' in index, f"{nb.name} missing from the notebooks index"
        link = re.search(rf'href="(\.\./_downloads/[0-9a-f]+/{re.escape(nb.name)})"', page.read_text())
        assert link, f"{nb.name}: its page has no download link"
        assert (page.parent / link.group(1)).read_bytes() == nb.read_bytes()


@pytest.mark.parametrize(
    "page, source",
    [
        ("ARCHITECTURE.html", "docs/ARCHITECTURE.md"),
        ("CONVENTIONS.html", "docs/CONVENTIONS.md"),
        ("EXPERIMENTS.html", "docs/EXPERIMENTS.md"),
        ("DYNAMIC.html", "docs/DYNAMIC.md"),
        ("benchmarks.html", "BENCHMARKS.md"),
    ],
)
def test_guide_pages_are_in_the_site_and_linked_from_the_index(site, page, source):
    title = (ROOT / source).read_text().splitlines()[0].lstrip("# ").strip()
    assert " ".join(title.split()) in _text(site / page)
    assert f'href="{page}"' in (site / "index.html").read_text()
