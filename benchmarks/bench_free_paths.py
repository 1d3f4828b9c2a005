"""Free-path GA against the exact free front, per encoding (issue 14).

For each MovingAI map and each of its ``--queries`` longest ``.scen`` queries
(by optimal length; MovingAI convention ``corner_cutting=False``), the exact
free front (:func:`gapath.planners.exact.free_front`, objectives length and
vulnerability) is computed, then one GA run per encoding and seeding:
:class:`gapath.algorithms.FastNSGA2` on a
:class:`gapath.problems.FreePathProblem`, population ``--pop`` for ``--gen``
generations, seed ``--seed``, run as ``gapath solve --paths free`` runs it
(:func:`gapath.solver.solve`: FastNSGA2, initial population from
:class:`gapath.operators.sampling.free_sampling.FreeSampling`, ``weighted``:
weighted-sum A* seeds, ``none``: all random; the smoothness tie-break with
two objectives).

Per run one JSON line: map, query, encoding, seeding, exact front size and
seconds, GA front size, ``hv_ratio`` (SPEC normalisation), ``coverage``
(share of exact points matched within the tolerance), GA wall seconds,
seconds per generation, the HV ratio after generations 1, 10, 25, 50, 100,
200 (``hv_at_gen``; of the run's archive, the front ``solve`` returns, when
it keeps one: ``refine`` re-routed paths per generation, ``--refine off``
for the last population's front), the generation and seconds at which it first reached
0.99 and 0.999, and the decode+evaluate throughput (paths per second
over ``--pop * 5`` random genomes, cache cold). Wall-clock times on a shared
machine: noisy.

Besides MovingAI maps (any map of the data folder with a
``-random-1.scen``, e.g. ``den312d``, ``Berlin_1_256``), ``--maps`` takes
generated instances, one query each (start and goal in opposite corners):

``maze-sN``
    :func:`gapath.dynamic.scenarios.complex_maze` with seed ``N``, an 11 x 11
    lattice of 2-cell corridors and 1-cell walls (32 x 32 cells, like
    MovingAI maze-32-32-2), braided until the shortest path is at most 1.6
    times the straight line, start and goal the farthest pair of the
    bottom-left and top-right corridor cells.
``rooms-sN``
    :func:`rooms_map` with seed ``N``: 8 x 8 rooms of 4 x 4 free cells
    behind 1-cell walls (39 x 39 cells), a door of one cell in every wall of
    a random spanning tree of the rooms and in 30 % of the other walls,
    start bottom-left, goal top-right.

Usage::

    python benchmarks/bench_free_paths.py [--maps room-32-32-4,maze-s1,...] [--queries 1]
        [--encodings via,field] [--seed-from weighted,none] [--pop 200] [--gen 200]
        [--objectives length,vulnerability,smoothness]
    python benchmarks/bench_free_paths.py --set two|three|unseeded --encodings field
        [--only-maps den312d,...] --out FILE      (the quality table's sets)
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

from gapath.convergence import HypervolumeRatioCallback
from gapath.dynamic.scenarios import complex_maze
from gapath.loaders import load_movingai, load_scenarios
from gapath.metrics import coverage, hv_ratio
from gapath.planners.exact import free_front
from gapath.problems import FreePathProblem
from gapath.solver import solve
from gapath.workspace import Workspace

ROOT = Path(__file__).resolve().parents[1]
MAPS = ("room-32-32-4", "maze-32-32-2", "random-32-32-20", "random-64-64-10")
_GEN = ("maze-s1", "maze-s2", "maze-s3", "rooms-s1", "rooms-s2", "rooms-s3")
#: The quality table's sets (docs/results/free_paths.md, "Quality table: every
#: instance"): name -> (objectives, seed_from, [(map, queries), ...]).
SETS = {
    "two": (
        "length,vulnerability",
        "weighted",
        [(m, 5) for m in (*MAPS, "den312d")] + [("Berlin_1_256", 1)] + [(g, 1) for g in _GEN],
    ),
    "three": (
        "length,vulnerability,smoothness",
        "weighted",
        [("random-32-32-20", 5), ("random-64-64-10", 5)]
        + [(m, 1) for m in ("den312d", "room-32-32-4", "maze-32-32-2", "maze-s1", "rooms-s1")],
    ),
    "unseeded": (
        "length,vulnerability",
        "none",
        [(m, 1) for m in (*MAPS, "den312d", "maze-s1", "rooms-s1")],
    ),
}


def data_dir(arg=None) -> Path:
    if arg:
        return Path(arg)
    env = os.environ.get("GAPATH_SHARED_DATA")
    base = Path(env) if env else ROOT.parent / "shared" / "data"
    return base / "movingai" / "mapf"


def rooms_map(seed: int, rooms: int = 8, inner: int = 4, extra: float = 0.3) -> Workspace:
    """A generated room map (see the module docstring): ``rooms x rooms``
    rooms of ``inner x inner`` free cells, 1-cell walls, one door per wall of
    a random spanning tree (depth-first) plus ``extra`` of the other walls."""
    rng = np.random.default_rng(seed)
    p = inner + 1
    n = rooms * p - 1
    occ = np.zeros((n, n), bool)
    for i in range(1, rooms):
        occ[i * p - 1, :] = True
        occ[:, i * p - 1] = True

    def door(a, b):
        (i1, j1), (i2, j2) = sorted((a, b))
        k = int(rng.integers(inner))
        if i1 == i2:
            occ[i1 * p + k, j2 * p - 1] = False
        else:
            occ[i2 * p - 1, j1 * p + k] = False

    seen = np.zeros((rooms, rooms), bool)
    stack, tree = [(rooms - 1, 0)], set()
    seen[rooms - 1, 0] = True
    while stack:
        i, j = stack[-1]
        nb = [
            (i + a, j + b)
            for a, b in ((0, 1), (1, 0), (0, -1), (-1, 0))
            if 0 <= i + a < rooms and 0 <= j + b < rooms and not seen[i + a, j + b]
        ]
        if not nb:
            stack.pop()
            continue
        nxt = nb[int(rng.integers(len(nb)))]
        door((i, j), nxt)
        tree.add(tuple(sorted(((i, j), nxt))))
        seen[nxt] = True
        stack.append(nxt)
    for i in range(rooms):
        for j in range(rooms):
            for nxt in ((i, j + 1), (i + 1, j)):
                if nxt[0] < rooms and nxt[1] < rooms and tuple(sorted(((i, j), nxt))) not in tree:
                    if rng.random() < extra:
                        door((i, j), nxt)
    return Workspace(occ, (n - 1, 0), (0, n - 1), corner_cutting=False, name=f"rooms-s{seed}")


class _Query:
    """A generated instance's one query."""

    def __init__(self, ws):
        self.start, self.goal, self.optimal = ws.start, ws.goal, None


def generated(name: str):
    """The workspace of a generated instance name, or None."""
    kind, _, s = name.rpartition("-s")
    if not s.isdigit():
        return None
    if kind == "maze":
        return complex_maze(int(s), rows=11, cols=11, corridor=2, max_detour=1.6, target_distance=1e6)
    if kind == "rooms":
        return rooms_map(int(s))
    return None


def instances(folder: Path, name: str, n: int):
    """``(query, workspace)`` pairs of a map name (see the module docstring)."""
    ws = generated(name)
    if ws is not None:
        return [(_Query(ws), ws)]
    out = []
    for sc in long_queries(folder, name, n):
        ws = load_movingai(folder / f"{name}.map", start=sc.start, goal=sc.goal, corner_cutting=False)
        out.append((sc, ws))
    return out


def long_queries(folder: Path, name: str, n: int):
    """The ``n`` longest queries of the map's scenario file (distinct pairs)."""
    scen = sorted(load_scenarios(folder / f"{name}-random-1.scen"), key=lambda s: -s.optimal)
    out, seen = [], set()
    for s in scen:
        if (s.start, s.goal) not in seen:
            seen.add((s.start, s.goal))
            out.append(s)
        if len(out) == n:
            break
    return out


def throughput(problem, n: int, seed: int) -> float:
    X = np.random.default_rng(seed).random((n, problem.n_var))
    problem.encoding._cache.clear()
    t0 = time.perf_counter()
    problem.evaluate(X, return_as_dictionary=True)
    return n / (time.perf_counter() - t0)


class _Timed(HypervolumeRatioCallback):
    """The HV ratio every generation, with the wall time since the start."""

    def __init__(self, reference, progress=None, label=None):
        super().__init__(reference)
        self.t0 = time.perf_counter()
        self.seconds = []
        self.progress, self.label = progress, label

    def notify(self, algorithm):
        super().notify(algorithm)
        self.seconds.append(time.perf_counter() - self.t0)
        g, _, h = self.history[-1]
        if self.progress and (g in (1, 10, 25, 50, 100, 150, 200, 500) or g % 20 == 0):
            with open(self.progress, "a") as f:  # partial figures of a run that may not finish
                f.write(
                    json.dumps(dict(self.label or {}, gen=g, hv_ratio=h, seconds=self.seconds[-1])) + "\n"
                )


def run(
    ws,
    ref,
    objectives,
    encoding,
    seed_from,
    pop,
    gen,
    seed,
    options,
    refine=None,
    progress=None,
    label=None,
    save=None,
):
    problem = FreePathProblem(ws, objectives, encoding=encoding, **options)
    rate = throughput(problem, 5 * pop, seed)
    tracker = _Timed(ref, progress, label)
    res = solve(
        ws,
        objectives=objectives,
        paths="free",
        encoding=encoding,
        pop_size=pop,
        n_gen=gen,
        seed=seed,
        seed_from=seed_from,
        callback=tracker,
        tiebreak="smoothness" if len(objectives) == 2 else None,
        refine=refine,
    )
    front = res.front
    if save:
        np.savez_compressed(save, exact=ref.F, ga=front.F)
    hist = tracker.history
    checkpoints = {str(g): round(hist[g - 1][2], 6) for g in (1, 10, 25, 50, 100, 200, 500) if g <= len(hist)}

    def reach(level):
        for (g, _, h), t in zip(hist, tracker.seconds):
            if h >= level:
                return [g, round(t, 3)]
        return None

    return dict(
        encoding=encoding,
        n_var=problem.n_var,
        seed_from=seed_from,
        pop=pop,
        gen=gen,
        seed=seed,
        refine=res.settings.get("refine", False),
        ga_size=len(front),
        hv_ratio=hv_ratio(front.F, ref.F),
        coverage=coverage(front.F, ref.F),
        ga_seconds=res.seconds,
        seconds_per_gen=res.seconds / gen,
        paths_per_second=rate,
        n_eval=res.n_eval,
        hv_at_gen=checkpoints,
        gen_seconds_to_099=reach(0.99),
        gen_seconds_to_0999=reach(0.999),
    )


def summary(path) -> str:
    """A Markdown table of the JSON lines in ``path`` (one row per run)."""
    rows = [
        "| map | query | objectives | encoding | seeds | exact points | GA points | HV ratio "
        "| coverage | HV at gen 1 / 10 / 50 | s/gen | paths/s |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for line in open(path):
        d = json.loads(line)
        h = d.get("hv_at_gen", {})
        at = " / ".join(f"{h[g]:.4f}" if g in h else "-" for g in ("1", "10", "50"))
        rows.append(
            f"| {d['map']} | {d['query']} | {len(d.get('objectives', [0, 0]))} "
            f"| {d['encoding']} | {d['seed_from']} | {d['exact_size']} | {d['ga_size']} "
            f"| {d['hv_ratio']:.6f} | {d['coverage']:.3f} | {at} "
            f"| {d['seconds_per_gen']:.3f} | {d['paths_per_second']:.0f} |"
        )
    return "\n".join(rows)


def _rows(path):
    out = {}
    for line in open(path):
        d = json.loads(line)
        out[(d["map"], d["query"], len(d["objectives"]), d["seed_from"])] = d
    return out


def compare(before, after) -> str:
    """A Markdown table, one row per instance of ``after`` (JSON lines),
    beside the same instance in ``before`` when it has it; then the median
    and range of the HV ratios and of the shares of points found."""
    b = {}
    for path in before.split(",") if before else ():  # later files override earlier ones
        b.update(_rows(path))
    a = _rows(after)
    rows = [
        "| map | query | exact points | HV ratio before | found before | HV ratio after | found after "
        "| GA points | HV at gen 1 | s/gen |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]

    def found(d):
        return f"{100 * d['coverage']:.0f} % ({round(d['coverage'] * d['exact_size'])})"

    for k, d in a.items():
        o = b.get(k)
        was = "| - | - " if o is None else f"| {o['hv_ratio']:.6f} | {found(o)} "
        rows.append(
            f"| {d['map']} | {d['query']} | {d['exact_size']} "
            + was
            + f"| {d['hv_ratio']:.6f} | {found(d)} | {d['ga_size']} | {d['hv_at_gen'].get('1', float('nan')):.4f} "
            f"| {d['seconds_per_gen']:.2f} |"
        )
    hv = np.array([d["hv_ratio"] for d in a.values()])
    cov = np.array([d["coverage"] for d in a.values()])
    rows.append(
        f"| **all {len(a)}** | | | | | median **{np.median(hv):.6f}**, min **{hv.min():.6f}** "
        f"| median {100 * np.median(cov):.0f} %, min {100 * cov.min():.0f} % | | | |"
    )
    return "\n".join(rows)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--summary", metavar="JSONL", help="print a Markdown table of a results file and exit")
    ap.add_argument(
        "--compare",
        nargs=2,
        metavar=("BEFORE", "AFTER"),
        help="print a before/after Markdown table of results files and exit (BEFORE: comma-separated files or '-')",
    )
    ap.add_argument(
        "--set",
        default=None,
        choices=sorted(SETS),
        help="run one of the quality table's sets (overrides --maps, --queries, --objectives, --seed-from)",
    )
    ap.add_argument("--only-maps", default=None, help="with --set: run only these maps of the set")
    ap.add_argument("--maps", default=",".join(MAPS))
    ap.add_argument("--queries", type=int, default=1)
    ap.add_argument(
        "--only", default=None, help="comma-separated indices among the --queries longest (e.g. 3,4)"
    )
    ap.add_argument("--encodings", default="via,field")
    ap.add_argument("--seed-from", default="weighted,none")
    ap.add_argument("--pop", type=int, default=200)
    ap.add_argument("--gen", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--objectives", default="length,vulnerability")
    ap.add_argument("--n-via", type=int, default=None)
    ap.add_argument("--data", default=None)
    ap.add_argument(
        "--refine",
        default=None,
        help="re-routed archive paths per generation (default: solve's, pop // 2; 'off': no archive)",
    )
    ap.add_argument("--progress", default=None, help="append the HV ratio every 20 generations to this file")
    ap.add_argument("--out", default=None, help="also append the JSON lines to this file")
    ap.add_argument(
        "--exact-stretches",
        type=int,
        default=None,
        help="exact stretch searches per generation in the archive (gapath.operators.archive.EXACT_STRETCHES)",
    )
    ap.add_argument(
        "--save-fronts", default=None, help="save each run's GA and exact F to DIR/MAP-qQ-mM-SEEDS.npz"
    )
    a = ap.parse_args(argv)
    if a.summary:
        print(summary(a.summary))
        return 0
    if a.compare:
        print(compare(None if a.compare[0] == "-" else a.compare[0], a.compare[1]))
        return 0
    folder = data_dir(a.data)
    if a.exact_stretches is not None:
        from gapath.operators import archive

        archive.EXACT_STRETCHES = a.exact_stretches
    out = open(a.out, "a") if a.out else None
    options = {} if a.n_via is None else {"n_via": a.n_via}
    if a.set:
        a.objectives, a.seed_from, plan = SETS[a.set]
        if a.only_maps:
            want = a.only_maps.split(",")
            plan = sorted((p for p in plan if p[0] in want), key=lambda p: want.index(p[0]))
    else:
        plan = [(name, a.queries) for name in a.maps.split(",")]
    for name, n_queries in plan:
        for q, (sc, ws) in enumerate(instances(folder, name, n_queries)):
            if a.only is not None and q not in {int(i) for i in a.only.split(",")}:
                continue
            t0 = time.perf_counter()
            objectives = tuple(a.objectives.split(","))
            ref = free_front(ws, objectives)
            exact_s = time.perf_counter() - t0
            for enc in a.encodings.split(","):
                for sf in a.seed_from.split(","):
                    opts = options if enc == "via" else {}
                    rec = dict(
                        map=name,
                        query=q,
                        objectives=list(objectives),
                        start=list(sc.start),
                        goal=list(sc.goal),
                        optimal=sc.optimal,
                        exact_size=len(ref),
                        exact_seconds=exact_s,
                    )
                    if a.exact_stretches is not None:
                        rec["exact_stretches"] = a.exact_stretches
                    refine = None if a.refine is None else (False if a.refine == "off" else int(a.refine))
                    rec.update(
                        run(
                            ws,
                            ref,
                            objectives,
                            enc,
                            sf,
                            a.pop,
                            a.gen,
                            a.seed,
                            opts,
                            refine,
                            a.progress,
                            dict(map=name, query=q, exact_size=len(ref)),
                            None
                            if not a.save_fronts
                            else os.path.join(a.save_fronts, f"{name}-q{q}-m{len(objectives)}-{sf}.npz"),
                        )
                    )
                    line = json.dumps(rec)
                    print(line, flush=True)
                    if out:
                        out.write(line + "\n")
                        out.flush()
    if out:
        out.close()


if __name__ == "__main__":
    sys.exit(main())
