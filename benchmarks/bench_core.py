"""Figures of the core issue, printed as JSON lines.

1. quality: one run of the seeds' NSGA-II (pop 500 x 500 generations, seed 1)
   on the bundled scenario, as ``gapath solve`` runs it (first population
   seeded with the shortest, safest and weighted-sum monotone paths) and as
   the seeds ran it (all random, ``--seed-from none``); hypervolume ratio
   (SPEC) against the exact column-monotone front and the share of exact
   points found.
2. speed: time per generation at pop 500 on the bundled scenario of
   (a) gapath's vectorised problem, (b) the same problem written the obvious
   way as a pymoo ElementwiseProblem (decode and evaluate one individual in
   Python), both with the same algorithm (stock pymoo NSGA2 with gapath's
   operators, ``paper_nsga2``), (c) stock NSGA2 on a trivial vectorised
   problem of the same size (pymoo's own floor), and (d) FastNSGA2 (what
   ``gapath solve`` runs). Measured in one process, one after the other,
   after a warm-up.
3. throughput of the batched kernels (decode + evaluate), paths per second,
   one core.

Usage: python benchmarks/bench_core.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time

import numpy as np
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.core.problem import ElementwiseProblem, Problem
from pymoo.optimize import minimize

from gapath import default_workspace
from gapath.algorithms import FastNSGA2, paper_nsga2
from gapath.encodings import Frame, IntegerEncoding
from gapath.metrics import coverage, hv_ratio
from gapath.planners.exact import monotone_front
from gapath.problems import GridPathProblem
from gapath.solver import solve


def emit(**record):
    record.setdefault("machine", f"{platform.machine()} {os.cpu_count()} cpu, {platform.python_version()}")
    print(json.dumps(record), flush=True)


class ElementwisePathProblem(ElementwiseProblem):
    """The baseline: the same objectives, one individual at a time, in Python."""

    def __init__(self, workspace):
        self.workspace = workspace
        self.encoding = IntegerEncoding(Frame.of(workspace))  # for gapath's repair
        self.pot = workspace.potential
        self.occ = workspace.occ
        super().__init__(
            n_var=self.encoding.n_var, n_obj=2, xl=self.encoding.xl, xu=self.encoding.xu, vtype=int
        )

    def _decode(self, x):
        (sr, sc), (gr, _gc) = self.workspace.start, self.workspace.goal
        h = self.workspace.shape[0]
        r = sr - int(x[0])
        path = [(rr, sc) for rr in range(sr, r - 1, -1)] if r <= sr else [(rr, sc) for rr in range(sr, r + 1)]
        for k in range(1, len(x) + 1):
            c = sc + k
            t = min(max(r - int(x[k]), 0), h - 1) if k < len(x) else gr
            step = (t > r) - (t < r)
            rr = r + step
            path.append((rr, c))
            while rr != t:
                rr += step
                path.append((rr, c))
            r = t
        return path

    def _evaluate(self, x, out, *args, **kwargs):
        path = self._decode(x)
        length = sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(path, path[1:]))
        vul = sum(self.pot[p] for p in path)
        interf = sum(bool(self.occ[p]) for p in path)
        turn = 0.0
        for a, b, c in zip(path, path[1:], path[2:]):
            h1 = math.atan2(a[0] - b[0], b[1] - a[1])
            h2 = math.atan2(b[0] - c[0], c[1] - b[1])
            d = abs(h2 - h1) % (2 * math.pi)
            turn += min(d, 2 * math.pi - d)
        out["F"] = [length + 1000 * interf, vul + 1000 * interf]
        out["smoothness"] = turn
        out["interfering"] = interf


class TrivialProblem(Problem):
    def __init__(self, n_var):
        super().__init__(n_var=n_var, n_obj=2, xl=0.0, xu=1.0)

    def _evaluate(self, X, out, *args, **kwargs):
        out["F"] = np.column_stack([X[:, 0], 1.0 - X[:, 0] + X[:, 1:].mean(axis=1)])


def time_per_gen(problem, make_algorithm, n_gen, seed=1):
    minimize(problem, make_algorithm(), ("n_gen", 3), seed=seed)  # warm-up
    t0 = time.perf_counter()
    minimize(problem, make_algorithm(), ("n_gen", n_gen), seed=seed)
    return (time.perf_counter() - t0) / n_gen


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="fewer generations")
    args = ap.parse_args()
    ws = default_workspace()
    problem = GridPathProblem(ws)

    # 1. quality ---------------------------------------------------------
    exact = monotone_front(ws, ("length", "vulnerability"))
    n_gen = 50 if args.quick else 500
    runs = {}
    for seed_from in ("weighted", "none"):
        runs[seed_from] = r = solve(ws, pop_size=500, n_gen=n_gen, seed=1, seed_from=seed_from)
        emit(
            bench="core.quality",
            map=ws.name,
            pop=500,
            n_gen=n_gen,
            seed=1,
            seed_from=seed_from,
            seconds=round(r.seconds, 2),
            front_size=len(r.front),
            exact_size=len(exact.F),
            hv_ratio=round(hv_ratio(r.front.F, exact.F), 6),
            exact_points_found=round(coverage(r.front.F, exact.F), 4),
            target_hv_ratio=0.99,
        )
    res = runs["weighted"].pymoo_result

    # 2. speed -----------------------------------------------------------
    g = 10 if args.quick else 60
    t_vec = time_per_gen(problem, lambda: paper_nsga2(500), g)
    t_elem = time_per_gen(ElementwisePathProblem(ws), lambda: paper_nsga2(500), g)
    t_floor = time_per_gen(TrivialProblem(problem.n_var), lambda: NSGA2(pop_size=500), g)
    t_fast = time_per_gen(problem, lambda: FastNSGA2(500), g)
    emit(
        bench="core.speed",
        map=ws.name,
        pop=500,
        generations_timed=g,
        gapath_ms_per_gen=round(1e3 * t_vec, 2),
        elementwise_ms_per_gen=round(1e3 * t_elem, 2),
        pymoo_floor_ms_per_gen=round(1e3 * t_floor, 2),
        elementwise_over_gapath=round(t_elem / t_vec, 2),
        target_elementwise_over_gapath=1.4,
        gapath_over_floor=round(t_vec / t_floor, 3),
        target_gapath_over_floor=1.25,
        fast_nsga2_ms_per_gen=round(1e3 * t_fast, 2),
    )

    # 3. kernel throughput ----------------------------------------------
    rng = np.random.default_rng(0)
    enc = problem.encoding
    populations = {
        "final population": res.pop.get("X"),
        "random (edge-fixed)": enc.edge_fix(rng.integers(enc.xl, enc.xu + 1, size=(500, enc.n_var)), rng),
    }
    for label, X in populations.items():
        X = X[:500]  # one population per call, as in a GA generation
        problem.metrics(X[:10])
        reps, t0 = 0, time.perf_counter()
        while time.perf_counter() - t0 < 2.0:
            problem.metrics(X)
            reps += 1
        rate = reps * len(X) / (time.perf_counter() - t0)
        entries, exits = enc.decode(X[:500])
        mean_cells = float((np.abs(exits - entries) + 1).sum(axis=1).mean())
        emit(
            bench="core.throughput",
            population=label,
            mean_cells_per_path=round(mean_cells, 1),
            paths_per_second=int(rate),
            target_paths_per_second=2_000_000,
        )


if __name__ == "__main__":
    sys.exit(main())
