"""Configured pymoo algorithms for grid path problems."""

from __future__ import annotations

from pymoo.algorithms.moo.nsga2 import NSGA2

from gapath.encodings import ENCODINGS
from gapath.errors import ConfigError
from gapath.operators import (
    EdgeFixingRepair,
    PathDuplicateElimination,
    RankAndSmoothnessSurvival,
    SmoothnessTournament,
    default_operators,
)


class PathNSGA2(NSGA2):
    """pymoo's NSGA2 whose duplicate elimination compares decoded paths.

    The changes to :class:`pymoo.algorithms.moo.nsga2.NSGA2`: on setup, a
    :class:`gapath.operators.PathDuplicateElimination` is bound to the
    problem so it can decode genomes; when the algorithm was configured for
    an encoding, the problem must use that encoding; when it was given
    ``operator_settings`` instead, the default operators are those of the
    problem's encoding (``problem.encoding.name``, read at setup).
    Everything else (mating, survival, termination, callbacks, output) is
    pymoo's.

    Parameters
    ----------
    encoding : name of the encoding the operators were chosen for, or
        ``None`` (no check).
    operator_settings : with ``encoding=None``, the settings of
        :func:`gapath.operators.default_operators` (``sbx_prob``,
        ``sbx_eta``, ``pm_eta``, ``pm_prob_var``): the crossover and the
        mutation (and the sampling, unless ``sampling_given``) are replaced
        at setup by the defaults of the problem's encoding when they were
        built for another one (``operators_for``).
    operators_for : the encoding the operators given were built for.
    sampling_given : the sampling was chosen by the caller (kept at setup).
    **kwargs : passed to :class:`pymoo.algorithms.moo.nsga2.NSGA2`.

    Raises
    ------
    ConfigError
        On setup, if the problem's encoding is not ``encoding``.
    """

    def __init__(
        self,
        *,
        encoding: str | None = None,
        operator_settings: dict | None = None,
        operators_for: str | None = None,
        sampling_given: bool = False,
        **kwargs,
    ):
        super().__init__(**kwargs)
        self.encoding_name = encoding
        self.operator_settings = operator_settings
        self.operators_for = operators_for
        self.sampling_given = sampling_given

    def _setup(self, problem, **kwargs):
        used = getattr(getattr(problem, "encoding", None), "name", None)
        if self.encoding_name is not None and used is not None and used != self.encoding_name:
            raise ConfigError(
                f"paper_nsga2 was configured for the {self.encoding_name!r} encoding but the "
                f"problem uses {used!r}; pass paper_nsga2(..., encoding={used!r})"
            )
        if self.encoding_name is None and self.operator_settings is not None:
            self._operators_of(used or "integer")
        super()._setup(problem, **kwargs)
        if isinstance(self.eliminate_duplicates, PathDuplicateElimination):
            self.eliminate_duplicates.bind(problem)

    def _operators_of(self, encoding: str) -> None:
        """The default operators of ``encoding``, unless they are already."""
        if encoding == self.operators_for:
            return
        ops = default_operators(encoding, **self.operator_settings)
        self.mating.crossover, self.mating.mutation = ops["crossover"], ops["mutation"]
        if not self.sampling_given:
            self.initialization.sampling = ops["sampling"]
        self.operators_for = encoding


def paper_nsga2(
    pop_size: int = 500,
    *,
    encoding: str | None = None,
    tiebreak: str | None = "smoothness",
    sbx_prob: float = 0.9,
    sbx_eta: float = 10,
    pm_eta: float = 20,
    pm_prob_var: float | None = None,
    sampling=None,
    **kwargs,
) -> PathNSGA2:
    """NSGA-II with Ahmed & Deb's settings (2013, sections 2 and 5.2).

    The encoding's operators from :func:`gapath.operators.default_operators`
    (integer and absolute: discrete SBX, prob 0.9, eta 10, and discrete
    polynomial mutation, eta 20, per-gene probability 1/n for an n-column
    path; binary: two-point crossover and a bit-flip whose rate decays to a
    fifth; mixed: single-point and discrete SBX, bit-flip and discrete PM),
    Ahmed & Deb's edge-fixing repair, a binary tournament on (feasibility,
    rank, smoothness, crowding), rank-and-smoothness survival and duplicate
    elimination by decoded path.

    Parameters
    ----------
    pop_size : population size (seeds: 500).
    encoding : the encoding of the operators (``"integer"``, ``"binary"``,
        ``"mixed"``, ``"absolute"``, or ``"field"``/``"via"`` for free
        paths). Default None: the problem's own encoding, read when
        ``minimize`` sets the algorithm up (until then the operators are the
        integer encoding's). Given, the problem must use the same one.
    tiebreak : ``"smoothness"`` (Ahmed & Deb's two-objective mode) or ``None``
        (plain rank and crowding, e.g. for three objectives).
    sbx_prob, sbx_eta, pm_eta, pm_prob_var : operator settings (see
        :func:`gapath.operators.default_operators`).
    sampling : initial population: a pymoo ``Sampling``, an array of genomes
        or a ``Population`` (default: the encoding's uniform random sampling).
    **kwargs : passed to :class:`pymoo.algorithms.moo.nsga2.NSGA2`.

    Returns
    -------
    PathNSGA2 (a pymoo ``NSGA2``). Pass the termination to
    ``pymoo.optimize.minimize``, not here (NSGA2 overwrites it). The
    algorithm pickles before and after ``minimize``, and so does pymoo's
    result (checkpoints, multiprocessing).

    Raises
    ------
    ConfigError
        On a population size below 2, an unknown encoding or tie-break; on
        setup (``minimize``), if the problem uses another encoding than
        ``encoding`` given.

    Examples
    --------
    >>> from pymoo.optimize import minimize
    >>> from gapath import default_workspace
    >>> from gapath.problems import GridPathProblem
    >>> res = minimize(GridPathProblem(default_workspace()), paper_nsga2(20), ("n_gen", 2), seed=1)
    >>> res.F.shape[1]
    2
    >>> p = GridPathProblem(default_workspace(), encoding="binary")
    >>> res = minimize(p, paper_nsga2(20), ("n_gen", 2), seed=1)  # the problem's encoding
    >>> res.pop.get("X").dtype
    dtype('bool')
    >>> import pickle
    >>> pickle.loads(pickle.dumps(res)).F.shape == res.F.shape
    True
    """
    try:
        pop_size = int(pop_size)
    except (TypeError, ValueError):
        raise ConfigError(f"pop_size must be an integer >= 2, got {pop_size!r}") from None
    if pop_size < 2:
        raise ConfigError(f"pop_size must be an integer >= 2, got {pop_size!r}")
    if tiebreak not in ("smoothness", None):
        raise ConfigError(f"tiebreak must be 'smoothness' or None, got {tiebreak!r}")
    from gapath.encodings.free import FREE_ENCODINGS

    if encoding is not None and encoding not in ENCODINGS and encoding not in FREE_ENCODINGS:
        raise ConfigError(f"unknown encoding {encoding!r}; expected one of {', '.join(ENCODINGS)}")
    settings = dict(sbx_prob=sbx_prob, sbx_eta=sbx_eta, pm_eta=pm_eta, pm_prob_var=pm_prob_var)
    ops = default_operators(encoding or "integer", **settings)
    return PathNSGA2(
        encoding=encoding,
        operator_settings=None if encoding is not None else settings,
        operators_for=encoding or "integer",
        sampling_given=sampling is not None,
        pop_size=pop_size,
        sampling=ops["sampling"] if sampling is None else sampling,
        selection=SmoothnessTournament(tiebreak=tiebreak is not None),
        crossover=ops["crossover"],
        mutation=ops["mutation"],
        survival=RankAndSmoothnessSurvival(tiebreak=tiebreak),
        repair=EdgeFixingRepair(),
        eliminate_duplicates=PathDuplicateElimination(),
        **kwargs,
    )


__all__ = ["PathNSGA2", "paper_nsga2"]
