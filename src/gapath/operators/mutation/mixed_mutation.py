"""Mutation of mixed genomes: bit-flip on the bits, discrete polynomial mutation on the integers."""

from __future__ import annotations

import numpy as np
from pymoo.core.mutation import Mutation
from pymoo.core.variable import get
from pymoo.operators.mutation.bitflip import BitflipMutation
from pymoo.operators.mutation.pm import PM

from gapath.operators.crossover.mixed_crossover import mixed_blocks


class MixedMutation(Mutation):
    """Ahmed & Deb's mutation of mixed genomes ``[bits | integers]``, one
    vectorised pymoo operator over the flat genome.

    The bit block gets pymoo's bit-wise mutation (on booleans, returned as
    0/1 integers), the integer block pymoo's polynomial mutation on real
    values rounded back to integers (discrete PM), both with the same
    per-gene probability and drawn from pymoo's ``random_state``.

    Parameters
    ----------
    eta : polynomial mutation distribution index (seeds: 20).
    prob_var : per-gene probability for both blocks; ``None`` means ``1 / n``
        with ``n`` the number of columns of the path (``n_genes + 1``), as
        for :class:`gapath.operators.DiscretePM`.
    n_bits : number of leading bit columns (default: from the problem's
        encoding, see :func:`gapath.operators.crossover.mixed_crossover.mixed_blocks`).
    **kwargs : passed to :class:`pymoo.core.mutation.Mutation`.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.problems import GridPathProblem
    >>> p = GridPathProblem(Workspace(np.zeros((8, 8), bool)), encoding="mixed")
    >>> X = np.array([[1] * 7 + [3] * 7] * 5)
    >>> Y = MixedMutation()._do(p, X, random_state=np.random.default_rng(0))
    >>> Y.dtype.kind, bool(((Y >= p.xl) & (Y <= p.xu)).all())
    ('i', True)
    """

    def __init__(self, eta=20, prob_var=None, n_bits=None, **kwargs):
        super().__init__(prob_var=prob_var, **kwargs)
        self.n_bits = n_bits
        self.pm = PM(eta=eta)

    @property
    def eta(self):
        """The polynomial mutation distribution index (a pymoo ``Real``)."""
        return self.pm.eta

    def gene_rate(self, problem) -> float:
        """The per-gene mutation probability."""
        if self.prob_var is None:
            n_bits, _ = mixed_blocks(problem, self.n_bits)
            return 1.0 / (n_bits + 1)
        return float(get(self.prob_var))

    def _do(self, problem, X, *args, random_state=None, **kwargs):
        if random_state is None:
            random_state = np.random.default_rng()
        n_bits, ints_problem = mixed_blocks(problem, self.n_bits)
        p = self.gene_rate(problem)
        X = np.asarray(X)
        bits = np.rint(X[:, :n_bits]) >= 1
        flipped = BitflipMutation(prob_var=p)._do(problem, bits, random_state=random_state)
        pm = PM(eta=get(self.pm.eta), prob_var=p, at_least_once=self.pm.at_least_once)
        ints = pm._do(ints_problem, X[:, n_bits:].astype(float), random_state=random_state)
        return np.concatenate([flipped, np.rint(ints)], axis=1).astype(np.int64)
