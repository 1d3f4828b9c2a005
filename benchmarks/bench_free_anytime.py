"""Anytime: the free-path GA against exact search on large maps (issue 14).

"Where the GA must win": three objectives (length, vulnerability,
smoothness) on large maps. For each instance the exact free front
(:func:`gapath.planners.exact.free_front`, NAMOA*-dr) is computed once, with
a wall-clock cap (``--exact-cap`` seconds, default 900: the search is ended
through its ``progress`` hook and the instance is reported as "not finished")
and a label budget (``--max-labels``), and cached as ``.npz`` in
``--cache``. Then one GA run as a user runs it: :func:`gapath.solver.solve`
with ``paths="free"`` (FastNSGA2, field genome, weighted-sum seeds, the
free-path archive with its default refinement, or ``--refine`` paths
re-routed per generation), population ``--pop``,
seed ``--seed``, for ``--gen`` generations or until ``--ga-cap`` CPU seconds,
recording after every generation the HV ratio of the run's front (the
archive's) against the exact front and the wall time since the call, minus
the time spent measuring the HV ratio (``ga_seconds`` is the GA's own time),
and the process CPU time (every thread's). ``threads`` is what
``GAPATH_THREADS`` asked for (1: serial; 2 or more: parallel batches and
the approximate search beside the faces in generation 1).

Instances (``--instances``, comma-separated)::

    gen128-sK   random_workspace((128, 128), 20 % obstacles, seed K),
                start bottom-left, goal top-right
    gen256-sK   the same on 256 x 256
    gen512-sK   the same on 512 x 512
    berlin      MovingAI Berlin_1_256, its longest .scen query
    random512   MovingAI random512-10-0, its longest .scen query
    random512-40  MovingAI random512-40-0 (dense: 40 % obstacles), the same
    8room       MovingAI 8room_000 (512 x 512 rooms), the same
    maze512     MovingAI maze512-1-0, the same
    berlin0     MovingAI Berlin_0_256, its longest .scen query
    NAME-qK     one of the five above, its K-th longest query (``8room-q2``)
    willow      the ROS map willow_full (584 x 526, an office floor), the
                double-sweep diameter query (``_diameter``)

(MovingAI maps with ``corner_cutting=False``.) One JSON line per instance:
exact front size and seconds (or ``exact_finished: false``), the GA's
per-generation ``trace`` ``[gen, wall seconds, CPU seconds, hv_ratio]``, the
seconds and generation at which the HV ratio first reached 0.95 and 0.99,
the final ratio and sizes. Where exact search did not finish, the ratios
are against the run's own final front (the best known front; every 5th
generation), and ``reference`` says so. ``--throughput`` instead prints decode+evaluate throughput
(paths per second of wall time and of process CPU time, ``--pop`` random
genomes, cache cold) and the seconds per
generation of a short GA run (``--throughput-gens`` generations after the
first population; median), one line per instance. ``--expansions N``
analyses the field decoder's search on N genomes (see :func:`expansions`).
``--faces`` prints the cost of the archive's exact face searches (see
:func:`faces`), ``--approx EPS,...`` that of its approximate
three-objective search and the HV ratio it reaches with and without the
faces (see :func:`approx`), ``--density`` the HV ratio of subsets of the cached exact
front (see :func:`density`), ``--gap RUN.npz`` where a saved run's front
falls short of it (see :func:`gap`).

Where exact search does not finish, the best known front is the merge of
long GA runs: run them with ``--skip-exact --save PREFIX`` (the fronts are
written as the run goes, so a run stopped early keeps them), merge them
with ``--merge OUT.npz --instances A.npz,B.npz`` and score a run against the
merge with ``--score OUT.npz --instances RUN.npz``; the lines then say
"best known front (merged GA runs), not exact".

Usage::

    python benchmarks/bench_free_anytime.py --instances gen128-s1,berlin [--gen 300]
    python benchmarks/bench_free_anytime.py --instances 8room-q226 --pop 50 --refine 3200
    python benchmarks/bench_free_anytime.py --exact-only --instances gen256-s1
    python benchmarks/bench_free_anytime.py --throughput --instances random512 --pop 200
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np
from pymoo.core.callback import Callback

from gapath.convergence import HypervolumeRatioCallback
from gapath.generators import random_workspace
from gapath.loaders import _read_ros, load_movingai, load_ros, load_scenarios
from gapath.metrics import coverage, hv_ratio
from gapath.operators.archive import run_archive
from gapath.planners.exact import free_front
from gapath.problems import FreePathProblem
from gapath.solver import solve

try:  # the parallel searches (absent before them: serial)
    from gapath.encodings.free import search_threads, wanted_threads
except ImportError:  # pragma: no cover

    def search_threads(n: int) -> int:
        return 0

    def wanted_threads() -> int:
        return 1


ROOT = Path(__file__).resolve().parents[1]
OBJECTIVES = ("length", "vulnerability", "smoothness")


def data_dir(arg=None) -> Path:
    if arg:
        return Path(arg)
    env = os.environ.get("GAPATH_SHARED_DATA")
    return Path(env) if env else ROOT.parent / "shared" / "data"


#: Instances on MovingAI's 512 x 512 grid maps (``movingai/grid``): the
#: sparse random field, the dense one (40 % obstacles), rooms and a maze.
GRID_MAPS = {
    "random512": "random512-10-0",
    "random512-40": "random512-40-0",
    "8room": "8room_000",
    "maze512": "maze512-1-0",
    "berlin0": "Berlin_0_256",
}

#: ROS maps (``ros/``): no queries ship with them, so the query is the
#: double-sweep diameter (:func:`_diameter`).
ROS_MAPS = {"willow": "willow_full/willow-full.yaml"}


def _diameter(occ):
    """A long query on a map without ``.scen`` file, chosen by rule: from
    the free cell nearest the centre, the cell farthest from it in 8-connected
    steps (no corner cutting), then the cell farthest from that one (a double
    sweep; ties go to the lowest row-major index). Returns ``(a, b)``."""
    from collections import deque

    h, w = occ.shape
    free = np.argwhere(~occ)
    c = free[np.argmin(((free - np.array([h / 2, w / 2])) ** 2).sum(1))]

    def farthest(src):
        dist = np.full(occ.shape, -1, np.int64)
        dist[tuple(src)] = 0
        q = deque([tuple(src)])
        while q:
            r, k = q.popleft()
            for dr in (-1, 0, 1):
                for dk in (-1, 0, 1):
                    rr, kk = r + dr, k + dk
                    if (dr or dk) and 0 <= rr < h and 0 <= kk < w and not occ[rr, kk] and dist[rr, kk] < 0:
                        if dr and dk and (occ[r, kk] or occ[rr, k]):
                            continue
                        dist[rr, kk] = dist[r, k] + 1
                        q.append((rr, kk))
        flat = int(np.argmax(dist))
        return divmod(flat, w)

    a = farthest(c)
    return a, farthest(a)


def _longest(scen_path, rank=1):
    """The ``rank``-th longest query of a ``.scen`` file (1: the longest)."""
    return sorted(load_scenarios(scen_path), key=lambda s: -s.optimal)[rank - 1]


def workspace(name: str, data: Path):
    """The workspace of instance ``name`` (see the module docstring)."""
    if name.startswith("gen"):
        size, seed = name[3:].split("-s")
        n = int(size)
        return random_workspace((n, n), int(round(0.2 * n * n)), seed=int(seed), name=name)
    if name == "berlin":
        d = data / "movingai" / "mapf"
        sc = _longest(d / "Berlin_1_256-random-1.scen")
        return load_movingai(d / "Berlin_1_256.map", start=sc.start, goal=sc.goal, corner_cutting=False)
    base, _, rank = name.rpartition("-q")
    base, rank = (base, int(rank)) if base in GRID_MAPS and rank.isdigit() else (name, 1)
    if base in GRID_MAPS:
        d = data / "movingai" / "grid"
        sc = _longest(d / f"{GRID_MAPS[base]}.map.scen", rank)
        return load_movingai(d / f"{GRID_MAPS[base]}.map", start=sc.start, goal=sc.goal, corner_cutting=False)
    if name in ROS_MAPS:
        path = data / "ros" / ROS_MAPS[name]
        occ = _read_ros(path).occupancy("blocked")  # as load_ros reads it, before start and goal
        a, b = _diameter(occ)
        return load_ros(path, start=a, goal=b, corner_cutting=False, name=name)
    raise SystemExit(f"unknown instance {name!r}")


class _Stop(Exception):
    pass


def exact(name, ws, cache: Path, cap: float, max_labels, cpu_cap=None):
    """The cached exact front of ``name``: ``(F or None, record)``.

    ``cap`` bounds the search's wall seconds; ``cpu_cap`` (when given) also
    its process CPU seconds (on a loaded machine the wall clock runs several
    times faster than the search's own CPU time: give a CPU cap and a wall
    cap as a safety)."""
    f = cache / f"{name}.npz"
    if f.exists():
        z = np.load(f, allow_pickle=False)
        rec = json.loads(str(z["record"]))
        return (z["F"] if rec["exact_finished"] else None), rec
    t0, c0 = time.perf_counter(), time.process_time()
    last: dict = {}

    def progress(info):
        last.update(info)
        if cpu_cap is not None and time.process_time() - c0 > cpu_cap:
            raise _Stop
        if time.perf_counter() - t0 > cap:
            raise _Stop

    rec = dict(instance=name, shape=list(ws.shape), start=list(ws.start), goal=list(ws.goal))
    rec["exact_cap"] = dict(wall_seconds=cap, cpu_seconds=cpu_cap)
    F = None
    try:
        front = free_front(ws, OBJECTIVES, max_labels=max_labels, progress=progress)
        F = np.asarray(front.F, float)
        rec.update(
            exact_finished=True,
            exact_size=len(F),
            exact_seconds=time.perf_counter() - t0,
            exact_cpu_seconds=time.process_time() - c0,
        )
        rec["exact_stats"] = {k: v for k, v in front.stats.items() if isinstance(v, (int, float))}
    except (_Stop, Exception) as e:  # the cap, the label budget or memory: not finished
        rec.update(
            exact_finished=False,
            exact_seconds=time.perf_counter() - t0,
            exact_cpu_seconds=time.process_time() - c0,
            exact_stopped_by="cap" if isinstance(e, _Stop) else f"{type(e).__name__}: {e}",
            exact_progress={k: v for k, v in last.items() if isinstance(v, (int, float))},
        )
    cache.mkdir(parents=True, exist_ok=True)
    np.savez(f, F=np.zeros((0, 3)) if F is None else F, record=json.dumps(rec))
    return F, rec


class _Trace(Callback):
    """The run's front (the archive's) every generation, with the GA's own
    wall and CPU time (the time spent here is subtracted); its HV ratio
    against ``reference`` at once, or, without one, the fronts themselves
    (every ``keep`` generations) to be measured against the run's final
    front afterwards."""

    def __init__(self, reference, cap, keep=5, progress=None, save=None):
        super().__init__()
        self.progress = progress
        self.save = save
        self.hv = None if reference is None else HypervolumeRatioCallback(reference)
        self.t0, self.c0 = time.perf_counter(), time.process_time()
        self.spent = self.cpu_spent = 0.0
        self.cap, self.keep = cap, keep
        self.trace: list[list[float]] = []
        self.fronts: list = []

    def dump(self, F):
        """Write the fronts kept so far (and ``F``, the latest) to ``save``."""
        Path(self.save).parent.mkdir(parents=True, exist_ok=True)
        tmp = f"{self.save}.tmp.npz"
        kept = {f"front_{i}": Fi for i, Fi in self.fronts}
        np.savez_compressed(tmp, F=np.asarray(F, float), trace=np.asarray(self.trace, float), **kept)
        os.replace(tmp, self.save)

    def initialize(self, algorithm):
        if self.hv is not None:
            self.hv.initialize(algorithm)

    def notify(self, algorithm):
        t, c = time.perf_counter(), time.process_time()
        g = int(algorithm.n_gen)
        if self.hv is not None:
            self.hv.notify(algorithm)
            h = self.hv.history[-1][2]
        else:
            h = float("nan")
            if g % self.keep == 1 or self.keep == 1 or algorithm.termination.has_terminated():
                self.fronts.append((len(self.trace), run_archive(algorithm).F.copy()))
        self.spent += time.perf_counter() - t
        self.cpu_spent += time.process_time() - c
        ga = time.perf_counter() - self.t0 - self.spent
        cpu = time.process_time() - self.c0 - self.cpu_spent
        self.trace.append([g, round(ga, 3), round(cpu, 3), round(h, 6)])
        if self.save and self.hv is None and self.fronts and self.fronts[-1][0] == len(self.trace) - 1:
            t, c = time.perf_counter(), time.process_time()
            self.dump(self.fronts[-1][1])  # a run stopped early keeps what it had
            self.spent += time.perf_counter() - t
            self.cpu_spent += time.process_time() - c
        if self.progress:  # partial figures of a run that may not finish
            with open(self.progress, "a") as f:
                f.write(json.dumps(self.trace[-1]) + "\n")
        if cpu > self.cap:
            algorithm.termination.force_termination = True


def anytime(ws, F, pop, gen, seed, cap, progress=None, keep=5, save=None, reference="exact", refine=None):
    """One GA run's trace against the front ``F`` (the exact front, or the
    best known one when ``reference`` says so; when None, against the run's
    own final front). ``save``: write the run's final front and the fronts
    kept every ``keep`` generations (with their trace rows) to this ``.npz``,
    to be measured against another front afterwards (``--score``)."""
    tracker = _Trace(F if save is None else None, cap, keep=keep, progress=progress, save=save)
    res = solve(
        ws,
        objectives=OBJECTIVES,
        paths="free",
        pop_size=pop,
        n_gen=gen,
        seed=seed,
        callback=tracker,
        refine=refine,
    )
    tr = tracker.trace
    arch = run_archive(res.pymoo_result.algorithm)
    retry = dict(
        approx_shortfall=getattr(arch, "approx_shortfall", None),  # the second search's test
        retry_size=getattr(arch, "retry_size", None),  # (points, finished) when it fired
    )
    if save is not None:
        tracker.dump(res.front.F)
        if F is not None:
            for i, Fi in tracker.fronts:
                tr[i][3] = round(hv_ratio(Fi, F), 6) if len(Fi) else 0.0
            tr[-1][3] = round(hv_ratio(res.front.F, F), 6)
            tr = [row for row in tr if row[3] == row[3]]  # the measured rows (NaN elsewhere)
    ref = F
    if F is None:  # the best known front: the run's own archive at the end
        reference = "final GA front"
        ref = res.front.F
        for row in tr:
            row[3] = None
        for i, Fi in tracker.fronts:
            tr[i][3] = round(hv_ratio(Fi, ref), 6) if len(Fi) else 0.0
        tr[-1][3] = 1.0
        tr = [row for row in tr if row[3] is not None]

    def reach(level):
        for g, t, c, h in tr:
            if h >= level:
                return dict(gen=g, seconds=t, cpu_seconds=c)
        return None

    return dict(
        pop=pop,
        gen_run=len(tracker.trace),
        seed=seed,
        reference=reference,
        ga_seconds=tracker.trace[-1][1] if tr else None,
        ga_cpu_seconds=tracker.trace[-1][2] if tr else None,
        ga_size=len(res.front),
        hv_ratio=hv_ratio(res.front.F, ref),
        coverage=coverage(res.front.F, ref),
        n_eval=res.n_eval,
        to_095=reach(0.95),
        to_099=reach(0.99),
        **retry,
        trace=tr,
    )


def merge_fronts(paths, out):
    """The non-dominated union of the final fronts saved in ``paths``
    (``--save``), written to ``out`` (``.npz``: ``F`` and the sources)."""
    from gapath.metrics import nondominated

    Fs = [np.load(p)["F"] for p in paths]
    allF = np.concatenate(Fs)
    keep = nondominated(allF)
    M = allF[keep]
    M = np.unique(M, axis=0)
    np.savez_compressed(out, F=M, sources=np.array([str(p) for p in paths]))
    return dict(
        merged=str(out),
        sources=[str(p) for p in paths],
        sizes=[len(f) for f in Fs],
        size=len(M),
        hv_ratio_of_each=[round(hv_ratio(f, M), 6) for f in Fs],
    )


def score(saved, ref_file, label):
    """The trace of a saved run (``--save``) against the front in ``ref_file``."""
    z = np.load(saved)
    R = np.load(ref_file)["F"]
    tr = z["trace"].tolist()
    rows = []
    for k in z.files:
        if k.startswith("front_"):
            i = int(k[6:])
            Fi = z[k]
            g, t, c, _ = tr[i]
            rows.append([int(g), t, c, round(hv_ratio(Fi, R), 6) if len(Fi) else 0.0])
    rows.sort()
    final = hv_ratio(z["F"], R)

    def reach(level):
        for g, t, c, h in rows:
            if h >= level:
                return dict(gen=g, seconds=t, cpu_seconds=c)
        return None

    return dict(
        saved=str(saved),
        reference=label,
        reference_file=str(ref_file),
        reference_size=len(R),
        gen_run=int(tr[-1][0]) if tr else 0,
        ga_seconds=tr[-1][1] if tr else None,
        ga_cpu_seconds=tr[-1][2] if tr else None,
        ga_size=len(z["F"]),
        hv_ratio=final,
        coverage=coverage(z["F"], R),
        generation0=rows[0] if rows else None,
        to_095=reach(0.95),
        to_099=reach(0.99),
        trace=rows,
    )


def expansions(ws, n, seed, gens):
    """Why the field decoder's search is close to a Dijkstra: for ``n``
    genomes of a short GA run (the offspring of generation ``gens``, as
    :func:`solve` makes them; ``gens == 0``: uniform random genomes) the share
    of the reachable cells an A* search with the decoder's heuristic must
    expand (``g(s, v) + h(v) <= C*``, exact ``g`` by Dijkstra), the heuristic
    at the start as a share of the true cost-to-go, and the same two for the
    best bound of the weight-bin kind (the exact cost-to-go of ``step + (b /
    (a mmin)) extra``, scaled by ``a mmin``: what costs-to-go cached per
    weight could give at most). Uses scipy's Dijkstra (analysis only)."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import dijkstra

    from gapath.encodings import _free_kernels as K
    from gapath.grid import DC, DR, STEP, move_mask

    problem = FreePathProblem(ws, OBJECTIVES)
    enc = problem.encoding
    gy, gx = enc.field_shape
    h, w = enc.shape
    if gens > 0:
        r = solve(ws, objectives=OBJECTIVES, paths="free", pop_size=200, n_gen=gens, seed=seed)
        alg = r.pymoo_result.algorithm
        X = (alg.off if alg.off is not None else alg.pop).get("X")[:n]
    else:
        X = np.random.default_rng(seed).random((n, problem.n_var))
    occ = enc._occ.ravel()
    rows, cols, ks = [], [], []
    for u in np.flatnonzero(~occ):
        mm = move_mask(occ, h, w, u // w, u % w, enc._cc)
        for k in range(8):
            if (mm >> k) & 1:
                rows.append(u)
                cols.append(u + DR[k] * w + DC[k])
                ks.append(k)
    rows, cols = np.array(rows), np.array(cols)
    steps = np.asarray(STEP)[np.array(ks)]
    # the bilinear field at every cell, as the kernel interpolates it
    rr = np.arange(h) * (gy - 1) / max(h - 1, 1)
    cc = np.arange(w) * (gx - 1) / max(w - 1, 1)
    i0 = np.minimum(rr.astype(int), gy - 2)
    j0 = np.minimum(cc.astype(int), gx - 2)
    ar, ac = (rr - i0)[:, None], (cc - j0)[None, :]
    out = []
    for x in X:
        genes = np.clip(x[:-1], 0, 1).reshape(gy, gx)
        a, b = K._weights.py_func(x[-1], *enc.lam_range)
        g00, g01 = genes[i0][:, j0], genes[i0][:, j0 + 1]
        g10, g11 = genes[i0 + 1][:, j0], genes[i0 + 1][:, j0 + 1]
        f = (1 - ar) * ((1 - ac) * g00 + ac * g01) + ar * ((1 - ac) * g10 + ac * g11)
        m = np.exp(enc.beta * (2 * f.ravel() - 1))
        G = csr_matrix((a * steps * m[cols] + b * enc._extra[cols], (rows, cols)), shape=(h * w, h * w))
        gs = dijkstra(G, indices=enc._s)
        gt = dijkstra(G.T.tocsr(), indices=enc._t)
        C = gs[enc._t]
        mmin = float(np.exp(enc.beta * (2 * genes.min() - 1)))
        hp = a * mmin * enc._hlen + b * enc._hext
        Gl = csr_matrix((steps + b / (a * mmin) * enc._extra[cols], (rows, cols)), shape=(h * w, h * w))
        hb = dijkstra(Gl.T.tocsr(), indices=enc._t) * a * mmin
        reach = np.isfinite(gs)
        out.append(
            dict(
                weight_gene=round(float(x[-1]), 3),
                gene_min=round(float(genes.min()), 3),
                expanded=round(float(np.mean((gs + hp <= C)[reach])), 4),
                h_share=round(float(hp[enc._s] / C), 3),
                bin_expanded=round(float(np.mean((gs + hb <= C)[reach])), 4),
                bin_h_share=round(float(hb[enc._s] / C), 3),
                path_share=round(float(np.mean((gs + gt <= C * (1 + 1e-9))[reach])), 4),
            )
        )
    med = {k: float(np.median([o[k] for o in out])) for k in out[0]}
    return dict(n=len(out), gens=gens, reachable=enc.n_reachable, median=med, genomes=out)


class _Clock(Callback):
    """Wall time after every generation."""

    def __init__(self):
        super().__init__()
        self.t0 = time.perf_counter()
        self.c0 = time.process_time()
        self.times: list[float] = []
        self.cpu: list[float] = []

    def notify(self, algorithm):
        self.times.append(time.perf_counter() - self.t0)
        self.cpu.append(time.process_time() - self.c0)


def throughput(ws, pop, seed, gens):
    problem = FreePathProblem(ws, OBJECTIVES)
    X = np.random.default_rng(seed).random((pop, problem.n_var))
    problem.evaluate(X[:2], return_as_dictionary=True)  # compiled
    problem.encoding._cache.clear()
    t0, c0 = time.perf_counter(), time.process_time()
    problem.evaluate(X, return_as_dictionary=True)
    rate = pop / (time.perf_counter() - t0)
    cpu_rate = pop / (time.process_time() - c0)
    clock = _Clock()
    res = solve(ws, objectives=OBJECTIVES, paths="free", pop_size=pop, n_gen=gens, seed=seed, callback=clock)
    per_gen = np.diff(clock.times)  # generation 1 is the initial population
    cpu_gen = np.diff(clock.cpu)
    return dict(
        threads=search_threads(pop),
        paths_per_second=rate,
        paths_per_cpu_second=cpu_rate,
        n_var=problem.n_var,
        gens=gens,
        first_population_seconds=clock.times[0],
        seconds_per_gen=float(np.median(per_gen)) if len(per_gen) else None,
        gen_seconds=[round(float(x), 3) for x in per_gen],
        cpu_seconds_per_gen=float(np.median(cpu_gen)) if len(cpu_gen) else None,
        ga_size=len(res.front),
    )


def faces(ws, budget=None):
    """Cost of the archive's exact face searches on ``ws``: for each pair of
    :data:`OBJECTIVES` (the archive's order), CPU seconds, points and
    expansions per reachable cell, searched to the end (``budget``: stop a
    search past this many expansions per reachable cell)."""
    from gapath.operators.archive import face_pairs
    from gapath.problems import FreePathProblem

    n = FreePathProblem(ws, OBJECTIVES).encoding.n_reachable
    out = []
    seen: dict = {}

    def hook(info):
        seen.update(info)
        if budget is not None and info["expansions"] > budget * n:
            raise _Stop

    for pair in face_pairs(OBJECTIVES):
        seen.clear()
        c0 = time.process_time()
        try:
            size = len(free_front(ws, pair, progress=hook))
        except _Stop:
            size = None
        out.append(
            dict(
                pair=list(pair),
                cpu_seconds=round(time.process_time() - c0, 3),
                points=size,
                expansions_per_cell=round(seen.get("expansions", 0) / n, 2),
            )
        )
    return dict(reachable=n, faces=out)


def approx(ws, E, epsilons):
    """The approximate three-objective search (``free_front(...,
    epsilon=eps)``) beside the exact faces, as the archive runs them: for
    each ``eps`` its CPU seconds, points, expansions and HV ratio against
    the exact front ``E``, alone and merged with the faces (each face path
    scored on all three objectives), and (``on_faces``) the HV ratio of its
    projection on each pair of objectives against that pair's exact front
    (the face: known at run time, unlike ``E``); the faces' own cost and
    ratio first."""
    from gapath.objectives import evaluate_paths, pad_paths
    from gapath.operators.archive import face_pairs

    c0 = time.process_time()
    face_fronts = {pair: free_front(ws, pair) for pair in face_pairs(OBJECTIVES)}
    face_paths = [p for front in face_fronts.values() for p in front.paths]
    face_cpu = time.process_time() - c0
    P, L = pad_paths(face_paths)  # each face path on all three objectives, as the problem scores it
    M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    FF = FreePathProblem(ws, OBJECTIVES).objective_values(M)
    rows = []
    for eps in epsilons:
        c0 = time.process_time()
        front = free_front(ws, OBJECTIVES, epsilon=eps)
        cpu = time.process_time() - c0
        rows.append(
            dict(
                epsilon=eps,
                cpu_seconds=round(cpu, 3),
                points=len(front),
                expansions=int(front.stats["expansions"]),
                hv_ratio=round(float(hv_ratio(front.F, E)), 6),
                factor=round(cover_factor(front.F, E), 6),
                with_faces=round(float(hv_ratio(np.vstack([FF, front.F]), E)), 6),
                with_faces_cpu_seconds=round(cpu + face_cpu, 3),
                # the approximate front projected on each pair, against that pair's exact front
                on_faces={
                    "/".join(pair): round(
                        float(hv_ratio(front.F[:, [OBJECTIVES.index(o) for o in pair]], face.F)), 6
                    )
                    for pair, face in face_fronts.items()
                },
            )
        )
    return dict(
        exact_size=len(E),
        faces=dict(cpu_seconds=round(face_cpu, 3), paths=len(FF), hv_ratio=round(float(hv_ratio(FF, E)), 6)),
        approx=rows,
    )


def cover_factor(A, E):
    """The least ``f`` such that every point of ``E`` (length, vulnerability,
    smoothness) is covered by a point of ``A`` with at most ``f`` times its
    length and vulnerability and no more turns (inf if none is): the factor
    that ``free_front(..., epsilon=e)`` guarantees to be at most ``1 + e``."""
    worst = 1.0
    for s in range(0, len(E), 500):
        e = E[s : s + 500, None, :]
        ok = A[None, :, 2] <= e[..., 2] + 1e-9
        ratio = np.maximum(
            A[None, :, 0] / np.maximum(e[..., 0], 1e-300), A[None, :, 1] / np.maximum(e[..., 1], 1e-300)
        )
        worst = max(worst, float(np.where(ok, ratio, np.inf).min(axis=1).max()))
    return worst


def density(F, sizes=(250, 500, 1000, 2000, 5000), seed=0):
    """HV ratio of subsets of the exact front ``F``: random ones (3 draws)
    and the crowding truncation the archive's cap uses; how many exact
    points a front needs for a given ratio."""
    from gapath.operators.archive import crowding_truncation

    rng = np.random.default_rng(seed)
    rows = []
    for n in sizes:
        if n >= len(F):
            continue
        rand = [round(hv_ratio(F[rng.choice(len(F), n, replace=False)], F), 5) for _ in range(3)]
        keep = crowding_truncation(F, n)
        rows.append(dict(points=n, random=rand, crowding=round(hv_ratio(F[keep], F), 5)))
    return dict(exact_size=len(F), subsets=rows)


def gap(E, G, parts=5):
    """Where the front ``G`` falls short of the exact front ``E``: for each
    exact point the smallest additive epsilon (objectives normalised by
    ``E``'s ranges) by which some point of ``G`` covers it; its quantiles,
    and its median in each ``1/parts`` quantile band of each objective
    (best band first)."""
    lo, span = E.min(0), np.ptp(E, axis=0)
    span = np.where(span > 0, span, 1.0)
    En, Gn = (E - lo) / span, (G - lo) / span
    eps = np.empty(len(En))
    for s in range(0, len(En), 500):
        eps[s : s + 500] = (Gn[None, :, :] - En[s : s + 500, None, :]).max(axis=2).min(axis=1)
    bands = {}
    for j, name in enumerate(OBJECTIVES):
        q = np.quantile(En[:, j], np.linspace(0, 1, parts + 1))
        band = np.clip(np.searchsorted(q, En[:, j], side="right") - 1, 0, parts - 1)
        bands[name] = [round(float(np.median(eps[band == b])), 4) for b in range(parts)]
    levels = (0.1, 0.5, 0.9, 0.99)
    quant = {str(k): round(float(v), 4) for k, v in zip(levels, np.quantile(eps, levels))}
    return dict(exact_size=len(E), size=len(G), epsilon_quantiles=quant, median_epsilon_by_band=bands)


def archive_variant(text):
    """``K=V,...`` (numbers; ``K=A/B`` a pair) as FreePathArchive keyword arguments, installed
    as the defaults of the archive :func:`gapath.solver.solve` builds; ``{}``
    for None."""
    if not text:
        return {}
    import gapath.operators.archive as archive

    opts = {}
    for item in text.split(","):
        k, _, v = item.partition("=")
        num = [float(x) if any(c in x for c in ".e") else int(x) for x in v.split("/")]
        opts[k.strip()] = tuple(num) if len(num) > 1 else num[0]
    base = archive.FreePathArchive

    class Variant(base):  # type: ignore[misc, valid-type]
        def __init__(self, problem, **kw):
            super().__init__(problem, **{**kw, **opts})

    archive.FreePathArchive = Variant  # solve() imports it at call time
    return opts


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--instances", default="gen128-s1,berlin,gen256-s1")
    ap.add_argument("--pop", type=int, default=200)
    ap.add_argument("--gen", type=int, default=300)
    ap.add_argument(
        "--refine",
        type=int,
        default=None,
        help="archived paths re-routed per generation (solve's refine, gapath solve --refine; default: auto)",
    )
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--ga-cap", type=float, default=900.0, help="stop the GA after this many CPU seconds")
    ap.add_argument("--exact-cap", type=float, default=900.0, help="give up exact search after this many s")
    ap.add_argument(
        "--exact-cpu-cap",
        type=float,
        default=None,
        help="also give up exact search after this many CPU seconds",
    )
    ap.add_argument("--max-labels", type=int, default=80_000_000)
    ap.add_argument("--exact-only", action="store_true")
    ap.add_argument("--faces", action="store_true", help="the cost of the archive's exact face searches")
    ap.add_argument(
        "--face-cap",
        type=float,
        default=100.0,
        help="with --faces: stop a search past this many expansions per cell",
    )
    ap.add_argument(
        "--approx",
        default=None,
        help="EPS,...: the approximate three-objective search at these epsilons, alone and with the faces",
    )
    ap.add_argument("--gap", default=None, help="where a saved run (--save) falls short of the exact front")
    ap.add_argument("--gap-front", default="F", help="with --gap: which saved front (F: the last, front_K)")
    ap.add_argument("--density", action="store_true", help="HV ratio of subsets of the (cached) exact front")
    ap.add_argument("--throughput", action="store_true")
    ap.add_argument("--throughput-gens", type=int, default=3)
    ap.add_argument(
        "--expansions", type=int, default=0, help="analyse the decoder's search on this many genomes"
    )
    ap.add_argument("--expansions-gens", type=int, default=25, help="...of the offspring of this generation")
    ap.add_argument("--cache", default=str(ROOT / "build" / "anytime"))
    ap.add_argument("--data", default=None)
    ap.add_argument("--label", default=None, help="a tag added to every line (e.g. before/after)")
    ap.add_argument("--out", default=None, help="also append the JSON lines to this file")
    ap.add_argument("--progress", default=None, help="append each trace row to PROGRESS.<instance>")
    ap.add_argument(
        "--skip-exact",
        action="store_true",
        help="no exact search (reference: --best-known, else the run's own front)",
    )
    ap.add_argument(
        "--best-known", default=None, help="an .npz (F) used as the reference front: best known, not exact"
    )
    ap.add_argument(
        "--archive",
        default=None,
        metavar="K=V,...",
        help="FreePathArchive keyword arguments for the GA runs (e.g. exact_stretches=8): a variant, recorded",
    )
    ap.add_argument("--save", default=None, help="save each run's fronts to SAVE.<instance>.s<seed>.npz")
    ap.add_argument("--keep", type=int, default=5, help="with --save: keep the front every KEEP generations")
    ap.add_argument(
        "--merge", default=None, help="merge the saved runs given as --instances (.npz paths) into MERGE"
    )
    ap.add_argument(
        "--score", default=None, help="score the saved runs given as --instances against SCORE (.npz)"
    )
    a = ap.parse_args(argv)
    data = data_dir(a.data)
    variant = archive_variant(a.archive)
    out = open(a.out, "a") if a.out else None

    def emit(rec):
        line = json.dumps(rec)
        print(line, flush=True)
        if out:
            out.write(line + "\n")
            out.flush()

    if a.merge:
        emit(dict(merge_fronts(a.instances.split(","), a.merge), label=a.label))
        return 0
    if a.score:
        for p in a.instances.split(","):
            emit(
                dict(
                    score(p, a.score, a.label or "best known front (merged GA runs), not exact"),
                    label=a.label,
                )
            )
        return 0
    for name in a.instances.split(","):
        ws = workspace(name, data)
        if a.faces:
            rec = dict(instance=name, shape=list(ws.shape), label=a.label)
            rec.update(faces(ws, a.face_cap))
        elif a.gap:
            F, rec = exact(name, ws, Path(a.cache), a.exact_cap, a.max_labels, a.exact_cpu_cap)
            z = np.load(a.gap)
            rec = dict(instance=name, label=a.label, run=a.gap, **gap(F, z[a.gap_front]))
        elif a.approx:
            F, rec = exact(name, ws, Path(a.cache), a.exact_cap, a.max_labels, a.exact_cpu_cap)
            rec = {k: rec[k] for k in ("instance", "exact_finished", "exact_cpu_seconds") if k in rec}
            rec["label"] = a.label
            if F is not None:
                rec.update(approx(ws, F, [float(e) for e in a.approx.split(",")]))
        elif a.density:
            F, rec = exact(name, ws, Path(a.cache), a.exact_cap, a.max_labels, a.exact_cpu_cap)
            rec = dict(instance=name, label=a.label, **(density(F) if F is not None else {}))
        elif a.expansions:
            rec = dict(instance=name, shape=list(ws.shape), label=a.label)
            rec.update(expansions(ws, a.expansions, a.seed, a.expansions_gens))
        elif a.throughput:
            rec = dict(instance=name, shape=list(ws.shape), pop=a.pop, label=a.label)
            rec.update(throughput(ws, a.pop, a.seed, a.throughput_gens))
        else:
            reference = "exact"
            if a.skip_exact:
                F, rec = None, dict(instance=name, shape=list(ws.shape), exact_finished=None)
            else:
                F, rec = exact(name, ws, Path(a.cache), a.exact_cap, a.max_labels, a.exact_cpu_cap)
            if F is None and a.best_known:
                F, reference = np.load(a.best_known)["F"], "best known front (merged GA runs), not exact"
            if a.label:
                rec["label"] = a.label
            if variant:
                rec["archive"] = variant
            if not a.exact_only:
                rec["threads"] = wanted_threads()  # GAPATH_THREADS: 1 serial
                progress = f"{a.progress}.{name}" if a.progress else None
                save = f"{a.save}.{name}.s{a.seed}.npz" if a.save else None
                rec["refine"] = "auto" if a.refine is None else a.refine
                rec.update(
                    anytime(
                        ws, F, a.pop, a.gen, a.seed, a.ga_cap, progress, a.keep, save, reference, a.refine
                    )
                )
        emit(rec)
    if out:
        out.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
