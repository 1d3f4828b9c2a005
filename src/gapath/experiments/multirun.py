"""Seeded multi-run aggregation (Ahmed & Deb, section 5: 10 runs merged).

:func:`multirun` runs :func:`gapath.solver.solve` with seeds ``s, s+1, ...,
s+k-1``, keeps every run's front and merges them into one non-dominated
front, keeping the smoothest path among identical objective vectors.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from gapath import solver  # solver.solve at call time (tests replace it)
from gapath.errors import ConfigError, positive_int
from gapath.front import PathFront, select_front
from gapath.results import versions

if TYPE_CHECKING:
    from gapath.solver import SolveResult
    from gapath.workspace import Workspace


@dataclass(eq=False)
class MultiRunResult:
    """Runs and their merged front.

    Attributes
    ----------
    runs : the :class:`gapath.solver.SolveResult` of every completed run, in
        seed order.
    front : the merged front (:class:`gapath.front.PathFront`).
    seeds : the seeds of ``runs``.
    interrupted : True when Ctrl-C stopped the sequence; ``runs`` then holds
        the completed runs and the interrupted one's last generation.
    n_runs : the number of runs asked for (default ``len(runs)``).
    """

    runs: list[SolveResult]
    front: PathFront
    seeds: list[int] = field(default_factory=list)
    interrupted: bool = False
    n_runs: int | None = None

    @property
    def workspace(self) -> Workspace:
        return self.runs[0].workspace

    def summary(self, extra: dict[str, Any] | None = None) -> dict[str, Any]:
        """The ``summary.json`` content of the merged front (``gapath solve
        --runs``): the first run's settings with the first seed and the
        number of runs asked for, every seed, the summed wall time and
        evaluations, the front sizes; ``extra`` entries are added (e.g.
        ``quality`` against a reference).

        Returns
        -------
        dict

        Examples
        --------
        >>> from gapath import default_workspace
        >>> m = multirun(default_workspace(), runs=2, pop_size=12, n_gen=2)
        >>> s = m.summary()
        >>> s["seeds"], s["settings"]["runs"], len(s["run_front_sizes"])
        ([1, 2], 2, 2)
        """

        runs = len(self.runs) if self.n_runs is None else self.n_runs
        return {
            "settings": {**self.runs[0].settings, "seed": self.seeds[0], "runs": runs},
            "seeds": self.seeds,
            "versions": versions(),
            "wall_time_s": round(sum(r.seconds for r in self.runs), 3),
            "evaluations": sum(r.n_eval for r in self.runs),
            "interrupted": self.interrupted,
            "front_size": len(self.front),
            "run_front_sizes": [len(r.front) for r in self.runs],
            **(extra or {}),
        }


def merge_fronts(fronts: Iterable[PathFront]) -> PathFront:
    """One front from several: feasible, non-dominated, one path per
    objective vector (SPEC tolerance; the smoothest), sorted.

    Raises
    ------
    ConfigError
        If the fronts have different objectives.

    Examples
    --------
    >>> import numpy as np
    >>> a = PathFront(("f",), np.array([[2.0]]), np.array([[2.0, 0, 1.0, 0]]), np.zeros((1, 0)), [[]])
    >>> b = PathFront(("f",), np.array([[2.0]]), np.array([[2.0, 0, 0.5, 0]]), np.zeros((1, 0)), [[]])
    >>> merge_fronts([a, b]).metrics[0, 2]
    np.float64(0.5)
    """
    fronts = list(fronts)
    if not fronts:
        raise ConfigError("merge_fronts needs at least one front")
    objectives = fronts[0].objectives
    for f in fronts[1:]:
        if f.objectives != objectives:
            raise ConfigError(f"cannot merge fronts over {objectives} and {f.objectives}")
    F = np.concatenate([f.F.reshape(-1, len(objectives)) for f in fronts])
    # 4 SPEC metrics, then a costmap's layer objectives (their count is the fronts' own)
    width = max((f.metrics.shape[-1] for f in fronts if len(f.F)), default=4)
    metrics = np.concatenate(
        [f.metrics.reshape(-1, width) if len(f.F) else np.empty((0, width)) for f in fronts]
    )
    # genomes only when every non-empty front has them (a free-path archive's
    # refined paths have none): never rows that are not the genomes of their paths
    given = [f for f in fronts if len(f.F)]
    if given and all(f.X.ndim == 2 and f.X.shape[1] > 0 for f in given):
        X = np.concatenate([f.X for f in given])
    else:
        X = np.zeros((len(F), 0))
    paths = [p for f in fronts for p in f.paths]
    keep = select_front(F, metrics)
    return PathFront(objectives, F[keep], metrics[keep], X[keep], [paths[i] for i in keep])


def multirun(
    workspace: Workspace,
    runs: int = 10,
    seed: int = 1,
    *,
    on_run: Callable[[SolveResult], object] | None = None,
    **solve_kwargs: Any,
) -> MultiRunResult:
    """Run the GA ``runs`` times with seeds ``seed .. seed+runs-1`` and merge.

    Parameters
    ----------
    workspace : :class:`gapath.Workspace`.
    runs : number of runs (Ahmed & Deb's protocol: 10).
    seed : first seed.
    on_run : called with each :class:`gapath.solver.SolveResult` as soon as
        its run ends (e.g. to write it), so an interruption loses nothing
        already finished.
    **solve_kwargs : passed to :func:`gapath.solver.solve`.

    Raises
    ------
    ConfigError
        On ``runs < 1`` or invalid solve settings.

    Examples
    --------
    >>> from gapath import default_workspace
    >>> m = multirun(default_workspace(), runs=2, pop_size=20, n_gen=3)
    >>> m.seeds
    [1, 2]
    """

    runs = positive_int(runs, "runs")
    results, seeds = [], []
    interrupted = False
    for s in range(int(seed), int(seed) + runs):
        r = solver.solve(workspace, seed=s, **solve_kwargs)
        results.append(r)
        seeds.append(s)
        if on_run is not None:
            on_run(r)
        if r.interrupted:
            interrupted = True
            break
    return MultiRunResult(results, merge_fronts([r.front for r in results]), seeds, interrupted, runs)
