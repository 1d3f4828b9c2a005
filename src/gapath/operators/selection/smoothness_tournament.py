"""Vectorised binary tournament: feasibility, rank, smoothness, crowding."""

from __future__ import annotations

import numpy as np
from pymoo.operators.selection.tournament import TournamentSelection

from gapath.operators.columns import ColumnCache, column


def tournament_keys(pop, tiebreak=True) -> list[tuple[np.ndarray, int]]:
    """The comparison keys, most important first, as (values, sign) with
    smaller ``sign * value`` better."""
    keys = [(_required(pop, "CV")[:, 0].astype(float), 1), (_required(pop, "rank").astype(float), 1)]
    if tiebreak:
        smooth = column(pop, "smoothness")
        if smooth is not None:
            keys.append((smooth.astype(float), 1))
    keys.append((_required(pop, "crowding").astype(float), -1))
    return keys


def _required(pop, name: str) -> np.ndarray:
    values = column(pop, name)
    if values is None:  # survival sets rank and crowding, evaluation CV
        raise ValueError(f"the population has no {name!r}: run a survival that sets it first")
    return values


def compare_rank_smoothness_crowding(
    pop, P, random_state=None, algorithm=None, tiebreak=True, keys=None, **kwargs
):
    """Winners of binary tournaments ``P`` (n, 2), all at once.

    Smaller constraint violation wins; between equals, smaller rank; then
    (when ``tiebreak``) smaller smoothness; then larger crowding distance;
    remaining ties are broken at random with ``random_state``.

    Returns
    -------
    (n, 1) int array of winners.
    """
    if random_state is None:
        random_state = algorithm.random_state if algorithm is not None else np.random.default_rng()
    a, b = P[:, 0], P[:, 1]
    if keys is None:
        keys = tournament_keys(pop, tiebreak)
    winner = np.full(len(P), -1)
    for values, sign in keys:
        undecided = winner < 0
        da = sign * values[a]
        db = sign * values[b]
        winner[undecided & (da < db)] = a[undecided & (da < db)]
        winner[undecided & (db < da)] = b[undecided & (db < da)]
    undecided = winner < 0
    coin = random_state.random(len(P)) < 0.5
    winner[undecided] = np.where(coin, a, b)[undecided]
    return winner[:, None]


class TournamentComparison:
    """:func:`compare_rank_smoothness_crowding` as the ``func_comp`` of a
    pymoo ``TournamentSelection``, with its keys cached per population.

    A module-level callable (not a closure), so that the selection, the
    algorithm and pymoo's result pickle (checkpoints, multiprocessing). The
    cache is not pickled nor copied: a copy starts with an empty one.

    Parameters
    ----------
    tiebreak : compare smoothness between equal ranks.

    Examples
    --------
    >>> import pickle
    >>> comp = pickle.loads(pickle.dumps(TournamentComparison(tiebreak=False)))
    >>> comp.tiebreak
    False
    """

    def __init__(self, tiebreak: bool = True):
        self.tiebreak = bool(tiebreak)
        self._cache = ColumnCache()

    def _keys(self, pop):
        return tournament_keys(pop, self.tiebreak)

    def __call__(self, pop, P, **kwargs):
        keys = self._cache.get(pop, self._keys)
        return compare_rank_smoothness_crowding(pop, P, tiebreak=self.tiebreak, keys=keys, **kwargs)

    def __getstate__(self):
        return {"tiebreak": self.tiebreak}

    def __setstate__(self, state):
        self.__init__(state["tiebreak"])

    def __repr__(self) -> str:
        return f"TournamentComparison(tiebreak={self.tiebreak})"


class SmoothnessTournament(TournamentSelection):
    """Binary tournament of :func:`compare_rank_smoothness_crowding`.

    Parameters
    ----------
    tiebreak : compare smoothness between equal ranks (default True).
    """

    def __init__(self, tiebreak: bool = True):
        super().__init__(func_comp=TournamentComparison(tiebreak), pressure=2)
        self.tiebreak = tiebreak
