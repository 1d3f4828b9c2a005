"""Fast column access to pymoo populations (used by the operators and by
:mod:`gapath.callbacks`).

``Population.get`` goes through ``Individual.get`` (several ``hasattr`` calls
per individual and key); the operators here read and write whole columns
directly, which is several times faster at pop sizes of hundreds.
"""

from __future__ import annotations

import numpy as np

_PROPERTIES = ("X", "F", "G", "H", "CV")


def column(pop, key: str) -> np.ndarray | None:
    """The values of ``key`` over ``pop`` as an array, or None if any
    individual lacks it."""
    if key in _PROPERTIES:
        return np.array([getattr(ind, key) for ind in pop])
    values = [ind.data.get(key) for ind in pop]
    if any(v is None for v in values):
        return None
    return np.array(values)


def set_columns(pop, **columns) -> None:
    """Set per-individual data columns (not X/F/G/CV) in one pass."""
    keys = list(columns)
    for i, ind in enumerate(pop):
        d = ind.data
        for k in keys:
            d[k] = columns[k][i]


class ColumnCache:
    """Remembers columns computed from one population object.

    pymoo's mating loop asks the selection and the duplicate elimination
    about the same parent population several times per generation (once per
    round of offspring). The cache holds a strong reference to the last
    population it saw, so an identity match means the very same, unchanged
    object (pymoo never edits the genes of an evaluated population in place).
    """

    def __init__(self):
        self._pop = None
        self._value = None

    def get(self, pop, compute):
        if pop is not self._pop:
            self._value = compute(pop)
            self._pop = pop
        return self._value
