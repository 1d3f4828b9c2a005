"""Seeded multi-run aggregation (Ahmed & Deb, section 5: 10 runs merged).

:func:`multirun` runs :func:`gapath.solver.solve` with seeds ``s, s+1, ...,
s+k-1``, keeps every run's front and merges them into one non-dominated
front, keeping the smoothest path among identical objective vectors.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from gapath.errors import ConfigError, positive_int
from gapath.front import PathFront, select_front


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
    """

    runs: list
    front: PathFront
    seeds: list[int] = field(default_factory=list)
    interrupted: bool = False

    @property
    def workspace(self):
        return self.runs[0].workspace


def merge_fronts(fronts) -> PathFront:
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
    metrics = np.concatenate([f.metrics.reshape(-1, 4) for f in fronts])
    n_var = max((f.X.shape[1] for f in fronts if f.X.ndim == 2), default=0)
    X = np.concatenate(
        [f.X.reshape(len(f.F), -1) if f.X.size else np.zeros((len(f.F), n_var)) for f in fronts]
    )
    paths = [p for f in fronts for p in f.paths]
    keep = select_front(F, metrics)
    return PathFront(objectives, F[keep], metrics[keep], X[keep], [paths[i] for i in keep])


def multirun(workspace, runs: int = 10, seed: int = 1, *, on_run=None, **solve_kwargs) -> MultiRunResult:
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
    from gapath.solver import solve

    runs = positive_int(runs, "runs")
    results, seeds = [], []
    interrupted = False
    for s in range(int(seed), int(seed) + runs):
        r = solve(workspace, seed=s, **solve_kwargs)
        results.append(r)
        seeds.append(s)
        if on_run is not None:
            on_run(r)
        if r.interrupted:
            interrupted = True
            break
    return MultiRunResult(results, merge_fronts([r.front for r in results]), seeds, interrupted)
