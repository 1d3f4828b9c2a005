"""The layering of docs/ARCHITECTURE.md, checked on the import graph of src/gapath.

The graph is read from the source with :mod:`ast` (nothing is imported): every
``import`` and ``from ... import`` statement counts, at module level, inside
functions and under ``if TYPE_CHECKING:`` alike. ``gapath/__init__.py`` (the
facade of top-level names) is left out as a source.

* An *area* is a top-level module or subpackage of ``gapath``
  (``gapath.workspace``, ``gapath.planners``, ...). The areas must form a
  directed acyclic graph: no import circle between two areas, however long.
* Every module has a *layer* (:data:`LAYERS`, the table of
  docs/ARCHITECTURE.md, longest prefix wins); a module never imports a module
  of a higher layer.
* No module outside ``gapath.cli`` imports :mod:`argparse` or the CLI.
* No two modules import each other, however indirectly, at module level.

One import is let through on purpose (:data:`LAZY_EXCEPTIONS`): it sits in a
named function, is run when that function is called, and says why; the
checks fail if it turns into a module-level import or is no longer needed,
and the same import anywhere else counts.

Run this file as a script to print the graph between areas.
"""

from __future__ import annotations

import ast
import sys
from collections import defaultdict
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"

#: Layers of docs/ARCHITECTURE.md, bottom (0) to top. A module's layer is the
#: one of its longest listed prefix; every module must have one.
LAYERS: dict[str, int] = {
    # ground floor
    "gapath.errors": 0,
    "gapath.grid": 0,
    "gapath.openlist": 0,
    "gapath.workspace": 0,
    "gapath.loaders": 0,
    "gapath.generators": 0,
    "gapath.monotone": 0,
    "gapath.objectives": 0,
    "gapath.costmap": 0,
    "gapath.front": 0,
    "gapath.metrics": 0,
    # search
    "gapath.planners": 1,
    # evolution
    "gapath.encodings": 2,
    "gapath.operators": 2,
    "gapath.problems": 2,
    "gapath.algorithms": 2,
    "gapath.constraints": 2,
    # running
    "gapath.solver": 3,
    "gapath.callbacks": 3,
    "gapath.progress": 3,
    "gapath.convergence": 3,
    "gapath._convergence_kernels": 3,
    "gapath.reference": 3,
    "gapath.results": 3,
    "gapath.plotting": 3,
    "gapath.dynamic": 3,
    # experiments (infrastructure), then the paper studies over it
    "gapath.experiments": 4,
    "gapath.studies": 5,
    # CLI
    "gapath.cli": 6,
}
LAYER_NAMES = ("ground floor", "search", "evolution", "running", "experiments", "studies", "CLI")

#: ``(importer, imported, function)``: imports of module ``imported`` inside
#: ``function`` (qualified name) of module ``importer`` left out of the
#: checks, with the reason.
LAZY_EXCEPTIONS: dict[tuple[str, str, str], str] = {
    ("gapath.workspace", "gapath.loaders", "Workspace.load"): (
        "Workspace.load(path) is gapath.loaders.load_map(path), and the loaders build Workspaces"
    ),
}


def module_name(path: Path, src: Path) -> str:
    parts = list(path.relative_to(src).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def imports_of(tree: ast.AST, name: str, is_package: bool) -> list[tuple[str, int, str | None]]:
    """``(imported name, line, function)`` of every import statement in
    ``tree``; ``function`` is the qualified name of the function it is in,
    None at module level (class bodies included).

    ``from a.b import c`` yields ``a.b`` and ``a.b.c`` (resolved to a module
    by :func:`resolve`); relative imports are made absolute.
    """
    package = name if is_package else name.rpartition(".")[0]
    out = []
    functions = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)

    def visit(node, path, in_function):
        local = ".".join(path) if in_function else None
        if isinstance(node, ast.Import):
            out.extend((alias.name, node.lineno, local) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            out.append((mod, node.lineno, local))
            out.extend((f"{mod}.{alias.name}", node.lineno, local) for alias in node.names)
        if isinstance(node, (*functions, ast.ClassDef)):
            path = [*path, getattr(node, "name", "<lambda>")]
            in_function = in_function or isinstance(node, functions)
        for child in ast.iter_child_nodes(node):
            visit(child, path, in_function)

    visit(tree, [], False)
    return out


def resolve(name: str, modules: set[str]) -> str | None:
    """The gapath module ``name`` refers to (its longest prefix that is a
    module), or None outside gapath."""
    parts = name.split(".")
    while parts:
        cand = ".".join(parts)
        if cand in modules:
            return cand
        parts.pop()
    return None


def import_sites(src: Path = SRC):
    """``(sites, external)``: ``sites[a][b]`` lists the ``(file, line,
    function)`` where gapath module ``a`` imports gapath module ``b``
    (``function`` as :func:`imports_of`); ``external[a]`` the
    top-level names of the other packages ``a`` imports, with a line each."""
    files = {module_name(p, src): p for p in sorted((src / "gapath").rglob("*.py"))}
    modules = set(files)
    sites: dict[str, dict[str, list[tuple[str, int, str | None]]]] = defaultdict(lambda: defaultdict(list))
    external: dict[str, dict[str, tuple[str, int]]] = defaultdict(dict)
    for name, path in files.items():
        if name == "gapath":  # the facade re-exports from everywhere
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        where = str(path.relative_to(src))
        for imported, line, local in imports_of(tree, name, path.name == "__init__.py"):
            target = resolve(imported, modules)
            if target is None:
                external[name].setdefault(imported.split(".")[0], (where, line))
            elif target not in (name, "gapath") and (where, line, local) not in sites[name][target]:
                sites[name][target].append((where, line, local))
    return sites, external


def import_graph(src: Path = SRC):
    """``(edges, external)`` as :func:`import_sites`, with ``edges[a][b]`` the
    first ``(file, line)`` of an import of ``b`` by ``a``, leaving out the
    function-local imports of :data:`LAZY_EXCEPTIONS`."""
    sites, external = import_sites(src)
    edges: dict[str, dict[str, tuple[str, int]]] = defaultdict(dict)
    for a, targets in sites.items():
        for b, where in targets.items():
            kept = [w for w in where if (a, b, w[2]) not in LAZY_EXCEPTIONS]
            if kept:
                edges[a][b] = kept[0][:2]
    return edges, external


def area(module: str) -> str:
    return ".".join(module.split(".")[:2])


def layer(module: str) -> int | None:
    parts = module.split(".")
    while parts:
        lay = LAYERS.get(".".join(parts))
        if lay is not None:
            return lay
        parts.pop()
    return None


def area_graph(edges) -> dict[str, dict[str, tuple[str, str, tuple[str, int]]]]:
    """``out[A][B] = (a, b, where)``: one import of area ``B`` by area ``A``."""
    out: dict[str, dict[str, tuple[str, str, tuple[str, int]]]] = defaultdict(dict)
    for a, targets in sorted(edges.items()):
        for b, where in sorted(targets.items()):
            if area(a) != area(b):
                out[area(a)].setdefault(area(b), (a, b, where))
    return out


def strongly_connected(graph) -> list[list[str]]:
    """The strongly connected components of more than one node (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    nodes = sorted(set(graph) | {b for t in graph.values() for b in t})

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in nodes:
        if v not in index:
            visit(v)
    return found


def describe_cycle(comp, graph) -> str:
    lines = [" <-> ".join(comp)]
    for a in comp:
        for b in comp:
            if b in graph.get(a, {}):
                src_mod, dst_mod, (file, line) = graph[a][b]
                lines.append(f"  {a} -> {b}: {file}:{line} ({src_mod} imports {dst_mod})")
    return "\n".join(lines)


# ---------------------------------------------------------------------------
# the checks
# ---------------------------------------------------------------------------


def check_no_area_cycle(src: Path = SRC) -> list[str]:
    edges, _ = import_graph(src)
    graph = area_graph(edges)
    return [describe_cycle(comp, graph) for comp in strongly_connected(graph)]


def check_layers(src: Path = SRC) -> list[str]:
    edges, _ = import_graph(src)
    problems = []
    for a, targets in sorted(edges.items()):
        la = layer(a)
        if la is None:
            problems.append(f"{a} has no layer: add it to LAYERS and to docs/ARCHITECTURE.md")
            continue
        for b, (file, line) in sorted(targets.items()):
            lb = layer(b)
            if lb is not None and lb > la:
                problems.append(
                    f"{file}:{line}: {a} ({LAYER_NAMES[la]}) imports {b} ({LAYER_NAMES[lb]}), a higher layer"
                )
    return problems


def check_cli_apart(src: Path = SRC) -> list[str]:
    edges, external = import_graph(src)
    problems = []
    for a, names in sorted(external.items()):
        if area(a) != "gapath.cli" and "argparse" in names:
            file, line = names["argparse"]
            problems.append(f"{file}:{line}: {a} imports argparse (only gapath.cli may)")
    for a, targets in sorted(edges.items()):
        if area(a) == "gapath.cli":
            continue
        for b, (file, line) in sorted(targets.items()):
            if area(b) == "gapath.cli":
                problems.append(f"{file}:{line}: {a} imports the CLI ({b})")
    return problems


def test_no_import_circle_between_areas():
    cycles = check_no_area_cycle()
    assert not cycles, "import circles between areas of gapath:\n" + "\n".join(cycles)


def check_no_module_cycle(src: Path = SRC) -> list[str]:
    """Import circles between single modules through module-level imports
    only (those run on import, in an order that must exist)."""
    sites, _ = import_sites(src)
    graph = {
        a: {b for b, where in t.items() if any(not local for _, _, local in where)} for a, t in sites.items()
    }
    return [" <-> ".join(comp) for comp in strongly_connected(graph)]


def test_no_module_level_import_circle():
    cycles = check_no_module_cycle()
    assert not cycles, "module-level import circles:\n" + "\n".join(cycles)


def test_lower_layers_never_import_higher_ones():
    problems = check_layers()
    assert not problems, "\n".join(problems)


def test_only_the_cli_imports_argparse():
    problems = check_cli_apart()
    assert not problems, "\n".join(problems)


def check_exceptions(src: Path = SRC) -> list[str]:
    """Each of :data:`LAZY_EXCEPTIONS` is still needed, and its two modules
    import each other nowhere at module level."""
    sites, _ = import_sites(src)
    problems = []
    for (a, b, function), reason in LAZY_EXCEPTIONS.items():
        where = sites.get(a, {}).get(b, [])
        if not any(scope == function for _, _, scope in where):
            problems.append(
                f"{a}.{function} no longer imports {b}: remove it from LAZY_EXCEPTIONS ({reason})"
            )
        problems.extend(
            f"{file}:{line}: {a} imports {b} at module level (allowed only in {function}: {reason})"
            for file, line, scope in where
            if scope is None
        )
    return problems


def test_the_exceptions_are_lazy_and_still_needed():
    problems = check_exceptions()
    assert not problems, "\n".join(problems)


def test_every_listed_layer_is_documented():
    text = (SRC.parent / "docs" / "ARCHITECTURE.md").read_text(encoding="utf-8")
    present = {module_name(p, SRC) for p in (SRC / "gapath").rglob("*.py")}
    missing = [m for m in LAYERS if m in present and m not in text]
    assert not missing, f"modules of LAYERS not named in docs/ARCHITECTURE.md: {missing}"


# ---------------------------------------------------------------------------
# the checks can fail: a small package with a circle and a back-arrow
# ---------------------------------------------------------------------------


def _write(root: Path, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        p = root / "gapath" / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")
    return root


def test_checks_find_a_circle_through_a_function_local_import(tmp_path):
    src = _write(
        tmp_path,
        {
            "__init__.py": "",
            "front.py": "def marked():\n    if True:\n        from gapath.metrics import hv\n",
            "metrics.py": "from gapath.front import PathFront\n",
            "errors.py": "",
        },
    )
    cycles = check_no_area_cycle(src)
    assert len(cycles) == 1 and "gapath.front <-> gapath.metrics" in cycles[0]
    assert "gapath/front.py:3" in cycles[0]


def test_the_exceptions_are_checked(tmp_path):
    files = {"__init__.py": "", "loaders.py": "from gapath.workspace import Workspace\n"}
    load = "class Workspace:\n    @classmethod\n    def load(cls):\n        from gapath.loaders import m\n"
    lazy = _write(tmp_path / "lazy", {**files, "workspace.py": load})
    assert check_no_area_cycle(lazy) == [] and check_exceptions(lazy) == []
    # the same import in another function counts
    other = _write(
        tmp_path / "other", {**files, "workspace.py": load + "def default():\n    import gapath.loaders\n"}
    )
    (cycle,) = check_no_area_cycle(other)
    assert "gapath/workspace.py:6 (gapath.workspace imports gapath.loaders)" in cycle
    eager = _write(
        tmp_path / "eager", {**files, "workspace.py": "from gapath.loaders import load_map\n" + load}
    )
    assert len(check_no_area_cycle(eager)) == 1
    assert check_no_module_cycle(eager) == ["gapath.loaders <-> gapath.workspace"]
    assert check_exceptions(eager) == [
        "gapath/workspace.py:1: gapath.workspace imports gapath.loaders at module level (allowed only in "
        f"Workspace.load: {LAZY_EXCEPTIONS['gapath.workspace', 'gapath.loaders', 'Workspace.load']})"
    ]
    gone = _write(
        tmp_path / "gone", {**files, "workspace.py": "def load():\n    from gapath.loaders import m\n"}
    )
    assert "gapath.workspace.Workspace.load no longer imports gapath.loaders" in check_exceptions(gone)[0]


def test_checks_find_a_circle_between_packages_and_a_back_arrow(tmp_path):
    src = _write(
        tmp_path,
        {
            "__init__.py": "",
            "encodings/__init__.py": "",
            "encodings/base.py": "from ..planners import exact\n",
            "planners/__init__.py": "",
            "planners/exact.py": "from gapath.encodings.base import Frame\n",
            "objectives.py": "import argparse\nfrom gapath import solver\n",
            "solver.py": "",
        },
    )
    cycles = check_no_area_cycle(src)
    assert len(cycles) == 1 and "gapath.encodings <-> gapath.planners" in cycles[0]
    assert check_no_module_cycle(src) == ["gapath.encodings.base <-> gapath.planners.exact"]
    layers = check_layers(src)
    assert any("gapath.planners.exact (search) imports gapath.encodings.base" in p for p in layers)
    assert any("gapath.objectives (ground floor) imports gapath.solver" in p for p in layers)
    assert check_cli_apart(src) == [
        "gapath/objectives.py:1: gapath.objectives imports argparse (only gapath.cli may)"
    ]


def test_every_module_needs_a_layer(tmp_path):
    src = _write(tmp_path, {"__init__.py": "", "newthing.py": "from gapath import errors\n", "errors.py": ""})
    assert check_layers(src) == ["gapath.newthing has no layer: add it to LAYERS and to docs/ARCHITECTURE.md"]


if __name__ == "__main__":  # print the graph between areas, by layer
    edges, _ = import_graph()
    graph = area_graph(edges)
    for a in sorted(set(map(area, edges)), key=lambda m: (layer(m) or -1, m)):
        lay = layer(a)
        print(
            f"{a} [{LAYER_NAMES[lay] if lay is not None else '?'}] -> {', '.join(sorted(graph.get(a, {})))}"
        )
    cycles = check_no_area_cycle()
    print("\n".join(["", "circles:", *cycles]) if cycles else "\nno circle")
    sys.exit(bool(cycles))
