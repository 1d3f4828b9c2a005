"""numba twins of pymoo's SBX crossover and polynomial mutation.

pymoo's ``Crossover.do`` + ``cross_sbx`` and ``Mutation.do`` + ``mut_pm``
are some fifty NumPy operations each; at 250 matings of 31 genes they cost
~1.7 ms and ~0.45 ms, and the mating loop calls them about five times per
generation (refill rounds), most of a vectorised generation.

:func:`sbx_crossover` and :func:`pm_mutation` compute the same children from
the same random numbers: they draw from the generator in the same calls, of
the same sizes, in the same order as pymoo's ``do`` and ``_do``, and do the
same IEEE arithmetic element by element (``pow`` of the C library, no fused
multiply-add), so they return bit-identical arrays and leave the generator
in the same state. :func:`sbx_supported` / :func:`pm_supported` say when an
operator is one of them (gapath's DiscreteSBX and DiscretePM are);
:class:`gapath.algorithms.FastNSGA2` sends any other operator through its
own ``_do``. ``tests/test_fast_nsga2.py`` checks the equality.
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


@numba.njit(cache=True)
def _sbx_mask(X0, X1, xl, xu, r, prob_var):
    n, m = X0.shape
    cross = np.zeros((n, m), np.bool_)
    for i in range(n):
        for j in range(m):
            cross[i, j] = (r[i, j] < prob_var and not abs(X0[i, j] - X1[i, j]) <= 1.0e-14
                           and xl[j] != xu[j])
    return cross


@numba.njit(cache=True, inline="always")
def _betaq(beta, eta, u):
    alpha = 2.0 - beta ** (-(eta + 1.0))
    if u <= 1.0 / alpha:
        return (u * alpha) ** (1.0 / (eta + 1.0))
    return (1.0 / (2.0 - u * alpha)) ** (1.0 / (eta + 1.0))


@numba.njit(cache=True)
def _sbx_children(X0, X1, xl, xu, eta, prob_bin, exch, prob_exch, cross, u, w, mating, rint):
    """Children ``(2 n, m)``: SBX children of the crossed matings (clamped
    to the bounds), copies of the parents for the others; rounded to the
    nearest integer (half to even, as ``np.around``) when ``rint``."""
    n, m = X0.shape
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
                beta = 1.0 + (2.0 * (y1 - xl[j]) / delta)
                c1 = 0.5 * ((y1 + y2) - _betaq(beta, eta, u[k]) * delta)
                beta = 1.0 + (2.0 * (xu[j] - y2) / delta)
                c2 = 0.5 * ((y1 + y2) + _betaq(beta, eta, u[k]) * delta)
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


def _sbx_inputs(op, X, random_state, xl, xu):
    """The random draws of ``Crossover.do`` with ``SimulatedBinaryCrossover._do``
    in pymoo's order, as the arguments of :func:`_sbx_children`."""
    _, n, m = X.shape
    mating = random_state.random(n) < float(_value(op.prob))
    if not mating.any():                           # pymoo does not call _do then
        none = np.zeros(0)
        return (X[0], X[1], xl, xu, 0.0, 0.0, np.zeros(n), 1.0, np.zeros((n, m), np.bool_),
                none, none, mating)
    eta, prob_var, prob_exch, prob_bin = (float(_value(v)) for v in
                                          (op.eta, op.prob_var, op.prob_exch, op.prob_bin))
    exch = random_state.random(n)                  # pymoo: random((n, 1)) > prob_exch
    r = random_state.random((n, m))
    cross = _sbx_mask(X[0], X[1], xl, xu, r, prob_var)
    n_cross = int(np.count_nonzero(cross))
    u = random_state.random(n_cross)
    w = random_state.random(n_cross)
    return X[0], X[1], xl, xu, eta, prob_bin, exch, prob_exch, cross, u, w, mating


def sbx_crossover(op, problem, X, random_state, bounds=None):
    """pymoo's ``Crossover.do`` with ``SimulatedBinaryCrossover._do`` on
    parents ``X`` (2, n_matings, n_var), already cast to the operator's
    ``vtype``: the ``(2 n_matings, n_var)`` float children, before the
    operator's own repair. ``bounds``: the problem's ``(xl, xu)`` as floats,
    if at hand."""
    xl, xu = _bounds(problem) if bounds is None else bounds
    X = X.astype(float, copy=False)
    return _sbx_children(*_sbx_inputs(op, X, random_state, xl, xu), False)


@numba.njit(cache=True)
def _pm_children(X, xl, xu, eta, mut, u, mutated, rint):
    """``X`` with the genes ``mut`` of the rows ``mutated`` moved by
    polynomial mutation (pymoo's ``mut_pm``, bounds clamped); the mutated
    rows rounded to the nearest integer when ``rint``."""
    n, m = X.shape
    Y = X.copy()
    mut_pow = 1.0 / (eta + 1.0)
    k = 0
    for i in range(n):
        for j in range(m):
            x, lo, hi = X[i, j], xl[j], xu[j]
            if mut[i, j]:
                delta1 = (x - lo) / (hi - lo)
                delta2 = (hi - x) / (hi - lo)
                r = u[k]
                k += 1
                if r <= 0.5:
                    xy = 1.0 - delta1
                    val = 2.0 * r + (1.0 - 2.0 * r) * (xy ** (eta + 1.0))
                    dq = val ** mut_pow - 1.0
                else:
                    xy = 1.0 - delta2
                    val = 2.0 * (1.0 - r) + 2.0 * (r - 0.5) * (xy ** (eta + 1.0))
                    dq = 1.0 - val ** mut_pow
                x = x + dq * (hi - lo)
            if not mutated[i]:
                continue
            if x < lo:                          # mut_pm's clamp, set_to_bounds_if_outside
                x = lo
            elif x > hi:
                x = hi
            Y[i, j] = np.rint(x) if rint else x
    return Y


def _pm_inputs(op, problem, shape, random_state, xl, xu):
    """The random draws of ``Mutation.do`` with ``PolynomialMutation._do``
    in pymoo's order: ``(eta, mut, u, mutated)`` for :func:`_pm_children`."""
    mut = random_state.random(shape) < op.get_prob_var(problem)
    if (xl == xu).any():
        mut[:, xl == xu] = False
    u = random_state.random(int(np.count_nonzero(mut)))
    mutated = random_state.random(size=shape[0]) <= float(_value(op.prob))
    return float(_value(op.eta)), mut, u, mutated


def pm_mutation(op, problem, X, random_state, bounds=None):
    """pymoo's ``Mutation.do`` with ``PolynomialMutation._do`` on genomes
    ``X`` (n, n_var): float genomes, each row mutated with probability
    ``prob``, before the operator's own repair. ``bounds``: the problem's
    ``(xl, xu)`` as floats, if at hand."""
    xl, xu = _bounds(problem) if bounds is None else bounds
    X = X.astype(float)
    return _pm_children(X, xl, xu, *_pm_inputs(op, problem, X.shape, random_state, xl, xu), False)


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
    ``(2 n_matings, n_var)`` integer children, in two numba passes."""
    xl, xu = _bounds(problem) if bounds is None else bounds
    X = X.astype(float, copy=False)
    Q = _sbx_children(*_sbx_inputs(crossover, X, random_state, xl, xu), True)
    pm = _pm_inputs(mutation, problem, Q.shape, random_state, xl, xu)
    return _pm_children(Q, xl, xu, *pm, True).astype(int)


def _bounds(problem):
    return np.asarray(problem.xl, dtype=float), np.asarray(problem.xu, dtype=float)
