"""The two-objective BOA* kernels against their previous version, paired.

Times, in one process and alternating call by call, the heuristics and the
search of :mod:`gapath.planners._boa_kernels` (``_boa_prepare`` then
``_boa_solve``: what :func:`gapath.planners.exact.free_front` spends on two
objectives, less its Python) and the same two calls of the verbatim copy of
the previous kernels in ``tests/_boa_reference.py``, on MovingAI queries
(``corner_cutting=False``, the smoothest tie-break). Thread CPU time; on a
shared machine the least of ``--repeats`` calls and the median of the paired
ratios are the figures least moved by other load. Checks that both give the
same front (F, smoothness, paths) and prints one JSON line per query: map,
query (``.scen`` line), expansions, points, ``ref_ms`` and ``new_ms`` (least
CPU), ``ratio_min`` (new / ref of the least) and ``ratio_paired`` (median of
the per-call ratios).

Usage::

    python benchmarks/bench_boa_kernels.py [--repeats 11] [--queries den312d:749,Berlin_1_256:999]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

from gapath.loaders import load_movingai, load_scenarios
from gapath.planners import _boa_kernels as K

ROOT = Path(__file__).resolve().parents[1]
SHARED = Path(os.environ.get("GAPATH_SHARED", ROOT.parent / "shared"))
MAPF = SHARED / "data" / "movingai" / "mapf"
DEFAULT = (
    "room-32-32-4:85,maze-32-32-2:166,random-64-64-10:999,den312d:0,den312d:749,"
    "Berlin_1_256:0,Berlin_1_256:749,Berlin_1_256:999"
)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=11)
    ap.add_argument("--queries", default=DEFAULT, help="map:line,... (.scen lines)")
    args = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT / "tests"))
    import _boa_reference as R

    for item in args.queries.split(","):
        name, line = item.split(":")
        sc = load_scenarios(MAPF / f"{name}-random-1.scen")[int(line)]
        ws = load_movingai(MAPF / f"{name}.map", sc.start, sc.goal, corner_cutting=False)
        occ = np.ascontiguousarray(ws.occ)
        pot = np.ascontiguousarray(ws.potential, dtype=np.float64)
        (sr, sc_), (gr, gc) = ws.start, ws.goal
        times = {"ref": [], "new": []}
        out = {}
        for _ in range(args.repeats + 1):  # the first call of each: warm-up (and compilation)
            for tag, M in (("ref", R), ("new", K)):
                t = time.thread_time()
                mask, hs, hd, hv = M._boa_prepare(occ, pot, gr, gc, False)
                res = M._boa_solve(
                    occ, pot, sr, sc_, gr, gc, 1.0, mask, hs, hd, hv, True, True, 1 << 60, 1 << 60
                )
                times[tag].append(time.thread_time() - t)
                out[tag] = res[1]
        ref, new = np.array(times["ref"][1:]), np.array(times["new"][1:])
        same = all(np.array_equal(a, b) for a, b in zip(out["ref"][:4], out["new"][:4]))
        print(
            json.dumps(
                dict(
                    map=name,
                    query=int(line),
                    expansions=int(out["new"][4][K.C_EXPANDED]),
                    points=len(out["new"][0]),
                    ref_ms=round(ref.min() * 1e3, 3),
                    new_ms=round(new.min() * 1e3, 3),
                    ratio_min=round(new.min() / ref.min(), 3),
                    ratio_paired=round(float(np.median(new / ref)), 3),
                    same_front=bool(same),
                    load=round(os.getloadavg()[0], 1),
                )
            ),
            flush=True,
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
