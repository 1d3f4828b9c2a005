"""Shared pieces of the benchmark scripts that compare exact fronts
between two sources (``exact_vs_revision.py``, ``exact_queries_same.py``,
``exact_near_ties_same.py``); not a benchmark itself."""

from __future__ import annotations

import pickle

import numpy as np


def random_query(occ: np.ndarray, rng: np.random.Generator):
    """A workspace on ``occ`` (cleared when it has fewer than two free
    cells) with start and goal drawn among its free cells and the corner
    rule by a coin, in that order of draws from ``rng``."""
    from gapath import Workspace

    free = np.argwhere(~occ)
    if len(free) < 2:
        occ[:] = False
        free = np.argwhere(~occ)
    a, b = rng.choice(len(free), 2, replace=False)
    return Workspace(
        occ,
        start=tuple(int(x) for x in free[a]),
        goal=tuple(int(x) for x in free[b]),
        corner_cutting=bool(rng.integers(2)),
    )


def save_dump(runs: dict, out: str, what: str) -> None:
    """Pickle ``runs`` to ``out`` and say how many ``what`` it holds."""
    with open(out, "wb") as fh:
        pickle.dump(runs, fh)
    print(len(runs), what)


def load_pair(fa: str, fb: str) -> tuple[dict, dict]:
    """The two pickled dumps to compare."""
    with open(fa, "rb") as fh:
        a = pickle.load(fh)
    with open(fb, "rb") as fh:
        b = pickle.load(fh)
    return a, b
