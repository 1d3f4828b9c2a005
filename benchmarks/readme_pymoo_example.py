"""What the README's "Use it from pymoo" example gives, unseeded and seeded.

Runs the README's code (the bundled 32x32 scenario, length and vulnerability,
pop 500 x 500 generations, seed 1) twice: with ``paper_nsga2``'s default
uniformly random first population (Ahmed & Deb's protocol, ``gapath solve
--seed-from none``) and with ``sampling=PlannerSampling()`` (what ``gapath
solve`` and ``gapath demo`` do). Prints one JSON line per variant: front
size, the shortest and the safest path of the front, its hypervolume ratio
against the exact monotone front, and the CPU seconds of ``minimize``.

    PYTHONPATH=src python benchmarks/readme_pymoo_example.py [--engine paper|fast]
        [--pop 500] [--gen 500] [--seed 1]

``--engine fast`` runs :class:`gapath.algorithms.FastNSGA2` instead of
``paper_nsga2`` (same population for the same seed, faster).
"""

from __future__ import annotations

import argparse
import json
import time

from pymoo.optimize import minimize

from gapath import default_workspace
from gapath.algorithms import FastNSGA2, paper_nsga2
from gapath.front import path_front
from gapath.metrics import hv_ratio
from gapath.operators import PlannerSampling
from gapath.problems import GridPathProblem


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--engine", choices=("paper", "fast"), default="paper")
    ap.add_argument("--pop", type=int, default=500)
    ap.add_argument("--gen", type=int, default=500)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    make = paper_nsga2 if args.engine == "paper" else FastNSGA2
    problem = GridPathProblem(default_workspace(), objectives=("length", "vulnerability"))
    exact = problem.pareto_front()
    for variant, sampling in (("unseeded", None), ("PlannerSampling()", PlannerSampling())):
        kwargs = {} if sampling is None else {"sampling": sampling}
        t0 = time.process_time()
        res = minimize(problem, make(pop_size=args.pop, **kwargs), ("n_gen", args.gen), seed=args.seed)
        cpu = time.process_time() - t0
        front = path_front(problem, res.pop.get("X"))
        print(
            json.dumps(
                {
                    "bench": "readme_pymoo_example",
                    "engine": args.engine,
                    "variant": variant,
                    "pop": args.pop,
                    "gen": args.gen,
                    "seed": args.seed,
                    "front_size": len(front),
                    "min_length": round(float(front.F[:, 0].min()), 4) if len(front) else None,
                    "min_vulnerability": round(float(front.F[:, 1].min()), 4) if len(front) else None,
                    "hv_ratio_vs_exact_monotone": round(hv_ratio(front.F, exact), 4),
                    "exact_min_length": round(float(exact[:, 0].min()), 4),
                    "exact_min_vulnerability": round(float(exact[:, 1].min()), 4),
                    "exact_size": len(exact),
                    "cpu_s": round(cpu, 1),
                }
            ),
            flush=True,
        )


if __name__ == "__main__":
    main()
