"""NSGA-II survival with path smoothness as the tie-breaker inside a rank."""

from __future__ import annotations

import numpy as np
from pymoo.core.survival import Survival
from pymoo.operators.survival.rank_and_crowding.metrics import calc_crowding_distance
from pymoo.util.nds.non_dominated_sorting import NonDominatedSorting

from gapath.errors import ConfigError
from gapath.operators.columns import column, set_columns


def survival_order(F, smoothness=None, CV=None, n_survive=None):
    """The ``n_survive`` best individuals, best first, as the survival ranks them.

    Feasible individuals (``CV <= 0``) first, by non-dominated rank; inside a
    rank by smaller ``smoothness`` (when given) then larger crowding
    distance; infeasible individuals after them, by smaller ``CV``. Fronts
    past the ones needed for ``n_survive`` are not ranked.

    Returns
    -------
    order : (n_survive,) indices, best first.
    rank : (n_survive,) int rank of each selected individual (infeasible ones
        get ranks after the last feasible front, in CV order).
    crowding : (n_survive,) float crowding distance (0 when infeasible).

    Examples
    --------
    >>> order, rank, _ = survival_order(np.array([[1., 2.], [2., 1.], [2., 2.]]), [3., 1., 0.])
    >>> order.tolist(), rank.tolist()
    ([1, 0, 2], [0, 0, 1])
    """
    F = np.asarray(F, dtype=float)
    n = len(F)
    n_survive = n if n_survive is None else min(int(n_survive), n)
    cv = np.zeros(n) if CV is None else np.asarray(CV, dtype=float).reshape(n, -1)[:, 0]
    smooth = np.zeros(n) if smoothness is None else np.asarray(smoothness, dtype=float)
    feasible = np.flatnonzero(cv <= 0)
    order, rank, crowding = [], [], []
    n_fronts = 0
    if len(feasible):
        fronts = NonDominatedSorting().do(F[feasible], n_stop_if_ranked=n_survive)
        for k, front in enumerate(fronts):
            idx = feasible[front]
            cd = calc_crowding_distance(F[idx])
            inner = np.lexsort((idx, -cd, smooth[idx]))  # last key is primary
            order.append(idx[inner])
            rank.append(np.full(len(idx), k))
            crowding.append(cd[inner])
            n_fronts = k + 1
    infeasible = np.flatnonzero(cv > 0)
    infeasible = infeasible[np.argsort(cv[infeasible], kind="stable")]
    order.append(infeasible)
    rank.append(n_fronts + np.arange(len(infeasible)))
    crowding.append(np.zeros(len(infeasible)))
    return (
        np.concatenate(order)[:n_survive],
        np.concatenate(rank)[:n_survive].astype(np.int64),
        np.concatenate(crowding)[:n_survive],
    )


class RankAndSmoothnessSurvival(Survival):
    """Elitist NSGA-II survival; inside a non-dominated rank, smaller total
    turn first, then larger crowding distance (Ahmed & Deb, section 5.1).

    With ``tiebreak=None`` it is plain NSGA-II rank-and-crowding. Sets
    ``rank`` and ``crowding`` on every survivor (infeasible ones included),
    which :func:`gapath.operators.compare_rank_smoothness_crowding` reads.

    Parameters
    ----------
    tiebreak : ``"smoothness"`` (default) or ``None``.
    """

    def __init__(self, tiebreak: str | None = "smoothness"):
        super().__init__(filter_infeasible=False)
        if tiebreak not in ("smoothness", None):
            raise ConfigError(f"tiebreak must be 'smoothness' or None, got {tiebreak!r}")
        self.tiebreak = tiebreak

    def _do(self, problem, pop, *args, n_survive=None, **kwargs):
        smooth = column(pop, "smoothness") if self.tiebreak else None
        CV = column(pop, "CV") if problem.has_constraints() else None
        order, rank, crowding = survival_order(column(pop, "F"), smooth, CV, n_survive)
        survivors = pop[order]
        set_columns(survivors, rank=rank, crowding=crowding)
        return survivors
