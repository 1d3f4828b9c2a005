"""Discrete simulated binary crossover (Deb & Agrawal 1995) for integer genes."""

from __future__ import annotations

from pymoo.operators.crossover.sbx import SBX
from pymoo.operators.repair.rounding import RoundingRepair


class DiscreteSBX(SBX):
    """pymoo's SBX on real values, rounded back to integers.

    The parents are cast to float for the crossover (``vtype=float``) and the
    children rounded (``RoundingRepair``), so integer genes stay integral and
    keep an integer dtype (PYMOO_NOTES: without both, SBX silently turns an
    integer genome into floats).

    Parameters
    ----------
    prob : probability that a mating is crossed over (seeds: 0.9).
    eta : distribution index (seeds: 10; 2 for the single-objective study).
    **kwargs : passed to :class:`pymoo.operators.crossover.sbx.SBX`.

    Examples
    --------
    >>> DiscreteSBX().eta.value
    10
    """

    def __init__(self, prob=0.9, eta=10, **kwargs):
        kwargs.setdefault("vtype", float)
        kwargs.setdefault("repair", RoundingRepair())
        super().__init__(prob=prob, eta=eta, **kwargs)
