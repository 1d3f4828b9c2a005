"""A* on the MovingAI benchmark scenarios, and against the PyPI ``pathfinding``.

Usage::

    python benchmarks/bench_astar_movingai.py            # all scenarios (minutes)
    python benchmarks/bench_astar_movingai.py --quick    # a small sample

Part 1 runs :func:`gapath.planners.astar.astar` on every scenario of every
``.scen`` file under ``<data>/movingai/{mapf,grid}`` (``--quick``: every 50th
line), maps loaded with ``corner_cutting=False``, and prints one JSON line per
file: ``matched``/``total`` (cost within ``abs(a - b) <= 1e-5 * max(1, b)`` of
column 9) and the median time per query (wall clock of the ``astar`` call,
after a warm-up call that compiles the kernel).

Part 2 times, on the four 512x512 grid maps, evenly spaced scenarios side by
side with ``pathfinding``'s ``AStarFinder`` (octile heuristic,
``DiagonalMovement.only_when_no_obstacle`` = no corner cutting): both costs are
recomputed from the step counts and must be identical; it prints the median
per-query speed-up (``pathfinding time / gapath time``). Only
``finder.find_path`` is timed for ``pathfinding`` (the grid is built and
cleaned outside the timer); for gapath the whole ``astar(ws, start, goal)``
call is timed, argument checks and result included (the warm-up call only
compiles the kernel and allocates the reusable per-thread scratch arrays).
The queries alternate, so each side starts with caches the other one left.
If ``pathfinding`` is not installed the comparison is skipped with a note.
The setup and summary records carry the load averages.

Progress goes to stderr, results (JSON lines) to stdout; ``--out FILE``
also writes them to a file.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from gapath.planners.astar import astar
from gapath.workspace import Workspace

SQRT2 = math.sqrt(2.0)
COMPARE_MAPS = ("random512-10-0", "random512-40-0", "maze512-1-0", "8room_000")


# ---------------------------------------------------------------------------
# data
# ---------------------------------------------------------------------------


def default_data_dir() -> Path | None:
    candidates = [Path(__file__).resolve().parents[2] / "shared" / "data"]
    if os.environ.get("GAPATH_SHARED_DATA"):
        candidates.append(Path(os.environ["GAPATH_SHARED_DATA"]))
    for folder in candidates:
        if (folder / "movingai").is_dir():
            return folder
    return None


def load_file(scen_path: Path):
    """``(occ, map name, [(start, goal, optimal), ...])`` of a ``.scen`` file."""
    try:
        from gapath.loaders import load_movingai, load_scenarios
    except ImportError:  # pragma: no cover - before gapath.loaders existed
        return _load_file_fallback(scen_path)
    scens = load_scenarios(scen_path)
    ref = next(s for s in scens if s.start != s.goal)
    ws = load_movingai(ref.resolve_map(), ref.start, ref.goal, corner_cutting=False)
    return ws.occ, ref.map, [(s.start, s.goal, s.optimal) for s in scens]


def _load_file_fallback(scen_path: Path):  # pragma: no cover
    rows = [ln.split("\t") for ln in scen_path.read_text().splitlines()[1:] if ln.strip()]
    map_name = rows[0][1].replace("\\", "/").split("/")[-1]
    text = (scen_path.parent / map_name).read_text().splitlines()
    h = int(text[1].split()[1])
    occ = np.array([[ch not in ".GS" for ch in ln.rstrip("\r")] for ln in text[4 : 4 + h]], bool)
    scens = [((int(r[5]), int(r[4])), (int(r[7]), int(r[6])), float(r[8])) for r in rows]
    return occ, map_name, scens


def matches(cost: float, optimal: float) -> bool:
    return abs(cost - optimal) <= 1e-5 * max(1.0, optimal)


def emit(record: dict, out) -> None:
    line = json.dumps(record, sort_keys=False)
    print(line, flush=True)
    if out is not None:
        out.write(line + "\n")
        out.flush()


def progress(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


def _loadavg():
    """1, 5 and 15 minute load averages (None where unavailable): timings on
    a shared machine depend on them."""
    try:
        return [round(v, 2) for v in os.getloadavg()]
    except (AttributeError, OSError):  # pragma: no cover - not on every OS
        return None


# ---------------------------------------------------------------------------
# part 1: all scenarios
# ---------------------------------------------------------------------------


def run_scenarios(scen_files, stride: int, out) -> dict:
    grand_matched = grand_total = 0
    all_times = []
    t_all = time.perf_counter()
    for scen_path in scen_files:
        occ, map_name, scens = load_file(scen_path)
        sample = scens[::stride]
        start, goal, _ = next(s for s in scens if s[0] != s[1])
        ws = Workspace(occ, start, goal, corner_cutting=False)
        astar(ws)  # warm-up (JIT compile, scratch arrays)
        times, expansions = [], []
        matched = 0
        worst = 0.0
        t_file = time.perf_counter()
        for i, (s, g, optimal) in enumerate(sample):
            t0 = time.perf_counter()
            res = astar(ws, s, g)
            times.append(time.perf_counter() - t0)
            expansions.append(res.expansions)
            ok = matches(res.cost, optimal)
            matched += ok
            worst = max(worst, abs(res.cost - optimal) / max(1.0, optimal))
            if (i + 1) % 500 == 0:
                progress(f"  {scen_path.name}: {i + 1}/{len(sample)} ({time.perf_counter() - t_file:.1f} s)")
        record = {
            "part": "scenarios",
            "file": f"{scen_path.parent.name}/{scen_path.name}",
            "map": map_name,
            "shape": list(occ.shape),
            "matched": matched,
            "total": len(sample),
            "lines_in_file": len(scens),
            "median_ms": round(1e3 * statistics.median(times), 4),
            "mean_ms": round(1e3 * statistics.fmean(times), 4),
            "max_ms": round(1e3 * max(times), 3),
            "median_expansions": int(statistics.median(expansions)),
            "max_rel_err": float(f"{worst:.3g}"),
            "seconds": round(time.perf_counter() - t_file, 2),
        }
        emit(record, out)
        progress(
            f"{record['file']}: {matched}/{len(sample)} matched, "
            f"median {record['median_ms']} ms, {record['seconds']} s"
        )
        grand_matched += matched
        grand_total += len(sample)
        all_times.extend(times)
    summary = {
        "part": "scenarios-summary",
        "files": len(scen_files),
        "matched": grand_matched,
        "total": grand_total,
        "median_ms": round(1e3 * statistics.median(all_times), 4),
        "seconds": round(time.perf_counter() - t_all, 1),
    }
    emit(summary, out)
    return summary


# ---------------------------------------------------------------------------
# part 2: against pathfinding
# ---------------------------------------------------------------------------


def _pf_cost(path_xy) -> float:
    n_diag = sum(1 for (x0, y0), (x1, y1) in zip(path_xy[:-1], path_xy[1:]) if x0 != x1 and y0 != y1)
    return (len(path_xy) - 1 - n_diag) + SQRT2 * n_diag


def run_comparison(grid_dir: Path, n_per_map: int, out) -> list[dict]:
    try:
        import pathfinding
        from pathfinding.core.diagonal_movement import DiagonalMovement
        from pathfinding.core.grid import Grid
        from pathfinding.finder.a_star import AStarFinder
    except ImportError:
        rec = {
            "part": "pathfinding",
            "skipped": True,
            "note": "PyPI package 'pathfinding' is not installed "
            "(pip install pathfinding) - comparison skipped",
        }
        emit(rec, out)
        return [rec]
    try:
        from importlib.metadata import version

        pf_version = version("pathfinding")
    except Exception:  # pragma: no cover
        pf_version = getattr(pathfinding, "__version__", "unknown")

    records = []
    ratios_all = []
    for name in COMPARE_MAPS:
        scen_path = grid_dir / f"{name}.map.scen"
        if not scen_path.is_file():
            rec = {"part": "pathfinding", "map": name, "skipped": True, "note": "file not found"}
            emit(rec, out)
            records.append(rec)
            continue
        occ, _, scens = load_file(scen_path)
        idx = np.unique(np.linspace(0, len(scens) - 1, n_per_map).round().astype(int))
        sample = [scens[i] for i in idx if scens[i][0] != scens[i][1]]
        start, goal, _ = sample[0]
        ws = Workspace(occ, start, goal, corner_cutting=False)
        astar(ws)  # warm-up
        progress(f"pathfinding {pf_version} on {name}: building its grid ...")
        grid = Grid(matrix=(~occ).astype(np.int8))
        finder = AStarFinder(diagonal_movement=DiagonalMovement.only_when_no_obstacle)
        ours_ms, theirs_ms, ratios = [], [], []
        identical = 0
        optimal_ok = 0
        for k, (s, g, optimal) in enumerate(sample):
            t0 = time.perf_counter()
            res = astar(ws, s, g)
            t_ours = time.perf_counter() - t0

            grid.cleanup()
            grid.dirty = False  # cleaned outside the timer
            a = grid.node(s[1], s[0])
            b = grid.node(g[1], g[0])
            t0 = time.perf_counter()
            path, _runs = finder.find_path(a, b, grid)
            t_theirs = time.perf_counter() - t0
            pts = [(p.x, p.y) if hasattr(p, "x") else tuple(p) for p in path]
            theirs_cost = _pf_cost(pts) if pts else math.inf
            identical += theirs_cost == res.cost
            optimal_ok += matches(theirs_cost, optimal)
            ours_ms.append(1e3 * t_ours)
            theirs_ms.append(1e3 * t_theirs)
            ratios.append(t_theirs / t_ours)
            progress(
                f"  {name} {k + 1}/{len(sample)}: cost {res.cost:.4f} vs {theirs_cost:.4f}, "
                f"{1e3 * t_ours:.2f} ms vs {1e3 * t_theirs:.0f} ms"
            )
        rec = {
            "part": "pathfinding",
            "map": name,
            "pathfinding_version": pf_version,
            "n": len(sample),
            "identical_costs": identical,
            "pathfinding_matches_scen": optimal_ok,
            "median_ms_gapath": round(statistics.median(ours_ms), 3),
            "median_ms_pathfinding": round(statistics.median(theirs_ms), 1),
            "median_speedup": round(statistics.median(ratios), 1),
            "min_speedup": round(min(ratios), 1),
        }
        emit(rec, out)
        records.append(rec)
        ratios_all.extend(ratios)
    if ratios_all:
        emit(
            {
                "part": "pathfinding-summary",
                "pathfinding_version": pf_version,
                "n": len(ratios_all),
                "identical_costs": sum(r.get("identical_costs", 0) for r in records),
                "median_speedup": round(statistics.median(ratios_all), 1),
                "loadavg": _loadavg(),
            },
            out,
        )
    return records


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--quick", action="store_true", help="every 50th scenario and 3 comparison queries per map"
    )
    parser.add_argument(
        "--stride", type=int, default=None, help="run every STRIDE-th scenario (default 1, --quick 50)"
    )
    parser.add_argument(
        "--compare",
        type=int,
        default=None,
        help="comparison queries per 512x512 map (default 12, --quick 3; 0 = skip)",
    )
    parser.add_argument(
        "--data",
        type=Path,
        default=None,
        help="shared data folder (default ../shared/data or $GAPATH_SHARED_DATA)",
    )
    parser.add_argument("--out", type=Path, default=None, help="also write the JSON lines here")
    args = parser.parse_args(argv)
    stride = args.stride or (50 if args.quick else 1)
    n_compare = args.compare if args.compare is not None else (3 if args.quick else 12)
    data = args.data or default_data_dir()
    if data is None or not (data / "movingai").is_dir():
        progress("MovingAI data not found (give --data or set GAPATH_SHARED_DATA)")
        return 2
    scen_files = sorted((data / "movingai").glob("*/*.scen"))
    out = open(args.out, "w") if args.out else None
    try:
        import numba

        emit(
            {
                "part": "setup",
                "python": platform.python_version(),
                "numpy": np.__version__,
                "numba": numba.__version__,
                "machine": platform.machine(),
                "cpus": os.cpu_count(),
                "stride": stride,
                "compare_per_map": n_compare,
                "data": str(data),
                "loadavg": _loadavg(),
            },
            out,
        )
        summary = run_scenarios(scen_files, stride, out)
        if n_compare > 0:
            run_comparison(data / "movingai" / "grid", n_compare, out)
    finally:
        if out is not None:
            out.close()
    return 0 if summary["matched"] == summary["total"] else 1


if __name__ == "__main__":
    sys.exit(main())
