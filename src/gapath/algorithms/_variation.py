"""numba twins of pymoo's SBX crossover and polynomial mutation.

pymoo's ``Crossover.do`` + ``cross_sbx`` and ``Mutation.do`` + ``mut_pm``
are some fifty NumPy operations each; at 250 matings of 31 genes they cost
~1.7 ms and ~0.45 ms, and the mating loop calls them about five times per
generation (refill rounds), most of a vectorised generation.

:func:`sbx_crossover` and :func:`pm_mutation` compute the same children from
the same random numbers: they draw from the generator in the same calls, of
the same sizes, in the same order as pymoo's ``do`` and ``_do``, and leave
it in the same state. Identity on every CPU: the powers are computed by the
same NumPy call pymoo makes (``np.power`` of two contiguous float64 arrays,
one call per power of ``calc_betaq``/``mut_pm`` for the whole generation),
because NumPy dispatches that call to SIMD code on CPUs that have it (AVX-512:
results that differ from the C library's ``pow`` in the last bit) and to
``pow`` elsewhere, and its result for an element does not depend on the
array's length or on the element's position (checked for lengths 1 to 40
at many offsets and for strided views; a reversed view takes the ``pow``
loop, so both sides pass fresh contiguous arrays). Everything else
(bases, exponents, branches, children, clamping) is IEEE arithmetic in numba
kernels around those calls (no fused multiply-add, IEEE division as NumPy's),
so both return bit-identical arrays whatever SIMD NumPy picked. Only the
branch pymoo keeps is powered for each element (pymoo powers both and masks).
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

__all__ = ["discrete_supported", "discrete_variation", "pm_mutation", "pm_supported",
           "sbx_crossover", "sbx_supported"]


def _value(v):
    return v.get() if isinstance(v, Variable) else v


def _scalars(*values) -> bool:
    return all(np.ndim(_value(v)) == 0 for v in values)


def sbx_supported(op) -> bool:
    """True when ``op._do`` is pymoo's SBX with two children and scalar
    parameters."""
    return (isinstance(op, SimulatedBinaryCrossover)
            and type(op)._do is SimulatedBinaryCrossover._do and type(op).do is Crossover.do
            and op.n_offsprings == 2
            and _scalars(op.prob, op.eta, op.prob_var, op.prob_exch, op.prob_bin))


def pm_supported(op, problem) -> bool:
    """True when ``op._do`` is pymoo's polynomial mutation without
    ``at_least_once`` and with scalar parameters."""
    return (isinstance(op, PolynomialMutation)
            and type(op)._do is PolynomialMutation._do and type(op).do is Mutation.do
            and not op.at_least_once and _scalars(op.eta, op.prob, op.get_prob_var(problem)))


_NJIT = dict(cache=True, error_model="numpy")      # IEEE division, as NumPy's


@numba.njit(**_NJIT)
def _sbx_mask(X0, X1, xl, xu, r, prob_var):
    n, m = X0.shape
    cross = np.zeros((n, m), np.bool_)
    for i in range(n):
        for j in range(m):
            cross[i, j] = (r[i, j] < prob_var and not abs(X0[i, j] - X1[i, j]) <= 1.0e-14
                           and xl[j] != xu[j])
    return cross


@numba.njit(**_NJIT)
def _sbx_betas(X0, X1, xl, xu, cross, n_cross):
    """``cross_sbx``'s two ``beta`` of every crossed gene, in the order of
    ``X[0][cross]``: ``B[:n_cross]`` from the lower bound (child 1),
    ``B[n_cross:]`` from the upper bound (child 2)."""
    n, m = X0.shape
    B = np.empty(2 * n_cross)
    k = 0
    for i in range(n):
        for j in range(m):
            if cross[i, j]:
                a, b = X0[i, j], X1[i, j]
                y1 = a if a < b else b
                y2 = b if a < b else a
                delta = y2 - y1
                B[k] = 1.0 + (2.0 * (y1 - xl[j]) / delta)
                B[n_cross + k] = 1.0 + (2.0 * (xu[j] - y2) / delta)
                k += 1
    return B


@numba.njit(**_NJIT)
def _sbx_bases(P, u):
    """``calc_betaq``'s base of the second power, given ``P = beta **
    -(eta + 1)`` (laid out as :func:`_sbx_betas`) and the draws ``u``:
    ``u alpha`` where ``u <= 1 / alpha``, ``1 / (2 - u alpha)`` where
    ``u > 1 / alpha``, NaN where neither holds (alpha is NaN; pymoo's
    ``betaq`` stays 0 there)."""
    n_cross = len(u)
    Z = np.empty(2 * n_cross)
    for h in range(2):
        for k in range(n_cross):
            r = u[k]
            alpha = 2.0 - P[h * n_cross + k]
            if r <= 1.0 / alpha:
                z = r * alpha
            elif r > 1.0 / alpha:
                z = 1.0 / (2.0 - r * alpha)
            else:
                z = np.nan
            Z[h * n_cross + k] = z
    return Z


@numba.njit(**_NJIT)
def _sbx_children(X0, X1, xl, xu, prob_bin, exch, prob_exch, cross, Z, Q2, w, mating, rint):
    """Children ``(2 n, m)``: SBX children of the crossed matings (clamped
    to the bounds), copies of the parents for the others; rounded to the
    nearest integer (half to even, as ``np.around``) when ``rint``. ``Q2``
    holds ``betaq`` (``Z ** (1 / (eta + 1))``, 0 where ``Z`` is NaN)."""
    n, m = X0.shape
    n_cross = len(w)
    Q = np.empty((2 * n, m))
    k = 0
    for i in range(n):
        for j in range(m):
            a, b = X0[i, j], X1[i, j]
            if cross[i, j]:
                sm = a < b
                y1 = a if sm else b
                y2 = b if sm else a
                delta = y2 - y1
                z1, z2 = Z[k], Z[n_cross + k]
                bq1 = Q2[k] if z1 == z1 else 0.0
                bq2 = Q2[n_cross + k] if z2 == z2 else 0.0
                c1 = 0.5 * ((y1 + y2) - bq1 * delta)
                c2 = 0.5 * ((y1 + y2) + bq2 * delta)
                ch1 = c1 if sm else c2
                ch2 = c2 if sm else c1
                pb = 0.0 if exch[i] > prob_exch else prob_bin
                if (w[k] < pb) != (a > b):
                    ch1, ch2 = ch2, ch1
                k += 1
                if mating[i]:
                    a, b = ch1, ch2
            if mating[i]:                       # pymoo's repair_clamp of the SBX output
                a = min(max(a, xl[j]), xu[j]) if a == a else a
                b = min(max(b, xl[j]), xu[j]) if b == b else b
            Q[i, j] = np.rint(a) if rint else a
            Q[n + i, j] = np.rint(b) if rint else b
    return Q


def _power(base, exponent):
    """``base ** exponent`` as pymoo computes it: one ``np.power`` of two
    contiguous float64 arrays (NumPy picks its SIMD or its libm loop from
    the CPU, for pymoo's call and this one alike)."""
    return np.power(base, np.full(len(base), exponent))


def _sbx(op, X, random_state, xl, xu, rint):
    """The random draws of ``Crossover.do`` with ``SimulatedBinaryCrossover._do``
    in pymoo's order, the powers of ``cross_sbx`` by NumPy, the rest by
    numba: the ``(2 n, m)`` children."""
    _, n, m = X.shape
    mating = random_state.random(n) < float(_value(op.prob))
    if not mating.any():                           # pymoo does not call _do then
        none = np.zeros(0)
        return _sbx_children(X[0], X[1], xl, xu, 0.0, np.zeros(n), 1.0,
                             np.zeros((n, m), np.bool_), none, none, none, mating, rint)
    eta, prob_var, prob_exch, prob_bin = (float(_value(v)) for v in
                                          (op.eta, op.prob_var, op.prob_exch, op.prob_bin))
    exch = random_state.random(n)                  # pymoo: random((n, 1)) > prob_exch
    r = random_state.random((n, m))
    cross = _sbx_mask(X[0], X[1], xl, xu, r, prob_var)
    n_cross = int(np.count_nonzero(cross))
    u = random_state.random(n_cross)
    w = random_state.random(n_cross)
    P = _power(_sbx_betas(X[0], X[1], xl, xu, cross, n_cross), -(eta + 1.0))
    Z = _sbx_bases(P, u)
    Q2 = _power(Z, 1.0 / (eta + 1.0))
    return _sbx_children(X[0], X[1], xl, xu, prob_bin, exch, prob_exch, cross, Z, Q2, w,
                         mating, rint)


def sbx_crossover(op, problem, X, random_state, bounds=None):
    """pymoo's ``Crossover.do`` with ``SimulatedBinaryCrossover._do`` on
    parents ``X`` (2, n_matings, n_var), already cast to the operator's
    ``vtype``: the ``(2 n_matings, n_var)`` float children, before the
    operator's own repair. ``bounds``: the problem's ``(xl, xu)`` as floats,
    if at hand."""
    xl, xu = _bounds(problem) if bounds is None else bounds
    return _sbx(op, X.astype(float, copy=False), random_state, xl, xu, False)


@numba.njit(**_NJIT)
def _pm_xy(X, xl, xu, mut, u):
    """``mut_pm``'s ``xy`` of every mutated gene (in the order of
    ``X[mut]``): ``1 - delta1`` where ``u <= 0.5``, else ``1 - delta2``."""
    n, m = X.shape
    xy = np.empty(len(u))
    k = 0
    for i in range(n):
        for j in range(m):
            if mut[i, j]:
                x, lo, hi = X[i, j], xl[j], xu[j]
                if u[k] <= 0.5:
                    xy[k] = 1.0 - (x - lo) / (hi - lo)
                else:
                    xy[k] = 1.0 - (hi - x) / (hi - lo)
                k += 1
    return xy


@numba.njit(**_NJIT)
def _pm_val(P, u):
    """``mut_pm``'s ``val`` of every mutated gene, given ``P = xy **
    (eta + 1)``."""
    val = np.empty(len(u))
    for k in range(len(u)):
        r = u[k]
        if r <= 0.5:
            val[k] = 2.0 * r + (1.0 - 2.0 * r) * P[k]
        else:
            val[k] = 2.0 * (1.0 - r) + 2.0 * (r - 0.5) * P[k]
    return val


@numba.njit(**_NJIT)
def _pm_children(X, xl, xu, mut, u, V, mutated, rint):
    """``X`` with the genes ``mut`` of the rows ``mutated`` moved by
    polynomial mutation (pymoo's ``mut_pm``, bounds clamped), given ``V =
    val ** (1 / (eta + 1))``; the mutated rows rounded to the nearest
    integer when ``rint``."""
    n, m = X.shape
    Y = X.copy()
    k = 0
    for i in range(n):
        for j in range(m):
            x, lo, hi = X[i, j], xl[j], xu[j]
            if mut[i, j]:
                dq = V[k] - 1.0 if u[k] <= 0.5 else 1.0 - V[k]
                k += 1
                x = x + dq * (hi - lo)
            if not mutated[i]:
                continue
            if x < lo:                          # mut_pm's clamp, set_to_bounds_if_outside
                x = lo
            elif x > hi:
                x = hi
            Y[i, j] = np.rint(x) if rint else x
    return Y


def _pm(op, problem, X, random_state, xl, xu, rint):
    """The random draws of ``Mutation.do`` with ``PolynomialMutation._do``
    in pymoo's order, the powers of ``mut_pm`` by NumPy, the rest by
    numba: the mutated ``X``."""
    mut = random_state.random(X.shape) < op.get_prob_var(problem)
    if (xl == xu).any():
        mut[:, xl == xu] = False
    u = random_state.random(int(np.count_nonzero(mut)))
    mutated = random_state.random(size=X.shape[0]) <= float(_value(op.prob))
    eta = float(_value(op.eta))
    P = _power(_pm_xy(X, xl, xu, mut, u), eta + 1.0)
    V = _power(_pm_val(P, u), 1.0 / (eta + 1.0))
    return _pm_children(X, xl, xu, mut, u, V, mutated, rint)


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
    return (sbx_supported(crossover) and pm_supported(mutation, problem)
            and all(op.vtype is float and type(op.repair) is RoundingRepair
                    for op in (crossover, mutation)))


def discrete_variation(crossover, mutation, problem, X, random_state, bounds=None):
    """Crossover then mutation, each with its rounding, as pymoo applies
    them (``Crossover.do``, ``RoundingRepair``, ``Mutation.do``,
    ``RoundingRepair``) to parents ``X`` (2, n_matings, n_var): the
    ``(2 n_matings, n_var)`` integer children."""
    xl, xu = _bounds(problem) if bounds is None else bounds
    Q = _sbx(crossover, X.astype(float, copy=False), random_state, xl, xu, True)
    return _pm(mutation, problem, Q, random_state, xl, xu, True).astype(int)


def _bounds(problem):
    return np.asarray(problem.xl, dtype=float), np.asarray(problem.xu, dtype=float)
