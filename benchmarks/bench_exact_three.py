"""Three-objective exact free fronts (length, vulnerability, smoothness) on
128x128 maps (issue 15, item 2: <= 10 s).

Prints one JSON line per map: map, size, front_size, expansions, generated,
labels, stair_searches (staircase searches that the per-cell summaries left
open; absent before they were counted), stair_mb (the staircase pool),
peak_mb, cpu_s (thread CPU time of ``free_front``, the minimum of
``--repeats`` runs after a warm-up call that also compiles), wall_s (the
wall time of the same run), runs, the 1-minute load average after the runs
(``load``) and ``--label`` if given.

Maps: random 128x128 workspaces with 20 % obstacles, corner to corner
(``random_workspace``'s default start and goal, seeds 0-2), the 17 % map of
BENCHMARKS.md (seed 1), and, when ``../shared/data`` holds it, the top-left
128x128 window of MovingAI's random512-10-0 between the free cells nearest
its bottom-left and top-right corners (``corner_cutting=False`` as in
MovingAI; the data have no 128x128 map).

Usage::

    python benchmarks/bench_exact_three.py [--repeats 1] [--maps random20-0,...]
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

import numpy as np

from gapath import Workspace
from gapath.generators import random_workspace
from gapath.planners.exact import free_front

LVS = ("length", "vulnerability", "smoothness")


def nearest_free(occ, cell):
    """The free cell nearest ``cell`` (Chebyshev, then Manhattan distance,
    then row-major order)."""
    rows, cols = np.nonzero(~occ)
    r0, c0 = cell
    key = np.lexsort(
        (cols, rows, abs(rows - r0) + abs(cols - c0), np.maximum(abs(rows - r0), abs(cols - c0)))
    )
    return int(rows[key[0]]), int(cols[key[0]])


def movingai_window():
    """The top-left 128x128 window of random512-10-0, or None without the data."""
    env = os.environ.get("GAPATH_SHARED_DATA")
    base = Path(env) if env else Path(__file__).resolve().parents[2] / "shared" / "data"
    path = base / "movingai" / "grid" / "random512-10-0.map"
    if not path.is_file():
        return None
    occ = _read_map(path)[:128, :128]
    start, goal = nearest_free(occ, (127, 0)), nearest_free(occ, (0, 127))
    return Workspace(occ, start, goal, corner_cutting=False, name="random512-10-0[:128,:128]")


def _read_map(path):
    """Obstacle grid of a MovingAI .map file ('.' and 'G' are free)."""
    lines = Path(path).read_text().splitlines()
    i = next(k for k, line in enumerate(lines) if line.strip() == "map") + 1
    rows = [line.rstrip("\n") for line in lines[i:] if line.strip()]
    return np.array([[ch not in ".G" for ch in row] for row in rows], bool)


def maps():
    out = {f"random20-{s}": random_workspace((128, 128), int(0.2 * 128 * 128), seed=s) for s in range(3)}
    out["random17-1"] = random_workspace((128, 128), int(0.17 * 128 * 128), seed=1)
    window = movingai_window()
    if window is not None:
        out["movingai-window"] = window
    return out


def run(name, ws, repeats):
    best = None
    for _ in range(repeats):
        c0, w0 = time.thread_time(), time.perf_counter()
        front = free_front(ws, LVS)
        cpu, wall = time.thread_time() - c0, time.perf_counter() - w0
        if best is None or cpu < best[0]:
            best = (cpu, wall)
    h, w = ws.shape
    return {
        "map": name,
        "name": ws.name,
        "size": f"{h}x{w}",
        "front_size": len(front),
        "expansions": front.stats["expansions"],
        "generated": front.stats["generated"],
        "labels": front.stats["labels"],
        "stair_searches": front.stats.get("stair_searches"),
        "stair_mb": round(front.stats.get("stair_floats", 0) * 8 / 1e6, 1),
        "peak_mb": round(front.stats["peak_bytes"] / 1e6, 1),
        "cpu_s": round(best[0], 3),
        "wall_s": round(best[1], 3),
        "runs": repeats,
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=1, help="timed runs per map (default 1)")
    ap.add_argument("--maps", default=None, help="comma-separated map keys (default: all)")
    ap.add_argument("--label", default=None, help="a tag added to every line (e.g. the commit)")
    args = ap.parse_args(argv)
    free_front(random_workspace((16, 16), 40, seed=1), LVS)  # compile / load the cache
    chosen = maps()
    if args.maps:
        chosen = {k: chosen[k] for k in args.maps.split(",")}
    for name, ws in chosen.items():
        row = run(name, ws, args.repeats)
        if args.label:
            row["label"] = args.label
        row["load"] = round(os.getloadavg()[0], 2)
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
