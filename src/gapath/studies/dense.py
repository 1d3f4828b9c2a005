"""Ahmed & Deb's dense-obstacle experiment (2013, section 6, Table 1).

Protocol: a random column-monotone path from start to goal is drawn first,
then every other cell becomes an obstacle with probability ``p0``
(:func:`gapath.dense_workspace`); grids 8, 16 and 32, ``p0`` = 0.1 .. 1.0;
the two-objective NSGA-II (length, vulnerability; integer encoding; penalty
handling) with population 200 runs for at most 500 generations and stops at
the first feasible path. The initial population is all random
(``seed_from="none"``), as in the paper. Noted per row: the success
percentage, the median generation of the first feasible path (over the
successful runs; pymoo's count, 1 = the initial population) and the mean
minimum path length (the shortest feasible path at that generation,
averaged over the successful runs).

*One map per row, 100 GA runs on it.* The paper says "for each problem, 100
runs are taken", gives one integer obstacle count per row (a map's count,
not a mean), repeats the same minimum lengths down the rows of a grid (one
random path, more obstacles around it as ``p0`` grows) and treats its
64x64 case as one map solved in several runs ("the same problem is solved
later ... feasible paths are found in 80 % runs"). So a row here is one map,
``dense_workspace(grid, p0, map_seed)``, with GA seeds 1..100; the map seed
is :data:`MAP_SEED` (= 1, the experiment's first seed, fixed before any run
was made) for every row, so the maps of a grid are nested like the paper's.
Which map a row gets matters (a few maps trap this GA), so the report also
gives the rows on further map seeds (``--map-seeds``) and the variant with
a new map for every run (``map_seed="run"``, ``--per-run-maps``: the
expected success over random maps). The choice is recorded in
``docs/CONVENTIONS.md``.

Then the larger grids with population 500 (same stop rule, 500 generations
at most), again one map each: 64x64 with about 791 obstacles and 128x128
with about 4,979, the counts the paper reports. ``dense_workspace`` takes a
probability, not a count: :func:`p0_for_obstacles` picks ``p0 = target /
(n^2 - E[path cells])``, the expected number of path cells being measured
over 2,000 random paths of the generator (64x64: 139.1 cells, ``p0 =
0.200``, 791 obstacles expected; 128x128: 287.1 cells, ``p0 = 0.309``,
4,974 expected).

:func:`table1_spec` and :func:`large_spec` build the experiment specs;
:func:`dense_report` turns their stores into ``dense.md``, ``dense.csv``
and ``dense.png`` beside the paper's numbers (:data:`PAPER_TABLE1`).
``gapath experiment dense [--quick] --out DIR`` does all of it.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np

from gapath.experiments.spec import ExperimentSpec

__all__ = [
    "LARGE",
    "MAP_SEED",
    "P0S",
    "PAPER_LARGE",
    "PAPER_TABLE1",
    "dense_report",
    "large_spec",
    "map_seed_of",
    "p0_for_obstacles",
    "paper_row",
    "table1_spec",
    "unsuccessful_runs",
]

#: Obstacle probabilities of Table 1.
P0S = (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)

_PAPER = """grid,p0,obstacles,success_pct,median_generations,mean_min_path_length
8,0.1,4,100,2,9.90
8,0.2,10,100,2,10.49
8,0.3,15,100,2,10.49
8,0.4,20,100,2,10.49
8,0.5,26,100,5,11.07
8,0.6,31,100,4,11.07
8,0.7,40,100,5,11.07
8,0.8,43,100,6,11.07
8,0.9,50,100,7,11.07
8,1.0,54,100,7,11.07
16,0.1,24,100,2,21.21
16,0.2,47,100,5,22.14
16,0.3,65,100,9,23.3
16,0.4,80,100,18,22.34
16,0.5,115,100,28,22.37
16,0.6,150,100,22,22.57
16,0.7,164,100,25,22.3
16,0.8,286,100,40,22.13
16,0.9,214,100,41,22.48
16,1.0,233,100,46,22.4
32,0.1,81,100,6,47.08
32,0.2,173,100,16,53.4
32,0.3,253,97,38,53.72
32,0.4,386,85,73,53.61
32,0.5,470,36,230,54.38
32,0.6,556,74,144,53.64
32,0.7,666,41,295,53.9
32,0.8,767,52,298,54.31
32,0.9,870,39,378,54.13
32,1.0,967,30,339,54.19
"""

#: Ahmed & Deb, Table 1 (shared/seeds/FIGURES.md): ``{(grid, p0): {obstacles,
#: success_pct, median_generations, mean_min_path_length}}``. (The 16x16
#: p0 = 0.8 row reads 286 obstacles, probably a misprint.)
PAPER_TABLE1 = {
    (int(r["grid"]), float(r["p0"])): {
        "obstacles": int(r["obstacles"]),
        "success_pct": float(r["success_pct"]),
        "median_generations": float(r["median_generations"]),
        "mean_min_path_length": float(r["mean_min_path_length"]),
    }
    for r in csv.DictReader(io.StringIO(_PAPER))
}

#: The paper's larger grids: obstacle counts and outcomes (pop 500, 500 gen).
PAPER_LARGE = {
    64: {"obstacles": 791, "outcome": "feasible paths in 80 % of runs"},
    128: {"obstacles": 4979, "outcome": "a feasible path found"},
}

#: The larger grids as run here: side -> p0 (from :func:`p0_for_obstacles`).
LARGE = {64: 0.200, 128: 0.309}

#: The map seed of every row: ``dense_workspace(grid, p0, MAP_SEED)``.
MAP_SEED = 1


def paper_row(grid: int, p0: float) -> dict | None:
    """The paper's Table 1 row for ``(grid, p0)``, or None."""
    return PAPER_TABLE1.get((int(grid), round(float(p0), 1)))


def p0_for_obstacles(n: int, target: int, samples: int = 2000, decimals: int = 3) -> float:
    """The ``p0`` for which ``dense_workspace(n, p0, seed)`` has ``target``
    obstacles on average: ``target / (n * n - E[path cells])``, the mean
    length of the generator's random path measured over ``samples`` seeds.

    Examples
    --------
    >>> p0_for_obstacles(64, 791, samples=200)
    0.2
    """
    from gapath.generators import random_monotone_path

    cells = [
        len(random_monotone_path((n, n), (n - 1, 0), (0, n - 1), np.random.default_rng(s)))
        for s in range(samples)
    ]
    return round(target / (n * n - float(np.mean(cells))), decimals)


def _map_seed(map_seed):
    if map_seed == "run":
        return "run"
    if isinstance(map_seed, bool) or not isinstance(map_seed, (int, np.integer)) or map_seed < 0:
        raise ValueError(f"map_seed: expected a non-negative integer or 'run', got {map_seed!r}")
    return int(map_seed)


def table1_spec(
    grids=(8, 16, 32),
    p0s=P0S,
    runs: int = 100,
    *,
    pop_size: int = 200,
    n_gen: int = 500,
    engine: str = "fast",
    first_seed: int = 1,
    name: str = "dense-table1",
    seed_from: str = "none",
    map_seed: int | str = MAP_SEED,
) -> ExperimentSpec:
    """The Table 1 experiment: ``grids x p0s`` rows, each one map
    ``dense_workspace(grid, p0, map_seed)`` solved by ``runs`` seeded GA runs
    (seeds ``first_seed, ...``), NSGA-II with ``pop_size`` for at most
    ``n_gen`` generations, stopped at the first feasible path, with an
    unseeded initial population (``seed_from="none"``, the paper's protocol;
    ``"weighted"`` etc. give the planner-seeded variant, reported beside it).
    ``map_seed="run"``: a new map for every run (map seed = run seed).

    Raises
    ------
    ValueError
        If ``map_seed`` is neither a non-negative integer nor ``"run"``.

    Examples
    --------
    >>> spec = table1_spec(grids=(8,), p0s=(0.5,), runs=3)
    >>> len(spec), spec.runs()[0]["settings"]["pop_size"], spec.runs()[0]["settings"]["seed_from"]
    (3, 200, 'none')
    >>> [(r["map"]["dense"]["seed"], r["seed"]) for r in spec.runs()]
    [(1, 1), (1, 2), (1, 3)]
    >>> [r["map"]["dense"]["seed"] for r in table1_spec((8,), (0.5,), 2, map_seed="run").runs()]
    ['run', 'run']
    """
    mseed = _map_seed(map_seed)
    maps = [{"dense": {"n": int(n), "p0": float(p0), "seed": mseed}} for n in grids for p0 in p0s]
    per = "a new map per run (map seed = run seed)" if mseed == "run" else f"map seed {mseed}"
    return ExperimentSpec(
        name=name,
        description="Ahmed & Deb 2013, Table 1: dense random obstacles, stop at the first "
        f"feasible path; {per} (gapath.studies.dense).",
        maps=maps,
        encodings=["integer"],
        engines=[engine],
        settings=dict(objectives="length,vulnerability", pop_size=pop_size, n_gen=n_gen, seed_from=seed_from),
        seeds={"start": first_seed, "count": runs},
        options={"stop_at_first_feasible": True},
    )


def large_spec(
    sizes=(64, 128),
    runs: int = 10,
    *,
    pop_size: int = 500,
    n_gen: int = 500,
    engine: str = "fast",
    first_seed: int = 1,
    name: str = "dense-large",
    map_seed: int | str = MAP_SEED,
) -> ExperimentSpec:
    """The larger grids: ``sizes`` from :data:`LARGE` (p0 for the paper's
    obstacle counts), one map each (``map_seed``; ``"run"``: a new map per
    run), ``runs`` GA runs, population ``pop_size``, at most ``n_gen``
    generations, stopped at the first feasible path.

    Examples
    --------
    >>> [r["map"]["dense"] for r in large_spec((64,), 1).runs()]
    [{'n': 64, 'p0': 0.2, 'seed': 1}]
    """
    mseed = _map_seed(map_seed)
    maps = [{"dense": {"n": int(n), "p0": LARGE[int(n)], "seed": mseed}} for n in sizes]
    return ExperimentSpec(
        name=name,
        description="Ahmed & Deb 2013, section 6: 64x64 (791 obstacles) and 128x128 (4,979 "
        "obstacles), population 500, stop at the first feasible path.",
        maps=maps,
        encodings=["integer"],
        engines=[engine],
        settings=dict(objectives="length,vulnerability", pop_size=pop_size, n_gen=n_gen, seed_from="none"),
        seeds={"start": first_seed, "count": runs},
        options={"stop_at_first_feasible": True},
    )


def map_seed_of(store_dir):
    """The map seed of a dense store's rows (an int, or ``"run"`` when every
    run has its own map; None for a store of mixed or non-dense maps)."""
    from gapath.experiments.store import ResultStore

    seeds = {
        m["dense"]["seed"] if isinstance(m, dict) and "dense" in m else None
        for m in ResultStore(store_dir).spec().to_dict()["maps"]
    }
    return seeds.pop() if len(seeds) == 1 else None


# ---------------------------------------------------------------------------
# the report
# ---------------------------------------------------------------------------


def _widened_spec(store) -> ExperimentSpec:
    """The store's spec with every stored seed (see :func:`_rows`)."""
    norm = store.spec().to_dict()
    norm["seeds"] = sorted(set(norm["seeds"]) | {store.read(k)["seed"] for k in store.done_keys()})
    return ExperimentSpec.from_dict(norm)


def _rows(store_dir) -> list[dict]:
    """One row per map configuration of a dense store, over every stored
    seed (the saved spec's seeds and those of earlier, larger or smaller,
    invocations: the runs of a row are the same computations whatever the
    seed list, so a store filled by ``--runs 10`` then ``--runs 100`` is one
    table)."""
    from gapath.experiments.report import configuration_rows
    from gapath.experiments.store import ResultStore

    store = ResultStore(store_dir)
    spec = _widened_spec(store)
    done = store.done_keys()
    rows, _, _ = configuration_rows(spec, store.results(spec.runs()), store.failed_keys() - done)
    out = []
    for conf, row in zip(spec.configurations(), rows):
        d = conf["map"]["dense"]
        out.append(
            {
                "grid": d["n"],
                "p0": d["p0"],
                "runs": row["done"],
                "failed": row["failed"],
                "obstacles_mean": row["obstacles_mean"],
                "success_pct": row["success_pct"],
                "median_generations": row.get("first_feasible_gen_median"),
                "generations_q1": row.get("first_feasible_gen_q1"),
                "generations_q3": row.get("first_feasible_gen_q3"),
                "mean_min_path_length": row.get("min_length_mean"),
                "best_min_path_length": row.get("min_length_best"),
                "pop_size": conf["settings"]["pop_size"],
                "n_gen": conf["settings"]["n_gen"],
                "engine": conf["engine"],
            }
        )
    return out


def unsuccessful_runs(store_dir) -> dict:
    """``{(grid, p0): [seeds]}``: the stored runs of a dense store that found
    no feasible path (over every stored seed, like the table's rows)."""
    from gapath.experiments.store import ResultStore

    store = ResultStore(store_dir)
    out = {}
    for r in store.results(_widened_spec(store).runs()):
        d = r["run"]["map"]["dense"]
        if r.get("status") == "ok" and not r["indicators"]["feasible"]:
            out.setdefault((d["n"], d["p0"]), []).append(int(r["seed"]))
    return {k: sorted(v) for k, v in sorted(out.items())}


def _timing(store_dir) -> dict:
    from gapath.experiments.store import ResultStore

    store = ResultStore(store_dir)
    secs = [r.get("runtime", {}).get("seconds") or 0.0 for r in store.results(_widened_spec(store).runs())]
    return {"runs": len(secs), "seconds": float(np.sum(secs))}


def _f(v, digits=4):
    from gapath.experiments.report import format_number

    return format_number(v, digits)


def _gens(row) -> str:
    med = row["median_generations"]
    return "-" if med is None else f"{_f(med)} [{_f(row['generations_q1'])}, {_f(row['generations_q3'])}]"


def _runs_cell(row) -> str:
    return f"{row['runs']}" + (f" ({row['failed']} failed)" if row["failed"] else "")


def _with_paper(rows: list[dict]) -> list[dict]:
    for row in rows:
        p = paper_row(row["grid"], row["p0"]) or {}
        row.update({f"paper_{k}": v for k, v in p.items()})
    return rows


def _below(rows: list[dict]) -> list[dict]:
    """The rows whose success is below the paper's."""
    return [
        r
        for r in rows
        if r.get("paper_success_pct") is not None
        and r["success_pct"] is not None
        and r["success_pct"] < r["paper_success_pct"]
    ]


def _below_text(rows: list[dict]) -> str:
    below = _below(rows)
    return f"{len(below)} of {len(rows)} rows are below the paper's success rate" + (
        ": "
        + ", ".join(
            f"{r['grid']}x{r['grid']} p0 {r['p0']:g} ({_f(r['success_pct'], 3)} "
            f"vs {_f(r['paper_success_pct'], 3)})"
            for r in below
        )
        if below
        else ""
    )


def _miss_lines(misses: dict) -> list[str]:
    lines = [f"- {g}x{g} p0 {p:g}: {', '.join(map(str, seeds))}" for (g, p), seeds in misses.items()]
    return lines or ["- none"]


def _exists(store_dir) -> bool:
    from gapath.experiments.store import ResultStore

    return store_dir is not None and ResultStore(store_dir).exists()


def _free_path_note(rows) -> str:
    """At p0 = 1 only the generator's random path is free: compare its
    length in cells with the paper's (n^2 minus its obstacle count)."""
    notes = []
    for r in rows:
        paper = paper_row(r["grid"], r["p0"])
        if r["p0"] == 1.0 and paper and r["obstacles_mean"] is not None:
            n = r["grid"]
            notes.append(
                f"{n}x{n}: {n * n - paper['obstacles']} in the paper, "
                f"{_f(n * n - r['obstacles_mean'], 3)} here"
            )
    if not notes:
        return ""
    return (
        " At p0 = 1 only the random path kept free is free, and ours (a random walk of -2 to "
        "2 rows per column) has more cells than the paper's (" + "; ".join(notes) + "), so "
        "our lengths are longer there."
    )


def dense_report(
    table1_dir,
    results_dir,
    large_dir=None,
    *,
    seeded_dir=None,
    other_map_dirs=(),
    per_run_dir=None,
    large_per_run_dir=None,
    basename: str = "dense",
    wall_seconds: dict | None = None,
    workers=None,
) -> dict:
    """Write ``<basename>.md``, ``.csv`` and ``.png`` into ``results_dir``:
    our Table 1 beside the paper's, its rows on other maps, and the larger
    grids.

    Parameters
    ----------
    table1_dir : store of :func:`table1_spec` (the main table; one map per
        row, or a new map per run).
    results_dir : where the files go (e.g. ``docs/results``).
    large_dir : store of :func:`large_spec` (optional).
    seeded_dir : store of the planner-seeded variant of the main table
        (optional): its success and median generation go in extra columns,
        marked as seeded.
    other_map_dirs : stores of :func:`table1_spec` with other map seeds: a
        table of every row's success on each map.
    per_run_dir, large_per_run_dir : stores with a new map for every run
        (``map_seed="run"``), reported in their own sections.
    wall_seconds : ``{store name: seconds}`` wall times to record.
    workers : the pool size, to record with the times.

    Returns
    -------
    dict with the rows of every part (``table1``, ``other_maps``,
    ``per_run``, ``large``, ``large_per_run``), the ``unsuccessful`` runs of
    the main table and the ``files`` written.

    Examples
    --------
    >>> import tempfile
    >>> from gapath.experiments.runner import run_experiment
    >>> d = Path(tempfile.mkdtemp())
    >>> _ = run_experiment(table1_spec((8,), (0.3,), 2, n_gen=30), d / "t1", workers=0,
    ...                    progress=False)
    >>> rep = dense_report(d / "t1", d / "out")
    >>> rep["table1"][0]["success_pct"], rep["table1"][0]["paper_success_pct"]
    (100.0, 100.0)
    """
    from gapath.experiments.report import markdown_table
    from gapath.plotting import png_bytes
    from gapath.results import atomic_write

    results_dir = Path(results_dir)
    main_seed = map_seed_of(table1_dir)
    t1 = _with_paper(_rows(table1_dir))
    seeded = {}
    if _exists(seeded_dir):
        seeded = {(r["grid"], r["p0"]): r for r in _rows(seeded_dir)}
        for row in t1:
            s_row = seeded.get((row["grid"], row["p0"]))
            if s_row:
                row.update(
                    seeded_success_pct=s_row["success_pct"],
                    seeded_runs=s_row["runs"],
                    seeded_median_generations=s_row["median_generations"],
                )
    other_dirs = {map_seed_of(d): d for d in other_map_dirs if _exists(d)}
    other_dirs.pop(main_seed, None)
    others = {m: _with_paper(_rows(d)) for m, d in other_dirs.items()}
    per_run = _with_paper(_rows(per_run_dir)) if _exists(per_run_dir) else []
    large = _rows(large_dir) if _exists(large_dir) else []
    large_per_run = _rows(large_per_run_dir) if _exists(large_per_run_dir) else []
    misses = unsuccessful_runs(table1_dir)

    # CSV: every part, full precision
    cols = [
        "part",
        "map_seed",
        "grid",
        "p0",
        "runs",
        "failed",
        "obstacles_mean",
        "paper_obstacles",
        "success_pct",
        "paper_success_pct",
        "median_generations",
        "generations_q1",
        "generations_q3",
        "paper_median_generations",
        "mean_min_path_length",
        "paper_mean_min_path_length",
        "best_min_path_length",
        "pop_size",
        "n_gen",
        "engine",
        "seeded_success_pct",
        "seeded_median_generations",
        "seeded_runs",
    ]
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(cols)
    parts = [("table1", main_seed, t1)] + [("table1-other-map", m, rows) for m, rows in others.items()]
    parts += [
        ("table1-per-run-maps", "run", per_run),
        ("large", map_seed_of(large_dir) if large else None, large),
        ("large-per-run-maps", "run", large_per_run),
    ]
    for part, mseed, rows in parts:
        for row in rows:
            r = dict(row, part=part, map_seed=mseed)
            if part.startswith("large"):
                r["paper_obstacles"] = PAPER_LARGE.get(row["grid"], {}).get("obstacles")
            w.writerow(
                ["" if r.get(c) is None else (repr(r[c]) if isinstance(r[c], float) else r[c]) for c in cols]
            )

    # Markdown
    spec = _saved_spec(table1_dir)
    settings = spec["settings"]
    counts = sorted({row["runs"] for row in t1}) or [0]
    runs_per_row = (f"{counts[0]}" if len(counts) == 1 else f"{counts[0]} to {counts[-1]}") + (
        "" if counts[0] >= 100 else " (the protocol asks for 100; see the runs column)"
    )
    single = main_seed != "run"
    if single:
        maps_text = (
            f"each row is one map, `dense_workspace(grid, p0, {main_seed})` (the same map "
            f"seed for every row, so the maps of a grid share their free path and nest "
            f"as p0 grows), solved by {runs_per_row} GA runs (GA seeds "
            f"{spec['seeds'][0]}, {spec['seeds'][1] if len(spec['seeds']) > 1 else ''}, ...)"
        )
    else:
        maps_text = (
            f"{runs_per_row} runs per row, each on its own `dense_workspace(grid, p0, seed)` "
            "(map seed = run seed)"
        )
    head = [
        "grid",
        "p0",
        "obstacles (paper)",
        "success % (paper)",
        "median gen. [q1, q3] (paper)",
        "mean min length (paper)",
        "shortest of all runs",
        "runs",
    ]
    if seeded:
        head.append("SEEDED success %, median gen.")
    body = []
    for row in t1:
        body.append(
            [
                f"{row['grid']}x{row['grid']}",
                f"{row['p0']:g}",
                f"{_f(row['obstacles_mean'], 4)} ({row.get('paper_obstacles', '-')})",
                f"{_f(row['success_pct'], 3)} ({_f(row.get('paper_success_pct'), 3)})",
                f"{_gens(row)} ({_f(row.get('paper_median_generations'))})",
                f"{_f(row['mean_min_path_length'], 4)} ({_f(row.get('paper_mean_min_path_length'), 4)})",
                _f(row["best_min_path_length"], 4),
                _runs_cell(row),
            ]
        )
        if seeded:
            body[-1].append(
                "-"
                if row.get("seeded_success_pct") is None
                else f"{_f(row['seeded_success_pct'], 3)}, {_f(row['seeded_median_generations'])}"
            )
    text = [
        "# Dense obstacles: Ahmed & Deb (2013), Table 1, reproduced",
        "",
        "Generated by `gapath experiment dense` (module `gapath.studies.dense`). "
        f"Integer encoding, objectives length and vulnerability (penalty), population "
        f"{settings.get('pop_size')}, at most {settings.get('n_gen')} generations, stopped "
        f"at the first feasible path; {maps_text}; all-random initial population "
        f'(`seed_from="none"`); engine `{t1[0]["engine"] if t1 else "-"}`.',
        "",
    ]
    if single:
        text += [
            'Why one map per row: the paper takes "100 runs" "for each problem", gives '
            "one integer obstacle count per row (a map's, not a mean), repeats the same "
            "minimum lengths down the rows of a grid (one random path, more obstacles around "
            'it as p0 grows), and says of its 64x64 case, one map, that "feasible paths are '
            "found in 80 % runs\". The map seed was fixed (the experiment's first seed) "
            "before any run was made. A few maps trap this GA, so which map a row gets "
            "matters: see the rows on other maps and with a new map for every run below.",
            "",
        ]
    text += [
        "Ours first, the paper's in parentheses. Success: a feasible path within the "
        "generation limit. Generations: median over the successful runs of the first "
        "generation whose population holds a feasible path, counted as pymoo does (the "
        "initial population is generation 1; the paper does not say how it counts), with "
        "quartiles. Mean min length: the shortest feasible path at that generation, "
        "averaged over the successful runs; shortest of all runs: its minimum. The paper's "
        "lengths are near-optimal values repeated across rows (9.90 = 7 sqrt 2, "
        "10.49 = 6 sqrt 2 + 2, 11.07 = 5 sqrt 2 + 4 on 8x8), below the shortest feasible "
        "path of a population at its first feasible generation: the paper probably "
        "measured them otherwise (e.g. after optimising further); we report ours as "
        "defined here."
        + _free_path_note(t1)
        + " Obstacles: "
        + ("the map's count." if single else "mean over the runs.")
        + (
            " SEEDED (last column, not the paper's protocol): the same runs with the "
            'initial population seeded from planners (`seed_from="weighted"`: the '
            "shortest, the safest and weighted-sum optimal monotone paths)."
            if seeded
            else ""
        ),
        "",
        markdown_table(head, body),
        "",
        "## Runs without a feasible path",
        "",
        _below_text(t1)
        + ". "
        + (
            f"The GA seeds of the runs that found no feasible path, per row (rerun one with "
            f"`gapath.solve(gapath.dense_workspace(grid, p0, {main_seed}), pop_size=200, "
            'seed=seed, seed_from="none")`):'
            if single
            else "The seeds (= map seeds) of the runs that found no feasible path, per row "
            "(rerun one with `gapath.dense_workspace(grid, p0, seed)` and "
            '`gapath.solve(..., pop_size=200, seed=seed, seed_from="none")`):'
        ),
        "",
        *_miss_lines(misses),
        "",
    ]
    if others:
        seeds_all = [main_seed, *sorted(others)]
        by = {m: {(r["grid"], r["p0"]): r for r in rows} for m, rows in others.items()}
        by[main_seed] = {(r["grid"], r["p0"]): r for r in t1}
        head = ["grid", "p0", "paper %", *[f"map {m}" for m in seeds_all], "maps at or above the paper"]
        body, met = [], 0
        for row in t1:
            k = (row["grid"], row["p0"])
            vals = [by[m].get(k, {}).get("success_pct") for m in seeds_all]
            paper = row.get("paper_success_pct")
            ok = sum(v is not None and paper is not None and v >= paper for v in vals)
            n = sum(v is not None for v in vals)
            met += ok == n
            body.append(
                [
                    f"{row['grid']}x{row['grid']}",
                    f"{row['p0']:g}",
                    _f(paper, 3),
                    *["-" if v is None else _f(v, 3) for v in vals],
                    f"{ok} of {n}",
                ]
            )
        per_map = {m: len(t1) - len(_below(list(by[m].values()))) for m in seeds_all}
        text += [
            "## The same rows on other maps",
            "",
            f"Success % of {runs_per_row} GA runs per row on the maps `dense_workspace(grid, "
            f"p0, map seed)` for map seeds {', '.join(map(str, seeds_all))} (the main table "
            "is map "
            + str(main_seed)
            + "). Rows at or above the paper per map: "
            + ", ".join(f"map {m} {per_map[m]} of {len(by[m])}" for m in seeds_all)
            + f". Rows at or above the paper on every map: {met} of {len(t1)}.",
            "",
            markdown_table(head, body),
            "",
        ]
    if per_run:
        head = [
            "grid",
            "p0",
            "obstacles, mean (paper)",
            "success % (paper)",
            "median gen. [q1, q3] (paper)",
            "mean min length",
            "runs",
        ]
        body = [
            [
                f"{r['grid']}x{r['grid']}",
                f"{r['p0']:g}",
                f"{_f(r['obstacles_mean'], 4)} ({r.get('paper_obstacles', '-')})",
                f"{_f(r['success_pct'], 3)} ({_f(r.get('paper_success_pct'), 3)})",
                f"{_gens(r)} ({_f(r.get('paper_median_generations'))})",
                _f(r["mean_min_path_length"], 4),
                _runs_cell(r),
            ]
            for r in per_run
        ]
        text += [
            "## A new map for every run",
            "",
            "The same protocol with one GA run on each of 100 maps per row (map seed = GA "
            "seed = 1..100): the success rate expected over random maps of our generator, "
            "not over runs on one map. " + _below_text(per_run) + ". The map seeds of the "
            "runs without a feasible path (`benchmarks/dense_hard_maps.py` reruns them with "
            "more generations and other GA seeds, and tries other random-path generators: "
            "see `dense_hard_maps.md`):",
            "",
            markdown_table(head, body),
            "",
            *_miss_lines(unsuccessful_runs(per_run_dir)),
            "",
        ]
    if large or large_per_run:
        head = [
            "grid",
            "p0",
            "map seed",
            "obstacles (paper)",
            "success %",
            "median gen. [q1, q3]",
            "mean min length",
            "runs",
            "paper",
        ]
        body = []
        for mseed, rows in (
            (map_seed_of(large_dir) if large else None, large),
            ("new per run", large_per_run),
        ):
            for row in rows:
                paper = PAPER_LARGE.get(row["grid"], {})
                body.append(
                    [
                        f"{row['grid']}x{row['grid']}",
                        f"{row['p0']:g}",
                        str(mseed),
                        f"{_f(row['obstacles_mean'], 5)} ({paper.get('obstacles', '-')})",
                        _f(row["success_pct"], 3),
                        _gens(row),
                        _f(row["mean_min_path_length"], 5),
                        _runs_cell(row),
                        paper.get("outcome", "-"),
                    ]
                )
        ref = (large or large_per_run)[0]
        text += [
            f"## Larger grids (population {ref['pop_size']})",
            "",
            f"At most {ref['n_gen']} generations, population {ref['pop_size']}, "
            "stopped at the first feasible path; one map per grid solved by several GA "
            'runs, as the paper\'s 64x64 case (rows "new per run": a new map for every '
            "run). `dense_workspace` takes a probability: "
            "p0 = target / (n^2 - E[path cells]) with the mean length of the generator's "
            "random path measured over 2,000 seeds (`p0_for_obstacles`): 139.1 cells on "
            "64x64 (p0 = 0.200, 791 obstacles expected), 287.1 on 128x128 (p0 = 0.309, "
            "4,974 expected).",
            "",
            markdown_table(head, body),
            "",
        ]
    timing = {"table1": table1_dir}
    if seeded:
        timing["table1-seeded"] = seeded_dir
    timing.update({f"table1-map{m}": d for m, d in other_dirs.items()})
    if per_run:
        timing["table1-per-run-maps"] = per_run_dir
    if large:
        timing["large"] = large_dir
    if large_per_run:
        timing["large-per-run-maps"] = large_per_run_dir
    lines = []
    for part, d in timing.items():
        t = _timing(d)
        line = f"- {part}: {t['runs']} runs, {t['seconds']:.0f} s of optimisation in total"
        if wall_seconds and wall_seconds.get(part) is not None:
            line += f"; wall time of the last invocation {wall_seconds[part]:.0f} s" + (
                f" with {workers} workers" if workers else ""
            )
        lines.append(line + ".")
    text += [
        "## Cost",
        "",
        "Measured on a shared 2-core machine (other jobs running: times are indicative).",
        "",
        *lines,
        "",
    ]
    files = []
    results_dir.mkdir(parents=True, exist_ok=True)
    for suffix, data in (
        (".md", "\n".join(text)),
        (".csv", buf.getvalue()),
        (".png", png_bytes(_plot(t1, per_run, others))),
    ):
        atomic_write(results_dir / f"{basename}{suffix}", data)
        files.append(results_dir / f"{basename}{suffix}")
    return {
        "table1": t1,
        "other_maps": others,
        "per_run": per_run,
        "large": large,
        "large_per_run": large_per_run,
        "unsuccessful": misses,
        "files": files,
    }


def _saved_spec(store_dir) -> dict:
    """The saved spec of a store, as a dict, with every stored seed."""
    from gapath.experiments.store import ResultStore

    return _widened_spec(ResultStore(store_dir)).to_dict()


def _plot(rows, per_run=(), others=None):
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.8))
    grids = sorted({r["grid"] for r in rows}, key=lambda g: g if isinstance(g, int) else g[0])
    for i, g in enumerate(grids):
        rr = [r for r in rows if r["grid"] == g]
        p0 = [r["p0"] for r in rr]
        color = f"C{i}"
        a1.plot(p0, [r["success_pct"] for r in rr], "o-", color=color, label=f"{g}x{g} gapath")
        a2.plot(
            p0,
            [np.nan if r["median_generations"] is None else r["median_generations"] for r in rr],
            "o-",
            color=color,
            label=f"{g}x{g} gapath",
        )
        if others:
            band = [
                [r["success_pct"]]
                + [
                    o["success_pct"]
                    for rows_m in others.values()
                    for o in rows_m
                    if o["grid"] == g and o["p0"] == r["p0"]
                ]
                for r in rr
            ]
            a1.fill_between(
                p0,
                [min(b) for b in band],
                [max(b) for b in band],
                color=color,
                alpha=0.12,
                lw=0,
                label=f"{g}x{g} gapath, min-max over {len(others) + 1} maps",
            )
        pr = [r for r in per_run if r["grid"] == g]
        if pr:
            a1.plot(
                [r["p0"] for r in pr],
                [r["success_pct"] for r in pr],
                ":",
                color=color,
                alpha=0.8,
                label=f"{g}x{g} gapath, new map per run",
            )
        paper = [(r["p0"], paper_row(g, r["p0"])) for r in rr]
        paper = [(p, q) for p, q in paper if q]
        if paper:
            a1.plot(
                [p for p, _ in paper],
                [q["success_pct"] for _, q in paper],
                "s--",
                color=color,
                alpha=0.6,
                mfc="none",
                label=f"{g}x{g} paper",
            )
            a2.plot(
                [p for p, _ in paper],
                [q["median_generations"] for _, q in paper],
                "s--",
                color=color,
                alpha=0.6,
                mfc="none",
                label=f"{g}x{g} paper",
            )
    a1.set_xlabel("p0")
    a1.set_ylabel("success %")
    a1.set_ylim(-5, 105)
    a2.set_xlabel("p0")
    a2.set_ylabel("median generation of the first feasible path")
    a2.set_yscale("log")
    a1.legend(fontsize=6)
    a2.legend(fontsize=7)
    a1.set_title("Table 1: success", fontsize=9)
    a2.set_title("Table 1: speed", fontsize=9)
    return a1


# ---------------------------------------------------------------------------
# the study (gapath experiment dense)
# ---------------------------------------------------------------------------

#: ``--quick``: small grids, a few runs per row (the test suite runs it).
QUICK = dict(
    grids=(8, 16),
    p0s=(0.3, 0.7),
    runs=2,
    n_gen=40,
    large_sizes=(64,),
    large_runs=1,
    large_pop=40,
    large_gen=5,
)


def run(
    out,
    *,
    quick: bool = False,
    grids=None,
    p0s=None,
    runs: int | None = None,
    map_seeds=(MAP_SEED,),
    per_run_maps: bool = False,
    large_runs: int | None = None,
    seeded: bool = False,
    engine: str = "fast",
    results=None,
    workers=None,
    scheduler=None,
    progress: bool = True,
    retry_failed: bool = True,
) -> dict:
    """Run the dense-obstacle study into the stores under ``out`` (resumably)
    and write its report (what ``gapath experiment dense`` does).

    Parameters
    ----------
    out : directory of the stores: ``out/table1-map<S>`` per map seed ``S``,
        ``out/large-map<S>``, and with the options below
        ``out/table1-map<S>-seeded``, ``out/table1-per-run-maps`` and
        ``out/large-per-run-maps``.
    quick : the small settings of :data:`QUICK` (tests, smoke runs); each
        setting given below overrides them.
    grids : grid sides of Table 1 (default ``(8, 16, 32)``).
    p0s : obstacle fractions (default :data:`P0S`).
    runs : GA runs per Table 1 row (default 100).
    map_seeds : map seeds of the rows: the first gives the main table, the
        others a table of every row's success per map.
    per_run_maps : also run every row with a new map per run.
    large_runs : GA runs on the 64x64 and 128x128 maps (default 10, as the
        paper; 0 skips them).
    seeded : also run the main table with a planner-seeded first population
        (``seed_from="weighted"``), reported beside the paper's protocol.
    engine : the GA engine of the specs (see
        :data:`gapath.experiments.spec.ENGINES`).
    results : where ``dense.md``, ``.csv`` and ``.png`` go (default
        ``docs/results``; with ``quick``: ``out``).
    workers, scheduler, progress, retry_failed : as
        :func:`gapath.experiments.runner.run_experiment`.

    Returns
    -------
    dict
        :func:`dense_report`'s dict, with ``failed`` (the number of failed
        runs) and ``wall_seconds`` (per store that ran something).

    Raises
    ------
    ConfigError
        On invalid settings or executor options.
    KeyboardInterrupt
        On Ctrl-C while the runs execute: the finished runs are kept in
        their stores, and the same call resumes.
    """
    import time

    from gapath.experiments.runner import run_experiment

    grids = tuple(grids) if grids else (QUICK["grids"] if quick else (8, 16, 32))
    p0s = tuple(p0s) if p0s else (QUICK["p0s"] if quick else P0S)
    runs = runs or (QUICK["runs"] if quick else 100)
    n_gen = QUICK["n_gen"] if quick else 500
    map_seeds = list(map_seeds)
    main = map_seeds[0]
    if large_runs is None:
        large_runs = QUICK["large_runs"] if quick else 10
    out = Path(out)
    sfx = "-quick" if quick else ""
    jobs = [
        (
            f"table1-map{m}",
            table1_spec(
                grids, p0s, runs, n_gen=n_gen, engine=engine, map_seed=m, name=f"dense-table1-map{m}{sfx}"
            ),
        )
        for m in map_seeds
    ]
    if seeded:
        jobs.append(
            (
                f"table1-map{main}-seeded",
                table1_spec(
                    grids,
                    p0s,
                    runs,
                    n_gen=n_gen,
                    engine=engine,
                    map_seed=main,
                    seed_from="weighted",
                    name=f"dense-table1-map{main}-seeded{sfx}",
                ),
            )
        )
    if per_run_maps:
        jobs.append(
            (
                "table1-per-run-maps",
                table1_spec(
                    grids,
                    p0s,
                    runs,
                    n_gen=n_gen,
                    engine=engine,
                    map_seed="run",
                    name=f"dense-table1-per-run-maps{sfx}",
                ),
            )
        )
    if large_runs > 0:
        lkw = dict(
            pop_size=QUICK["large_pop"] if quick else 500,
            n_gen=QUICK["large_gen"] if quick else 500,
            engine=engine,
        )
        sizes = QUICK["large_sizes"] if quick else (64, 128)
        jobs.append(
            (
                f"large-map{main}",
                large_spec(sizes, large_runs, map_seed=main, name=f"dense-large-map{main}{sfx}", **lkw),
            )
        )
        if per_run_maps:
            jobs.append(
                (
                    "large-per-run-maps",
                    large_spec(
                        sizes, large_runs, map_seed="run", name=f"dense-large-per-run-maps{sfx}", **lkw
                    ),
                )
            )
    wall = {}
    kw = dict(workers=workers, scheduler=scheduler, progress=progress, retry_failed=retry_failed)
    failed = 0
    for name, spec in jobs:
        t0 = time.perf_counter()
        r = run_experiment(spec, out / name, **kw)
        failed += r.failed
        if r.ran:  # a resumed store that ran nothing has no wall time to report
            wall[name] = time.perf_counter() - t0
    results = Path(results) if results else (out if quick else Path("docs/results"))
    wall = {
        k.replace(f"-map{main}", "")
        if k in (f"table1-map{main}", f"table1-map{main}-seeded", f"large-map{main}")
        else k: v
        for k, v in wall.items()
    }
    rep = dense_report(
        out / f"table1-map{main}",
        results,
        out / f"large-map{main}" if large_runs > 0 else None,
        seeded_dir=out / f"table1-map{main}-seeded",
        other_map_dirs=[out / f"table1-map{m}" for m in map_seeds[1:]],
        per_run_dir=out / "table1-per-run-maps",
        large_per_run_dir=out / "large-per-run-maps" if large_runs > 0 else None,
        wall_seconds=wall,
        workers=workers,
    )
    return {**rep, "failed": failed, "wall_seconds": wall}
