"""The monotone DP against the free search on the same maps (issue 15 item 3).

For each map, corner to corner, objectives length and vulnerability:
:func:`gapath.planners.exact.monotone_front` and
:func:`gapath.planners.exact.free_front` (and, with ``--reference``, the
monotone DP as it was before, kept as ``tests/_monotone_reference.py``).
Prints one JSON line per (map, solver): thread CPU seconds and wall seconds
(median of ``--repeats`` runs after a warm-up call on a small map that
compiles the kernels), front size, the solver's label counts and peak
bytes; then one line per map with the monotone / free ratios. The monotone
front's paths are a subset of the free ones, so the DP should cost no more.

Maps: ``random_workspace((n, n), 10 % obstacles, seed)`` for each ``--sizes``
entry (start bottom-left, goal top-right, corner cutting allowed), and with
``--movingai`` the MovingAI map random512-10-0 between the free cells
nearest its bottom-left and top-right corners (``corner_cutting=False``).

Usage::

    python benchmarks/bench_monotone.py [--sizes 128,256] [--repeats 3] [--reference] [--movingai]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from gapath.generators import random_workspace
from gapath.planners.exact import free_front, monotone_front

ROOT = Path(__file__).resolve().parents[1]
LV = ("length", "vulnerability")


def movingai_512():
    """random512-10-0 corner to corner, or None when the map is missing."""
    from gapath.loaders import load_movingai

    env = os.environ.get("GAPATH_SHARED_DATA")
    base = Path(env) if env else ROOT.parent / "shared" / "data"
    path = base / "movingai" / "grid" / "random512-10-0.map"
    if not path.is_file():
        return None
    rows = path.read_text().splitlines()[4:]
    occ = np.array([[ch not in ".GS" for ch in r] for r in rows if r])
    start = nearest_free(occ, (occ.shape[0] - 1, 0))
    goal = nearest_free(occ, (0, occ.shape[1] - 1))
    return load_movingai(path, start, goal, corner_cutting=False, name="random512-10-0(corners)")


def nearest_free(occ, cell):
    """The free cell nearest ``cell`` (Chebyshev distance, then row-major)."""
    rows, cols = np.nonzero(~occ)
    d = np.maximum(np.abs(rows - cell[0]), np.abs(cols - cell[1]))
    i = np.lexsort((cols, rows, d))[0]
    return int(rows[i]), int(cols[i])


def reference_solver():
    """The monotone DP before issue 15 item 3 (the tests' reference)."""
    sys.path.insert(0, str(ROOT / "tests"))
    from _monotone_reference import reference_front

    def run(ws, objectives):
        F, smooth, labels = reference_front(ws, objectives)
        return {"front_size": len(F), "labels_made": labels, "table_bytes_at_least": 40 * labels}

    return run


def measure(solve, ws, repeats):
    cpu, wall = [], []
    for _ in range(repeats):
        c0, w0 = time.thread_time(), time.perf_counter()
        out = solve(ws, LV)
        cpu.append(time.thread_time() - c0)
        wall.append(time.perf_counter() - w0)
    return out, statistics.median(cpu), statistics.median(wall)


def row(kind, ws, out, cpu, wall, repeats):
    h, w = ws.shape
    line = {
        "map": ws.name,
        "size": f"{h}x{w}",
        "solver": kind,
        "cpu_s": round(cpu, 4),
        "wall_s": round(wall, 4),
        "runs": repeats,
    }
    if isinstance(out, dict):
        line.update(out)
    else:
        s = out.stats
        line["front_size"] = len(out)
        for key in (
            "labels",
            "labels_peak",
            "labels_made",
            "candidates",
            "pruned",
            "expansions",
            "peak_bytes",
        ):
            if key in s:
                line[key] = s[key]
    return line


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--sizes", default="128,256", help="square random maps, 10 %% obstacles (default 128,256)"
    )
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--repeats", type=int, default=3, help="timed runs per solver (default 3)")
    parser.add_argument("--reference", action="store_true", help="also time the previous monotone DP")
    parser.add_argument("--movingai", action="store_true", help="add random512-10-0 (one run each)")
    parser.add_argument("--only", choices=("monotone", "free"), help="time one solver only")
    args = parser.parse_args(argv)

    solvers = {"monotone": monotone_front, "free": free_front}
    if args.only:
        solvers = {args.only: solvers[args.only]}
    if args.reference:
        solvers["monotone_before"] = reference_solver()
    warm = random_workspace((16, 16), 25, seed=0)
    for solve in solvers.values():
        solve(warm, LV)

    cases = [
        (random_workspace((n, n), int(0.10 * n * n), seed=args.seed), args.repeats)
        for n in (int(x) for x in args.sizes.split(",") if x)
    ]
    if args.movingai:
        big = movingai_512()
        if big is None:
            print(json.dumps({"skip": "random512-10-0.map not found"}), flush=True)
        else:
            cases.append((big, 1))
    for ws, repeats in cases:
        got = {}
        for kind, solve in solvers.items():
            out, cpu, wall = measure(solve, ws, repeats)
            line = row(kind, ws, out, cpu, wall, repeats)
            got[kind] = line
            print(json.dumps(line), flush=True)
        if "monotone" in got and "free" in got:
            m, f = got["monotone"], got["free"]
            print(
                json.dumps(
                    {
                        "map": ws.name,
                        "monotone_over_free_cpu": round(m["cpu_s"] / f["cpu_s"], 3),
                        "monotone_over_free_bytes": round(m["peak_bytes"] / f["peak_bytes"], 4),
                        **(
                            {"before_over_now_cpu": round(got["monotone_before"]["cpu_s"] / m["cpu_s"], 2)}
                            if "monotone_before" in got
                            else {}
                        ),
                    }
                ),
                flush=True,
            )


if __name__ == "__main__":
    main()
