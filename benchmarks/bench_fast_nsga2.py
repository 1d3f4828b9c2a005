"""FastNSGA2 against pymoo's NSGA2 with gapath's operators, as JSON lines.

1. ``fast_nsga2.speed``: pop 500 x 500 generations on the bundled scenario
   (seed 1), stock pymoo NSGA2 with gapath's operators (``paper_nsga2``) and
   ``FastNSGA2`` run alternately ``--repeats`` times in one process after a
   warm-up: median wall-clock and CPU (``process_time``, i.e. one core)
   seconds, the speed-ups, and whether both returned the same population.
2. ``fast_nsga2.fig3``: the seeds' Fig. 3 protocol (10 runs x pop 500 x 500
   generations, integer encoding, seeds 1..10) with FastNSGA2.
3. ``fast_nsga2.breakdown``: FastNSGA2's time per generation by phase
   (thread CPU time, median over the Fig. 3 runs); ``pymoo_and_glue`` is the
   rest of the run's CPU time (termination, callbacks, array merging, the
   final ``Result``).
4. ``fast_nsga2.equivalence``: over 20 seeds on the bundled scenario and on
   two MovingAI 32x32 maps, the HV ratio of each engine's final front
   against the exact column-monotone front: median, quartiles, a one-sided
   Mann-Whitney U test (H1: FastNSGA2's ratios are stochastically smaller),
   and how many runs returned bit-identical populations. MovingAI start and
   goal: the first line of the map's ``-random-1.scen`` whose start and goal
   are at least 16 columns apart and joined by a feasible monotone path.

The machine is shared (2 cores): timings are medians of repeats; the load
average is printed with every record. CPU time is less affected by other
processes than wall-clock time.

Usage: python benchmarks/bench_fast_nsga2.py [--quick] [--repeats N]
       [--parts speed,fig3,equivalence] [--study-pop P] [--study-gens G] [--study-seeds S]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np
from pymoo.optimize import minimize
from scipy.stats import mannwhitneyu

from gapath import default_workspace
from gapath.algorithms import FastNSGA2, paper_nsga2
from gapath.algorithms.fast_nsga2 import PHASES
from gapath.errors import NoPathError
from gapath.front import path_front
from gapath.loaders import load_movingai, load_scenarios
from gapath.metrics import hv_ratio
from gapath.planners.exact import monotone_front
from gapath.problems import GridPathProblem

MOVINGAI = Path(__file__).resolve().parents[2] / "shared" / "data" / "movingai" / "mapf"
MAPS = ("random-32-32-10", "room-32-32-4")


def emit(**record):
    record.setdefault(
        "machine", f"{platform.machine()} {os.cpu_count()} cpu, python {platform.python_version()}"
    )
    record["load_avg_1min"] = round(os.getloadavg()[0], 2)
    print(json.dumps(record), flush=True)


def timed_run(problem, algorithm, n_gen, seed):
    """(result, wall seconds, CPU seconds) of one ``minimize``."""
    w, c = time.perf_counter(), time.process_time()
    res = minimize(problem, algorithm, ("n_gen", n_gen), seed=seed)
    return res, time.perf_counter() - w, time.process_time() - c


def fast(pop_size):
    alg = FastNSGA2(pop_size)
    alg.clock = time.thread_time  # phase timings in CPU time
    return alg


def movingai_workspace(name):
    """The map with the first scenario whose start and goal are >= 16
    columns apart and joined by a feasible monotone path."""
    scen_file = MOVINGAI / f"{name}-random-1.scen"
    for sc in load_scenarios(scen_file):
        if abs(sc.start[1] - sc.goal[1]) < 16:
            continue
        # corner_cutting=True: the rule these figures were recorded with (before
        # MovingAI maps defaulted to MovingAI's own rule)
        ws = load_movingai(sc.resolve_map(), sc.start, sc.goal, corner_cutting=True)
        try:
            return ws, monotone_front(ws), sc.line
        except NoPathError:
            continue
    raise SystemExit(f"no usable scenario in {scen_file}")


def speed(args, problem):
    n_gen = 60 if args.quick else 500
    minimize(problem, paper_nsga2(500), ("n_gen", 3), seed=1)  # warm-up (and numba caches)
    minimize(problem, fast(500), ("n_gen", 3), seed=1)
    stock_w, stock_c, fast_w, fast_c, same = [], [], [], [], []
    for _ in range(args.repeats):
        a, w, c = timed_run(problem, paper_nsga2(500), n_gen, 1)
        stock_w.append(w)
        stock_c.append(c)
        b, w, c = timed_run(problem, fast(500), n_gen, 1)
        fast_w.append(w)
        fast_c.append(c)
        same.append(bool(np.array_equal(a.pop.get("X"), b.pop.get("X"))))
    sw, sc, fw, fc = (float(np.median(v)) for v in (stock_w, stock_c, fast_w, fast_c))
    emit(
        bench="fast_nsga2.speed",
        map=problem.workspace.name,
        pop=500,
        n_gen=n_gen,
        repeats=args.repeats,
        paper_nsga2_wall_s=round(sw, 2),
        paper_nsga2_cpu_s=round(sc, 2),
        fast_nsga2_wall_s=round(fw, 3),
        fast_nsga2_cpu_s=round(fc, 3),
        fast_nsga2_wall_runs_s=[round(v, 3) for v in fast_w],
        fast_nsga2_cpu_runs_s=[round(v, 3) for v in fast_c],
        speedup_wall=round(sw / fw, 1),
        speedup_cpu=round(sc / fc, 1),
        paper_nsga2_ms_per_gen=round(1e3 * sc / n_gen, 2),
        fast_nsga2_ms_per_gen=round(1e3 * fc / n_gen, 2),
        identical_populations=all(same),
        target_speedup=15,
        target_fast_nsga2_s=2.0 * n_gen / 500,
    )


def fig3(args, problem):
    n_runs, n_gen = (3, 60) if args.quick else (10, 500)
    wall = cpu = 0.0
    per_gen = {k: [] for k in PHASES}
    rest = []
    for seed in range(1, n_runs + 1):
        res, w, c = timed_run(problem, fast(500), n_gen, seed)
        wall, cpu = wall + w, cpu + c
        t = res.algorithm.timings
        for k in PHASES:
            per_gen[k].append(1e3 * t[k] / n_gen)
        rest.append(1e3 * (c - sum(t.values())) / n_gen)
    emit(
        bench="fast_nsga2.fig3",
        map=problem.workspace.name,
        runs=n_runs,
        pop=500,
        n_gen=n_gen,
        seeds=list(range(1, n_runs + 1)),
        wall_s=round(wall, 2),
        cpu_s=round(cpu, 2),
        target_s=20.0 * n_runs * n_gen / 5000,
    )
    phases = {k: round(float(np.median(v)), 3) for k, v in per_gen.items()}
    total = sum(phases.values()) + float(np.median(rest))
    emit(
        bench="fast_nsga2.breakdown",
        map=problem.workspace.name,
        pop=500,
        n_gen=n_gen,
        clock="thread CPU time, median over runs",
        ms_per_gen=phases,
        pymoo_and_glue_ms_per_gen=round(float(np.median(rest)), 3),
        total_ms_per_gen=round(total, 3),
        floor_target_ms_per_gen=[1, 2],
    )


def equivalence(args):
    n_seeds = 5 if args.quick else args.study_seeds
    pop, n_gen = (100, 30) if args.quick else (args.study_pop, args.study_gens)
    ws0 = default_workspace()
    cases = [(ws0.name, ws0, monotone_front(ws0), None)]
    for name in MAPS:
        ws, exact, line = movingai_workspace(name)
        cases.append((name, ws, exact, line))
    for name, ws, exact, line in cases:
        problem = GridPathProblem(ws)
        ratios = {"paper_nsga2": [], "fast_nsga2": []}
        identical = 0
        for seed in range(1, n_seeds + 1):
            a = minimize(problem, paper_nsga2(pop), ("n_gen", n_gen), seed=seed)
            b = minimize(problem, FastNSGA2(pop), ("n_gen", n_gen), seed=seed)
            for key, res in (("paper_nsga2", a), ("fast_nsga2", b)):
                ratios[key].append(hv_ratio(path_front(problem, res.pop.get("X")).F, exact.F))
            identical += bool(np.array_equal(a.pop.get("X"), b.pop.get("X")))
        stats = {
            k: dict(
                median=round(float(np.median(v)), 6),
                q1=round(float(np.quantile(v, 0.25)), 6),
                q3=round(float(np.quantile(v, 0.75)), 6),
            )
            for k, v in ratios.items()
        }
        test = mannwhitneyu(ratios["fast_nsga2"], ratios["paper_nsga2"], alternative="less")
        emit(
            bench="fast_nsga2.equivalence",
            map=name,
            scen_line=line,
            start=list(ws.start),
            goal=list(ws.goal),
            exact_front_size=len(exact.F),
            seeds=n_seeds,
            pop=pop,
            n_gen=n_gen,
            hv_ratio=stats,
            identical_populations=f"{identical}/{n_seeds}",
            mannwhitney_u=float(test.statistic),
            p_fast_worse=round(float(test.pvalue), 4),
            fast_not_worse=bool(test.pvalue > 0.05),
        )


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small budgets")
    ap.add_argument("--repeats", type=int, default=3, help="speed runs per engine (default 3)")
    ap.add_argument(
        "--parts", default="speed,fig3,equivalence", help="comma-separated parts to run (default all)"
    )
    ap.add_argument("--study-pop", type=int, default=200, help="equivalence study pop size")
    ap.add_argument("--study-gens", type=int, default=200, help="equivalence study generations")
    ap.add_argument("--study-seeds", type=int, default=20, help="equivalence study seeds")
    args = ap.parse_args()
    if args.quick:
        args.repeats = 1
    parts = {p.strip() for p in args.parts.split(",")}
    problem = GridPathProblem(default_workspace())
    if "speed" in parts:
        speed(args, problem)
    if "fig3" in parts:
        fig3(args, problem)
    if "equivalence" in parts:
        equivalence(args)


if __name__ == "__main__":
    sys.exit(main())
