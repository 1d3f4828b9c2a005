"""Post-hoc check (issue 17 §2): does an archive of the feasible paths a run
met lift the unseeded Fig. 3 HV ratio?

The encodings study's ``seeds`` runs (integer encoding, bundled map, pop
500 x 500, ``seed_from="none"``) under each handling; after every
generation the feasible survivors join a non-dominated archive. One JSON
line per run: the HV ratio (against the exact monotone front) of the
run's final front and of its archive.

Usage: python benchmarks/penalty_archive.py HANDLINGS FIRST_SEED LAST_SEED
(HANDLINGS: comma-separated penalties or names of gapath.constraints.HANDLINGS).
"""

import json
import sys

import numpy as np
from pymoo.core.callback import Callback

from gapath import default_workspace
from gapath.callbacks import population_arrays
from gapath.constraints import HANDLINGS
from gapath.metrics import hv_ratio, nondominated
from gapath.planners.exact import monotone_front
from gapath.solver import solve


class Archive(Callback):
    def __init__(self):
        super().__init__()
        self.F = np.zeros((0, 2))

    def notify(self, algorithm):
        A = population_arrays(algorithm)
        feas = np.asarray(A.feasible, bool)
        F = np.asarray(A.F)[feas]
        if len(F):
            self.F = np.vstack([self.F, F])
            self.F = self.F[nondominated(self.F)]


ws = default_workspace()
exact = monotone_front(ws, ("length", "vulnerability"))
handlings = sys.argv[1].split(",")
seeds = range(int(sys.argv[2]), int(sys.argv[3]) + 1)
for h in handlings:
    kw = (
        {"constraints": "adaptive", "penalty": 1000.0, "adaptive_penalty": HANDLINGS[h]}
        if h in HANDLINGS
        else {"penalty": float(h)}
    )
    for s in seeds:
        cb = Archive()
        r = solve(ws, pop_size=500, n_gen=500, seed=s, seed_from="none", progress=False, callback=cb, **kw)
        print(
            json.dumps(
                dict(
                    handling=h,
                    seed=s,
                    final=round(float(hv_ratio(r.front.F, exact.F)), 6),
                    archive=round(float(hv_ratio(cb.F, exact.F)), 6) if len(cb.F) else 0.0,
                )
            ),
            flush=True,
        )
