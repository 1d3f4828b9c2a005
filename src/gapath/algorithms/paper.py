"""Configured pymoo algorithms for grid path problems."""

from __future__ import annotations

from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.operators.sampling.rnd import IntegerRandomSampling

from gapath.errors import ConfigError
from gapath.operators import (
    DiscretePM,
    DiscreteSBX,
    EdgeFixingRepair,
    PathDuplicateElimination,
    RankAndSmoothnessSurvival,
    SmoothnessTournament,
)


class PathNSGA2(NSGA2):
    """pymoo's NSGA2 whose duplicate elimination compares decoded paths.

    The only change to :class:`pymoo.algorithms.moo.nsga2.NSGA2` is that, on
    setup, a :class:`gapath.operators.PathDuplicateElimination` is bound to
    the problem so it can decode genomes; everything else (mating, survival,
    termination, callbacks, output) is pymoo's.
    """

    def _setup(self, problem, **kwargs):
        super()._setup(problem, **kwargs)
        if isinstance(self.eliminate_duplicates, PathDuplicateElimination):
            self.eliminate_duplicates.bind(problem)


def paper_nsga2(pop_size: int = 500, *, tiebreak: str | None = "smoothness",
                sbx_prob: float = 0.9, sbx_eta: float = 10, pm_eta: float = 20,
                pm_prob_var: float | None = None, sampling=None, **kwargs) -> PathNSGA2:
    """NSGA-II with the seeds' settings (Ahmed & Deb 2013, section 5.2).

    Discrete SBX (prob 0.9, eta 10), discrete polynomial mutation (eta 20,
    per-gene probability 1/n for an n-column path), the seeds' edge-fixing
    repair, a binary tournament on (feasibility, rank, smoothness, crowding),
    rank-and-smoothness survival and duplicate elimination by decoded path.

    Parameters
    ----------
    pop_size : population size (seeds: 500).
    tiebreak : ``"smoothness"`` (seeds' two-objective mode) or ``None``
        (plain rank and crowding, e.g. for three objectives).
    sbx_prob, sbx_eta, pm_eta, pm_prob_var : operator settings.
    sampling : initial population: a pymoo ``Sampling``, an array of genomes
        or a ``Population`` (default: uniform random integers).
    **kwargs : passed to :class:`pymoo.algorithms.moo.nsga2.NSGA2`.

    Returns
    -------
    PathNSGA2 (a pymoo ``NSGA2``). Pass the termination to
    ``pymoo.optimize.minimize``, not here (NSGA2 overwrites it).

    Raises
    ------
    ConfigError
        On a population size below 2 or an unknown tie-break.

    Examples
    --------
    >>> from pymoo.optimize import minimize
    >>> from gapath import default_workspace
    >>> from gapath.problems import GridPathProblem
    >>> res = minimize(GridPathProblem(default_workspace()), paper_nsga2(20), ("n_gen", 2), seed=1)
    >>> res.F.shape[1]
    2
    """
    try:
        pop_size = int(pop_size)
    except (TypeError, ValueError):
        raise ConfigError(f"pop_size must be an integer >= 2, got {pop_size!r}") from None
    if pop_size < 2:
        raise ConfigError(f"pop_size must be an integer >= 2, got {pop_size!r}")
    if tiebreak not in ("smoothness", None):
        raise ConfigError(f"tiebreak must be 'smoothness' or None, got {tiebreak!r}")
    return PathNSGA2(
        pop_size=pop_size,
        sampling=IntegerRandomSampling() if sampling is None else sampling,
        selection=SmoothnessTournament(tiebreak=tiebreak is not None),
        crossover=DiscreteSBX(prob=sbx_prob, eta=sbx_eta),
        mutation=DiscretePM(eta=pm_eta, prob_var=pm_prob_var),
        survival=RankAndSmoothnessSurvival(tiebreak=tiebreak),
        repair=EdgeFixingRepair(),
        eliminate_duplicates=PathDuplicateElimination(),
        **kwargs,
    )


__all__ = ["PathNSGA2", "paper_nsga2"]
