"""Crossover of mixed genomes: single-point on the bits, discrete SBX on the integers."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
from pymoo.core.crossover import Crossover
from pymoo.operators.crossover.pntx import SinglePointCrossover
from pymoo.operators.crossover.sbx import SBX


def mixed_blocks(problem, n_bits=None) -> tuple[int, SimpleNamespace]:
    """The number of leading bit columns of a flat mixed genome and a
    stand-in problem (bounds and size) for the integer columns after them.

    ``n_bits`` defaults to the problem's ``encoding.n_bits`` (a gapath
    problem with the mixed encoding), else to half of ``problem.n_var``.
    """
    if n_bits is None:
        n_bits = getattr(getattr(problem, "encoding", None), "n_bits", None)
    if n_bits is None:
        n_bits = problem.n_var // 2
    n_bits = int(n_bits)
    xl = np.asarray(problem.xl)[n_bits:]
    xu = np.asarray(problem.xu)[n_bits:]
    return n_bits, SimpleNamespace(xl=xl, xu=xu, n_var=len(xl))


class MixedCrossover(Crossover):
    """Ahmed & Deb's crossover of mixed genomes ``[bits | integers]``, one
    vectorised pymoo operator over the flat genome.

    The bit block gets pymoo's single-point crossover, the integer block
    pymoo's SBX on real values rounded back to integers (discrete SBX), both
    on the same pair of parents and drawn from pymoo's ``random_state``. The
    mating as a whole is crossed with probability ``prob`` (pymoo's
    ``Crossover``); otherwise the children are copies of the parents.

    Parameters
    ----------
    prob : probability that a mating is crossed over (seeds: 0.9).
    eta : SBX distribution index (seeds: 10).
    n_bits : number of leading bit columns (default: from the problem's
        encoding, see :func:`mixed_blocks`).
    **kwargs : passed to :class:`pymoo.core.crossover.Crossover`.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.problems import GridPathProblem
    >>> p = GridPathProblem(Workspace(np.zeros((8, 8), bool)), encoding="mixed")
    >>> X = np.array([[[1] * 7 + [1] * 7], [[0] * 7 + [3] * 7]])
    >>> Q = MixedCrossover()._do(p, X, random_state=np.random.default_rng(0))
    >>> Q.shape, Q.dtype.kind, bool(((Q >= p.xl) & (Q <= p.xu)).all())
    ((2, 1, 14), 'i', True)
    """

    def __init__(self, prob=0.9, eta=10, n_bits=None, **kwargs):
        super().__init__(2, 2, prob=prob, **kwargs)
        self.n_bits = n_bits
        self.bits_crossover = SinglePointCrossover()
        self.sbx = SBX(eta=eta)

    @property
    def eta(self):
        """The SBX distribution index (a pymoo ``Real``)."""
        return self.sbx.eta

    def _do(self, problem, X, *args, random_state=None, **kwargs):
        n_bits, ints_problem = mixed_blocks(problem, self.n_bits)
        X = np.asarray(X)
        bits = X[..., :n_bits]
        if n_bits >= 2:
            Qb = self.bits_crossover._do(problem, bits, random_state=random_state)
        else:  # a single bit has no crossing point
            Qb = bits.copy()
        Qi = self.sbx._do(ints_problem, X[..., n_bits:].astype(float), random_state=random_state)
        return np.concatenate([Qb, np.rint(Qi)], axis=-1).astype(np.int64)
