"""Ahmed & Deb's sampling, crossover and mutation for each encoding."""

from __future__ import annotations

from pymoo.operators.crossover.pntx import TwoPointCrossover
from pymoo.operators.sampling.rnd import BinaryRandomSampling, IntegerRandomSampling

from gapath.errors import ConfigError
from gapath.operators.crossover.discrete_sbx import DiscreteSBX
from gapath.operators.crossover.mixed_crossover import MixedCrossover
from gapath.operators.mutation.decaying_bitflip import DecayingBitflipMutation
from gapath.operators.mutation.discrete_pm import DiscretePM
from gapath.operators.mutation.mixed_mutation import MixedMutation


def default_operators(
    encoding_name: str,
    *,
    sbx_prob: float = 0.9,
    sbx_eta: float = 10,
    pm_eta: float = 20,
    pm_prob_var: float | None = None,
) -> dict:
    """Fresh sampling, crossover and mutation operators for an encoding,
    with Ahmed & Deb's settings (sections 2 and 5.2).

    * ``integer`` and ``absolute``: ``IntegerRandomSampling``, ``DiscreteSBX``
      (prob 0.9, eta 10), ``DiscretePM`` (eta 20, per-gene 1/n, n columns).
    * ``binary``: ``BinaryRandomSampling``, pymoo's ``TwoPointCrossover``
      (prob 0.9), ``DecayingBitflipMutation`` (per-bit 1/n_bits at
      generation 1, linearly down to a fifth of it at the last generation).
    * ``mixed``: ``IntegerRandomSampling`` (each bit in {0, 1}, each integer
      in [0, H]), ``MixedCrossover`` (prob 0.9; single-point on the bits,
      discrete SBX eta 10 on the integers), ``MixedMutation`` (bit-flip and
      discrete PM eta 20, per-gene 1/n).

    Parameters
    ----------
    encoding_name : a name in :data:`gapath.encodings.ENCODINGS`.
    sbx_prob : probability that a mating is crossed over (every encoding).
    sbx_eta : SBX distribution index (integer, absolute, mixed).
    pm_eta : polynomial mutation distribution index (integer, absolute, mixed).
    pm_prob_var : per-gene mutation probability; for the binary encoding the
        initial per-bit probability, also ``"bits"`` (1 / number of bits,
        the default) or ``"grid"`` (1 / n for n columns, Ahmed & Deb's
        rate). ``None`` keeps each operator's default.

    Returns
    -------
    dict with keys ``sampling``, ``crossover``, ``mutation``.

    Raises
    ------
    ConfigError
        If the encoding is unknown.

    Examples
    --------
    >>> ops = default_operators("binary")
    >>> type(ops["mutation"]).__name__
    'DecayingBitflipMutation'
    """
    if isinstance(pm_prob_var, str) and encoding_name != "binary":
        raise ConfigError(
            f"pm_prob_var={pm_prob_var!r} (a named bit-flip rate) is for the binary encoding; "
            f"give the {encoding_name!r} encoding a probability or None"
        )
    if encoding_name in ("integer", "absolute"):
        return dict(
            sampling=IntegerRandomSampling(),
            crossover=DiscreteSBX(prob=sbx_prob, eta=sbx_eta),
            mutation=DiscretePM(eta=pm_eta, prob_var=pm_prob_var),
        )
    if encoding_name == "binary":
        return dict(
            sampling=BinaryRandomSampling(),
            crossover=TwoPointCrossover(prob=sbx_prob),
            mutation=DecayingBitflipMutation(prob_var=pm_prob_var),
        )
    if encoding_name == "mixed":
        return dict(
            sampling=IntegerRandomSampling(),
            crossover=MixedCrossover(prob=sbx_prob, eta=sbx_eta),
            mutation=MixedMutation(eta=pm_eta, prob_var=pm_prob_var),
        )
    from gapath.encodings import ENCODINGS
    from gapath.encodings.free import FREE_ENCODINGS

    if encoding_name in FREE_ENCODINGS:  # real genes in [0, 1]: pymoo's SBX and PM
        from pymoo.operators.crossover.sbx import SBX
        from pymoo.operators.mutation.pm import PM
        from pymoo.operators.sampling.rnd import FloatRandomSampling

        return dict(
            sampling=FloatRandomSampling(),
            crossover=SBX(prob=sbx_prob, eta=sbx_eta),
            mutation=PM(eta=pm_eta, prob_var=pm_prob_var),
        )
    raise ConfigError(f"unknown encoding {encoding_name!r}; expected one of {', '.join(ENCODINGS)}")


__all__ = ["default_operators"]
