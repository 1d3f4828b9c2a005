"""The monotone GA at pop 500 x 500 against the exact monotone front
(issue 14's last figure), printed as JSON lines.

Protocol (docs/results/monotone_lift.md): 32x32 maps made as the bundled
map was (``random_workspace((32, 32), 173, seed=s)``), a tuning set (map
seeds 1-5) and an evaluation set (101-120); objectives length and
vulnerability; ``gapath.solver.solve`` as ``gapath solve MAP --paths
monotone`` runs it (integer encoding, weighted-sum seeds, FastNSGA2, penalty
1000); one run = GA seed 1, merged = the union of GA seeds 1-10.

One line per run (``bench="monotone_lift.run"``: HV ratio, exact points
found, the first population's figures, front size, seconds, evaluations),
one per map for the merged front (``"monotone_lift.merged"``) and a summary
per set (``"monotone_lift.summary"``: median and minimum).

Usage::

    python benchmarks/bench_monotone_lift.py --maps 1-5 --seeds 1-10 --variant baseline
    python benchmarks/bench_monotone_lift.py --maps 101-120 --seeds 1-10 --variant archive

``--variant baseline`` runs ``solve(..., refine=False)`` (the last
population's front, as before the archive); ``archive`` runs ``solve(...,
refine=True)`` (what ``gapath solve --paths monotone`` runs); ``refine=N``
sets the re-routed paths per generation; ``--maps bundled`` runs the
bundled map. ``--segment LO,HI`` and ``--weights LO,HI`` set the archive's
``segment`` and ``weight_range``, ``--pareto N``, ``--pareto-span LO,HI``
and ``--pareto-cap C`` its Pareto stretches (``--pareto 0``: the archive
before the Pareto stretches, v2).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time

import numpy as np

from gapath import default_workspace
from gapath.callbacks import population_arrays
from gapath.generators import random_workspace
from gapath.metrics import coverage, hv_ratio, nondominated
from gapath.operators import monotone_archive
from gapath.planners.exact import monotone_front
from gapath.solver import solve

OBJECTIVES = ("length", "vulnerability")


def emit(**record):
    record.setdefault("machine", f"{platform.machine()} {os.cpu_count()} cpu, {platform.python_version()}")
    print(json.dumps(record), flush=True)


def seeds(text: str) -> list[int]:
    out = []
    for part in text.split(","):
        if "-" in part:
            a, b = part.split("-")
            out += list(range(int(a), int(b) + 1))
        elif part:
            out.append(int(part))
    return out


def workspace_of(name):
    if name == "bundled":
        return default_workspace()
    return random_workspace((32, 32), 173, seed=int(name))


class FirstPopulation:
    """Keeps the feasible objective vectors of the first population."""

    def __init__(self):
        self.F = None

    def __call__(self, algorithm):
        if self.F is None:
            A = population_arrays(algorithm)
            self.F = A.F[A.feasible]


def variant_kwargs(variant: str) -> dict:
    if variant == "baseline":
        return {"refine": False}
    if variant == "archive":
        return {"refine": True}
    if variant.startswith("refine="):
        return {"refine": int(variant.split("=", 1)[1])}
    raise SystemExit(f"unknown variant {variant!r}")


def front_of(F):
    F = np.asarray(F, float).reshape(-1, len(OBJECTIVES))
    return F[nondominated(F)] if len(F) else F


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--maps", default="1-5", help="map seeds (e.g. 1-5, 101-120) or 'bundled'")
    ap.add_argument("--seeds", default="1-10", help="GA seeds; the first one is the single run")
    ap.add_argument("--variant", default="archive", help="baseline | archive | refine=N")
    ap.add_argument("--pop", type=int, default=500)
    ap.add_argument("--gen", type=int, default=500)
    ap.add_argument("--label", default="", help="set label written in every line")
    ap.add_argument("--segment", default=None, help="archive segment share LO,HI (tuning)")
    ap.add_argument("--weights", default=None, help="archive log10 weight range LO,HI (tuning)")
    ap.add_argument("--pareto", default=None, help="archive Pareto stretches per generation (tuning)")
    ap.add_argument("--pareto-span", default=None, help="Pareto stretch columns LO,HI (tuning)")
    ap.add_argument("--pareto-cap", default=None, help="Pareto labels kept per exit row (tuning)")
    args = ap.parse_args(argv)
    tuned = {}
    for key, attr, conv in (("pareto", "N_PARETO", int), ("pareto_cap", "PARETO_CAP", int)):
        text = getattr(args, key)
        if text:
            setattr(monotone_archive, attr, conv(text))
            tuned[key] = text
    for key, attr in (("segment", "SEGMENT"), ("weights", "WEIGHT_RANGE"), ("pareto_span", "PARETO_SPAN")):
        text = getattr(args, key)
        if text:
            setattr(monotone_archive, attr, tuple(float(v) for v in text.split(",")))
            tuned[key] = text
    maps = ["bundled"] if args.maps == "bundled" else [str(s) for s in seeds(args.maps)]
    ga_seeds = seeds(args.seeds)
    kw = variant_kwargs(args.variant)
    single, merged, gen0 = [], [], []
    for name in maps:
        ws = workspace_of(name)
        exact = monotone_front(ws, OBJECTIVES).F
        union = []
        for s in ga_seeds:
            first = FirstPopulation()
            t0 = time.process_time()
            r = solve(
                ws, objectives=OBJECTIVES, pop_size=args.pop, n_gen=args.gen, seed=s, callback=first, **kw
            )
            cpu = time.process_time() - t0
            F = r.front.F
            union.append(F)
            F0 = front_of(first.F)
            rec = dict(
                bench="monotone_lift.run",
                label=args.label,
                variant=args.variant,
                **tuned,
                map=ws.name,
                map_seed=name,
                ga_seed=s,
                pop=args.pop,
                n_gen=args.gen,
                exact_points=len(exact),
                front_size=len(F),
                hv_ratio=round(hv_ratio(F, exact), 6),
                points_found=round(coverage(F, exact), 4),
                gen0_hv_ratio=round(hv_ratio(F0, exact), 6),
                gen0_points_found=round(coverage(F0, exact), 4),
                n_eval=r.n_eval,
                seconds=round(r.seconds, 2),
                cpu_seconds=round(cpu, 2),
                load=round(os.getloadavg()[0], 1),
            )
            emit(**rec)
            if s == ga_seeds[0]:
                single.append(rec)
                gen0.append(rec)
        if len(ga_seeds) > 1:
            U = front_of(np.concatenate(union))
            rec = dict(
                bench="monotone_lift.merged",
                label=args.label,
                variant=args.variant,
                map=ws.name,
                map_seed=name,
                ga_seeds=args.seeds,
                exact_points=len(exact),
                front_size=len(U),
                hv_ratio=round(hv_ratio(U, exact), 6),
                points_found=round(coverage(U, exact), 4),
            )
            emit(**rec)
            merged.append(rec)

    def stats(rows, key):
        v = np.array([r[key] for r in rows])
        return dict(median=round(float(np.median(v)), 6), min=round(float(v.min()), 6)) if len(v) else {}

    emit(
        bench="monotone_lift.summary",
        label=args.label,
        variant=args.variant,
        **tuned,
        maps=args.maps,
        seeds=args.seeds,
        n_maps=len(maps),
        single_hv_ratio=stats(single, "hv_ratio"),
        single_points_found=stats(single, "points_found"),
        single_hv_ge_0995=sum(r["hv_ratio"] >= 0.995 for r in single),
        single_points_ge_90=sum(r["points_found"] >= 0.9 for r in single),
        gen0_hv_ratio=stats(gen0, "gen0_hv_ratio"),
        gen0_points_found=stats(gen0, "gen0_points_found"),
        merged_hv_ratio=stats(merged, "hv_ratio"),
        merged_points_found=stats(merged, "points_found"),
        merged_hv_ge_0999=sum(r["hv_ratio"] >= 0.999 for r in merged),
        date=time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
    )


if __name__ == "__main__":
    sys.exit(main())
