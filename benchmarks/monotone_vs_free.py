"""The cost of monotone paths: exact monotone front against exact free front.

The GA encodings only describe column-monotone paths (SPEC). This script
measures what that restriction costs on the bundled scenario and on the
MovingAI 32x32 maps: for each map it computes both exact fronts
(:func:`gapath.planners.exact.monotone_front` and
:func:`gapath.planners.exact.free_front`, objectives length and
vulnerability), the hypervolume ratio of the monotone front against the
free front (SPEC normalisation: the free front's ideal and nadir points,
reference point 1.1), the share of free-front points a monotone path
matches, the best length and vulnerability of each front, the front sizes
and the computing times (median of ``--repeats`` runs after a warm-up run
that also compiles the kernels).

Maps
    * the bundled scenario ``default-32x32-173`` (start bottom-left, goal
      top-right, corner cutting allowed: the SPEC default);
    * the MovingAI maps empty-32-32, random-32-32-10, random-32-32-20,
      maze-32-32-2 and room-32-32-4, with the start and goal of the first
      line of their ``-random-1.scen`` file whose start and goal columns
      differ (a monotone path needs two distinct columns), and
      ``corner_cutting=False``: the MovingAI convention, under which the
      ``.scen`` optimal lengths are computed.

Outputs ``docs/results/monotone_vs_free.md`` (a Markdown table with a short
explanation) and ``docs/results/monotone_vs_free.csv``, and prints one JSON
line per map.

Usage::

    python benchmarks/monotone_vs_free.py [--repeats 5] [--data DIR] [--out docs/results]
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import statistics
import time
from pathlib import Path

from gapath import NoPathError
from gapath.generators import default_workspace
from gapath.loaders import load_movingai, load_scenarios
from gapath.metrics import coverage, hv_ratio
from gapath.planners.exact import free_front, monotone_front

OBJECTIVES = ("length", "vulnerability")
MOVINGAI_MAPS = ("empty-32-32", "random-32-32-10", "random-32-32-20", "maze-32-32-2", "room-32-32-4")
ROOT = Path(__file__).resolve().parents[1]
COLUMNS = (
    "map",
    "size",
    "start",
    "goal",
    "corner_cutting",
    "free_size",
    "monotone_size",
    "hv_ratio",
    "coverage",
    "free_best_length",
    "monotone_best_length",
    "free_best_vulnerability",
    "monotone_best_vulnerability",
    "free_seconds",
    "monotone_seconds",
    "runs",
)


def data_dir(arg=None) -> Path:
    """The MovingAI folder: ``--data``, ``$GAPATH_SHARED_DATA/movingai/mapf`` or
    ``/work/shared/data/movingai/mapf``."""
    if arg:
        return Path(arg)
    env = os.environ.get("GAPATH_SHARED_DATA")
    base = Path(env) if env else ROOT.parent / "shared" / "data"
    return base / "movingai" / "mapf"


def first_scenario(scen_path: Path):
    """The first scenario whose start and goal columns differ."""
    for sc in load_scenarios(scen_path):
        if sc.start[1] != sc.goal[1]:
            return sc
    raise NoPathError(f"{scen_path}: no scenario with distinct start and goal columns")


def workspaces(folder: Path):
    yield default_workspace()
    for name in MOVINGAI_MAPS:
        sc = first_scenario(folder / f"{name}-random-1.scen")
        yield load_movingai(folder / f"{name}.map", sc.start, sc.goal, corner_cutting=False, name=name)


def timed(solver, ws, repeats):
    """``(front or None, median seconds)``; None when no path exists."""
    try:
        front = solver(ws, OBJECTIVES)  # warm-up (and JIT)
    except NoPathError:
        return None, float("nan")
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        front = solver(ws, OBJECTIVES)
        times.append(time.perf_counter() - t0)
    return front, statistics.median(times)


def compare(ws, repeats) -> dict:
    free, t_free = timed(free_front, ws, repeats)
    mono, t_mono = timed(monotone_front, ws, repeats)
    h, w = ws.shape
    row = {
        "map": ws.name,
        "size": f"{h}x{w}",
        "start": list(ws.start),
        "goal": list(ws.goal),
        "corner_cutting": ws.corner_cutting,
        "free_size": len(free),
        "monotone_size": len(mono) if mono is not None else 0,
        "hv_ratio": hv_ratio(mono.F, free.F) if mono is not None else 0.0,
        "coverage": coverage(mono.F, free.F) if mono is not None else 0.0,
        "free_best_length": float(free.F[:, 0].min()),
        "monotone_best_length": float(mono.F[:, 0].min()) if mono is not None else None,
        "free_best_vulnerability": float(free.F[:, 1].min()),
        "monotone_best_vulnerability": float(mono.F[:, 1].min()) if mono is not None else None,
        "free_seconds": round(t_free, 5),
        "monotone_seconds": round(t_mono, 5) if mono is not None else None,
        "runs": repeats,
    }
    return row


def _fmt(v, digits=4):
    if v is None:
        return "–"
    if isinstance(v, float):
        return f"{v:.{digits}g}" if abs(v) < 1e4 else f"{v:.0f}"
    return str(v)


def finding(r) -> str:
    """One sentence on what monotonicity costs on the map of row ``r``."""
    name = f"**{r['map']}**"
    dr = abs(r["start"][0] - r["goal"][0])
    dc = abs(r["start"][1] - r["goal"][1])
    if r["monotone_size"] == 0:
        return (
            f"{name}: no feasible monotone path at all (every route must step back a "
            f"column); the free front has {r['free_size']} "
            f"point{'s' if r['free_size'] != 1 else ''}."
        )
    parts = [f"HV ratio {r['hv_ratio']:.4f}"]
    for key, label in (("length", "shortest length"), ("vulnerability", "least vulnerability")):
        free, mono = r[f"free_best_{key}"], r[f"monotone_best_{key}"]
        if mono <= free + 1e-9 * max(1.0, abs(free)):
            parts.append(f"same {label}")
        else:
            rel = f" (+{100 * (mono - free) / free:.0f} %)" if free > 0 else ""
            parts.append(f"{label} {_fmt(mono)} instead of {_fmt(free)}{rel}")
    text = f"{name}: " + "; ".join(parts) + "."
    if r["hv_ratio"] >= 0.999:
        text += " Monotone paths lose (almost) nothing here."
    if dr > dc:
        text += (
            f" Start and goal are {dr} rows but only {dc} columns apart, so a monotone "
            f"path has only {dc} column transitions to go round obstacles."
        )
    return text


def write_markdown(rows, path: Path):
    lines = [
        "# The cost of monotone paths",
        "",
        "The GA encodings describe column-monotone paths only (SPEC: one column",
        "per transition, from the start column to the goal column). This table",
        "compares, per map, the exact Pareto front of the feasible monotone paths",
        "(`monotone_front`) with the exact front of all feasible 8-connected paths",
        "(`free_front`), objectives length and vulnerability.",
        "",
        "* **HV ratio**: hypervolume of the monotone front divided by that of the",
        "  free front, both normalised by the free front's ideal and nadir points",
        "  (reference point 1.1, SPEC). 1 means monotone paths lose nothing; it is",
        "  the best a GA on the monotone encodings can reach against the free",
        "  reference front.",
        "* **coverage**: share of free-front points that some monotone path matches",
        "  within SPEC's tolerance.",
        "* **best L / best V**: the smallest length and vulnerability of each front",
        "  (free / monotone).",
        "* **time**: median wall time of one exact computation after a warm-up run",
        "  (numba compilation excluded), on a shared 2-core machine.",
        "",
        "The bundled scenario uses the SPEC default, corner cutting allowed. The",
        "MovingAI maps use `corner_cutting=False` (MovingAI's convention, under",
        "which the `.scen` optimal lengths are computed) and the start and goal of",
        "the first line of their `-random-1.scen` file whose start and goal",
        "columns differ.",
        "",
        "| map | start → goal | free front | monotone front | HV ratio | coverage "
        "| best L (free / mono) | best V (free / mono) | time free / mono (s) |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        lines.append(
            f"| {r['map']} | {tuple(r['start'])} → {tuple(r['goal'])} | {r['free_size']} "
            f"| {r['monotone_size']} | {r['hv_ratio']:.4f} | {r['coverage']:.2f} "
            f"| {_fmt(r['free_best_length'])} / {_fmt(r['monotone_best_length'])} "
            f"| {_fmt(r['free_best_vulnerability'])} / {_fmt(r['monotone_best_vulnerability'])} "
            f"| {_fmt(r['free_seconds'], 3)} / {_fmt(r['monotone_seconds'], 3)} |"
        )
    lines += ["", "## Findings", ""]
    lines += [f"* {finding(r)}" for r in rows]
    lines += [
        "",
        "Vulnerability is the sum of the potentials of the path's cells; on sparse",
        "maps many paths are equal within SPEC's tolerance, so compare fronts by HV",
        "ratio and coverage rather than by their sizes.",
        "",
        "Produced by `python benchmarks/monotone_vs_free.py`; raw numbers in",
        "`monotone_vs_free.csv`.",
        "",
    ]
    path.write_text("\n".join(lines), encoding="utf-8")


def write_csv(rows, path: Path):
    with path.open("w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=COLUMNS)
        writer.writeheader()
        for r in rows:
            writer.writerow({k: (" ".join(map(str, v)) if isinstance(v, list) else v) for k, v in r.items()})


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="timed runs per front (default 5)")
    parser.add_argument("--data", help="folder of the MovingAI maps and .scen files")
    parser.add_argument(
        "--out", default=str(ROOT / "docs" / "results"), help="output folder (default docs/results)"
    )
    args = parser.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for ws in workspaces(data_dir(args.data)):
        row = compare(ws, args.repeats)
        rows.append(row)
        print(json.dumps(row), flush=True)
    write_markdown(rows, out / "monotone_vs_free.md")
    write_csv(rows, out / "monotone_vs_free.csv")


if __name__ == "__main__":
    main()
