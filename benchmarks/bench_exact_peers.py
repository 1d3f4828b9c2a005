"""gapath's exact free fronts side by side with the published C solvers.

Builds the C anchors in ``../shared/peers`` (BOA* of Hernandez et al. for two
objectives, LT-MOA*v of Hernandez Ulloa et al. with AVX-512 for three) with
their ``build.sh`` into a temporary directory, converts each workspace with
their ``convert.py`` (integer costs: 10000 / 14142 per step, potential times
a scale, 7854 per eighth turn), runs both on the same queries and prints one
JSON line per query:

    map, query (``.scen`` line), objectives, gapath_ms (median wall of
    ``--repeats`` calls of :func:`gapath.planners.exact.free_front` after a
    warm-up call that also compiles), gapath_cpu_ms (the same calls' thread
    CPU time: on a loaded machine a run of tens of milliseconds is preempted
    while the C program's few milliseconds mostly are not), c_ms (median of
    the C program's own wall runtime, which includes its backward Dijkstra
    heuristics and excludes reading the graph), ratio = gapath_ms / c_ms,
    ratio_cpu = gapath_cpu_ms / c_ms, ratio_min = gapath_cpu_ms_min / c_ms_min
    (the least of the repeats on both sides: the figure least moved by other
    load on a shared machine), the front sizes, the
    expansions of both, and hv = HV(C front) / HV(gapath front), both
    normalised by gapath's front (reference point 1.1): integer rounding
    merges near-ties, so the sizes may differ while hv is 1.0.

With ``--same-costs`` (two objectives) gapath also solves the problem the C
program solves: the workspace's potential replaced by the converter's
integer costs, ``rint(P * s2) / s2`` (so that vulnerabilities the peers'
rounding makes equal are equal within SPEC's tolerance in gapath too, and
distinct ones differ by at least ``1 / s2``); the line then has
``*_same`` fields beside the native ones (``gapath_ms_same``,
``gapath_cpu_ms_same``, ``ratio_same``, ``ratio_cpu_same``,
``gapath_points_same``, ``gapath_expansions_same``, ``hv_same``). The native
ratio is the one the issue's target is about (gapath on SPEC's problem); the
same-costs ratio separates the implementations' speed from the problem's size
(the front and the expansions). Lengths stay gapath's (sqrt(2) per diagonal
step against the converter's 14142 / 10000): they order paths differently
only when their diagonal counts differ by dozens, which front points rarely do.

A last line ``{"summary": ...}`` gives the median and range of the ratios per
map and objective count (and of the same-costs ratios).

What the C time covers (read from the patched sources, ``call_boastar``):
its timer starts after the graph is read and its adjacency tables are
built, and stops when the search ends; inside are the two backward
Dijkstra passes and BOA*, not the solution paths (the patch writes them
after the timer). gapath's time is the whole :func:`free_front` call: the
move masks (its adjacency), both heuristic passes, the search, the paths,
the tolerance filter and the result object. So gapath's figure includes a
little more than the C one (the masks, the paths, the Python call). Skips (a JSON line with ``"skip"``) where gcc or,
for three objectives, AVX-512 is missing.

Usage::

    python benchmarks/bench_exact_peers.py [--repeats 3] [--queries 5] [--objectives 2,3]
        [--maps room-32-32-4,maze-32-32-2,...] [--tie-break smoothest|none] [--same-costs] [--quick]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from gapath.loaders import load_movingai, load_scenarios
from gapath.metrics import hv_ratio
from gapath.planners.exact import free_front

SHARED = Path(os.environ.get("GAPATH_SHARED", Path(__file__).resolve().parents[2] / "shared"))
PEERS = SHARED / "peers"
MAPF = SHARED / "data" / "movingai" / "mapf"
MAPS2 = ("room-32-32-4", "maze-32-32-2", "random-64-64-10", "den312d", "Berlin_1_256")
MAPS3 = ("room-32-32-4", "maze-32-32-2", "random-64-64-10", "den312d")
LV = ("length", "vulnerability")
LVS = ("length", "vulnerability", "smoothness")


def emit(**row):
    print(json.dumps(row), flush=True)


def has_avx512() -> bool:
    try:
        return "avx512f" in Path("/proc/cpuinfo").read_text()
    except OSError:
        return False


def build(out: Path) -> dict:
    """Build the peers into ``out``; returns the paths of the programs."""
    proc = subprocess.run(["bash", str(PEERS / "build.sh"), str(out)], capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"build.sh failed: {proc.stderr[-2000:]}")
    return {"boa": out / "boa" / "boa", "moa": out / "moa" / "moastarv"}


def queries(name: str, k: int) -> list:
    """``k`` .scen lines spread evenly over the file (later lines are longer)."""
    scen = load_scenarios(MAPF / f"{name}-random-1.scen")
    idx = np.unique(np.linspace(0, len(scen) - 1, k).round().astype(int))
    return [(int(i), scen[i]) for i in idx]


def run_gapath(ws, objectives, repeats, tie_break):
    """Median wall, median and least thread-CPU milliseconds of ``repeats``
    calls, and the front."""
    free_front(ws, objectives, tie_break=tie_break)  # warm-up (and numba compilation)
    wall, cpu, front = [], [], None
    for _ in range(repeats):
        t, c = time.perf_counter(), time.thread_time()
        front = free_front(ws, objectives, tie_break=tie_break)
        wall.append(time.perf_counter() - t)
        cpu.append(time.thread_time() - c)
    return statistics.median(wall) * 1e3, statistics.median(cpu) * 1e3, min(cpu) * 1e3, front


def run_c(prog, graph, info, n_obj, repeats, tmp):
    """Median and least C runtime (ms, as the program reports it), its front
    and expansions."""
    sol = tmp / "solutions.txt"
    env = dict(os.environ, PEER_OUT=str(sol))
    args = [str(prog), str(graph), str(info["start"]), str(info["goal"])]
    if n_obj == 3:
        args.append("3")
    times, fields = [], []
    for _ in range(repeats):
        proc = subprocess.run(args, capture_output=True, text=True, env=env, timeout=3600)
        if proc.returncode != 0:
            raise RuntimeError(f"{prog.name} exited {proc.returncode}: {proc.stderr[-500:]}")
        fields = proc.stdout.strip().splitlines()[-1].replace(":", ";").split(";")
        times.append(float(fields[3]))
    import convert  # noqa: E402  (the peers' converter, on sys.path)

    F = []
    for line in sol.read_text().split("\n"):
        parts = line.split()
        if not parts:
            continue
        c = [int(x) for x in parts[:n_obj]]
        ns, nd = convert.decode_length(c[0])
        row = [ns + np.sqrt(2.0) * nd, c[1] / info["s2"] + info["p_start"]]
        if n_obj == 3:
            row.append(c[2] / convert.TURN_UNIT * np.pi / 4)
        F.append(row)
    expanded = int(fields[5]) if n_obj == 2 else None
    return statistics.median(times), min(times), np.array(F), expanded


def same_costs(map_path, sc, s2):
    """The query's workspace with the potential the converter gives the C
    program: ``rint(P * s2) / s2`` (its cost2 per cell, back in gapath's
    units)."""
    ws = load_movingai(map_path, sc.start, sc.goal, corner_cutting=False)
    pot = np.rint(np.asarray(ws.potential, dtype=np.float64) * s2) / s2
    pot.setflags(write=False)
    ws.__dict__["potential"] = pot  # the cached property, replaced
    return ws


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--queries", type=int, default=5, help="queries per map (.scen lines)")
    ap.add_argument("--objectives", default="2,3")
    ap.add_argument("--maps", default=None, help="comma-separated map names (default: all)")
    ap.add_argument(
        "--tie-break",
        default="smoothest",
        choices=("smoothest", "none"),
        help="gapath's tie_break for two objectives (default: %(default)s)",
    )
    ap.add_argument(
        "--same-costs",
        action="store_true",
        help="two objectives: also time gapath on the converter's integer-rounded potential (ratio_same)",
    )
    ap.add_argument("--quick", action="store_true", help="2 queries per map, 1 repeat")
    args = ap.parse_args(argv)
    if args.quick:
        args.queries, args.repeats = 2, 1
    if shutil.which("gcc") is None:
        emit(skip="gcc not found: the C peers cannot be built")
        return 0
    if not (PEERS / "build.sh").is_file() or not MAPF.is_dir():
        emit(skip=f"peers or MovingAI maps missing under {SHARED}")
        return 0
    sys.path.insert(0, str(PEERS))
    import convert

    counts = [int(x) for x in args.objectives.split(",")]
    if 3 in counts and not has_avx512():
        emit(skip="no AVX-512 on this CPU: LT-MOA*v (three objectives) skipped")
        counts = [c for c in counts if c != 3]
    wanted = args.maps.split(",") if args.maps else None
    ratios, ratios_cpu, ratios_min, same, same_cpu, same_min = {}, {}, {}, {}, {}, {}
    with tempfile.TemporaryDirectory(prefix="gapath-peers-") as tmpname:
        tmp = Path(tmpname)
        progs = build(tmp / "build")
        for n_obj in counts:
            objectives = LV if n_obj == 2 else LVS
            for name in MAPS2 if n_obj == 2 else MAPS3:
                if wanted and name not in wanted:
                    continue
                for qi, sc in queries(name, args.queries):
                    ws = load_movingai(MAPF / f"{name}.map", sc.start, sc.goal, corner_cutting=False)
                    s2 = convert.choose_s2(ws, n_obj)[0]
                    graph = tmp / "graph.txt"
                    info = (convert.graph2 if n_obj == 2 else convert.graph3)(ws, graph, s2)
                    g_ms, g_cpu, g_min, front = run_gapath(ws, objectives, args.repeats, args.tie_break)
                    prog = progs["boa" if n_obj == 2 else "moa"]
                    c_ms, c_min, cF, c_exp = run_c(prog, graph, info, n_obj, args.repeats, tmp)
                    ratio = g_ms / max(c_ms, 1e-3)
                    ratios.setdefault(f"{name}/{n_obj}", []).append(ratio)
                    ratios_cpu.setdefault(f"{name}/{n_obj}", []).append(g_cpu / max(c_ms, 1e-3))
                    ratios_min.setdefault(f"{name}/{n_obj}", []).append(g_min / max(c_min, 1e-3))
                    extra = {}
                    if args.same_costs and n_obj == 2:
                        wq = same_costs(MAPF / f"{name}.map", sc, s2)
                        q_ms, q_cpu, q_min, qfront = run_gapath(wq, objectives, args.repeats, args.tie_break)
                        same.setdefault(f"{name}/{n_obj}", []).append(q_ms / max(c_ms, 1e-3))
                        same_cpu.setdefault(f"{name}/{n_obj}", []).append(q_cpu / max(c_ms, 1e-3))
                        same_min.setdefault(f"{name}/{n_obj}", []).append(q_min / max(c_min, 1e-3))
                        extra = dict(
                            gapath_ms_same=round(q_ms, 3),
                            gapath_cpu_ms_same=round(q_cpu, 3),
                            ratio_same=round(q_ms / max(c_ms, 1e-3), 2),
                            ratio_cpu_same=round(q_cpu / max(c_ms, 1e-3), 2),
                            gapath_cpu_ms_min_same=round(q_min, 3),
                            ratio_min_same=round(q_min / max(c_min, 1e-3), 2),
                            gapath_points_same=len(qfront),
                            gapath_expansions_same=qfront.stats["expansions"],
                            hv_same=round(hv_ratio(cF, qfront.F), 6),
                            s2=s2,
                        )
                    emit(
                        map=name,
                        query=qi,
                        objectives=n_obj,
                        gapath_ms=round(g_ms, 3),
                        gapath_cpu_ms=round(g_cpu, 3),
                        c_ms=round(c_ms, 3),
                        ratio=round(ratio, 2),
                        ratio_cpu=round(g_cpu / max(c_ms, 1e-3), 2),
                        gapath_cpu_ms_min=round(g_min, 3),
                        c_ms_min=round(c_min, 3),
                        ratio_min=round(g_min / max(c_min, 1e-3), 2),
                        gapath_points=len(front),
                        c_points=len(cF),
                        hv=round(hv_ratio(cF, front.F), 6),
                        gapath_expansions=front.stats["expansions"],
                        c_expansions=c_exp,
                        tie_edges=front.stats.get("tie_edges"),
                        peak_mb=round(front.stats["peak_bytes"] / 1e6, 2),
                        c_solver="BOA*" if n_obj == 2 else "LT-MOA*v",
                        tie_break=args.tie_break if n_obj == 2 else None,
                        **extra,
                    )

    def spread(v):
        return {
            "median": round(statistics.median(v), 2),
            "min": round(min(v), 2),
            "max": round(max(v), 2),
            "queries": len(v),
        }

    summary = {
        k: {"wall": spread(v), "cpu": spread(ratios_cpu[k]), "min": spread(ratios_min[k])}
        for k, v in ratios.items()
    }
    for k, v in same.items():
        summary[k]["wall_same"] = spread(v)
        summary[k]["cpu_same"] = spread(same_cpu[k])
        summary[k]["min_same"] = spread(same_min[k])
    emit(summary=summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
