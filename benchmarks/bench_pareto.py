"""Timings of the costmap planners (gapath.planners.pareto), as JSON lines.

On ``--maps`` random 100x100 workspaces of the Mars study
(gapath.studies.mars: ~23 % obstacles of three sizes, Mars DTM
elevation, one risk cell, solar vector turning 1 rad per step) and the four
objectives F1..F4, for every planner (weighted-sum A* and D* Lite, A*-PO,
D*-PO):

* ``plan``: one plan from scratch (costmap model, search, objectives
  recomputed on the path), median of ``--repeats`` runs after a warm-up;
* ``replan`` (D* planners): 5 cells of the current path are blocked, then
  ``replan()``; median over the repeats (each on a fresh planner);
* one line per (map, planner) and one summary line per planner with the
  median and maximum over the maps of the per-map medians.

Wall-clock ``time.perf_counter`` and CPU ``time.process_time`` are both
reported: the machine has 2 shared cores, wall times are noisy.

Target: D*-PO on a 100x100 workspace with four objectives <= 50 ms per plan.

Usage: python benchmarks/bench_pareto.py [--maps 20] [--repeats 5] [--quick]
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import time

import numpy as np

from gapath.planners.pareto import PLANNERS, DStarPO, WeightedSumDStar, plan
from gapath.studies.mars import OBJECTIVES, mars_costmap, mars_workspace

DSTAR = {"dstar-po": DStarPO, "dstar-lite": WeightedSumDStar}


def timed(fn):
    w0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w0, time.process_time() - c0


def bench_map(cm, name, repeats):
    res = plan(cm, name, OBJECTIVES)  # warm-up (and JIT)
    walls, cpus = [], []
    for _ in range(repeats):
        res, w, c = timed(lambda: plan(cm, name, OBJECTIVES))
        walls.append(w)
        cpus.append(c)
    rec = {
        "planner": name,
        "plan_ms": 1000 * statistics.median(walls),
        "plan_cpu_ms": 1000 * statistics.median(cpus),
        "expansions": res.expansions,
        "F": [round(float(v), 6) for v in res.F],
    }
    if name in DSTAR:
        walls, cpus = [], []
        for _ in range(repeats):
            planner = DSTAR[name](cm, OBJECTIVES)
            path = planner.plan().path
            mid = len(path) // 2
            cells = [tuple(c) for c in path[mid - 2 : mid + 3]]
            planner.update_cells(cells, blocked=True)
            try:
                _, w, c = timed(planner.replan)
            except Exception:  # goal cut off: not timed
                continue
            walls.append(w)
            cpus.append(c)
        if walls:
            rec["replan_ms"] = 1000 * statistics.median(walls)
            rec["replan_cpu_ms"] = 1000 * statistics.median(cpus)
    return rec


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--maps", type=int, default=20)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--seed", type=int, default=2015)
    ap.add_argument("--quick", action="store_true", help="3 maps, 3 repeats")
    args = ap.parse_args(argv)
    if args.quick:
        args.maps, args.repeats = 3, 3
    per = {name: [] for name in PLANNERS}
    for i in range(args.maps):
        seed = args.seed * 1000 + i
        ws = mars_workspace(seed)
        cm = mars_costmap(ws, seed)
        for name in PLANNERS:
            rec = bench_map(cm, name, args.repeats)
            per[name].append(rec)
            print(
                json.dumps(
                    {
                        "bench": "pareto_plan",
                        "map": ws.name,
                        "shape": list(ws.shape),
                        "obstacles": ws.n_obstacles,
                        "objectives": list(OBJECTIVES),
                        "repeats": args.repeats,
                        **rec,
                    }
                ),
                flush=True,
            )
    for name, recs in per.items():
        out = {
            "bench": "pareto_summary",
            "planner": name,
            "maps": len(recs),
            "shape": [100, 100],
            "objectives": list(OBJECTIVES),
            "repeats": args.repeats,
            "machine": f"{platform.machine()} {platform.python_version()}, 2 shared cores",
        }
        for key in ("plan_ms", "plan_cpu_ms", "replan_ms", "replan_cpu_ms", "expansions"):
            vals = [r[key] for r in recs if key in r]
            if vals:
                out[f"{key}_median"] = float(np.median(vals))
                out[f"{key}_max"] = float(np.max(vals))
        if name == "dstar-po":
            out["target_plan_ms"] = 50.0
            out["maps_within_target"] = int(sum(r["plan_ms"] <= 50.0 for r in recs))
        print(json.dumps(out), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
