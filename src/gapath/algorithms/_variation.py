"""numba twins of pymoo's SBX crossover and polynomial mutation.

pymoo's ``Crossover.do`` + ``cross_sbx`` and ``Mutation.do`` + ``mut_pm``
are some fifty NumPy operations each; at 250 matings of 31 genes they cost
~1.7 ms and ~0.45 ms, and the mating loop calls them three to four times
per generation (refill rounds), most of a vectorised generation.

Speed inside the twins: the masks of crossed and mutated genes are
computed without branches (a branch on a uniform draw is mispredicted half
the time) and compacted into index lists, so the per-gene work runs only
where a gene changes; consecutive draws are made in one ``random`` call
(the generator yields the same numbers for ``random(a)`` then
``random(b)`` as for ``random(a + b)``), including, with ``then``, the
first draws of the operator that follows (an edge-fixing repair).

:func:`sbx_crossover` and :func:`pm_mutation` compute the same children from
the same random numbers: they draw from the generator in the same calls, of
the same sizes, in the same order as pymoo's ``do`` and ``_do``, and leave
it in the same state.

Identity on every CPU: every power is computed by the same NumPy call pymoo
makes, ``np.power`` of two contiguous float64 arrays (bases and exponents),
one call per power of ``calc_betaq``/``mut_pm`` for the whole batch of
matings. NumPy dispatches that call to SIMD code on CPUs that have it
(AVX-512: results that differ from the C library's ``pow``, which numba's
``**`` calls, in the last bit) and to ``pow`` elsewhere, and its result for
an element does not depend on the array's length or on the element's
position (checked for lengths 1 to 40 at many offsets and for strided views;
a reversed view takes the ``pow`` loop, so both sides pass fresh contiguous
arrays). Hence the twins power only the branch pymoo keeps for each element
(pymoo powers both and masks) and both betas of a gene in one call. The
exponents are arrays, as pymoo's: with a scalar exponent NumPy computes
``x ** 0.5``, ``x ** 2`` and ``x ** -1`` by ``sqrt``, ``x * x`` and ``1 / x``
(eta 1 would differ). Everything else (bases, branches, children, clamping)
is IEEE arithmetic in numba kernels around those calls (no fused
multiply-add; IEEE division, as NumPy's), so twins and pymoo return
bit-identical arrays whatever SIMD NumPy picked.

:func:`sbx_supported` / :func:`pm_supported` say when an operator is one of
them (gapath's DiscreteSBX and DiscretePM are);
:class:`gapath.algorithms.FastNSGA2` sends any other operator through its
own ``_do``. ``tests/test_fast_nsga2.py`` checks the equality and
``tests/test_simd_dispatch.py`` checks it again with NumPy's SIMD dispatch
disabled.
"""

from __future__ import annotations

import numba
import numpy as np
from pymoo.core.crossover import Crossover
from pymoo.core.mutation import Mutation
from pymoo.core.variable import Variable
from pymoo.operators.crossover.sbx import SimulatedBinaryCrossover
from pymoo.operators.mutation.pm import PolynomialMutation
from pymoo.operators.repair.rounding import RoundingRepair

__all__ = [
    "discrete_supported",
    "discrete_variation",
    "pm_mutation",
    "pm_supported",
    "sbx_crossover",
    "sbx_supported",
]


def _value(v):
    return v.get() if isinstance(v, Variable) else v


def _scalars(*values) -> bool:
    return all(np.ndim(_value(v)) == 0 for v in values)


def sbx_supported(op) -> bool:
    """True when ``op._do`` is pymoo's SBX with two children and scalar
    parameters."""
    return (
        isinstance(op, SimulatedBinaryCrossover)
        and type(op)._do is SimulatedBinaryCrossover._do
        and type(op).do is Crossover.do
        and op.n_offsprings == 2
        and _scalars(op.prob, op.eta, op.prob_var, op.prob_exch, op.prob_bin)
    )


def pm_supported(op, problem) -> bool:
    """True when ``op._do`` is pymoo's polynomial mutation without
    ``at_least_once`` and with scalar parameters."""
    return (
        isinstance(op, PolynomialMutation)
        and type(op)._do is PolynomialMutation._do
        and type(op).do is Mutation.do
        and not op.at_least_once
        and _scalars(op.eta, op.prob, op.get_prob_var(problem))
    )


_NJIT = dict(cache=True, error_model="numpy")  # IEEE division, as NumPy's


@numba.njit(**_NJIT)
def _sbx_betas(X0, X1, xl, xu, r, prob_var, eta):
    """``cross_sbx``'s crossed genes and the first power's bases and
    exponents.

    Returns ``idx``, the flat indices ``i m + j`` of the crossed genes in
    row-major order (the order of ``X[0][cross]``), and ``B``, ``E``: the two
    ``beta`` of the ``k``-th crossed gene at ``2 k`` (from the lower bound,
    child 1) and ``2 k + 1`` (from the upper bound, child 2), each with
    exponent ``-(eta + 1)``. The mask is computed without branches (its
    draws are random, a branch on them is mispredicted half the time) and
    compacted by index."""
    n, m = X0.shape
    idx = np.empty(n * m, np.int64)
    k = 0
    for i in range(n):
        for j in range(m):
            near = abs(X0[i, j] - X1[i, j]) <= 1.0e-14
            c = (r[i, j] < prob_var) & (not near) & (xl[j] != xu[j])
            idx[k] = i * m + j  # k <= i m + j: in bounds
            k += np.int64(c)
    B = np.empty(2 * k)
    E = np.full(2 * k, -(eta + 1.0))
    for q in range(k):
        i = idx[q] // m
        j = idx[q] - i * m
        a, b = X0[i, j], X1[i, j]
        y1 = a if a < b else b
        y2 = b if a < b else a
        delta = y2 - y1
        B[2 * q] = 1.0 + (2.0 * (y1 - xl[j]) / delta)
        B[2 * q + 1] = 1.0 + (2.0 * (xu[j] - y2) / delta)
    return idx[:k], B, E


@numba.njit(**_NJIT)
def _sbx_bases(P, u, eta):
    """``calc_betaq``'s second power, given ``P = beta ** -(eta + 1)`` (laid
    out as by :func:`_sbx_betas`) and the draws ``u``: its bases, ``u alpha``
    where ``u <= 1 / alpha``, ``1 / (2 - u alpha)`` where ``u > 1 / alpha``,
    NaN where neither holds (alpha is NaN; pymoo's ``betaq`` stays 0 there),
    and its exponents ``1 / (eta + 1)``."""
    Z = np.empty(len(P))
    for k in range(len(P)):
        r = u[k // 2]
        alpha = 2.0 - P[k]
        ia = 1.0 / alpha
        z_low = r * alpha
        z_high = 1.0 / (2.0 - r * alpha)
        Z[k] = z_low if r <= ia else (z_high if r > ia else np.nan)
    return Z, np.full(len(P), 1.0 / (eta + 1.0))


@numba.njit(**_NJIT)
def _clamp(x, lo, hi):
    return min(max(x, lo), hi) if x == x else x


@numba.njit(**_NJIT)
def _sbx_children(X0, X1, xl, xu, prob_bin, exch, prob_exch, idx, Z, Q2, w, mating, rint):
    """Children ``(2 n, m)``: SBX children of the crossed genes ``idx`` of
    the crossed matings (clamped to the bounds), copies of the parents
    elsewhere (clamped in crossed matings, as pymoo's ``repair_clamp`` of
    the whole SBX output); rounded to the nearest integer (half to even, as
    ``np.around``) when ``rint``. ``Q2`` holds ``betaq`` (``Z ** (1 / (eta +
    1))``, 0 where ``Z`` is NaN)."""
    n, m = X0.shape
    Q = np.empty((2 * n, m))
    for i in range(n):
        clamp = mating[i]
        for j in range(m):
            a, b = X0[i, j], X1[i, j]
            if clamp:
                a = _clamp(a, xl[j], xu[j])
                b = _clamp(b, xl[j], xu[j])
            Q[i, j] = np.rint(a) if rint else a
            Q[n + i, j] = np.rint(b) if rint else b
    for k in range(len(idx)):
        i = idx[k] // m
        j = idx[k] - i * m
        if not mating[i]:
            continue
        a, b = X0[i, j], X1[i, j]
        sm = a < b
        y1 = a if sm else b
        y2 = b if sm else a
        delta = y2 - y1
        bq1 = Q2[2 * k] if Z[2 * k] == Z[2 * k] else 0.0
        bq2 = Q2[2 * k + 1] if Z[2 * k + 1] == Z[2 * k + 1] else 0.0
        c1 = 0.5 * ((y1 + y2) - bq1 * delta)
        c2 = 0.5 * ((y1 + y2) + bq2 * delta)
        pb = 0.0 if exch[i] > prob_exch else prob_bin
        swap = (w[k] < pb) != (a > b)
        ch1 = (c2 if sm else c1) if swap else (c1 if sm else c2)
        ch2 = (c1 if sm else c2) if swap else (c2 if sm else c1)
        ch1 = _clamp(ch1, xl[j], xu[j])
        ch2 = _clamp(ch2, xl[j], xu[j])
        Q[i, j] = np.rint(ch1) if rint else ch1
        Q[n + i, j] = np.rint(ch2) if rint else ch2
    return Q


def _sbx_draws(op, random_state, n, m):
    """``Crossover.do``'s first draws: which matings cross, and (when any
    does) ``SimulatedBinaryCrossover._do``'s exchange and per-gene draws,
    in one call (consecutive ``random`` calls draw the same stream as one).
    Returns ``(mating, exch, r)``, ``exch`` and ``r`` None when no mating
    crosses (pymoo does not call ``_do`` then)."""
    mating = random_state.random(n) < float(_value(op.prob))
    if not mating.any():
        return mating, None, None
    d = random_state.random(n + n * m)
    return mating, d[:n], d[n:].reshape(n, m)


def _sbx(op, X, random_state, xl, xu, rint, then=0):
    """The random draws of ``Crossover.do`` with ``SimulatedBinaryCrossover._do``
    in pymoo's order, the powers of ``cross_sbx`` by NumPy (see the module
    docstring), the rest by numba: the ``(2 n, m)`` children.

    ``then``: the number of draws that follow ``_do``'s last ones (the
    mutation's first), made in the same call as those and returned too
    (``(Q, draws)``)."""
    _, n, m = X.shape
    mating, exch, r = _sbx_draws(op, random_state, n, m)
    if exch is None:
        none = np.zeros(0)
        Q = _sbx_children(
            X[0],
            X[1],
            xl,
            xu,
            0.0,
            np.zeros(n),
            1.0,
            np.zeros(0, np.int64),
            none,
            none,
            none,
            mating,
            rint,
        )
        return (Q, random_state.random(then)) if then else Q
    eta, prob_var, prob_exch, prob_bin = (
        float(_value(v)) for v in (op.eta, op.prob_var, op.prob_exch, op.prob_bin)
    )
    idx, B, E = _sbx_betas(X[0], X[1], xl, xu, r, prob_var, eta)
    k = len(idx)
    d = random_state.random(2 * k + then)
    u, w = d[:k], d[k : 2 * k]
    Z, E = _sbx_bases(np.power(B, E), u, eta)  # cross_sbx: np.power(beta, -(eta + 1.0))
    Q2 = np.power(Z, E)  # np.power(rand * alpha, 1.0 / (eta + 1.0)), ...
    Q = _sbx_children(X[0], X[1], xl, xu, prob_bin, exch, prob_exch, idx, Z, Q2, w, mating, rint)
    return (Q, d[2 * k :]) if then else Q


def sbx_crossover(op, problem, X, random_state, bounds=None):
    """pymoo's ``Crossover.do`` with ``SimulatedBinaryCrossover._do`` on
    parents ``X`` (2, n_matings, n_var), already cast to the operator's
    ``vtype``: the ``(2 n_matings, n_var)`` float children, before the
    operator's own repair. ``bounds``: the problem's ``(xl, xu)`` as floats,
    if at hand."""
    xl, xu = _bounds(problem) if bounds is None else bounds
    return _sbx(op, X.astype(float, copy=False), random_state, xl, xu, False)


@numba.njit(**_NJIT)
def _pm_genes(D, prob_var, xl, xu):
    """``mut_pm``'s mutated genes: the flat indices ``i m + j``, row-major,
    where the draw ``D[i, j] < prob_var`` and the gene is not fixed
    (``xl == xu``), compacted without branches."""
    n, m = D.shape
    idx = np.empty(n * m, np.int64)
    k = 0
    for i in range(n):
        for j in range(m):
            c = (D[i, j] < prob_var) & (xl[j] != xu[j])
            idx[k] = i * m + j  # k <= i m + j: in bounds
            k += np.int64(c)
    return idx[:k]


@numba.njit(**_NJIT)
def _pm_xy(X, xl, xu, idx, u, eta):
    """``mut_pm``'s first power: its bases ``xy`` for every mutated gene
    ``idx`` (in the order of ``X[mut]``), ``1 - delta1`` where ``u <= 0.5``,
    else ``1 - delta2``, and its exponents ``eta + 1``."""
    m = X.shape[1]
    xy = np.empty(len(idx))
    for k in range(len(idx)):
        i = idx[k] // m
        j = idx[k] - i * m
        x, lo, hi = X[i, j], xl[j], xu[j]
        d1 = 1.0 - (x - lo) / (hi - lo)
        d2 = 1.0 - (hi - x) / (hi - lo)
        xy[k] = d1 if u[k] <= 0.5 else d2
    return xy, np.full(len(idx), eta + 1.0)


@numba.njit(**_NJIT)
def _pm_val(P, u, eta):
    """``mut_pm``'s second power, given ``P = xy ** (eta + 1)``: its bases
    ``val`` and its exponents ``1 / (eta + 1)``."""
    val = np.empty(len(u))
    for k in range(len(u)):
        r = u[k]
        v_low = 2.0 * r + (1.0 - 2.0 * r) * P[k]
        v_high = 2.0 * (1.0 - r) + 2.0 * (r - 0.5) * P[k]
        val[k] = v_low if r <= 0.5 else v_high
    return val, np.full(len(u), 1.0 / (eta + 1.0))


@numba.njit(**_NJIT)
def _pm_finish(x, lo, hi, rint):
    if x < lo:  # mut_pm's clamp, set_to_bounds_if_outside
        x = lo
    elif x > hi:
        x = hi
    return np.rint(x) if rint else x


@numba.njit(**_NJIT)
def _pm_children(X, xl, xu, idx, u, V, mutated, rint, Y):
    """``Y`` (preallocated, float or int64): ``X`` with the genes ``idx``
    of the rows ``mutated`` moved by polynomial mutation (pymoo's
    ``mut_pm``, bounds clamped), given ``V = val ** (1 / (eta + 1))``; the
    mutated rows rounded to the nearest integer when ``rint``."""
    n, m = X.shape
    for i in range(n):
        if mutated[i]:
            for j in range(m):
                Y[i, j] = _pm_finish(X[i, j], xl[j], xu[j], rint)
        else:
            for j in range(m):
                Y[i, j] = X[i, j]
    for k in range(len(idx)):
        i = idx[k] // m
        j = idx[k] - i * m
        if mutated[i]:
            lo, hi = xl[j], xu[j]
            dq = V[k] - 1.0 if u[k] <= 0.5 else 1.0 - V[k]
            Y[i, j] = _pm_finish(X[i, j] + dq * (hi - lo), lo, hi, rint)
    return Y


def _pm(op, problem, X, random_state, xl, xu, rint, first=None, extra=0, dtype=float):
    """The random draws of ``Mutation.do`` with ``PolynomialMutation._do``
    in pymoo's order, the powers of ``mut_pm`` by NumPy (see the module
    docstring), the rest by numba: the mutated ``X`` (of ``dtype``).

    ``first``: the per-gene draws, if already drawn (see :func:`_sbx`'s
    ``then``); ``extra``: the number of draws that follow ``Mutation.do``'s
    last ones (the next operator's), made in the same call and returned
    too (``(Y, draws)``)."""
    D = random_state.random(X.shape) if first is None else first.reshape(X.shape)
    idx = _pm_genes(D, op.get_prob_var(problem), xl, xu)
    k = len(idx)
    d = random_state.random(k + len(X) + extra)
    u = d[:k]
    mutated = d[k : k + len(X)] <= float(_value(op.prob))
    eta = float(_value(op.eta))
    xy, E = _pm_xy(X, xl, xu, idx, u, eta)
    val, E = _pm_val(np.power(xy, E), u, eta)  # mut_pm: np.power(xy, (eta + 1.0))
    V = np.power(val, E)  # np.power(val, mut_pow)
    Y = _pm_children(X, xl, xu, idx, u, V, mutated, rint, np.empty(X.shape, dtype))
    return Y if extra == 0 and first is None else (Y, d[k + len(X) :])


def pm_mutation(op, problem, X, random_state, bounds=None):
    """pymoo's ``Mutation.do`` with ``PolynomialMutation._do`` on genomes
    ``X`` (n, n_var): float genomes, each row mutated with probability
    ``prob``, before the operator's own repair. ``bounds``: the problem's
    ``(xl, xu)`` as floats, if at hand."""
    xl, xu = _bounds(problem) if bounds is None else bounds
    return _pm(op, problem, X.astype(float), random_state, xl, xu, False)


def discrete_supported(crossover, mutation, problem) -> bool:
    """True when both operators have twins and round their float output to
    integers with pymoo's ``RoundingRepair`` (gapath's DiscreteSBX and
    DiscretePM), so :func:`discrete_variation` applies."""
    return (
        sbx_supported(crossover)
        and pm_supported(mutation, problem)
        and all(op.vtype is float and type(op.repair) is RoundingRepair for op in (crossover, mutation))
    )


def discrete_variation(crossover, mutation, problem, X, random_state, bounds=None, then=None):
    """Crossover then mutation, each with its rounding, as pymoo applies
    them (``Crossover.do``, ``RoundingRepair``, ``Mutation.do``,
    ``RoundingRepair``) to parents ``X`` (2, n_matings, n_var): the
    ``(2 n_matings, n_var)`` integer children.

    ``then``: the number of uniform draws per child the next operator makes
    first (e.g. 1 per gene, ``n_var``, for an edge-fixing repair); they are
    drawn in the same call as the mutation's last ones, which leaves the
    generator where those calls leave it, and returned: ``(children,
    draws)``, ``draws`` of shape ``(2 n_matings, then)``."""
    xl, xu = _bounds(problem) if bounds is None else bounds
    n, m = X.shape[1], X.shape[2]
    extra = 0 if then is None else 2 * n * then
    Q, D = _sbx(crossover, X.astype(float, copy=False), random_state, xl, xu, True, 2 * n * m)
    Y, U = _pm(mutation, problem, Q, random_state, xl, xu, True, first=D, extra=extra, dtype=np.int64)
    return Y if then is None else (Y, U.reshape(2 * n, then))


def _bounds(problem):
    return np.asarray(problem.xl, dtype=float), np.asarray(problem.xu, dtype=float)
