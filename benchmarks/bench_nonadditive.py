"""Free-path GA on non-additive objectives against weighted-sum planners (issue 14).

Objective pairs
    * ``length, elevation``: the mean elevation over the path's cells (Lavin's
      F2, eq. 5). A mean is not a sum over the steps: no label-setting search
      gives its exact front, and none is claimed here.
    * ``length, risk_max``: the worst (largest) risk of the path's cells
      (``<layer>_max`` in :mod:`gapath.costmap`). Its exact front *is*
      computable: for every threshold ``t`` the shortest path through cells
      of risk ``<= t`` (:func:`threshold_front`, proof in its docstring).
      That front judges both the GA and the planner.

Instances (fixed before running, :func:`instances`)
    * ``mars-0``, ``mars-1``: workspaces 0 and 1 of the Mars study
      (:func:`gapath.studies.mars.study_workspace`, seed 2015, 100x100,
      23 % square obstacles, start bottom-left, goal top-right, elevation:
      a reflected window of the HiRISE Mars DTM normalised to [0, 1]);
    * ``fractal-64``: ``mars_workspace(7, size=64)`` with seeded fractal
      terrain ``fractal_terrain((64, 64), seed=7)``;
    * ``dem-64``: ``mars_workspace(8, size=64)`` with the Jacksboro fault DEM
      (``dem/jacksboro_fault_dem_elevation.npy``, 344x403) stretched over the
      grid (bilinear) and normalised.
    For ``risk_max`` each instance gets 4 risk cells (``risk_layer``, cap 1)
    drawn by ``numpy.random.default_rng(100 + i)`` (``i`` the instance's
    index) among the free cells at Chebyshev distance >= 6 from the start
    and the goal. Corner cutting is allowed (the study's rule).

Per instance and pair
    (a) the GA: :func:`gapath.solver.solve` with ``paths="free"`` as users
        run it (field encoding, weighted-sum seeding, the free-path archive
        and its re-routing), ``--pop`` x ``--gen`` (200 x 200), seeds
        ``--seeds`` (1, 2, 3); the front is the one ``solve`` returns; the
        generation-0 front is the non-dominated set of the initial
        population (what the seeding gave);
    (b) the weighted-sum planner: :func:`gapath.planners.weighted_sum_astar`
        (exact A* on the statically normalised weighted sum, module
        :mod:`gapath.planners.pareto`) over the *summed* surrogate
        (``length`` and the layer summed over the cells), ``--weights``
        (101) weights ``w`` evenly spaced in [0, 1] (length ``w``, layer
        ``1 - w``; 0 replaced by 1e-6), every path evaluated on the true
        objectives, the non-dominated set of those;
    (c) ``risk_max`` only: the exact front (:func:`threshold_front`).

Measures (``metrics.hypervolume``, reference point 1.1 after normalising)
    Normalisation: for ``risk_max`` SPEC's rule, the exact front's ideal and
    nadir; for ``elevation`` (no exact front) the ideal and nadir of the union
    of every front of the instance (all GA seeds, generation-0 fronts and the
    planner's), the same bounds for every front of the instance. Reported:
    HV of each front, ``ga/planner`` HV ratio, HV ratio to the exact front
    (``risk_max``), how many GA points no planner point dominates and how
    many planner points no GA point dominates (SPEC tolerance 1e-9
    relative), front sizes, wall and CPU seconds.

Sum front (``--sum-front FILE``, after a run)
    For the ``elevation`` instances of FILE: the exact front of (length,
    elevation *summed* over the cells) (:func:`gapath.planners.exact.free_front`
    with ``elevation_sum``: every path any planner of the summed surrogate
    could return, the non-supported ones included), each path evaluated on the
    mean, its non-dominated set, HV with the instance's stored normalisation:
    ``hv_sum_front`` and ``ga_over_sum_front`` (median GA HV over it).

Output: one JSON line per GA run (``"kind": "run"``) and one per instance and
pair (``"kind": "instance"``, with the median and range over seeds), on
stdout and appended to ``--out``. ``--table FILE`` prints the Markdown table of
a JSONL file instead of running.

Usage::

    nice -n 10 python benchmarks/bench_nonadditive.py [--instances mars-0,...]
        [--pairs elevation,risk_max] [--seeds 1,2,3] [--pop 200] [--gen 200]
        [--weights 101] [--out docs/results/free_nonadditive.jsonl]
    python benchmarks/bench_nonadditive.py --table docs/results/free_nonadditive.jsonl
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np
from pymoo.core.callback import Callback

from gapath.callbacks import population_arrays
from gapath.costmap import Costmap, elevation_from_dem, fractal_terrain
from gapath.errors import NoPathError
from gapath.grid import path_length
from gapath.metrics import close, hypervolume, nondominated, normalisation_bounds
from gapath.planners import weighted_sum_astar
from gapath.planners.astar import astar
from gapath.solver import solve
from gapath.studies.mars import find_mars_dtm, mars_workspace, study_workspace
from gapath.workspace import Workspace

ROOT = Path(__file__).resolve().parents[1]
INSTANCES = ("mars-0", "mars-1", "fractal-64", "dem-64")
PAIRS = ("elevation", "risk_max")
N_RISK = 4
RISK_MARGIN = 6


def shared_data() -> Path:
    env = os.environ.get("GAPATH_SHARED_DATA")
    return Path(env) if env else ROOT.parent / "shared" / "data"


def risk_cells(ws: Workspace, seed: int, n: int = N_RISK, margin: int = RISK_MARGIN) -> list:
    """``n`` free cells at Chebyshev distance >= ``margin`` from start and goal."""
    h, w = ws.shape
    rr, cc = np.mgrid[0:h, 0:w]
    far = np.ones((h, w), bool)
    for r, c in (ws.start, ws.goal):
        far &= np.maximum(abs(rr - r), abs(cc - c)) >= margin
    cand = np.argwhere(~ws.occ & far)
    pick = np.random.default_rng(seed).choice(len(cand), size=n, replace=False)
    return [tuple(int(v) for v in cand[i]) for i in sorted(pick)]


def instances(names=INSTANCES):
    """``{name: (workspace, costmap)}``: elevation set, risk set (4 cells)."""
    out = {}
    for i, name in enumerate(INSTANCES):
        if name not in names:
            continue
        if name.startswith("mars-"):
            if find_mars_dtm() is None:
                raise SystemExit("the Mars DTM dem/mars_dtm.npy was not found")
            ws, cm = study_workspace(int(name.split("-")[1]))
        else:
            ws = mars_workspace({"fractal-64": 7, "dem-64": 8}[name], size=64)
            if name == "fractal-64":
                elev = fractal_terrain(ws.shape, seed=7)
            else:
                dem = shared_data() / "dem" / "jacksboro_fault_dem_elevation.npy"
                elev = elevation_from_dem(dem, ws.shape, method="bilinear")
            cm = Costmap(ws, elevation=elev, solar_rate=1.0)
        cm.set_risk(risk_cells(ws, 100 + i), cap=1.0)
        out[name] = (ws, cm)
    return out


def dominates(a, b) -> bool:
    """``a`` dominates ``b`` beyond SPEC's tolerance."""
    eq = close(a, b)
    return bool(np.all((a <= b) | eq) and np.any((a < b) & ~eq))


def n_undominated(F, by) -> int:
    """How many rows of ``F`` no row of ``by`` dominates."""
    return int(sum(not any(dominates(b, f) for b in by) for f in F))


def front_of(F) -> np.ndarray:
    F = np.asarray(F, float).reshape(-1, 2)
    F = F[nondominated(F)]
    keep = []
    for f in F[np.lexsort(F.T[::-1])]:
        if not any(np.all(close(f, k)) for k in keep):
            keep.append(f)
    return np.array(keep).reshape(-1, 2)


def true_objectives(cm: Costmap, path, pair: str) -> np.ndarray:
    v = cm.evaluate_path(path, ["length", pair])
    return np.array([v["length"], v[pair]])


def planner_front(cm: Costmap, pair: str, n_weights: int):
    """(b): weighted-sum A* over the summed surrogate, true objectives."""
    layer = cm.base_layer(pair)
    F, t0 = [], time.perf_counter()
    for w in np.linspace(0.0, 1.0, n_weights):
        wl, wc = max(w, 1e-6), max(1.0 - w, 1e-6)
        res = weighted_sum_astar(cm, ("length", layer), weights=(wl, wc))
        F.append(true_objectives(cm, res.path, pair))
    return front_of(F), time.perf_counter() - t0


def threshold_front(ws: Workspace, layer: np.ndarray):
    """The exact front of (length, max of ``layer`` over the path's cells).

    Start with ``t = inf``; find the shortest path using only free cells of
    ``layer <= t``; record (its length, its maximum ``m``); set ``t`` to the
    largest layer value below ``m``; repeat until no path exists. Each Pareto
    point ``(L*, m*)`` is found: let ``t_k`` be the last threshold ``>= m*``;
    the shortest path under it has length ``<= L*`` and maximum ``m_k <=
    m*`` (if ``m_k > m*``, the next threshold would still be ``>= m*``), so it
    weakly dominates ``(L*, m*)``, hence equals it. Shortest paths are simple,
    so this is the front over simple paths. Needs ``corner_cutting=True``
    (blocking a risky cell must not change the corner rule of its
    neighbours' diagonals).
    """
    if not ws.corner_cutting:
        raise ValueError("threshold_front needs corner_cutting=True")
    values = np.unique(layer[~ws.occ])
    F, t, n_search, t0 = [], np.inf, 0, time.perf_counter()
    while True:
        occ = ws.occ | (layer > t)
        if occ[ws.start] or occ[ws.goal]:
            break
        try:
            p = astar(Workspace(occ, ws.start, ws.goal, cell_size=ws.cell_size)).path
        except NoPathError:
            break
        n_search += 1
        m = float(layer[p[:, 0], p[:, 1]].max())
        F.append([path_length(p, ws.cell_size), m])
        below = values[values < m]
        if len(below) == 0:
            break
        t = below[-1]
    return front_of(F), time.perf_counter() - t0, n_search


class FirstGeneration(Callback):
    """Keeps the objective values of the initial population."""

    def __init__(self):
        super().__init__()
        self.F = None

    def notify(self, algorithm):
        if self.F is None:
            X = population_arrays(algorithm).X
            p = algorithm.problem
            self.F = p.objective_values(p.metrics(X))


def run_ga(ws, cm, pair, seed, pop, gen):
    cb = FirstGeneration()
    c0, t0 = time.process_time(), time.perf_counter()
    r = solve(
        ws,
        objectives=("length", pair),
        paths="free",
        costmap=cm,
        pop_size=pop,
        n_gen=gen,
        seed=seed,
        callback=cb,
    )
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    # objectives recomputed from the paths (the problem's F must agree)
    F = np.array([true_objectives(cm, p, pair) for p in r.front.paths]).reshape(-1, 2)
    assert np.allclose(F, r.front.F, rtol=1e-9, atol=1e-12), "front F differs from its paths"
    return front_of(F), front_of(cb.F), wall, cpu, r.n_eval


def span(values):
    v = [x for x in values if x is not None]
    if not v:
        return None
    return {"median": statistics.median(v), "min": min(v), "max": max(v)}


def study(name, ws, cm, pair, seeds, pop, gen, n_weights, emit):
    P, p_sec = planner_front(cm, pair, n_weights)
    exact, e_sec, n_search = None, None, None
    if pair == "risk_max":
        exact, e_sec, n_search = threshold_front(ws, cm.layer("risk"))
    runs = []
    for seed in seeds:
        G, G0, wall, cpu, n_eval = run_ga(ws, cm, pair, seed, pop, gen)
        runs.append(dict(seed=seed, G=G, G0=G0, wall=wall, cpu=cpu, n_eval=n_eval))
    if exact is not None:
        ideal, nadir = normalisation_bounds(exact)
        basis = "exact front (SPEC)"
    else:
        ideal, nadir = normalisation_bounds(np.vstack([P] + [r["G"] for r in runs] + [r["G0"] for r in runs]))
        basis = "union of the instance's fronts"
    hv = lambda F: hypervolume(F, ideal, nadir)  # noqa: E731
    hv_p, hv_e = hv(P), (hv(exact) if exact is not None else None)
    rows = []
    for r in runs:
        row = dict(
            kind="run",
            instance=name,
            pair=pair,
            seed=r["seed"],
            pop=pop,
            gen=gen,
            n_ga=len(r["G"]),
            n_gen0=len(r["G0"]),
            n_planner=len(P),
            hv_ga=hv(r["G"]),
            hv_gen0=hv(r["G0"]),
            hv_planner=hv_p,
            ga_over_planner=hv(r["G"]) / hv_p,
            gen0_over_planner=hv(r["G0"]) / hv_p,
            ga_not_dominated_by_planner=n_undominated(r["G"], P),
            planner_not_dominated_by_ga=n_undominated(P, r["G"]),
            wall_s=round(r["wall"], 2),
            cpu_s=round(r["cpu"], 2),
            n_eval=r["n_eval"],
            front=r["G"].tolist(),
        )
        if exact is not None:
            row.update(
                n_exact=len(exact),
                ga_over_exact=hv(r["G"]) / hv_e,
                gen0_over_exact=hv(r["G0"]) / hv_e,
                ga_dominates_exact=n_undominated(exact, r["G"]) < len(exact),
                exact_points_found=int(sum(any(np.all(close(e, g)) for g in r["G"]) for e in exact)),
            )
        rows.append(row)
        emit(row)
    summary = dict(
        kind="instance",
        instance=name,
        pair=pair,
        shape=list(ws.shape),
        start=list(ws.start),
        goal=list(ws.goal),
        risk_cells=cm.risk_cells if pair == "risk_max" else None,
        seeds=list(seeds),
        normalisation=basis,
        ideal=ideal.tolist(),
        nadir=nadir.tolist(),
        n_planner=len(P),
        planner_s=round(p_sec, 3),
        hv_planner=hv_p,
        planner_front=P.tolist(),
    )
    for key in ("hv_ga", "hv_gen0", "ga_over_planner", "gen0_over_planner", "n_ga", "wall_s", "cpu_s"):
        summary[key] = span([r[key] for r in rows])
    for key in ("ga_not_dominated_by_planner", "planner_not_dominated_by_ga"):
        summary[key] = [r[key] for r in rows]
    if exact is not None:
        summary.update(
            n_exact=len(exact),
            exact_s=round(e_sec, 3),
            exact_searches=n_search,
            hv_exact=hv_e,
            planner_over_exact=hv_p / hv_e,
            ga_over_exact=span([r["ga_over_exact"] for r in rows]),
            gen0_over_exact=span([r["gen0_over_exact"] for r in rows]),
            exact_points_found=[r["exact_points_found"] for r in rows],
            planner_exact_points=int(sum(any(np.all(close(e, p)) for p in P) for e in exact)),
            ga_dominates_exact=any(r["ga_dominates_exact"] for r in rows),
        )
    emit(summary)


def sum_fronts(path, emit):
    """``--sum-front``: the exact summed-surrogate front of every elevation instance."""
    from gapath.planners.exact import free_front

    rows = [json.loads(x) for x in Path(path).read_text().splitlines() if x.strip()]
    for r in rows:
        if r.get("kind") != "instance" or r["pair"] != "elevation":
            continue
        ws, cm = instances([r["instance"]])[r["instance"]]
        t0 = time.perf_counter()
        fr = free_front(ws, ["length", "elevation_sum"], costmap=cm)
        sec = time.perf_counter() - t0
        S = front_of([true_objectives(cm, p, "elevation") for p in fr.paths])
        hv_s = hypervolume(S, r["ideal"], r["nadir"])
        emit(
            dict(
                kind="sum_front",
                instance=r["instance"],
                pair="elevation",
                n_sum_exact=len(fr.paths),
                n_sum_front=len(S),
                sum_front_s=round(sec, 3),
                hv_sum_front=hv_s,
                sum_front_over_planner=hv_s / r["hv_planner"],
                ga_over_sum_front={k: v / hv_s for k, v in r["hv_ga"].items()},
                gen0_over_sum_front={k: v / hv_s for k, v in r["hv_gen0"].items()},
                sum_front=S.tolist(),
            )
        )


def _fmt(s, digits=4):
    if s is None:
        return "-"
    if isinstance(s, dict):
        return f"{s['median']:.{digits}f} [{s['min']:.{digits}f}, {s['max']:.{digits}f}]"
    return f"{s:.{digits}f}"


def table(path) -> str:
    rows = [json.loads(x) for x in Path(path).read_text().splitlines() if x.strip()]
    rows = [r for r in rows if r.get("kind") == "instance"]
    head = (
        "| instance | pair | GA / planner HV | gen 0 / planner HV | GA / exact HV | planner / exact HV "
        "| gen 0 / exact HV | GA pts not dominated by planner | planner pts not dominated by GA "
        "| front sizes GA / planner / exact | GA wall s |"
    )
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        n_ga = r["n_ga"]
        sizes = f"{int(n_ga['median'])} [{int(n_ga['min'])}-{int(n_ga['max'])}] / {r['n_planner']} / {r.get('n_exact', '-')}"
        und = lambda v: "/".join(str(x) for x in v)  # noqa: E731
        lines.append(
            f"| {r['instance']} | length, {r['pair']} | {_fmt(r['ga_over_planner'])} | {_fmt(r['gen0_over_planner'])} "
            f"| {_fmt(r.get('ga_over_exact'))} | {_fmt(r.get('planner_over_exact'))} | {_fmt(r.get('gen0_over_exact'))} "
            f"| {und(r['ga_not_dominated_by_planner'])} of GA | {und(r['planner_not_dominated_by_ga'])} of {r['n_planner']} "
            f"| {sizes} | {_fmt(r['wall_s'], 0)} |"
        )
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--instances", default=",".join(INSTANCES))
    ap.add_argument("--pairs", default=",".join(PAIRS))
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--pop", type=int, default=200)
    ap.add_argument("--gen", type=int, default=200)
    ap.add_argument("--weights", type=int, default=101)
    ap.add_argument("--out", default=None, help="JSONL file the lines are appended to")
    ap.add_argument("--table", default=None, help="print the Markdown table of a JSONL file and exit")
    ap.add_argument(
        "--sum-front",
        default=None,
        help="exact summed-surrogate fronts of a JSONL file's elevation instances",
    )
    a = ap.parse_args(argv)
    if a.table:
        print(table(a.table))
        return 0
    if a.sum_front:
        with open(a.out or os.devnull, "a") as out:
            sum_fronts(
                a.sum_front,
                lambda row: (print(json.dumps(row), flush=True), out.write(json.dumps(row) + "\n")),
            )
        return 0
    names = [n.strip() for n in a.instances.split(",") if n.strip()]
    pairs = [p.strip() for p in a.pairs.split(",") if p.strip()]
    bad = [n for n in names if n not in INSTANCES] + [p for p in pairs if p not in PAIRS]
    if bad:
        raise SystemExit(f"unknown instance or pair {bad}; expected {INSTANCES} and {PAIRS}")
    seeds = [int(s) for s in a.seeds.split(",")]
    out = open(a.out, "a") if a.out else None

    def emit(row):
        line = json.dumps(row)
        print(line, flush=True)
        if out:
            out.write(line + "\n")
            out.flush()

    emit(
        dict(
            kind="settings",
            host=os.uname().nodename,
            cpus=os.cpu_count(),
            date=time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
            pop=a.pop,
            gen=a.gen,
            seeds=seeds,
            weights=a.weights,
            argv=sys.argv[1:],
        )
    )
    for name, (ws, cm) in instances(names).items():
        for pair in pairs:
            study(name, ws, cm, pair, seeds, a.pop, a.gen, a.weights, emit)
    return 0


if __name__ == "__main__":
    sys.exit(main())
