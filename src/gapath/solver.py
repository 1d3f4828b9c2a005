"""One GA run on a workspace, from settings to a front (the CLI's engine)."""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from pymoo.optimize import minimize

from gapath.algorithms import FastNSGA2, paper_nsga2
from gapath.callbacks import Callbacks, ProgressBar, population_arrays
from gapath.errors import ConfigError, positive_int
from gapath.front import PathFront, path_front
from gapath.operators import PlannerSampling
from gapath.problems import GridPathProblem
from gapath.workspace import Workspace

#: Engines that run Ahmed & Deb's NSGA-II (same results for the same seed).
ENGINES = {"fast": lambda pop_size, **kw: FastNSGA2(pop_size, **kw), "pymoo": paper_nsga2}


@dataclass(eq=False)
class SolveResult:
    """What :func:`solve` returns.

    Attributes
    ----------
    workspace, problem : what was solved.
    front : the feasible non-dominated paths (:class:`gapath.front.PathFront`).
    settings : the run's settings (JSON-serialisable).
    seconds : wall time of the optimisation.
    n_eval : evaluations made (with free paths, the re-routed paths of
        the archive included).
    n_gen : generations completed.
    interrupted : True when the run was stopped (Ctrl-C) and ``front`` is
        that of the last complete generation.
    """

    workspace: Workspace
    problem: GridPathProblem
    front: PathFront
    settings: dict
    seconds: float
    n_eval: int
    n_gen: int
    interrupted: bool = False
    pymoo_result: object = field(default=None, repr=False)


def objective_mode(objectives, constraints=None, sbx_eta=None, tiebreak="smoothness") -> dict:
    """Ahmed & Deb's settings for the objective mode of ``objectives``.

    * two objectives: penalty handling, SBX eta 10, smoothness tie-break;
    * three objectives: the same with plain rank and crowding (pass
      ``tiebreak=None``);
    * one objective (length or vulnerability): ``interfering`` as a
      constraint and SBX eta 2 (Ahmed & Deb's single-objective comparison).

    Explicit values win over the mode's defaults.
    """
    names = objectives.split(",") if isinstance(objectives, str) else list(objectives)
    single = len([n for n in names if n.strip()]) == 1
    return dict(
        constraints=constraints or ("constraint" if single else "penalty"),
        sbx_eta=sbx_eta if sbx_eta is not None else (2.0 if single else 10.0),
        tiebreak=tiebreak,
    )


def solve(
    workspace: Workspace,
    *,
    objectives=("length", "vulnerability"),
    encoding=None,
    paths="monotone",
    constraints=None,
    penalty=1000.0,
    pop_size=500,
    n_gen=500,
    seed=1,
    tiebreak="smoothness",
    sbx_eta=None,
    seed_from="weighted",
    engine="fast",
    progress=False,
    callback=None,
    pm_prob_var=None,
    adaptive_penalty=None,
    repair=None,
    refine=None,
    costmap=None,
) -> SolveResult:
    """Run Ahmed & Deb's NSGA-II on ``workspace`` and return its front.

    Parameters
    ----------
    workspace : :class:`gapath.Workspace`.
    objectives, encoding, constraints, penalty : see
        :class:`gapath.problems.GridPathProblem` (``paths="monotone"``,
        encoding default ``"integer"``) and
        :class:`gapath.problems.FreePathProblem` (``paths="free"``, encoding
        default ``"field"``); ``constraints`` defaults by objective mode
        (:func:`objective_mode`). ``constraints="adaptive"``: the problem
        returns ``interfering`` as its constraint and the fast engine ranks
        on objectives penalised by a
        :class:`gapath.constraints.AdaptivePenalty` that starts at
        ``penalty`` and adapts to the share of feasible paths (see
        :mod:`gapath.constraints`; not with ``engine="pymoo"``).
    adaptive_penalty : with ``constraints="adaptive"``, the keyword
        arguments of :class:`gapath.constraints.AdaptivePenalty` (a dict;
        ``maximum`` defaults to ``penalty``).
    refine : free paths: the run keeps an external archive of every
        non-dominated path it meets and re-routes a segment of ``refine``
        archived paths per generation
        (:class:`gapath.operators.archive.FreePathArchive`); the front is
        the archive's. Default
        :func:`gapath.operators.archive.default_refine`: ``pop_size // 2``
        with two objectives, ``16 * pop_size`` with three or more among
        which smoothness (over short segments), ``2 * pop_size`` with other
        three or more (docs/results/free_paths.md;
        with three or more objectives the archive's first refinement also
        adds the exact front of each pair of objectives, where that search
        is cheap, then, for length, vulnerability and smoothness, an
        approximate three-objective front: ``FreePathArchive``'s ``faces``
        and ``approx``); 0 keeps the archive
        without re-routing; ``False``: no archive (the last population's
        front). Monotone paths: default None, no archive (Ahmed & Deb's
        runs, as the reproductions use them); an integer or ``True`` (the
        default count, :func:`gapath.operators.monotone_archive.default_refine`,
        what ``gapath solve --paths monotone`` passes) installs
        :class:`gapath.operators.monotone_archive.MonotonePathArchive`,
        which re-routes a stretch of columns of ``refine`` archived paths
        per generation (docs/results/monotone_lift.md).
    paths : ``"monotone"`` (default: Ahmed & Deb's column-monotone paths) or
        ``"free"`` (any simple 8-connected path); seeds from
        :class:`gapath.operators.sampling.free_sampling.FreeSampling` for
        free paths (``"astar"`` seeds as ``"weighted"``).
    costmap : :class:`gapath.costmap.Costmap`, optional: its layer
        objectives (``elevation``, ``risk``, ``risk_max``, ...) may be named
        in ``objectives`` (passed to the problem).
    pop_size, n_gen : population size and generations (seeds: 500 x 500).
    seed : random seed; the same seed gives the same front, bit for bit.
    tiebreak : ``"smoothness"`` or ``None`` (see :func:`gapath.algorithms.paper_nsga2`).
    sbx_eta : SBX distribution index (default by objective mode: 10, or 2
        for a single objective).
    seed_from : initial population: ``"weighted"`` (default: the shortest,
        the safest and weighted-sum optimal monotone paths, the rest random),
        ``"exact"`` (the exact monotone front), ``"astar"`` (A* paths
        projected onto monotone paths) or ``"none"`` (all random: Ahmed & Deb's
        protocol). See :class:`gapath.operators.PlannerSampling`.
    engine : ``"fast"`` (default: :class:`gapath.algorithms.FastNSGA2`, the
        same NSGA-II on whole arrays, bit-identical results) or ``"pymoo"``
        (:func:`gapath.algorithms.paper_nsga2`, stock pymoo NSGA2).
    progress : show a live progress bar on stderr.
    callback : an extra pymoo ``Callback`` notified every generation.
    pm_prob_var : per-gene mutation probability of the encoding's default
        mutation (default None: the operator's own default). For the binary
        encoding the initial per-bit rate: a number, ``"bits"`` (1 / number
        of bits, gapath's default) or ``"grid"`` (1 / n for an n-column
        grid, Ahmed & Deb's "1/n"); see
        :class:`gapath.operators.DecayingBitflipMutation`.
    repair : the repair of every new genome: None or ``"edge"`` (default:
        Ahmed & Deb's edge-fixing), or a name in
        :data:`gapath.operators.repair.feasible.REPAIRS` such as
        ``"feasible-local"`` (the edge-fixing, then every column step that
        touches an obstacle moved to the nearest free exit row, written back
        into the genes; see
        :class:`gapath.operators.repair.feasible.FeasibleStepRepair`).
        Column-monotone paths and ``engine="fast"`` only.

    Raises
    ------
    ConfigError
        On invalid settings.

    Examples
    --------
    >>> from gapath import default_workspace
    >>> r = solve(default_workspace(), pop_size=20, n_gen=3)
    >>> r.n_gen
    3
    """
    pop_size = positive_int(pop_size, "pop_size")
    n_gen = positive_int(n_gen, "n_gen")
    seed = int(seed)
    mode = objective_mode(objectives, constraints, sbx_eta, tiebreak)
    constraints, sbx_eta = mode["constraints"], mode["sbx_eta"]
    from gapath.problems.free_path import path_problem

    handling = None
    if constraints == "adaptive":
        from gapath.constraints import AdaptivePenalty

        if engine == "pymoo":
            raise ConfigError(
                "constraints='adaptive' needs engine='fast' (the stock pymoo engine has no "
                "adaptive penalty); use constraints='penalty' with engine='pymoo'"
            )
        try:
            handling = AdaptivePenalty(**{"maximum": penalty, **dict(adaptive_penalty or {})})
        except TypeError as exc:  # an unknown keyword
            raise ConfigError(
                f"adaptive_penalty: {exc}; expected keywords among initial, target, factor, minimum, maximum"
            ) from None
    problem = path_problem(
        workspace,
        objectives,
        paths=paths,
        encoding=encoding,
        constraints="constraint" if handling is not None else constraints,
        penalty=penalty,
        **({} if costmap is None else {"costmap": costmap}),
    )
    encoding = problem.encoding.name
    if paths == "free":
        from gapath.operators.sampling.free_sampling import FreeSampling

        sampling = FreeSampling("weighted" if seed_from == "astar" else seed_from)
    else:
        sampling = None if seed_from == "none" else PlannerSampling(seed_from)
    if engine not in ENGINES:
        raise ConfigError(f"unknown engine {engine!r}; expected one of {', '.join(ENGINES)}")
    extra = {} if handling is None else {"constraint_handling": handling}
    if repair is not None and repair != "edge":
        from gapath.operators.repair.feasible import make_repair

        if paths != "monotone" or engine != "fast":
            raise ConfigError(
                f"repair={repair!r} needs paths='monotone' and engine='fast' "
                f"(got paths={paths!r}, engine={engine!r})"
            )
        extra["repair"] = make_repair(repair)
    if pm_prob_var is not None:
        extra["pm_prob_var"] = pm_prob_var
    algorithm = ENGINES[engine](pop_size, tiebreak=tiebreak, sbx_eta=sbx_eta, sampling=sampling, **extra)
    archive = None
    if paths == "free" and refine is not False:
        from gapath.operators.archive import FreePathArchive, default_refine

        if refine is None or refine is True:  # the fronts outgrow the population with 3+ objectives
            n_refine = default_refine(problem.objectives, pop_size)
        else:
            n_refine = refine
        archive = FreePathArchive(problem, n_refine=n_refine, seed=seed)
    elif paths == "monotone" and refine not in (None, False):
        from gapath.operators.monotone_archive import MonotonePathArchive, default_refine

        n_refine = default_refine(pop_size) if refine is True else refine
        archive = MonotonePathArchive(problem, n_refine=n_refine, seed=seed)
    elif refine not in (None, False):
        raise ConfigError(f"refine applies to free paths only (paths='free'), got paths={paths!r}")
    bar = ProgressBar(n_gen, disable=not progress)
    callbacks = Callbacks(archive, bar, callback)

    settings = dict(
        **workspace.describe(),
        objectives=list(problem.objectives),
        paths=paths,
        encoding=encoding,
        constraints=constraints,
        penalty=problem.penalty,
        pop_size=pop_size,
        n_gen=n_gen,
        seed=seed,
        tiebreak=tiebreak,
        sbx_eta=sbx_eta,
        seed_from=seed_from,
        engine=engine,
        algorithm="NSGA-II (Ahmed & Deb 2013 settings)",
    )
    if handling is not None:
        settings["adaptive_penalty"] = handling.settings()
    if pm_prob_var is not None:
        settings["pm_prob_var"] = pm_prob_var
    if "repair" in extra:
        settings["repair"] = repair if isinstance(repair, str) else repr(extra["repair"])
    if archive is not None:
        settings["refine"] = archive.n_refine
    if paths == "free":  # GAPATH_THREADS / --threads: the same results, another time
        from gapath.encodings.free import wanted_threads

        settings["threads"] = wanted_threads()
    t0 = time.perf_counter()
    interrupted = False
    res = None
    try:
        if archive is not None:  # (the free archive's second-thread search, GAPATH_THREADS)
            archive.start()
        res = minimize(
            problem, algorithm, ("n_gen", n_gen), seed=seed, callback=callbacks, copy_algorithm=False
        )
    except KeyboardInterrupt:
        interrupted = True
    finally:
        bar.close()
        if archive is not None:
            archive.close()
    seconds = time.perf_counter() - t0
    # the last complete generation's genomes (the engine's arrays, or pymoo's pop)
    A = population_arrays(algorithm)
    X = np.empty((0, problem.n_var)) if A is None or len(A) == 0 else A.X
    front = path_front(problem, X)
    if archive is not None:
        archive.add(X)
        front = archive.front()
    return SolveResult(
        workspace,
        problem,
        front,
        settings,
        seconds,
        int(algorithm.evaluator.n_eval) + (0 if archive is None else archive.n_eval),
        bar.last_gen,
        interrupted,
        res,
    )
