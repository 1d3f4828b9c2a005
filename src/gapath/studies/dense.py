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
is :data:`MAP_SEED` (= 1, the experiment's first seed) for every row, so the
maps of a grid are nested like the paper's. Map 1 was not chosen blind: it
had succeeded in every row under the earlier protocol (a new map per run),
so the report headlines the distribution over map seeds, map 1 being one of
them.
Which map a row gets matters (a few maps trap this GA), so the report also
gives the rows on further map seeds (``--map-seeds``) and the variant with
a new map for every run (``map_seed="run"``, ``--per-run-maps``: the
expected success over random maps). The choice is recorded in
``docs/CONVENTIONS.md``.

*Two map generators.* ``"columns"`` (:func:`gapath.dense_workspace`, the
default) keeps free a random walk of -2..2 rows per column ending with the
integer encoding's own end-fix climb, so its corridor hugs the bottom rows
and climbs the right edge; ``"walk"`` (:func:`walk_workspace`) keeps free a
goal-biased 8-connected walk (:func:`goal_walk_path`) that crosses the grid
near the diagonal. ``run(generator="walk")`` (``--generator walk``) runs the
Table 1 rows on walk maps and reports them beside the columns rows; the
report's headline is the success per row over map seeds (median and range,
:func:`headline_lines`), and it lists every map's free cells and exact
shortest lengths (:func:`map_stats`).

*With a repair* (``run(repair="feasible-local")``, ``--repair``): the Table 1
rows run again with a feasibility-preserving repair
(:mod:`gapath.operators.repair.feasible`, a GA change, not the paper's
method) on either generator, one store per map seed
(:func:`repair_store_name`), and the report gives them their own section
and goal bullets beside the penalty rows (:func:`repair_lines`,
``dense_repair.csv``).

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
import re
from pathlib import Path

import numpy as np

from gapath.errors import ConfigError
from gapath.experiments.report import configuration_rows, format_number, markdown_table
from gapath.experiments.runner import run_experiment
from gapath.experiments.spec import ExperimentSpec
from gapath.experiments.store import ResultStore
from gapath.generators import dense_workspace, random_monotone_path
from gapath.planners import astar
from gapath.planners.weighted_sum import weighted_sum_path
from gapath.results import atomic_write
from gapath.workspace import Workspace

__all__ = [
    "GENERATORS",
    "LARGE",
    "MAP_SEED",
    "MATCH_POINTS",
    "P0S",
    "PAPER_LARGE",
    "PAPER_TABLE1",
    "REPAIR_CSV_COLUMNS",
    "REPAIR_DEVELOPMENT",
    "REPAIR_PARTS",
    "WALK_BIAS",
    "WALK_PROTOCOL_SEEDS",
    "check_repair",
    "dense_report",
    "distribution_rows",
    "generated_workspace",
    "goal_walk_path",
    "headline_lines",
    "large_spec",
    "map_seed_of",
    "map_stats",
    "map_stats_lines",
    "p0_for_obstacles",
    "paper_row",
    "read_dense_csv",
    "read_repair_csv",
    "repair_dirs",
    "repair_goal_bullets",
    "repair_lines",
    "repair_store_name",
    "table1_spec",
    "unsuccessful_runs",
    "walk_lines",
    "walk_table1_spec",
    "walk_workspace",
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
    repair: str | None = None,
) -> ExperimentSpec:
    """The Table 1 experiment: ``grids x p0s`` rows, each one map
    ``dense_workspace(grid, p0, map_seed)`` solved by ``runs`` seeded GA runs
    (seeds ``first_seed, ...``), NSGA-II with ``pop_size`` for at most
    ``n_gen`` generations, stopped at the first feasible path, with an
    unseeded initial population (``seed_from="none"``, the paper's protocol;
    ``"weighted"`` etc. give the planner-seeded variant, reported beside it).
    ``map_seed="run"``: a new map for every run (map seed = run seed).
    ``repair``: a name of :data:`gapath.operators.repair.feasible.REPAIRS`
    (e.g. ``"feasible-local"``, a GA change, not the paper's method); None or
    ``"edge"``: Ahmed & Deb's edge-fixing alone, and the runs' keys are
    those of a spec without the setting.

    Raises
    ------
    ValueError
        If ``map_seed`` is neither a non-negative integer nor ``"run"``.
    ConfigError
        On an unknown ``repair``, or a repair with ``engine="pymoo"``.

    Examples
    --------
    >>> spec = table1_spec(grids=(8,), p0s=(0.5,), runs=3)
    >>> len(spec), spec.runs()[0]["settings"]["pop_size"], spec.runs()[0]["settings"]["seed_from"]
    (3, 200, 'none')
    >>> [(r["map"]["dense"]["seed"], r["seed"]) for r in spec.runs()]
    [(1, 1), (1, 2), (1, 3)]
    >>> [r["map"]["dense"]["seed"] for r in table1_spec((8,), (0.5,), 2, map_seed="run").runs()]
    ['run', 'run']
    >>> table1_spec((8,), (0.5,), 1, repair="feasible-local").runs()[0]["settings"]["repair"]
    'feasible-local'
    """
    mseed = _map_seed(map_seed)
    maps = [{"dense": {"n": int(n), "p0": float(p0), "seed": mseed}} for n in grids for p0 in p0s]
    per = "a new map per run (map seed = run seed)" if mseed == "run" else f"map seed {mseed}"
    return ExperimentSpec(
        name=name,
        description="Ahmed & Deb 2013, Table 1: dense random obstacles, stop at the first "
        f"feasible path; {per}{_repair_text(repair)} (gapath.studies.dense).",
        maps=maps,
        encodings=["integer"],
        engines=[engine],
        settings=_table1_settings(pop_size, n_gen, seed_from, repair),
        seeds={"start": first_seed, "count": runs},
        options={"stop_at_first_feasible": True},
    )


def _table1_settings(pop_size, n_gen, seed_from, repair) -> dict:
    """The settings of a Table 1 spec; ``repair`` only when it is one (so
    the runs without it keep their keys)."""
    settings = dict(objectives="length,vulnerability", pop_size=pop_size, n_gen=n_gen, seed_from=seed_from)
    if repair not in (None, "edge"):
        settings["repair"] = repair
    return settings


def _repair_text(repair) -> str:
    return "" if repair in (None, "edge") else f"; with the repair {repair} (a GA change, not the paper's)"


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


def walk_table1_spec(
    maps_dir,
    grids=(8, 16, 32),
    p0s=P0S,
    runs: int = 100,
    *,
    map_seed: int = MAP_SEED,
    pop_size: int = 200,
    n_gen: int = 500,
    engine: str = "fast",
    first_seed: int = 1,
    name: str = "dense-table1-walk",
    repair: str | None = None,
) -> ExperimentSpec:
    """:func:`table1_spec` on the maps of the ``"walk"`` generator
    (:func:`walk_workspace`, map seed ``map_seed``): the maps are written as
    text grids into ``maps_dir`` (``walk-<n>x<n>-p<p0>-s<seed>.txt``, start
    ``S`` bottom-left, goal ``G`` top-right) and the spec names those files,
    so the store records each map's sha256. ``repair`` as in
    :func:`table1_spec`.

    Raises
    ------
    ValueError
        If ``map_seed`` is not a non-negative integer (a new walk map per run
        is not offered: the files are written per map).
    ConfigError
        On an unknown ``repair``, or a repair with ``engine="pymoo"``.

    Examples
    --------
    >>> import tempfile
    >>> spec = walk_table1_spec(tempfile.mkdtemp(), grids=(8,), p0s=(0.5,), runs=2)
    >>> [(r["map"]["file"]["name"], r["seed"]) for r in spec.runs()]
    [('walk-8x8-p0.5-s1.txt', 1), ('walk-8x8-p0.5-s1.txt', 2)]
    """

    mseed = _map_seed(map_seed)
    if mseed == "run":
        raise ValueError("map_seed: the walk generator takes one map seed per store, not 'run'")
    maps_dir = Path(maps_dir).resolve()
    maps_dir.mkdir(parents=True, exist_ok=True)
    maps = []
    for n in grids:
        for p0 in p0s:
            ws = walk_workspace(int(n), float(p0), mseed)
            path = maps_dir / f"{ws.name}.txt"
            text = ws.to_text()
            if not path.exists() or path.read_text() != text:
                atomic_write(path, text)
            maps.append({"file": {"path": str(path)}})
    return ExperimentSpec(
        name=name,
        description="Ahmed & Deb 2013, Table 1, on maps whose kept free path is a goal-biased "
        f"8-connected walk (gapath.studies.dense.walk_workspace), map seed {mseed}"
        f"{_repair_text(repair)}.",
        maps=maps,
        encodings=["integer"],
        engines=[engine],
        settings=_table1_settings(pop_size, n_gen, "none", repair),
        seeds={"start": first_seed, "count": runs},
        options={"stop_at_first_feasible": True},
    )


_WALK_NAME = re.compile(r"^walk-(\d+)x(\d+)-p([0-9.]+)-s(\d+)(?:\.txt)?$")


def _dense_args(map_spec) -> dict | None:
    """``{"n", "p0", "seed"}`` of a dense map spec, or of a walk map file
    written by :func:`walk_table1_spec`; None for other maps."""
    if not isinstance(map_spec, dict):
        return None
    if "dense" in map_spec:
        return map_spec["dense"]
    m = _WALK_NAME.match(str(map_spec.get("file", {}).get("name", "")))
    if m is None:
        return None
    return {"n": int(m[1]), "p0": float(m[3]), "seed": int(m[4]), "generator": "walk"}


def map_seed_of(store_dir):
    """The map seed of a dense store's rows (an int, or ``"run"`` when every
    run has its own map; None for a store of mixed or non-dense maps)."""

    seeds = {(_dense_args(m) or {}).get("seed") for m in ResultStore(store_dir).spec().to_dict()["maps"]}
    return seeds.pop() if len(seeds) == 1 else None


# ---------------------------------------------------------------------------
# a second map generator (issue 17 §1): a goal-biased 8-connected walk
# ---------------------------------------------------------------------------

#: The map generators of the study: ``"columns"`` is
#: :func:`gapath.dense_workspace` (each column moves -2..2 rows, then the goal
#: column is climbed: the integer encoding's own end-fixing shape);
#: ``"walk"`` is :func:`walk_workspace` (a goal-biased 8-connected walk).
GENERATORS = ("columns", "walk")

#: The walk's pull towards the goal: a move's weight is
#: ``exp(-WALK_BIAS * (distance after - distance before))`` (Euclidean
#: distance to the goal, in cells).
WALK_BIAS = 1.25

#: The walk map seeds of the protocol stated before the walk runs were made
#: (issue 17: seeds 1-4, 30 GA runs per row); seeds added later are reported
#: too, and the report gives this subset's summary beside theirs.
WALK_PROTOCOL_SEEDS = (1, 2, 3, 4)

_WALK_MOVES = ((0, 1), (-1, 1), (1, 1), (-1, 0), (1, 0))  # (row, column step sign)


def goal_walk_path(shape, start, goal, rng: np.random.Generator, bias: float = WALK_BIAS) -> np.ndarray:
    """A random 8-connected walk from ``start`` to ``goal`` pulled towards the
    goal, never stepping back a column.

    Each step picks one of the moves ahead, ahead-diagonal (up or down) or
    vertical (up or down) that stays on the grid and does not revisit a
    cell, with weight ``exp(-bias * (d' - d))`` (``d``: Euclidean distance to
    the goal before, ``d'`` after the move); in the goal's column it goes
    straight to the goal. The path wanders anywhere between start and goal
    (it does not follow the bottom rows and the last column the way
    :func:`gapath.generators.random_monotone_path` does) yet stays
    representable by the column-monotone encodings: its cells in a column are
    one vertical run entered from a neighbour of the previous column's last
    cell.

    Parameters
    ----------
    shape : (rows, cols).
    start, goal : (row, col) cells in different columns.
    rng : the random generator (the only source of randomness).
    bias : the pull towards the goal (0: a uniform choice of the moves).

    Returns
    -------
    (m, 2) int array of cells, start to goal, each step 8-connected.

    Raises
    ------
    ConfigError
        If start and goal share a column.

    Examples
    --------
    >>> p = goal_walk_path((8, 8), (7, 0), (0, 7), np.random.default_rng(1))
    >>> p[0].tolist(), p[-1].tolist(), bool((np.abs(np.diff(p, axis=0)).max(axis=1) == 1).all())
    ([7, 0], [0, 7], True)
    """

    h, w = (int(v) for v in shape)
    (sr, sc), (gr, gc) = (int(v) for v in start), (int(v) for v in goal)
    if sc == gc:
        raise ConfigError(f"start {start} and goal {goal} share a column: no column-monotone walk")
    step_c = 1 if gc > sc else -1
    r, c = sr, sc
    cells, seen = [(r, c)], {(r, c)}
    while (r, c) != (gr, gc):
        if c == gc:  # the goal's column: straight to the goal
            r += 1 if gr > r else -1
        else:
            d0 = np.hypot(gr - r, gc - c)
            cand = [
                (r + dr, c + dc * step_c)
                for dr, dc in _WALK_MOVES
                if 0 <= r + dr < h and (r + dr, c + dc * step_c) not in seen
            ]
            weight = np.array([np.exp(-bias * (np.hypot(gr - a, gc - b) - d0)) for a, b in cand])
            r, c = cand[int(rng.choice(len(cand), p=weight / weight.sum()))]
        cells.append((r, c))
        seen.add((r, c))
    return np.asarray(cells, dtype=np.int64)


def walk_workspace(n, p0: float, seed: int = 0, *, start=None, goal=None, bias: float = WALK_BIAS):
    """:func:`gapath.dense_workspace` with :func:`goal_walk_path` as the kept
    free path: the walk is drawn first, then every other cell becomes an
    obstacle with probability ``p0`` (the same uniform draws for every
    ``p0``, so the maps of a seed nest as ``p0`` grows). Seeded and
    deterministic.

    Raises
    ------
    ConfigError
        On a bad size, ``p0`` outside [0, 1], or start and goal in one column.

    Examples
    --------
    >>> ws = walk_workspace(8, 1.0, 3)
    >>> ws.shape, int((~ws.occ).sum()) == len(goal_walk_path((8, 8), (7, 0), (0, 7),
    ...                                                      np.random.default_rng(3)))
    ((8, 8), True)
    """

    h, w = (int(n), int(n)) if np.isscalar(n) else (int(n[0]), int(n[1]))
    if h < 1 or w < 2:
        raise ConfigError(f"walk_workspace: expected at least 1 row and 2 columns, got {h}x{w}")
    if not (0.0 <= float(p0) <= 1.0):
        raise ConfigError(f"p0 must be in [0, 1], got {p0!r}")
    start = (h - 1, 0) if start is None else tuple(start)
    goal = (0, w - 1) if goal is None else tuple(goal)
    rng = np.random.default_rng(seed)
    path = goal_walk_path((h, w), start, goal, rng, bias)
    occ = rng.random((h, w)) < p0
    occ[path[:, 0], path[:, 1]] = False
    return Workspace(occ, start, goal, name=f"walk-{h}x{w}-p{p0:g}-s{seed}")


def generated_workspace(generator: str, n, p0: float, seed: int):
    """The map of ``generator`` (one of :data:`GENERATORS`) for ``(n, p0,
    seed)``.

    Raises
    ------
    ConfigError
        On an unknown generator.
    """

    if generator == "columns":
        return dense_workspace(n, p0, seed)
    if generator == "walk":
        return walk_workspace(n, p0, seed)
    raise ConfigError(f"generator: expected one of {', '.join(GENERATORS)}, got {generator!r}")


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

    store = ResultStore(store_dir)
    spec = _widened_spec(store)
    done = store.done_keys()
    rows, _, _ = configuration_rows(spec, store.results(spec.runs()), store.failed_keys() - done)
    out = []
    for conf, row in zip(spec.configurations(), rows):
        d = _dense_args(conf["map"])
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
        if "repair" in conf["settings"]:
            out[-1]["repair"] = conf["settings"]["repair"]
    return out


def _first_generations(store_dir) -> dict:
    """``{(grid, p0): (initial %, largest generation)}`` over the successful
    runs of a store: the % whose first feasible path was in the initial
    population (pymoo's generation 1) and the latest first feasible
    generation."""

    store = ResultStore(store_dir)
    gens: dict = {}
    for r in store.results(_widened_spec(store).runs()):
        if r.get("status") == "ok" and r["indicators"]["feasible"]:
            d = _dense_args(r["run"]["map"])
            if d is None:  # not a dense map
                continue
            gens.setdefault((d["n"], d["p0"]), []).append(int(r["indicators"]["first_feasible_gen"]))
    return {k: (100.0 * sum(g == 1 for g in v) / len(v), max(v)) for k, v in gens.items()}


def unsuccessful_runs(store_dir) -> dict:
    """``{(grid, p0): [seeds]}``: the stored runs of a dense store that found
    no feasible path (over every stored seed, like the table's rows)."""

    store = ResultStore(store_dir)
    out = {}
    for r in store.results(_widened_spec(store).runs()):
        d = _dense_args(r["run"]["map"])
        if r.get("status") == "ok" and not r["indicators"]["feasible"]:
            out.setdefault((d["n"], d["p0"]), []).append(int(r["seed"]))
    return {k: sorted(v) for k, v in sorted(out.items())}


def _timing(store_dir) -> dict:

    store = ResultStore(store_dir)
    secs = [r.get("runtime", {}).get("seconds") or 0.0 for r in store.results(_widened_spec(store).runs())]
    return {"runs": len(secs), "seconds": float(np.sum(secs))}


def _f(v, digits=4):

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
    walk_dirs=(),
    from_csv=None,
    map_stats_seeds: int | None = None,
    repair_dirs=(),
    repair_csv=None,
) -> dict:
    """Write ``<basename>.md``, ``.csv`` and ``.png`` into ``results_dir``:
    our Table 1 beside the paper's, its rows on other maps, and the larger
    grids; with repair rows also ``<basename>_repair.csv``.

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
    walk_dirs : stores of :func:`walk_table1_spec` (one per map seed): the
        walk generator's rows, in the headline and their own section.
    from_csv : a ``dense.csv`` written earlier, read instead of the stores
        (``table1_dir`` etc. may then be None): every part it holds is
        reported again (its walk rows unless ``walk_dirs`` are given); the
        lists of unsuccessful runs and the cost of its runs are not in it.
    map_stats_seeds : map seeds 1..k of the maps section (default: the
        columns rows' map seeds, and the walk rows').
    repair_dirs : stores of :func:`table1_spec` / :func:`walk_table1_spec`
        with a ``repair``, named as :func:`repair_store_name` names them:
        the section "With the feasibility-preserving repair" and the goal's
        bullets with the repair.
    repair_csv : a ``dense_repair.csv`` written earlier: its rows for every
        (generator, repair, map seed) that no store of ``repair_dirs`` holds.

    Returns
    -------
    dict with the rows of every part (``table1``, ``other_maps``,
    ``per_run``, ``large``, ``large_per_run``, ``repair``), the
    ``unsuccessful`` runs of the main table and the ``files`` written.

    Raises
    ------
    ConfigError
        If ``from_csv`` or ``repair_csv`` cannot be read or is not such a
        file.

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

    results_dir = Path(results_dir)
    csv_rows = read_dense_csv(from_csv) if from_csv is not None else None
    repair_rows = _repair_parts(repair_dirs, repair_csv)
    walk = {map_seed_of(d): _with_paper(_rows(d)) for d in walk_dirs if _exists(d)}
    if csv_rows is not None:
        (t1, main_seed, seeded, others, per_run, large, large_seed, large_per_run, walk) = _csv_parts(
            csv_rows, walk
        )
        misses = per_run_misses = other_dirs = None
    else:
        t1, main_seed, seeded, others, other_dirs, misses = _store_parts(
            table1_dir, seeded_dir, other_map_dirs
        )
        per_run = _with_paper(_rows(per_run_dir)) if _exists(per_run_dir) else []
        per_run_misses = unsuccessful_runs(per_run_dir) if per_run else None
        large = _rows(large_dir) if _exists(large_dir) else []
        large_seed = map_seed_of(large_dir) if large else None
        large_per_run = _rows(large_per_run_dir) if _exists(large_per_run_dir) else []
    return _write_report(**locals())


def _store_parts(table1_dir, seeded_dir, other_map_dirs):
    """The main table (with the seeded variant's columns) and the other
    maps' rows of :func:`dense_report`, from their stores."""
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
    return t1, main_seed, seeded, others, other_dirs, unsuccessful_runs(table1_dir)


def _csv_parts(csv_rows, walk):
    """The parts of :func:`dense_report` from the rows of a ``dense.csv``
    (its walk rows unless ``walk`` already holds stored ones)."""

    def part(name):
        return [dict(r) for r in csv_rows if r["part"] == name]

    t1 = part("table1")
    main_seed = t1[0]["map_seed"] if t1 else None
    seeded = {(r["grid"], r["p0"]): r for r in t1 if r.get("seeded_success_pct") is not None}
    others, csv_walk = {}, {}
    for r in part("table1-other-map"):
        others.setdefault(r["map_seed"], []).append(r)
    for r in part("table1-walk"):
        csv_walk.setdefault(r["map_seed"], []).append(r)
    large = part("large")
    large_seed = large[0]["map_seed"] if large else None
    return (
        t1,
        main_seed,
        seeded,
        others,
        part("table1-per-run-maps"),
        large,
        large_seed,
        part("large-per-run-maps"),
        walk or csv_walk,
    )


_NOT_IN_CSV = "not in dense.csv (see this file's history before issue 17)."


def _walk_dirs_by_seed(walk_dirs) -> dict:
    return {map_seed_of(d): d for d in walk_dirs if _exists(d)}


def _runs_text(counts) -> str | None:
    counts = sorted(set(counts))
    if not counts:
        return None
    return str(counts[0]) if len(counts) == 1 else f"{counts[0]} to {counts[-1]}"


def _commands(
    main_seed, t1, others, per_run, seeded, large, walk, from_csv, repair=(), repair_csv=None
) -> dict:
    """The ``gapath experiment dense`` commands behind the report's rows
    (``repair``: the repair rows; ``repair_csv``: where they are kept)."""
    seeds = (
        [main_seed, *sorted(m for m in others if isinstance(m, int))] if isinstance(main_seed, int) else []
    )
    runs = _runs_text([r["runs"] for r in t1]) or "100"
    cols = "gapath experiment dense" + (f" --map-seeds {_seed_arg(seeds)}" if seeds != [MAP_SEED] else "")
    cols += "" if runs == "100" else f" --runs {runs}"
    cols += " --per-run-maps" if per_run else ""
    cols += " --seeded" if seeded else ""
    cols += f" --large-runs {large[0]['runs']}" if large else " --large-runs 0"
    cols += " --out DIR"
    wseeds = sorted(m for m in walk if isinstance(m, int))
    wruns = _runs_text([r["runs"] for rows in walk.values() for r in rows]) or "100"
    wcmd = (
        f"gapath experiment dense --generator walk --map-seeds {_seed_arg(wseeds) or MAP_SEED} "
        f"--runs {wruns} --out DIR"
    )
    last = (wcmd if walk else cols) + (f" --from-csv {from_csv}" if from_csv is not None else "")
    src = f" --from-csv {from_csv}" if from_csv is not None else ""
    rcmds: dict = {}
    for name in dict.fromkeys(r["repair"] for r in repair):
        rcmds[name] = {"csv": repair_csv}
        for gen, part in REPAIR_PARTS.items():
            rows = [r for r in repair if r["repair"] == name and r["part"] == part]
            if rows:
                rseeds = sorted({r["map_seed"] for r in rows})
                rcmds[name][gen] = (
                    f"gapath experiment dense --repair {name}"
                    + (" --generator walk" if gen == "walk" else "")
                    + f" --map-seeds {_seed_arg(rseeds)} --runs {_runs_text([r['runs'] for r in rows])}"
                    + f" --out DIR{src}"
                )
        last = rcmds[name].get("walk") or rcmds[name]["columns"]
        last += f" --repair-csv {repair_csv}" if repair_csv else ""
    return {"columns": cols, "walk": wcmd, "last": last, "repair": rcmds}


def walk_lines(walk: dict, t1: list[dict], *, command: str) -> list[str]:
    """The walk generator's section of ``dense.md``: its protocol and
    command, then every row's success on each walk map beside the paper.

    Examples
    --------
    >>> rows = {1: [{"grid": 8, "p0": 0.5, "success_pct": 90.0, "runs": 30, "obstacles_mean": 25.0,
    ...              "median_generations": 3.0}]}
    >>> "| 8x8 | 0.5 | 100 | 90 (25, 3) | 0 of 1 |" in "\\n".join(walk_lines(rows, [], command="c"))
    True
    """

    if not walk:
        return []
    seeds = sorted(walk, key=str)
    by = {m: {(r["grid"], round(r["p0"], 3)): r for r in rows} for m, rows in walk.items()}
    keys = sorted({k for m in by for k in by[m]})
    runs = _runs_text([r["runs"] for rows in walk.values() for r in rows])
    head = ["grid", "p0", "paper %", *[f"walk map {m}: % (obstacles, median gen.)" for m in seeds]]
    head.append("maps at or above the paper")
    body = []
    for k in keys:
        paper = (paper_row(*k) or {}).get("success_pct")
        vals = [by[m].get(k) for m in seeds]
        ok = sum(v is not None and paper is not None and v["success_pct"] >= paper for v in vals)
        body.append(
            [
                f"{k[0]}x{k[0]}",
                f"{k[1]:g}",
                _f(paper, 3),
                *[
                    "-"
                    if v is None
                    else f"{_f(v['success_pct'], 3)} ({_f(v['obstacles_mean'], 4)}, "
                    f"{_f(v.get('median_generations'))})"
                    for v in vals
                ],
                f"{ok} of {sum(v is not None for v in vals)}",
            ]
        )
    stated = [m for m in seeds if m in WALK_PROTOCOL_SEEDS]
    subset = ""
    if set(seeds) - set(WALK_PROTOCOL_SEEDS) and stated:
        sub = distribution_rows([dict(r, part="table1-walk", map_seed=m) for m in stated for r in walk[m]])
        g = _goal_counts(sub, "walk")
        subset = (
            f" The protocol stated before the runs was map seeds {_seed_text(WALK_PROTOCOL_SEEDS)}; "
            f"seeds {_seed_text(sorted(set(seeds) - set(WALK_PROTOCOL_SEEDS)))} were added after "
            f"those had been seen, to match the columns generator's map seeds. Over seeds "
            f"{_seed_text(stated)} alone: every map at or above the paper in {g['every']} of "
            f"{g['rows']} rows, the median over maps in {g['median']} of {g['rows']}."
        )
    return [
        "## The walk generator",
        "",
        f"Regenerate: `{command}`.",
        "",
        f"Protocol (a reduced one): walk map seeds {_seed_text(seeds)}, "
        f"{runs} GA runs per row and map (GA seeds 1, 2, ...), every other setting as the "
        "columns rows (population 200, at most 500 generations, stop at the first feasible "
        'path, all-random initial population). The paper says only that it draws "a random '
        "valid path\" and keeps it free. The columns generator's path is a random walk of -2 "
        "to 2 rows per column that ends with the integer encoding's own end-fix climb, so its "
        "corridor hugs the bottom rows and climbs the right edge, the shape the encoding's "
        "end-fixing and edge rule give its random individuals. The walk generator "
        "(`walk_workspace`) keeps free a random 8-connected walk pulled towards the goal (a "
        "move's weight is exp(-1.25 x the change of its Euclidean distance to the goal); it "
        "never steps back a column, so the integer encoding can still represent it), which "
        "crosses the grid near the diagonal and enters the goal's column near the goal. Its "
        "mean length at p0 = 1 over 500 seeds is 11.5 cells on 8x8, 23.6 on 16x16 and 47.5 on "
        "32x32 (the paper's p0 = 1 rows leave 10, 23 and 57 cells free; the columns "
        "generator: 13.5, 30.4 and 66.8). Each cell: success % (obstacles, median generation "
        "of the first feasible path)." + subset,
        "",
        markdown_table(head, body),
        "",
    ]


def _write_report(
    *,
    t1,
    main_seed,
    seeded,
    others,
    other_dirs,
    misses,
    per_run,
    per_run_misses,
    large,
    large_seed,
    large_per_run,
    walk,
    csv_rows,
    results_dir,
    basename,
    wall_seconds,
    workers,
    table1_dir,
    seeded_dir,
    per_run_dir,
    large_dir,
    large_per_run_dir,
    map_stats_seeds,
    from_csv,
    walk_dirs,
    repair_rows,
    repair_dirs,
    **_,
) -> dict:
    """The files of :func:`dense_report` from its parts' rows."""
    from gapath.plotting import png_bytes

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
        ("large", large_seed, large),
        ("large-per-run-maps", "run", large_per_run),
    ]
    parts += [("table1-walk", m, rows) for m, rows in sorted(walk.items())]
    for part, mseed, rows in parts:
        for row in rows:
            r = dict(row, part=part, map_seed=mseed)
            if part.startswith("large"):
                r["paper_obstacles"] = PAPER_LARGE.get(row["grid"], {}).get("obstacles")
            w.writerow(
                ["" if r.get(c) is None else (repr(r[c]) if isinstance(r[c], float) else r[c]) for c in cols]
            )

    # Markdown
    if csv_rows is None:
        spec = _saved_spec(table1_dir)
    else:  # the CSV keeps the settings per row, not the GA seed list
        spec = {
            "settings": {"pop_size": t1[0]["pop_size"], "n_gen": t1[0]["n_gen"]} if t1 else {},
            "seeds": [1, 2],
        }
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
    repair_file = results_dir / f"{basename}_repair.csv"
    walk_stored = bool(_walk_dirs_by_seed(walk_dirs))
    commands = _commands(
        main_seed, t1, others, per_run, seeded, large, walk, from_csv, repair_rows, repair_file
    )
    regen_cols = (
        f"Regenerate: `{commands['columns']}`"
        + (f" (rewritten here from `{from_csv}` by `{commands['last']}`)" if csv_rows is not None else "")
        + "."
    )
    text = [
        "# Dense obstacles: Ahmed & Deb (2013), Table 1, over random maps",
        "",
        "Generated by `gapath experiment dense` (module `gapath.studies.dense`). "
        f"Integer encoding, objectives length and vulnerability (penalty), population "
        f"{settings.get('pop_size')}, at most {settings.get('n_gen')} generations, stopped "
        f"at the first feasible path; all-random initial population "
        f'(`seed_from="none"`); engine `{t1[0]["engine"] if t1 else "-"}`.'
        + (
            (
                f" This page was regenerated from `{from_csv}` (the columns generator's rows) and "
                "the walk generator's stores: the stores of the columns runs are not kept, so the "
                "lists of the GA seeds of their unsuccessful runs and their cost are not repeated "
                "here (they are in this file's history before issue 17)."
                if walk_stored
                else f" This page was regenerated from `{from_csv}` (the penalty rows of both "
                "generators): their stores are not kept, so the lists of the GA seeds of their "
                "unsuccessful runs and their cost are not repeated here (they are in this file's "
                "history: issue 17)."
            )
            if csv_rows is not None
            else ""
        )
        + (
            ' The section "With the feasibility-preserving repair" runs the same rows with a '
            "repair that is not the paper's method (a GA change, issue 17); every other table is "
            "the paper's protocol."
            if repair_rows
            else ""
        ),
        "",
    ]
    parts_flat = [dict(r, part=p, map_seed=m) for p, m, rows in parts for r in rows]
    runs_of = {
        "columns": _runs_text([r["runs"] for p, _, rows in parts[: 1 + len(others)] for r in rows]),
        "walk": _runs_text([r["runs"] for rows in walk.values() for r in rows]),
    }
    text += headline_lines(
        parts_flat, commands=commands, runs=runs_of, extra=repair_goal_bullets(repair_rows)
    )
    stat_seeds = {
        "columns": sorted(m for m in [main_seed, *others] if isinstance(m, int)),
        "walk": sorted(m for m in walk if isinstance(m, int)),
    }
    if map_stats_seeds:
        stat_seeds = {g: list(range(1, int(map_stats_seeds) + 1)) if v else [] for g, v in stat_seeds.items()}
    grids = sorted({r["grid"] for r in t1}) or [8, 16, 32]
    p0s = sorted({r["p0"] for r in t1}) or list(P0S)
    stats = [r for g, seeds in stat_seeds.items() if seeds for r in map_stats(g, grids, p0s, seeds)]
    text += map_stats_lines(stats, command=commands["last"])
    text += walk_lines(walk, t1, command=commands["walk"])
    for name, cmd in commands["repair"].items():
        text += repair_lines([r for r in repair_rows if r["repair"] == name], parts_flat, command=cmd)
    text += [
        f"## Map {main_seed}: one map per row (the columns generator)" if single else "## Table 1",
        "",
        regen_cols,
        "",
        f"The rows here: {maps_text}.",
        "",
    ]
    if single:
        text += [
            'Why one map per row: the paper takes "100 runs" "for each problem", gives '
            "one integer obstacle count per row (a map's, not a mean), repeats the same "
            "minimum lengths down the rows of a grid (one random path, more obstacles around "
            'it as p0 grows), and says of its 64x64 case, one map, that "feasible paths are '
            "found in 80 % runs\". The map seed is the experiment's first seed, 1, but it "
            "was not chosen blind: this table was first run with a new map for every run, "
            "where seed 1 is the first run's map (GA seed 1 on map seed 1), and that run had "
            "found a feasible path in every row; "
            'the headline changed from "not met: 21 of 30 rows" (a new map per run) to "met: '
            '30 of 30 rows on map 1" after those results were known. Hence the headline of '
            "this page is the distribution over map seeds, and this table is one of its "
            "columns. A few maps trap this GA, so which map a row gets matters: see the rows "
            "on other maps and with a new map for every run below.",
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
        *(_miss_lines(misses) if misses is not None else [_NOT_IN_CSV]),
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
            regen_cols,
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
            regen_cols,
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
            *(_miss_lines(per_run_misses) if per_run_misses is not None else [_NOT_IN_CSV]),
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
            (large_seed, large),
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
            regen_cols,
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
    timing = {}
    if csv_rows is None:
        timing["table1"] = table1_dir
        if seeded:
            timing["table1-seeded"] = seeded_dir
        timing.update({f"table1-map{m}": d for m, d in other_dirs.items()})
        if per_run:
            timing["table1-per-run-maps"] = per_run_dir
        if large:
            timing["large"] = large_dir
        if large_per_run:
            timing["large-per-run-maps"] = large_per_run_dir
    timing.update({f"table1-walk-map{m}": d for m, d in _walk_dirs_by_seed(walk_dirs).items()})
    timing.update({Path(d).name: d for d in repair_dirs if _exists(d)})
    lines = [] if csv_rows is None else ["- the columns runs: " + _NOT_IN_CSV]
    if repair_rows and not any(_exists(d) for d in repair_dirs):
        lines.append("- the runs with a repair: not in dense_repair.csv (see this file's history).")
    if csv_rows is not None and walk and not walk_stored:
        lines.append("- the walk runs without repair: not in dense.csv (see this file's history: issue 17).")
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
        (".png", png_bytes(_plot(t1, per_run, others, walk))),
    ):
        atomic_write(results_dir / f"{basename}{suffix}", data)
        files.append(results_dir / f"{basename}{suffix}")
    if repair_rows:
        atomic_write(repair_file, _repair_csv_text(repair_rows))
        files.append(repair_file)
    return {
        "table1": t1,
        "other_maps": others,
        "per_run": per_run,
        "large": large,
        "large_per_run": large_per_run,
        "unsuccessful": misses,
        "repair": repair_rows,
        "files": files,
    }


def _repair_csv_text(rows) -> str:
    """``dense_repair.csv``: the repair rows, full precision."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(REPAIR_CSV_COLUMNS)
    for r in rows:
        w.writerow(
            [
                "" if r.get(c) is None else (repr(r[c]) if isinstance(r[c], float) else r[c])
                for c in REPAIR_CSV_COLUMNS
            ]
        )
    return buf.getvalue()


def _saved_spec(store_dir) -> dict:
    """The saved spec of a store, as a dict, with every stored seed."""

    return _widened_spec(ResultStore(store_dir)).to_dict()


def _plot(rows, per_run=(), others=None, walk=None):
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.6))
    grids = sorted({r["grid"] for r in rows}, key=lambda g: g if isinstance(g, int) else g[0])
    for i, g in enumerate(grids):
        rr = [r for r in rows if r["grid"] == g]
        p0 = [r["p0"] for r in rr]
        color = f"C{i}"
        a1.plot(
            p0,
            [r["success_pct"] for r in rr],
            "o-" if not others else "o",
            color=color,
            ms=4 if others else 6,
            label=f"{g}x{g} " + ("columns, map 1" if others else "gapath"),
        )
        # per p0: map 1's success and the other maps' (the median and the band)
        band = [
            [r["success_pct"]]
            + [
                o["success_pct"]
                for rows_m in (others or {}).values()
                for o in rows_m
                if o["grid"] == g and o["p0"] == r["p0"]
            ]
            for r in rr
        ]
        if others:
            med = [float(np.median(b)) for b in band]
            a1.plot(
                p0, med, "-", color=color, lw=2, label=f"{g}x{g} columns, median over {len(others) + 1} maps"
            )
        a2.plot(
            p0,
            [np.nan if r["median_generations"] is None else r["median_generations"] for r in rr],
            "o-",
            color=color,
            label=f"{g}x{g} gapath",
        )
        if others:
            a1.fill_between(
                p0,
                [min(b) for b in band],
                [max(b) for b in band],
                color=color,
                alpha=0.12,
                lw=0,
                label=f"{g}x{g} columns, min-max over {len(others) + 1} maps",
            )
        if walk:
            wr = distribution_rows(
                [dict(o, part="table1-walk", map_seed=m) for m, rows_m in walk.items() for o in rows_m]
            )
            wr = [d for d in wr if d["grid"] == g]
            a1.plot(
                [d["p0"] for d in wr],
                [d["walk_median"] for d in wr],
                "-.",
                color=color,
                alpha=0.9,
                label=f"{g}x{g} walk maps, median over {len(walk)}",
            )
        pr = [r for r in per_run if r["grid"] == g]
        if pr:
            a1.plot(
                [r["p0"] for r in pr],
                [r["success_pct"] for r in pr],
                ":",
                color=color,
                alpha=0.8,
                label=f"{g}x{g} columns, new map per run",
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
    a1.legend(fontsize=5, ncol=3, loc="lower left")
    a2.legend(fontsize=7)
    a1.set_title("Table 1: success", fontsize=9)
    a2.set_title("Table 1: speed", fontsize=9)
    return a1


# ---------------------------------------------------------------------------
# the report's headline: the distribution over maps, both generators
# ---------------------------------------------------------------------------

#: Points of success within which a row "reproduces" the paper (headline).
MATCH_POINTS = 10.0

_INT_COLS = {
    "grid",
    "runs",
    "failed",
    "pop_size",
    "n_gen",
    "seeded_runs",
    "paper_obstacles",
    "generations_max",
}


def read_dense_csv(path, flag: str = "--from-csv") -> list[dict]:
    """The rows of a ``dense.csv`` (or ``dense_repair.csv``) written by
    :func:`dense_report`, numbers parsed (empty cells None; ``map_seed`` an
    int, ``"run"`` or None). ``flag`` names the file in messages.

    Raises
    ------
    ConfigError
        If the file is missing or has no ``part`` column.
    """

    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise ConfigError(f"{flag}: cannot read {str(path)!r}: {exc.strerror}") from None
    reader = csv.DictReader(io.StringIO(text))
    if "part" not in (reader.fieldnames or ()):
        raise ConfigError(f"{flag}: {str(path)!r} is not a dense.csv (no 'part' column)")
    out = []
    for raw in reader:
        row = {}
        for k, v in raw.items():
            if v in ("", None):
                row[k] = None
            elif k in ("part", "engine", "repair"):
                row[k] = v
            elif k == "map_seed":
                row[k] = v if v == "run" else int(v)
            elif k in _INT_COLS:
                row[k] = int(float(v))
            else:
                row[k] = float(v)
        out.append(row)
    return out


def _median_range(vals) -> tuple:
    vals = [v for v in vals if v is not None]
    if not vals:
        return None, None, None
    return float(np.median(vals)), float(min(vals)), float(max(vals))


def _spread(vals, mean: bool = False) -> str:
    vals = [v for v in vals if v is not None]
    med, lo, hi = _median_range(vals)
    if med is None:
        return "-"
    return f"{_f(med, 3)} [{_f(lo, 3)}, {_f(hi, 3)}]" + (f", {_f(float(np.mean(vals)), 3)}" if mean else "")


def distribution_rows(parts: list[dict]) -> list[dict]:
    """Per Table 1 row ``(grid, p0)``, the success over maps of each
    generator, from CSV-shaped rows (``part``, ``map_seed``, ``grid``,
    ``p0``, ``success_pct``, ``runs``): ``columns`` ``{map seed: %}``
    (parts ``table1`` and ``table1-other-map``), ``per_run`` (part
    ``table1-per-run-maps``), ``walk`` ``{map seed: %}`` (part
    ``table1-walk``), the paper's %, and each generator's median, min and
    max over its maps.

    Examples
    --------
    >>> rows = distribution_rows([
    ...     {"part": "table1", "map_seed": 1, "grid": 8, "p0": 0.5, "success_pct": 100.0},
    ...     {"part": "table1-other-map", "map_seed": 2, "grid": 8, "p0": 0.5, "success_pct": 80.0},
    ...     {"part": "table1-walk", "map_seed": 1, "grid": 8, "p0": 0.5, "success_pct": 90.0}])
    >>> r = rows[0]
    >>> r["columns_median"], r["columns_min"], r["walk_median"], r["paper_success_pct"]
    (90.0, 80.0, 90.0, 100.0)
    """
    by: dict = {}
    for row in parts:
        key = (int(row["grid"]), round(float(row["p0"]), 3))
        d = by.setdefault(key, {"grid": key[0], "p0": key[1], "columns": {}, "walk": {}, "per_run": None})
        part = row["part"]
        if part in ("table1", "table1-other-map"):
            d["columns"][row["map_seed"]] = row["success_pct"]
        elif part == "table1-walk":
            d["walk"][row["map_seed"]] = row["success_pct"]
        elif part == "table1-per-run-maps":
            d["per_run"] = row["success_pct"]
    out = []
    for key in sorted(by):
        d = by[key]
        if not d["columns"] and not d["walk"]:
            continue
        d["columns"] = dict(sorted(d["columns"].items()))
        d["walk"] = dict(sorted(d["walk"].items()))
        for gen in ("columns", "walk"):
            med, lo, hi = _median_range(d[gen].values())
            d.update({f"{gen}_median": med, f"{gen}_min": lo, f"{gen}_max": hi})
        d["paper_success_pct"] = (paper_row(*key) or {}).get("success_pct")
        out.append(d)
    return out


def _verdict(value, paper) -> str:
    if value is None or paper is None:
        return "-"
    gap = value - paper
    if abs(gap) <= MATCH_POINTS:
        return "reproduced" if gap >= 0 else "reproduced (below)"
    return f"ABOVE by {_f(gap, 3)}" if gap > 0 else f"BELOW by {_f(-gap, 3)}"


def _seed_text(seeds) -> str:
    seeds = sorted(seeds)
    if seeds and seeds == list(range(seeds[0], seeds[-1] + 1)) and len(seeds) > 2:
        return f"{seeds[0]}-{seeds[-1]}"
    return ", ".join(map(str, seeds))


def _seed_arg(seeds) -> str:
    """Map seeds as ``--map-seeds`` takes them (``1-10``, ``1,3``)."""
    return _seed_text(seeds).replace(", ", ",")


def _goal_counts(dist, gen) -> dict:
    rows = [d for d in dist if d[gen] and d["paper_success_pct"] is not None]
    return {
        "rows": len(rows),
        "median": sum(d[f"{gen}_median"] >= d["paper_success_pct"] for d in rows),
        "every": sum(d[f"{gen}_min"] >= d["paper_success_pct"] for d in rows),
        "maps": sum(len(d[gen]) for d in rows),
        "maps_ok": sum(v >= d["paper_success_pct"] for d in rows for v in d[gen].values()),
    }


def headline_lines(parts: list[dict], *, commands: dict, runs: dict, extra=()) -> list[str]:
    """The headline sections of ``dense.md`` from CSV-shaped rows (see
    :func:`distribution_rows`): success per row as median [min, max] over
    the maps of each generator beside the paper, map 1 and the new map per
    run as columns, a verdict per row and the goal's counts.

    ``commands``: ``{"columns": ..., "last": ...}``, the command that
    produced the columns rows and the one that regenerates the page; ``runs``: GA runs per row and map of each;
    ``extra``: further goal bullets (e.g. :func:`repair_goal_bullets`).

    Examples
    --------
    >>> rows = [{"part": "table1", "map_seed": 1, "grid": 32, "p0": 0.5, "success_pct": 98.0},
    ...         {"part": "table1-other-map", "map_seed": 2, "grid": 32, "p0": 0.5,
    ...          "success_pct": 80.0}]
    >>> text = "\\n".join(headline_lines(rows, commands={"columns": "c"}, runs={"columns": 100}))
    >>> "| 32x32 | 0.5 | 36 | 89 [80, 98], 89 | 98 | ABOVE by 53 |" in text
    True
    """

    dist = distribution_rows(parts)
    if not dist:
        return []
    col_seeds = sorted({s for d in dist for s in d["columns"]}, key=str)
    walk_seeds = sorted({s for d in dist for s in d["walk"]}, key=str)
    has_per_run = any(d["per_run"] is not None for d in dist)
    main = 1 if 1 in col_seeds else (col_seeds[0] if col_seeds else None)
    head = ["grid", "p0", "paper %"]
    if col_seeds:
        head += [f"columns: median [min, max], mean over maps {_seed_text(col_seeds)}", f"columns map {main}"]
    if has_per_run:
        head.append("columns, new map per run")
    if walk_seeds:
        head.append(f"walk: median [min, max], mean over maps {_seed_text(walk_seeds)}")
    head += ["columns median vs paper"] if col_seeds else []
    head += ["walk median vs paper"] if walk_seeds else []
    body = []
    for d in dist:
        paper = d["paper_success_pct"]
        line = [f"{d['grid']}x{d['grid']}", f"{d['p0']:g}", _f(paper, 3)]
        if col_seeds:
            line += [_spread(d["columns"].values(), mean=True), _f(d["columns"].get(main), 3)]
        if has_per_run:
            line.append(_f(d["per_run"], 3))
        if walk_seeds:
            line.append(_spread(d["walk"].values(), mean=True))
        if col_seeds:
            line.append(_verdict(d["columns_median"], paper))
        if walk_seeds:
            line.append(_verdict(d["walk_median"], paper))
        body.append(line)
    text = [
        "## Headline: success over random maps, beside the paper",
        "",
        f"Regenerate: `{commands.get('last', commands.get('columns'))}`"
        + (
            f" (the columns rows come from `{commands['columns']}`)"
            if commands.get("columns") and commands.get("last")
            else ""
        )
        + ".",
        "",
        "Success % per Table 1 row as the median [min, max] over map seeds, for two map "
        "generators: **columns** (`gapath.dense_workspace`, the one used so far: a random "
        "walk of -2 to 2 rows per column, then the goal column climbed, the integer "
        "encoding's own end-fix shape) and **walk** (`gapath.studies.dense.walk_workspace`: "
        "a goal-biased 8-connected walk, see below). "
        + (f"Columns: {runs.get('columns')} GA runs per row and map. " if col_seeds else "")
        + (f"Walk: {runs.get('walk')} GA runs per row and map (a reduced protocol). " if walk_seeds else "")
        + (
            "New map per run: one GA run on each of 100 maps per row (map seed = GA seed). "
            if has_per_run
            else ""
        )
        + "The mean over maps estimates the success expected over random maps (as the new map "
        "per run does, with fewer maps). "
        + f"Verdict (on the median): within {MATCH_POINTS:g} points of the paper is *reproduced*; further "
        "above or below is a different result, marked ABOVE or BELOW.",
        "",
        markdown_table(head, body),
        "",
    ]
    # plain words
    said = []
    for gen, label in (("columns", "columns generator"), ("walk", "walk generator")):
        if not any(d[gen] for d in dist):
            continue
        above = [
            d
            for d in dist
            if d[gen] and _verdict(d[f"{gen}_median"], d["paper_success_pct"]).startswith("ABOVE")
        ]
        below = [
            d
            for d in dist
            if d[gen] and _verdict(d[f"{gen}_median"], d["paper_success_pct"]).startswith("BELOW")
        ]
        g = _goal_counts(dist, gen)

        def _list(rows, gen=gen):
            return ", ".join(
                f"{d['grid']}x{d['grid']} p0 {d['p0']:g} ({_f(d[f'{gen}_median'], 3)} vs "
                f"{_f(d['paper_success_pct'], 3)})"
                for d in rows
            )

        big = [d for d in dist if d["grid"] == max(x["grid"] for x in dist) and d["p0"] >= 0.5 and d[gen]]
        big_text = ""
        if big and all(d["paper_success_pct"] is not None for d in big):
            n = big[0]["grid"]
            far = sum(abs(d[f"{gen}_median"] - d["paper_success_pct"]) > 35 for d in big)
            big_text = (
                f"At {n}x{n} with p0 >= 0.5 its median over maps is "
                f"{_f(min(d[f'{gen}_median'] for d in big), 3)}-{_f(max(d[f'{gen}_median'] for d in big), 3)} % "
                f"against the paper's {_f(min(d['paper_success_pct'] for d in big), 3)}-"
                f"{_f(max(d['paper_success_pct'] for d in big), 3)} %, more than 35 points apart in "
                f"{far} of {len(big)} rows"
                + (
                    ": a different result, not a match. "
                    if 2 * far >= len(big)
                    else (": those rows are a different result. " if far else ". ")
                )
            )
        met = g["every"] == g["rows"]
        said.append(
            f"- **{label}**: goal {'met' if met else 'NOT met'} ("
            f"every map at or above the paper in {g['every']} of {g['rows']} rows). "
            + big_text
            + f"The median over maps is at or above the paper in {g['median']} of "
            f"{g['rows']} rows; {g['maps_ok']} of {g['maps']} (row, map) pairs are at or above it. "
            + (
                f"Not reproduced, ABOVE the paper by more than {MATCH_POINTS:g} points: {_list(above)}. "
                if above
                else ""
            )
            + (f"Not reproduced, BELOW: {_list(below)}." if below else "")
        )
    said += list(extra)
    if has_per_run:
        pr = [d for d in dist if d["per_run"] is not None and d["paper_success_pct"] is not None]
        ok = sum(d["per_run"] >= d["paper_success_pct"] for d in pr)
        gaps = [(float(np.mean(list(d["columns"].values()))) - d["per_run"], d) for d in pr if d["columns"]]
        gap_text = ""
        if gaps:
            gap, d = max(gaps, key=lambda t: abs(t[0]))
            gap_text = (
                f" The mean over the {len(d['columns'])} columns map seeds differs from it by up to "
                f"{_f(abs(gap), 3)} points ({d['grid']}x{d['grid']} p0 {d['p0']:g}): "
                f"{len(d['columns'])} maps are few where the success varies this much from map to map."
            )
        said.append(
            f"- **columns, a new map per run**: at or above the paper in {ok} of {len(pr)} rows." + gap_text
        )
    text += [
        "The goal (at or above the paper in every row over random maps, with both generators):",
        "",
        *said,
        "",
        "The 10 rows of a grid share one map per seed: `dense_workspace(grid, p0, seed)` (and "
        "`walk_workspace`) draws the "
        "free path and the cells' uniform numbers from the seed alone, so the maps of a grid "
        "differ only in the threshold p0 and nest (every obstacle at p0 is an obstacle at any "
        "larger p0). A row's success on map 1 is therefore not an independent sample: "
        '"30 of 30 rows at or above the paper on map 1" rests on three maps (one per grid '
        "size), and on map 1, which had already succeeded in every row when it was chosen "
        "(see below). The distribution over map seeds is the figure to read; map 1 is one of "
        "its columns.",
        "",
    ]
    return text


def _path_length(path) -> float:
    d = np.diff(np.asarray(path, dtype=float), axis=0)
    return float(np.hypot(d[:, 0], d[:, 1]).sum())


def map_stats(generator: str, grids=(8, 16, 32), p0s=P0S, seeds=(MAP_SEED,)) -> list[dict]:
    """Each map's free-cell count, obstacle count and exact shortest path
    lengths: ``shortest_free`` (8-connected, :func:`gapath.planners.astar`)
    and ``shortest_monotone`` (the shortest column-monotone path, what the
    integer encoding can represent:
    :func:`gapath.planners.weighted_sum.weighted_sum_path` with length
    only), for the maps ``generated_workspace(generator, grid, p0, seed)``.

    Examples
    --------
    >>> (r,) = map_stats("columns", (8,), (1.0,), (1,))
    >>> r["free"] + r["obstacles"] == 64, r["shortest_monotone"] >= r["shortest_free"] >= 7 * 2**0.5
    (True, True)
    """

    out = []
    for n in grids:
        for p0 in p0s:
            for s in seeds:
                ws = generated_workspace(generator, int(n), float(p0), int(s))
                out.append(
                    {
                        "generator": generator,
                        "grid": int(n),
                        "p0": float(p0),
                        "map_seed": int(s),
                        "free": int((~ws.occ).sum()),
                        "obstacles": ws.n_obstacles,
                        "shortest_free": float(astar(ws).length),
                        "shortest_monotone": _path_length(weighted_sum_path(ws, 1.0, 0.0)),
                    }
                )
    return out


def _p1_lengths(stats) -> list[str]:
    out = []
    for n in sorted({r["grid"] for r in stats}):
        paper = paper_row(n, 1.0)
        parts = [
            f"{g} {_f(float(np.median([r['shortest_monotone'] for r in rows])), 4)}"
            for g in dict.fromkeys(r["generator"] for r in stats)
            if (rows := [r for r in stats if r["generator"] == g and r["grid"] == n and r["p0"] == 1.0])
        ]
        if parts and paper:
            out.append(f"{n}x{n}: paper {_f(paper['mean_min_path_length'], 4)}, median " + ", ".join(parts))
    return out


def map_stats_lines(stats: list[dict], *, command: str) -> list[str]:
    """The maps section of ``dense.md``: per Table 1 row, the paper's obstacle
    count and length beside each generator's obstacles, free cells and exact
    shortest lengths (map 1, and median [min, max] over the seeds).

    Examples
    --------
    >>> text = "\\n".join(map_stats_lines(map_stats("walk", (8,), (1.0,), (1, 2)), command="c"))
    >>> "| 8x8 | 1 | 54 | 11.07 |" in text
    True
    """

    if not stats:
        return []
    gens = list(dict.fromkeys(r["generator"] for r in stats))
    by: dict = {}
    for r in stats:
        by.setdefault((r["grid"], round(r["p0"], 3)), {}).setdefault(r["generator"], []).append(r)
    head = ["grid", "p0", "paper obstacles", "paper mean min length"]
    for g in gens:
        seeds = sorted({r["map_seed"] for r in stats if r["generator"] == g})
        head += [
            f"{g} map 1: obstacles / free / shortest 8-conn. / shortest monotone",
            f"{g} maps {_seed_text(seeds)}: obstacles",
            f"{g}: shortest monotone",
        ]
    body = []
    for (n, p0), per in sorted(by.items()):
        paper = paper_row(n, p0) or {}
        line = [
            f"{n}x{n}",
            f"{p0:g}",
            str(paper.get("obstacles", "-")),
            _f(paper.get("mean_min_path_length"), 4),
        ]
        for g in gens:
            rows = per.get(g, [])
            m1 = next((r for r in rows if r["map_seed"] == 1), None)
            line.append(
                "-"
                if m1 is None
                else f"{m1['obstacles']} / {m1['free']} / {_f(m1['shortest_free'], 4)} / "
                f"{_f(m1['shortest_monotone'], 4)}"
            )
            line.append(_spread([float(r["obstacles"]) for r in rows]).replace(" [", " ["))
            line.append(_spread([r["shortest_monotone"] for r in rows]))
        body.append(line)
    return [
        "## The maps: obstacles, free cells and exact shortest lengths",
        "",
        f"Regenerate: `{command}`.",
        "",
        "Every map of the report, computed from the generators (no GA): its obstacle count, "
        "free cells, the exact shortest 8-connected path (A*) and the exact shortest "
        "column-monotone path (the shortest path the integer encoding can represent; dynamic "
        "programme `weighted_sum_path(ws, 1, 0)`), beside the paper's obstacle count and mean "
        "minimum length. The paper's 16x16 p0 0.8 row reads 286 obstacles on a grid of 256 "
        "cells: a misprint (its neighbours are 164 at p0 0.7 and 214 at 0.9). At p0 = 1 only "
        "the kept path is free, so the exact shortest path is about the kept path's length: "
        + "; ".join(_p1_lengths(stats))
        + ". A mean minimum length below a map's exact shortest path is impossible, so where "
        "the paper's is lower its maps kept a straighter path than ours.",
        "",
        markdown_table(head, body),
        "",
    ]


# ---------------------------------------------------------------------------
# Table 1 with a feasibility-preserving repair (issue 17 §1-2: a GA change)
# ---------------------------------------------------------------------------

#: The report parts of the repair rows, per generator (``dense_repair.csv``).
REPAIR_PARTS = {"columns": "table1-repair", "walk": "table1-walk-repair"}

_REPAIR_STORE = re.compile(r"^table1-(walk-)?map(\d+)-(.+)$")

#: What was run with a repair before its protocol was stated (reported
#: with its rows): development runs, not results.
REPAIR_DEVELOPMENT = {
    "feasible-local": "Before this protocol was stated, and not among its results: GA seeds 1-2 on "
    "maps 1-3 of both generators in the rows 16x16 p0 0.6 and 32x32 p0 0.6 and 1.0, and 10 GA "
    "runs per row on columns map 1, to measure the cost; nothing was tuned (the repair has no "
    "parameter besides its mode and share, fixed in `penalty.md`'s protocol).",
}

#: The columns of ``dense_repair.csv``.
REPAIR_CSV_COLUMNS = [
    "part",
    "repair",
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
    "generations_max",
    "initial_pct",
    "paper_median_generations",
    "mean_min_path_length",
    "paper_mean_min_path_length",
    "best_min_path_length",
    "pop_size",
    "n_gen",
    "engine",
]


def check_repair(repair, engine: str = "fast") -> str | None:
    """``repair`` as the study runs it: None for Ahmed & Deb's edge-fixing
    alone (None or ``"edge"``), else a name of
    :data:`gapath.operators.repair.feasible.REPAIRS`.

    Raises
    ------
    ConfigError
        On an unknown name, or a repair with an engine other than ``fast``.

    Examples
    --------
    >>> check_repair("edge"), check_repair("feasible-local")
    (None, 'feasible-local')
    """

    from gapath.operators.repair.feasible import REPAIRS

    if repair in (None, "edge"):
        return None
    if repair not in REPAIRS:
        raise ConfigError(f"--repair: expected one of {', '.join(REPAIRS)}, got {repair!r}")
    if engine != "fast":
        raise ConfigError(f"--repair {repair} needs --engine fast (got --engine {engine})")
    return str(repair)


def repair_store_name(generator: str, map_seed: int, repair: str) -> str:
    """The store of the Table 1 rows with ``repair`` on the maps of
    ``generator`` and ``map_seed`` (under ``gapath experiment dense --out``).

    Examples
    --------
    >>> repair_store_name("columns", 3, "feasible-local"), repair_store_name("walk", 1, "feasible-reach")
    ('table1-map3-feasible-local', 'table1-walk-map1-feasible-reach')
    """
    return f"table1-{'walk-' if generator == 'walk' else ''}map{int(map_seed)}-{repair}"


def repair_dirs(out, repair: str | None = None) -> list[Path]:
    """The repair stores under ``out`` (of ``repair``, or of every repair),
    columns first, by map seed."""

    from gapath.operators.repair.feasible import REPAIRS

    found = []
    for p in Path(out).glob("table1-*map*-*"):
        m = _REPAIR_STORE.match(p.name)
        if m and m[3] in REPAIRS and m[3] != "edge" and (repair is None or m[3] == repair):
            found.append((bool(m[1]), int(m[2]), m[3], p))
    return [p for *_, p in sorted(found)]


def _repair_store_rows(store_dir) -> list[dict]:
    """The CSV-shaped rows of one repair store."""
    m = _REPAIR_STORE.match(Path(store_dir).name)
    generator = "walk" if m and m[1] else "columns"
    shares = _first_generations(store_dir)
    out = []
    for r in _with_paper(_rows(store_dir)):
        initial, latest = shares.get((r["grid"], r["p0"]), (None, None))
        out.append(
            dict(
                r,
                part=REPAIR_PARTS[generator],
                map_seed=map_seed_of(store_dir),
                initial_pct=initial,
                generations_max=latest,
            )
        )
    return out


def read_repair_csv(path) -> list[dict]:
    """The rows of a ``dense_repair.csv`` written by :func:`dense_report`.

    Raises
    ------
    ConfigError
        If the file is missing or holds no repair rows.
    """

    rows = read_dense_csv(path, flag="--repair-csv")
    if not rows or any(r["part"] not in REPAIR_PARTS.values() or not r.get("repair") for r in rows):
        raise ConfigError(f"--repair-csv: {str(path)!r} is not a dense_repair.csv (expected repair rows)")
    return rows


def _repair_parts(dirs, repair_csv) -> list[dict]:
    """The repair rows of :func:`dense_report`: from the stores, and from
    ``repair_csv`` for each (part, repair, map seed) no store holds."""

    rows = [r for d in dirs if _exists(d) for r in _repair_store_rows(d)]
    have = {(r["part"], r.get("repair"), r["map_seed"]) for r in rows}
    if repair_csv is not None:
        rows += [
            r for r in read_repair_csv(repair_csv) if (r["part"], r["repair"], r["map_seed"]) not in have
        ]
    return sorted(
        rows, key=lambda r: (r["repair"], r["part"] != "table1-repair", r["map_seed"], r["grid"], r["p0"])
    )


def _repair_dist(rows, name) -> list[dict]:
    """:func:`distribution_rows` of one repair's rows (``columns`` and
    ``walk`` their generators' maps)."""

    as_penalty = {"table1-repair": "table1-other-map", "table1-walk-repair": "table1-walk"}
    return distribution_rows([dict(r, part=as_penalty[r["part"]]) for r in rows if r["repair"] == name])


def _initial_share(rows) -> tuple:
    """(% of the successful runs of ``rows`` whose first feasible path was in
    the initial population, successful runs)."""
    succ = [(r["runs"] * r["success_pct"] / 100.0, r.get("initial_pct")) for r in rows if r["success_pct"]]
    total = sum(n for n, v in succ if v is not None)
    return (sum(n * v for n, v in succ if v is not None) / total if total else None), round(total)


def repair_goal_bullets(rows: list[dict]) -> list[str]:
    """The headline's goal bullets with a repair: per repair and generator,
    whether every map is at or above the paper in every row.

    Examples
    --------
    >>> rows = [{"part": "table1-repair", "repair": "feasible-local", "map_seed": 1, "grid": 32,
    ...          "p0": 0.5, "success_pct": 100.0, "runs": 10, "initial_pct": 80.0}]
    >>> print(repair_goal_bullets(rows)[0][:89])
    - **columns generator with the repair `feasible-local`**: goal met with the repair (every
    """

    out = []
    for name in dict.fromkeys(r["repair"] for r in rows):
        dist = _repair_dist(rows, name)
        for gen, part in REPAIR_PARTS.items():
            if not any(d[gen] for d in dist):
                continue
            g = _goal_counts(dist, gen)
            share, n = _initial_share([r for r in rows if r["repair"] == name and r["part"] == part])
            out.append(
                f"- **{gen} generator with the repair `{name}`**: goal "
                f"{'met' if g['every'] == g['rows'] else 'NOT met'} with the repair (every map at or "
                f"above the paper in {g['every']} of {g['rows']} rows; {g['maps_ok']} of {g['maps']} "
                "(row, map) pairs). A GA change, not Ahmed & Deb's method"
                + (
                    f": {_f(share, 3)} % of the {n} successful runs had their first feasible path in "
                    "the initial population, so there the repair, not evolution, found it"
                    if share is not None
                    else ""
                )
                + ' (see "With the feasibility-preserving repair").'
            )
    return out


def _penalty_runs(parts) -> str:
    """The GA runs per row and map of the penalty rows of the headline, per
    generator (``"columns 100, walk 30"``)."""
    which = {"columns": ("table1", "table1-other-map"), "walk": ("table1-walk",)}
    out = [
        f"{g} {text}"
        for g, names in which.items()
        if (text := _runs_text([r["runs"] for r in parts if r["part"] in names]))
    ]
    return ", ".join(out)


def _above_text(dist, gen) -> str:
    """The rows where ``gen``'s median over maps exceeds the paper by more
    than :data:`MATCH_POINTS`: not a reproduction."""
    above = [
        d for d in dist if d[gen] and _verdict(d[f"{gen}_median"], d["paper_success_pct"]).startswith("ABOVE")
    ]
    if not above:
        return ""
    return (
        f" Above the paper by more than {MATCH_POINTS:g} points in {len(above)} rows ("
        + ", ".join(
            f"{d['grid']}x{d['grid']} p0 {d['p0']:g}: {_f(d[f'{gen}_median'], 3)} vs {_f(d['paper_success_pct'], 3)}"
            for d in above
        )
        + "): that exceeds the paper and is the repair's result, not a reproduction of it."
    )


def _gen_spread(rows) -> str:
    """Median [min, max] over maps of each map's median first feasible
    generation, and the latest run's."""
    meds = [r.get("median_generations") for r in rows]
    text = _spread(meds)
    latest = [r.get("generations_max") for r in rows if r.get("generations_max") is not None]
    return text + (f"; latest {_f(max(latest))}" if latest else "")


def repair_lines(rows: list[dict], penalty_parts: list[dict], *, command: dict) -> list[str]:
    """The section of ``dense.md`` on the Table 1 rows run with a repair:
    per row, the success over maps of each generator with the repair beside
    the penalty protocol's and the paper's, and the first feasible
    generation.

    ``command``: ``{"columns": ..., "walk": ..., "csv": ...}``, the
    commands behind the rows (``csv``: the file the rows are kept in).

    Examples
    --------
    >>> rows = [{"part": "table1-walk-repair", "repair": "feasible-local", "map_seed": 1, "grid": 8,
    ...          "p0": 0.5, "success_pct": 100.0, "runs": 10, "initial_pct": 100.0,
    ...          "median_generations": 1.0, "generations_max": 1}]
    >>> text = "\\n".join(repair_lines(rows, [], command={"walk": "w"}))
    >>> "| 8x8 | 0.5 | 100 | - | - | - | - | - | 100 [100, 100] | 1 of 1 | 1 [1, 1]; latest 1; 100 % in 1 |" in text
    True
    """

    from gapath.operators.repair.feasible import REPAIRS

    if not rows:
        return []
    penalty = {(d["grid"], d["p0"]): d for d in distribution_rows(penalty_parts)}
    text = [
        "## With the feasibility-preserving repair",
        "",
        "Regenerate: "
        + ", then ".join(
            f"`{command[g]}` ({g} maps)" for g in ("columns", "walk") if command.get(g) is not None
        )
        + (
            f"; without the stores, the same with `--repair-csv {command['csv']}` (the rows are kept in "
            f"`{command['csv']}`)"
            if command.get("csv")
            else ""
        )
        + ".",
        "",
    ]
    for name in dict.fromkeys(r["repair"] for r in rows):
        mine = [r for r in rows if r["repair"] == name]
        dist = _repair_dist(rows, name)
        kw = REPAIRS.get(name) or {}
        seeds = {
            g: sorted({r["map_seed"] for r in mine if r["part"] == p}, key=str)
            for g, p in REPAIR_PARTS.items()
        }
        runs = _runs_text([r["runs"] for r in mine])
        head = ["grid", "p0", "paper %"]
        for g in ("columns", "walk"):
            head += [
                f"{g}, penalty only: median [min, max]",
                f"{g} + repair: median [min, max]",
                f"{g} + repair: maps at or above the paper",
                f"{g} + repair: first feasible gen., median [min, max] over maps; latest; "
                "% of the successful runs in gen. 1",
            ]
        body = []
        for d in dist:
            k = (d["grid"], d["p0"])
            paper = d["paper_success_pct"]
            line = [f"{k[0]}x{k[0]}", f"{k[1]:g}", _f(paper, 3)]
            for g, part in REPAIR_PARTS.items():
                rr = [r for r in mine if r["part"] == part and (r["grid"], round(r["p0"], 3)) == k]
                pen = penalty.get(k, {}).get(g) or {}
                vals = list(d[g].values())
                line += [
                    _spread(pen.values()) if pen else "-",
                    _spread(vals) if vals else "-",
                    f"{sum(paper is not None and v >= paper for v in vals)} of {len(vals)}" if vals else "-",
                    f"{_gen_spread(rr)}; {_f(_initial_share(rr)[0], 3)} % in 1" if rr else "-",
                ]
            body.append(line)
        said = []
        for g, part in REPAIR_PARTS.items():
            rr = [r for r in mine if r["part"] == part]
            if not rr:
                continue
            goal = _goal_counts(dist, g)
            share, n = _initial_share(rr)
            med1 = sum(
                1
                for d in dist
                if d[g]
                and (
                    m := _median_range(
                        r.get("median_generations")
                        for r in rr
                        if (r["grid"], round(r["p0"], 3)) == (d["grid"], d["p0"])
                    )[0]
                )
                is not None
                and m <= 1
            )
            latest = max(
                (r for r in rr if r.get("generations_max") is not None),
                key=lambda r: r["generations_max"],
                default=None,
            )
            said.append(
                f"- **{g}**: every map at or above the paper in {goal['every']} of {goal['rows']} rows "
                f"(goal {'met' if goal['every'] == goal['rows'] else 'NOT met'} with the repair), the "
                f"median over maps in {goal['median']} of {goal['rows']}. "
                + (
                    f"{_f(share, 3)} % of the {n} successful runs found their first feasible path in the "
                    "initial population (pymoo's generation 1, before any selection or variation): for "
                    "those the repair, not evolution, found the path. "
                    if share is not None
                    else ""
                )
                + f"The median over maps of the median first feasible generation is 1 in {med1} of "
                f"{goal['rows']} rows"
                + (
                    f"; the latest first feasible path came in generation {latest['generations_max']} "
                    f"({latest['grid']}x{latest['grid']} p0 {latest['p0']:g}, map {latest['map_seed']})."
                    if latest
                    else "."
                )
                + _above_text(dist, g)
            )
        mode = f"`FeasibleStepRepair(mode={kw.get('mode')!r}, share={kw.get('share', 1.0):g})`"
        text += [
            f"### `{name}`",
            "",
            f"Protocol (stated before the runs): the Table 1 rows of the penalty protocol above "
            "(integer encoding, objectives length and vulnerability with gapath's penalty 1000, "
            "population 200, at most 500 generations, stop at the first feasible path, "
            f'all-random initial population, `seed_from="none"`), with `repair="{name}"` ({mode}, '
            "`gapath.operators.repair.feasible`): every new genome, the initial population's "
            "included, is edge-fixed as in the paper and then every column step that touches an "
            "obstacle is moved to the nearest exit row from which it is free, written back into "
            f"the genes. {runs} GA runs per row and map (GA seeds 1, 2, ...), map seeds "
            + "; ".join(f"{g} {_seed_text(v)}" for g, v in seeds.items() if v)
            + ". The penalty-only columns repeat the headline's figures"
            + (f" ({pen_runs} GA runs per row and map)" if (pen_runs := _penalty_runs(penalty_parts)) else "")
            + ". The repair is a GA change, as issue 17 allows (§2: feasibility-preserving "
            "variation), not Ahmed & Deb's method: the penalty-only rows above stay the "
            "reproduction of the paper. It builds feasible paths from the random genomes by "
            "itself wherever the nearest free exit rows lead to the goal, so on Table 1 it "
            "measures the repair more than evolution (`docs/results/penalty.md`, the repair "
            "section). Generations as in pymoo (1 = the initial population); per map the median "
            "over its successful runs, then median [min, max] over maps and the latest run's."
            + (f" {REPAIR_DEVELOPMENT[name]}" if name in REPAIR_DEVELOPMENT else ""),
            "",
            markdown_table(head, body),
            "",
            *said,
            "",
        ]
    return text


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
    generator: str = "columns",
    from_csv=None,
    repair: str | None = None,
    repair_csv=None,
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
    generator : ``"columns"`` (default, :func:`gapath.dense_workspace`) or
        ``"walk"`` (:func:`walk_workspace`): with ``"walk"`` only the Table 1
        rows run, one store per map seed, ``out/table1-walk-map<S>`` (maps in
        ``out/walk-maps``), and the report puts them beside the
        ``"columns"`` rows (from their stores under ``out``, or from
        ``from_csv``).
    from_csv : a ``dense.csv`` written earlier: the ``"columns"`` rows of the
        report come from it instead of the stores (when the stores are gone;
        the lists of unsuccessful runs and the cost then are not reported).
    repair : a name of :data:`gapath.operators.repair.feasible.REPAIRS`
        other than ``"edge"`` (e.g. ``"feasible-local"``; a GA change, not
        the paper's method): only the Table 1 rows run, with that repair, on
        the maps of ``generator`` and ``map_seeds``, one store per map seed
        (:func:`repair_store_name`: ``out/table1-map<S>-<repair>``,
        ``out/table1-walk-map<S>-<repair>``), and the report puts them
        beside the penalty rows (their stores under ``out``, or
        ``from_csv``). Every invocation reports the repair stores it finds
        under ``out``.
    repair_csv : a ``dense_repair.csv`` written earlier: the repair rows no
        store under ``out`` holds come from it.

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

    from gapath.experiments.spec import resolve_engine

    if generator not in GENERATORS:
        raise ConfigError(f"generator: expected one of {', '.join(GENERATORS)}, got {generator!r}")
    repair = check_repair(repair, resolve_engine(engine))
    if repair_csv is not None:
        read_repair_csv(repair_csv)  # fail before the runs, not after
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
    run_kw = dict(workers=workers, scheduler=scheduler, progress=progress, retry_failed=retry_failed)
    if repair is not None:
        return _run_repair(
            out,
            grids,
            p0s,
            runs,
            n_gen,
            map_seeds,
            sfx,
            generator=generator,
            repair=repair,
            engine=engine,
            results=Path(results) if results else (out if quick else Path("docs/results")),
            from_csv=from_csv,
            repair_csv=repair_csv,
            run_kw=run_kw,
        )
    if generator == "walk":
        return _run_walk(
            out,
            grids,
            p0s,
            runs,
            n_gen,
            map_seeds,
            sfx,
            engine=engine,
            results=Path(results) if results else (out if quick else Path("docs/results")),
            from_csv=from_csv,
            repair_csv=repair_csv,
            run_kw=run_kw,
        )
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
        repair_dirs=repair_dirs(out),
        repair_csv=repair_csv,
    )
    return {**rep, "failed": failed, "wall_seconds": wall}


def _penalty_report_kw(out, from_csv, what: str) -> dict:
    """The :func:`dense_report` arguments of the columns generator's
    penalty rows beside which ``what`` reports: their stores under ``out``,
    or ``from_csv``.

    Raises
    ------
    ConfigError
        If there are neither, or ``from_csv`` is not a dense.csv (before any
        run).
    """

    cols = sorted(
        (int(m[1]), p) for p in out.glob("table1-map*") if (m := re.fullmatch(r"table1-map(\d+)", p.name))
    )
    if from_csv is None and not cols:
        raise ConfigError(
            f"{what} reports beside the columns generator's rows: none in {str(out)!r}; "
            "run `gapath experiment dense` with the same --out first, or give --from-csv"
        )
    if from_csv is not None:
        read_dense_csv(from_csv)  # fail before the runs, not after
        return {"table1_dir": None, "from_csv": from_csv}
    main = dict(cols).get(MAP_SEED, cols[0][1])
    main_seed = MAP_SEED if MAP_SEED in dict(cols) else cols[0][0]
    return dict(
        table1_dir=main,
        large_dir=out / f"large-map{main_seed}",
        seeded_dir=out / f"table1-map{main_seed}-seeded",
        other_map_dirs=[p for _, p in cols if p != main],
        per_run_dir=out / "table1-per-run-maps",
        large_per_run_dir=out / "large-per-run-maps",
    )


def _run_walk(
    out, grids, p0s, runs, n_gen, map_seeds, sfx, *, engine, results, from_csv, repair_csv, run_kw
) -> dict:
    """``run(generator="walk")``: the Table 1 rows on walk maps, one store per
    map seed, then the report with both generators."""
    import time

    report_kw = _penalty_report_kw(out, from_csv, "--generator walk")
    wall, failed, walk_dirs = {}, 0, []
    for m in map_seeds:
        name = f"table1-walk-map{m}"
        spec = walk_table1_spec(
            out / "walk-maps",
            grids,
            p0s,
            runs,
            map_seed=m,
            n_gen=n_gen,
            engine=engine,
            name=f"dense-{name}{sfx}",
        )
        t0 = time.perf_counter()
        r = run_experiment(spec, out / name, **run_kw)
        failed += r.failed
        if r.ran:
            wall[name] = time.perf_counter() - t0
        walk_dirs.append(out / name)
    rep = dense_report(
        results_dir=results,
        walk_dirs=walk_dirs,
        wall_seconds=wall,
        workers=run_kw.get("workers"),
        repair_dirs=repair_dirs(out),
        repair_csv=repair_csv,
        **report_kw,
    )
    return {**rep, "failed": failed, "wall_seconds": wall}


def _run_repair(
    out,
    grids,
    p0s,
    runs,
    n_gen,
    map_seeds,
    sfx,
    *,
    generator,
    repair,
    engine,
    results,
    from_csv,
    repair_csv,
    run_kw,
) -> dict:
    """``run(repair=...)``: the Table 1 rows with the repair on the maps of
    ``generator``, one store per map seed, then the report with the penalty
    rows and every repair store under ``out``."""
    import time

    report_kw = _penalty_report_kw(out, from_csv, "--repair")
    wall, failed = {}, 0
    for m in map_seeds:
        name = repair_store_name(generator, m, repair)
        common = dict(n_gen=n_gen, engine=engine, name=f"dense-{name}{sfx}", repair=repair)
        if generator == "walk":
            spec = walk_table1_spec(out / "walk-maps", grids, p0s, runs, map_seed=m, **common)
        else:
            spec = table1_spec(grids, p0s, runs, map_seed=m, **common)
        t0 = time.perf_counter()
        r = run_experiment(spec, out / name, **run_kw)
        failed += r.failed
        if r.ran:
            wall[name] = time.perf_counter() - t0
    walk_dirs = sorted(p for p in out.glob("table1-walk-map*") if re.fullmatch(r"table1-walk-map\d+", p.name))
    rep = dense_report(
        results_dir=results,
        walk_dirs=walk_dirs,
        wall_seconds=wall,
        workers=run_kw.get("workers"),
        repair_dirs=repair_dirs(out),
        repair_csv=repair_csv,
        **report_kw,
    )
    return {**rep, "failed": failed, "wall_seconds": wall}
