"""Timings of the exact fronts (gapath.planners.exact.monotone_front and
free_front).

Prints one JSON line per case: front ("monotone" or "free"), map, size,
start, goal, objectives, corner_cutting, seconds (median of ``--repeats``
runs after one warm-up run that also triggers the JIT compilation), runs,
front_size, labels and peak_mb (from the front's ``stats``: label rows held,
largest memory of the search arrays) and, for free fronts, expansions.

Usage::

    python benchmarks/bench_exact.py [--repeats 5] [--only monotone|free]

Targets (2 objectives, after warm-up): monotone front, 32x32 with ~17 %
obstacles <= 0.2 s, 128x128 <= 5 s; free front (length, vulnerability),
32x32 bundled scenario <= 1 s, 64x64 MovingAI random-64-64-10 <= 10 s.
Three-objective free fronts (16x16, 32x32) are reported, not targeted.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time
from pathlib import Path

from gapath.generators import random_workspace
from gapath.planners.exact import free_front, monotone_front

LV = ("length", "vulnerability")
LVS = ("length", "vulnerability", "smoothness")


def default_scenario():
    """The bundled default scenario, or its recipe when the map loader is
    not available."""
    try:
        from gapath.generators import default_workspace

        return default_workspace()
    except ImportError:
        return random_workspace((32, 32), 173, seed=2013, name="default-32x32-173(recipe)")


def movingai_64():
    """random-64-64-10 (MovingAI, corner_cutting=False as in its .scen files)
    from its first scenario and between the free cells nearest the
    bottom-left and top-right corners; None when the data are missing."""
    from gapath.loaders import load_movingai, load_scenarios

    env = os.environ.get("GAPATH_SHARED_DATA")
    base = Path(env) if env else Path(__file__).resolve().parents[2] / "shared" / "data"
    folder = base / "movingai" / "mapf"
    if not (folder / "random-64-64-10.map").is_file():
        return []
    sc = load_scenarios(folder / "random-64-64-10-random-1.scen")[0]
    scen = load_movingai(
        folder / "random-64-64-10.map",
        sc.start,
        sc.goal,
        corner_cutting=False,
        name="random-64-64-10(scen 1)",
    )
    corners = scen.replace(
        start=nearest_free(scen.occ, (63, 0)),
        goal=nearest_free(scen.occ, (0, 63)),
        name="random-64-64-10(corners)",
    )
    return [scen, corners]


def nearest_free(occ, cell):
    """The free cell nearest ``cell`` (Chebyshev, then Manhattan distance,
    then row-major order)."""
    h, w = occ.shape
    r0, c0 = cell
    free = [
        (max(abs(r - r0), abs(c - c0)), abs(r - r0) + abs(c - c0), r, c)
        for r in range(h)
        for c in range(w)
        if not occ[r, c]
    ]
    _, _, r, c = min(free)
    return r, c


def cases():
    """``(front kind, workspace, objectives)`` triples."""
    default = default_scenario()
    big = random_workspace((128, 128), int(0.17 * 128 * 128), seed=1)
    small = random_workspace((16, 16), int(0.17 * 16 * 16), seed=1)
    out = [
        ("monotone", default, LV),
        ("monotone", default, ("length", "smoothness")),
        ("monotone", default, LVS),
        ("monotone", default.replace(corner_cutting=False), LV),
        ("monotone", big, LV),
        ("free", default, LV),
        ("free", default.replace(corner_cutting=False), LV),
    ]
    out += [("free", ws, LV) for ws in movingai_64()]
    out += [("free", small, LVS), ("free", default, LVS)]
    return out


SOLVERS = {"monotone": monotone_front, "free": free_front}


def time_case(kind, ws, objectives, repeats):
    solver = SOLVERS[kind]
    front = solver(ws, objectives)  # warm-up (and JIT)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        front = solver(ws, objectives)
        times.append(time.perf_counter() - t0)
    h, w = ws.shape
    return {
        "front": kind,
        "map": ws.name,
        "size": f"{h}x{w}",
        "start": list(ws.start),
        "goal": list(ws.goal),
        "objectives": list(objectives),
        "corner_cutting": ws.corner_cutting,
        "seconds": round(statistics.median(times), 5),
        "runs": repeats,
        "front_size": len(front),
        "labels": front.stats["labels"],
        "peak_mb": round(front.stats["peak_bytes"] / 1e6, 3),
        **({"expansions": front.stats["expansions"]} if kind == "free" else {}),
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="timed runs per case (default 5)")
    parser.add_argument("--only", choices=sorted(SOLVERS), help="time one kind of front only")
    args = parser.parse_args(argv)
    for kind, ws, objectives in cases():
        if args.only is None or args.only == kind:
            print(json.dumps(time_case(kind, ws, objectives, args.repeats)), flush=True)


if __name__ == "__main__":
    main()
