"""The penalty decides the unseeded GA: a sweep over obstacle handlings.

Two measurements per handling (a fixed penalty per interfering cell, or
``adaptive``: :class:`gapath.constraints.AdaptivePenalty` from 1000):

* ``fig3``: Ahmed & Deb's Fig. 3 set-up (pop 500 x 500 generations,
  all-random first population) through the encodings study
  (:func:`gapath.studies.encodings.run`, protocol ``seeds``): the
  per-run hypervolume ratio against the exact column-monotone front, per
  encoding, on the bundled map (it keeps a 60-cell free corridor along the
  bottom and right edges) and on corridor-free maps with the same 173
  obstacles (:func:`corridor_free_workspace`).
* ``table1``: Ahmed & Deb's Table 1 set-up through the dense study
  (:func:`gapath.studies.dense.table1_spec` run by
  :func:`gapath.experiments.runner.run_one`: integer encoding, pop 200, at
  most 500 generations, stopped at the first feasible path, all-random first
  population, fast engine): success per map.

Prints one JSON line per run. ``--report FILE`` turns the lines into
``docs/results/penalty.md``. Usage::

    python benchmarks/bench_penalty.py [--parts fig3,table1] [--fig3-seeds 5] > penalty.jsonl
    python benchmarks/bench_penalty.py --report penalty.jsonl --out docs/results/penalty.md
"""

from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np

from gapath import Workspace, default_workspace
from gapath.errors import NoPathError

#: The handlings swept: fixed penalties (the issue's values), then adaptive.
HANDLINGS = (1000.0, 3.0, 1.0, 0.3, 0.1, 0.01, "adaptive")
FIG3_ENCODINGS = ("integer", "mixed", "binary")
#: Table 1 rows: (grid, p0).
TABLE1_ROWS = ((32, 0.3), (32, 0.6), (32, 0.8))


def corridor_free_workspace(seed: int, shape=(32, 32), n_obstacles: int = 173) -> Workspace:
    """``n_obstacles`` obstacles drawn uniformly over every cell but the
    start and the goal (no path kept free), redrawn from the same generator
    until a feasible column-monotone path exists. Seeded.

    The bundled map was made by drawing a random monotone path first and
    keeping it free (``random_workspace``): its 60-cell corridor hugs the
    bottom and right edges. These maps have the same obstacle count and no
    such corridor.
    """
    from gapath.planners.exact import monotone_front

    h, w = shape
    start, goal = (h - 1, 0), (0, w - 1)
    cells = np.array([i for i in range(h * w) if i not in (start[0] * w + start[1], goal[0] * w + goal[1])])
    rng = np.random.default_rng(seed)
    for attempt in range(1, 1001):
        occ = np.zeros(h * w, bool)
        occ[rng.choice(cells, size=n_obstacles, replace=False)] = True
        ws = Workspace(occ.reshape(h, w), start, goal, name=f"nocorridor-{h}x{w}-{n_obstacles}-s{seed}")
        try:
            monotone_front(ws, ("length",))
        except NoPathError:
            continue
        ws.attempts = attempt
        return ws
    raise RuntimeError(f"no feasible monotone map in 1000 draws (seed {seed})")


def _handling_label(h) -> str:
    return h if isinstance(h, str) else f"penalty {h:g}"


def fig3(maps, seeds: int, handlings=HANDLINGS, encodings=FIG3_ENCODINGS, emit=print, first_seed=1):
    from gapath.studies.encodings import run

    for ws in maps:
        for h in handlings:
            info = {}

            def on_run(key, r, info=info):
                A = r.pymoo_result.algorithm
                ch = getattr(A, "constraint_handling", None)
                info.setdefault(key, []).append(
                    dict(
                        seed=r.settings["seed"],
                        seconds=round(r.seconds, 3),
                        # interfering == 0: CV is 0 for every row in penalty mode
                        feasible_share=round(float(np.mean(A.arrays.data["interfering"] == 0)), 4),
                        final_penalty=None if ch is None else ch.value,
                        front_size=len(r.front),
                    )
                )

            res = run(
                ws,
                runs=seeds,
                seed=first_seed,
                encodings=encodings,
                protocols=("seeds",),
                penalties=(h,),
                on_run=on_run,
            )
            for key, hvs in res["per_run"].items():
                for hv, extra in zip(hvs, info[key]):
                    emit(
                        json.dumps(
                            dict(
                                part="fig3",
                                map=ws.name,
                                obstacles=int(ws.n_obstacles),
                                handling=_handling_label(h),
                                encoding=key[2],
                                hv_ratio=round(hv, 6),
                                **extra,
                            )
                        )
                    )
                    sys.stdout.flush()


def table1(rows, map_seeds, seeds: int, handlings=HANDLINGS, emit=print):
    from gapath.experiments.spec import ExperimentSpec
    from gapath.studies.dense import table1_spec

    for grid, p0 in rows:
        for m in map_seeds:
            for h in handlings:
                d = table1_spec((grid,), (p0,), seeds, map_seed=m, engine="fast").to_dict()
                if isinstance(h, str):  # a named adaptive handling
                    d["settings"].update(constraints="adaptive", penalty=1000.0)
                else:
                    d["settings"].update(constraints="penalty", penalty=float(h))
                for run in ExperimentSpec.from_dict(d).runs():
                    r = _run_one(run, h)
                    if r["status"] != "ok":
                        raise RuntimeError(r["error"])
                    ind = r["indicators"]
                    emit(
                        json.dumps(
                            dict(
                                part="table1",
                                grid=grid,
                                p0=p0,
                                map_seed=m,
                                obstacles=ind["n_obstacles"],
                                handling=_handling_label(h),
                                encoding="integer",
                                seed=r["seed"],
                                success=bool(ind["feasible"]),
                                first_feasible_gen=ind.get("first_feasible_gen"),
                                seconds=round(r["runtime"]["seconds"], 3),
                            )
                        )
                    )
                    sys.stdout.flush()


def _run_one(run, handling):
    """The dense study's ``run_one``; a named adaptive handling other than
    ``adaptive`` reaches ``solve`` through its ``adaptive_penalty``."""
    from unittest import mock

    from gapath import solver
    from gapath.constraints import HANDLINGS
    from gapath.experiments.runner import run_one

    if not isinstance(handling, str) or not HANDLINGS[handling]:
        return run_one(run)
    solve = solver.solve

    def with_handling(*args, **kwargs):
        return solve(*args, adaptive_penalty=HANDLINGS[handling], **kwargs)

    with mock.patch.object(solver, "solve", with_handling):
        return run_one(run)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--parts", default="fig3,table1")
    ap.add_argument("--fig3-seeds", type=int, default=5, help="GA seeds per map and encoding")
    ap.add_argument("--fig3-first-seed", type=int, default=1, help="the first of them (default 1)")
    ap.add_argument(
        "--fig3-maps",
        default="bundled,1,2",
        help="'bundled' (the bundled map) and corridor-free map seeds, comma-separated",
    )
    ap.add_argument("--table1-maps", default="1-5", help="dense map seeds")
    ap.add_argument("--table1-seeds", type=int, default=10, help="GA seeds 1..N per map")
    ap.add_argument(
        "--table1-rows", default=",".join(f"{g}:{p:g}" for g, p in TABLE1_ROWS), help="GRID:P0,..."
    )
    ap.add_argument("--handlings", default=",".join(_handling_label(h).split()[-1] for h in HANDLINGS))
    ap.add_argument("--encodings", default=",".join(FIG3_ENCODINGS))
    ap.add_argument(
        "--repair",
        help="a repair of gapath.operators.repair.feasible.REPAIRS for every run (solve's repair=); "
        "each line then carries it",
    )
    ap.add_argument("--report", help="JSON lines to turn into penalty.md (no runs)")
    ap.add_argument("--fresh", help="JSON lines of a check on fresh GA seeds (with --report)")
    ap.add_argument("--out", default="docs/results/penalty.md")
    args = ap.parse_args(argv)
    if args.report:
        from penalty_report import write_report

        write_report(args.report, args.out, args.fresh)
        return 0
    handlings = tuple(h if h.startswith("adaptive") else float(h) for h in args.handlings.split(","))
    emit = with_repair(args.repair) if args.repair else print
    parts = args.parts.split(",")
    t0 = time.perf_counter()
    if "fig3" in parts:
        names = args.fig3_maps.split(",")
        maps = [default_workspace()] if "bundled" in names else []
        maps += [corridor_free_workspace(s) for s in _seeds(",".join(n for n in names if n != "bundled"))]
        fig3(
            maps,
            args.fig3_seeds,
            handlings,
            tuple(args.encodings.split(",")),
            emit=emit,
            first_seed=args.fig3_first_seed,
        )
    if "table1" in parts:
        rows = [(int(g), float(p)) for g, p in (x.split(":") for x in args.table1_rows.split(","))]
        table1(rows, _seeds(args.table1_maps), args.table1_seeds, handlings, emit=emit)
    print(json.dumps({"part": "wall", "seconds": round(time.perf_counter() - t0, 1)}))
    return 0


def with_repair(name: str):
    """Every later ``solver.solve`` call (the studies' runs) gets
    ``repair=name``; returns the ``emit`` that adds ``repair`` to each line."""
    from gapath import solver
    from gapath.operators.repair.feasible import make_repair

    make_repair(name)  # an unknown name fails here, before any run
    solve = solver.solve

    def solve_with_repair(*args, **kwargs):
        return solve(*args, repair=name, **kwargs)

    solver.solve = solve_with_repair

    def emit(line):
        print(json.dumps({**json.loads(line), "repair": name}))

    return emit


def _seeds(text: str) -> list[int]:
    out = []
    for part in filter(None, text.split(",")):
        a, _, b = part.partition("-")
        out += range(int(a), int(b or a) + 1)
    return out


if __name__ == "__main__":
    sys.exit(main())
