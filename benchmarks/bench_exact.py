"""Timings of the exact monotone front (gapath.planners.exact.monotone_front).

Prints one JSON line per case: map, size, objectives, corner_cutting,
seconds (median of ``--repeats`` runs after one warm-up run that also
triggers the JIT compilation), runs, front_size.

Usage::

    python benchmarks/bench_exact.py [--repeats 5]

Targets (2 objectives, after warm-up): 32x32 with ~17 % obstacles <= 0.2 s,
128x128 <= 5 s.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

from gapath.planners.exact import monotone_front
from gapath.workspace import random_workspace

LV = ("length", "vulnerability")
LVS = ("length", "vulnerability", "smoothness")


def default_scenario():
    """The bundled default scenario, or its recipe when the map loader is
    not available."""
    try:
        from gapath.workspace import default_workspace

        return default_workspace()
    except ImportError:
        return random_workspace((32, 32), 173, seed=2013, name="default-32x32-173(recipe)")


def cases():
    default = default_scenario()
    big = random_workspace((128, 128), int(0.17 * 128 * 128), seed=1)
    return [
        (default, LV),
        (default, ("length", "smoothness")),
        (default, LVS),
        (default.replace(corner_cutting=False), LV),
        (big, LV),
    ]


def time_case(ws, objectives, repeats):
    front = monotone_front(ws, objectives)  # warm-up (and JIT)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        front = monotone_front(ws, objectives)
        times.append(time.perf_counter() - t0)
    h, w = ws.shape
    return {
        "map": ws.name,
        "size": f"{h}x{w}",
        "objectives": list(objectives),
        "corner_cutting": ws.corner_cutting,
        "seconds": round(statistics.median(times), 5),
        "runs": repeats,
        "front_size": len(front),
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="timed runs per case (default 5)")
    args = parser.parse_args(argv)
    for ws, objectives in cases():
        print(json.dumps(time_case(ws, objectives, args.repeats)), flush=True)


if __name__ == "__main__":
    main()
