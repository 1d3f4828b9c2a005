"""k-objective exact fronts (``free_front`` with costmap layers, issue 15
item 2): the Mars study's objectives in additive form on its 100x100 maps,
and three objectives against the specialised (length, vulnerability,
smoothness) search.

Prints one JSON line per run: map, objectives, solver, CPU seconds (thread
time of the call, after a warm-up call on a small map), wall seconds, front
size, expansions, labels, peak bytes of the search arrays; ``status`` is
``ok`` or the error (``LabelBudgetError`` when ``--max-labels`` is reached).

    python benchmarks/bench_exact_k.py --part mars --maps 3
    python benchmarks/bench_exact_k.py --part mars --sets LESR0 --sizes 30,40,50,60 --maps 3 --max-seconds 120
    python benchmarks/bench_exact_k.py --part three --size 64 --queries 3

Sets of the ``mars`` part (the study's workspaces and costmaps,
:func:`gapath.studies.mars.study_workspace`):

* ``LER``: length, elevation_sum, risk_sum;
* ``LESR0``: length, elevation_sum, solar, risk_sum with ``solar_rate=0``
  (the solar cost depends on the step direction only);
* ``LESR``: the same at the study's ``solar_rate=1`` (the step index is part
  of the state, the solar bound is per (step index, cell); under
  ``--max-labels``).

The ``mars`` lines also carry the set counters of ``ExactFront.stats``:
members tested (``state_tests``, ``goal_tests``), kd-tree nodes visited
(``state_nodes``, ``goal_nodes``, ``drop_nodes``) and members written by tree
builds (``built``).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from gapath import random_workspace
from gapath.errors import GapathError
from gapath.planners.exact import free_front

MARS_SETS = {
    "LER": (("length", "elevation_sum", "risk_sum"), 1.0),
    "LESR0": (("length", "elevation_sum", "solar", "risk_sum"), 0.0),
    "LESR": (("length", "elevation_sum", "solar", "risk_sum"), 1.0),
}
LVS = ("length", "vulnerability", "smoothness")
#: ``--reference``: the k-objective search before its contiguous sets
#: (tests/_multi_reference.py, linked lists scanned linearly), for before/after figures.
REFERENCE = None


class _TimeUp(Exception):
    pass


def _run(ws, names, cm=None, search="auto", max_labels=None, max_seconds=None):
    t0, c0 = time.perf_counter(), time.thread_time()
    last = {}

    def progress(p):
        last.update(p)
        if max_seconds is not None and time.thread_time() - c0 > max_seconds:
            raise _TimeUp

    try:
        if REFERENCE and cm is not None:
            front = REFERENCE(ws, names, costmap=cm, max_labels=max_labels, progress=progress)
        else:
            front = free_front(ws, names, costmap=cm, search=search, max_labels=max_labels, progress=progress)
    except _TimeUp:
        return {
            "status": f"not finished in {max_seconds:g} s CPU",
            "cpu_s": round(time.thread_time() - c0, 4),
            "wall_s": round(time.perf_counter() - t0, 4),
            **{k: last[k] for k in ("expansions", "generated", "labels", "solutions") if k in last},
        }
    except GapathError as exc:
        return {
            "status": type(exc).__name__,
            "cpu_s": round(time.thread_time() - c0, 4),
            "wall_s": round(time.perf_counter() - t0, 4),
            **{
                k: v
                for k, v in getattr(exc, "stats", {}).items()
                if k in ("expansions", "labels", "solutions")
            },
        }
    st = front.stats
    return {
        "status": "ok",
        "cpu_s": round(time.thread_time() - c0, 4),
        "wall_s": round(time.perf_counter() - t0, 4),
        "front": len(front),
        "expansions": st["expansions"],
        "labels": st["labels"],
        "peak_mb": round(st["peak_bytes"] / 2**20, 1),
        **{
            k: st[k]
            for k in (
                "generated",
                "state_tests",
                "goal_tests",
                "state_nodes",
                "goal_nodes",
                "drop_nodes",
                "built",
                "set_sizes",
            )
            if k in st
        },
    }


def _warm_up():
    """Compile the kernels on tiny maps (a timed-solar front grows fast with
    the map: 8x8 and a budget)."""
    from gapath.studies.mars import study_workspace

    for rate in (0.0, 1.0):
        ws, cm = study_workspace(0, size=8, solar_rate=rate)
        for fn in (free_front, REFERENCE) if REFERENCE else (free_front,):
            try:
                fn(ws, MARS_SETS["LESR0"][0], costmap=cm, max_labels=10**5)
            except GapathError:
                pass
    ws = random_workspace((8, 8), 6, seed=0)
    free_front(ws, LVS, search="k")
    free_front(ws, LVS)


def mars(args):
    from gapath.studies.mars import study_workspace

    sizes = [int(v) for v in args.sizes.split(",")] if args.sizes else [args.size]
    for size in sizes:
        for i in range(args.first, args.first + args.maps):
            for key in args.sets.split(","):
                names, rate = MARS_SETS[key]
                ws, cm = study_workspace(i, size=size, solar_rate=rate)
                budget = args.max_labels if key == "LESR" else None
                rec = {
                    "part": "mars",
                    "solver": "reference (linked lists)" if REFERENCE else "k-objective",
                    "map": ws.name,
                    "size": size,
                    "workspace": i,
                    "set": key,
                    "objectives": list(names),
                    "solar_rate": rate,
                }
                rec.update(_run(ws, names, cm, max_labels=budget, max_seconds=args.max_seconds))
                print(json.dumps(rec), flush=True)


def three(args):
    for q in range(args.queries):
        n = args.size
        ws = random_workspace((n, n), int(0.1 * n * n), seed=q)
        for search in ("auto", "k"):
            rec = {"part": "three", "map": ws.name, "objectives": list(LVS), "search": search}
            rec["solver"] = "MODE_THREE" if search == "auto" else "k-objective"
            rec.update(_run(ws, LVS, search=search, max_labels=args.max_labels))
            print(json.dumps(rec), flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", choices=("mars", "three"), default="mars")
    ap.add_argument("--maps", type=int, default=3, help="mars: workspaces 0 .. maps-1 (after --first)")
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument(
        "--sets", default="LER,LESR0,LESR", help="mars: comma-separated of " + ",".join(MARS_SETS)
    )
    ap.add_argument("--size", type=int, default=None, help="grid side (mars: 100, three: 64)")
    ap.add_argument("--sizes", default=None, help="mars: comma-separated grid sides (instead of --size)")
    ap.add_argument(
        "--max-seconds", type=float, default=None, help="mars: stop a run after this much CPU (reported)"
    )
    ap.add_argument("--queries", type=int, default=3, help="three: random maps (10 %% obstacles), seeds 0..")
    ap.add_argument("--max-labels", type=int, default=20_000_000, help="budget of the timed-solar runs")
    ap.add_argument(
        "--reference",
        action="store_true",
        help="mars: run the previous k-objective search (tests/_multi_reference.py) instead",
    )
    args = ap.parse_args()
    if args.reference:
        global REFERENCE
        sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
        from _multi_reference import multi_front

        REFERENCE = multi_front
    if args.size is None:
        args.size = 100 if args.part == "mars" else 64
    _warm_up()
    (mars if args.part == "mars" else three)(args)


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
