"""Discrete polynomial mutation (Deb 2001) for integer genes."""

from __future__ import annotations

from pymoo.core.variable import get
from pymoo.operators.mutation.pm import PM
from pymoo.operators.repair.rounding import RoundingRepair


class DiscretePM(PM):
    """pymoo's polynomial mutation on real values, rounded back to integers.

    Parameters
    ----------
    eta : distribution index (seeds: 20).
    prob_var : per-gene mutation probability; ``None`` means ``1 / n`` with
        ``n`` the number of columns of the path (Ahmed & Deb's ``1/n`` for an
        ``n x n`` grid, whose genome has ``n - 1`` genes).
    **kwargs : passed to :class:`pymoo.operators.mutation.pm.PM`.
    """

    def __init__(self, eta=20, prob_var=None, **kwargs):
        kwargs.setdefault("vtype", float)
        kwargs.setdefault("repair", RoundingRepair())
        super().__init__(eta=eta, prob_var=prob_var, **kwargs)

    def get_prob_var(self, problem, **kwargs):
        if self.prob_var is None:
            return get(1.0 / (problem.n_var + 1), **kwargs)
        return super().get_prob_var(problem, **kwargs)
