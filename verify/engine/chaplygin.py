"""Chaplygin's two integrals of a rolling body of revolution (for the disk from rows 2 and 3 of paper Eq. 17).

Rows 2 and 3 of the rolling equations make w = (omega2, omega3) obey the linear ODE
dw/dtheta = A(theta) w (``models.base.ChaplyginSystem``).  With Phi(theta) its fundamental
matrix, Phi(theta_ref) = identity, the two numbers

    (chaplygin_1, chaplygin_2) = Phi(theta)^-1 w(theta)

(w carried back to ``theta_ref``) are constant along every motion.  Two routes compute them:

* **the transport** (``method="fundamental-matrix"``; what ``"auto"``, the default, uses): heyoka integrates
  dPhi/dtheta = A(theta) Phi in theta from ``theta_ref`` and reads Phi at the run's distinct
  thetas from one ``propagate_grid`` each side of ``theta_ref``.  The integrator is built once
  per (matrix, precision) and borrowed from :mod:`verify.engine.integrators` (thread-safe, no
  JIT per call).  It runs at :func:`transport_precision`, at least 10 bits above the run's (as
  the closed form's ``workprec(bits + 10)``), and Phi^-1 w is formed there and rounded once to
  the run's precision.  Against the closed form at bits + 80 it is within 0.33 eps * (|c1| + |c2|)
  from theta = 1e-12 to pi - 1e-9 (k 0.1 to 0.5, double and quad): the exact value rounded once,
  to the last bit but for ties of the rounding (tests/test_chaplygin.py argues the bound);
* **the closed form** (``method="closed-form"``, where the model has one: the thin disk's
  Legendre functions through mpmath's 2F1 at the run's bits + 10, more near the ends,
  ``models.disk``): the independent check of the transport, ~4 ms a point.

A(theta) of the disk and the ring is singular only where sin(theta) = 0, the ends of the disk's
domain (0, pi) and the lower end of the ring's (0, pi/2): every theta of a run inside its
model's domain is reached by the transport without crossing a singularity.  A theta outside the
domain (``solve(..., events=False)`` integrates on past it) cannot be transported through
sin(theta) = 0; there the closed form, where the model has one, gives what it always gave (its
formula continued: even in theta about 0 and pi).  A non-finite theta gives NaN.
"""
from __future__ import annotations

from functools import lru_cache

import heyoka as hy
import mpmath
import numpy as np

from models.base import Model
from models.symbols import theta

from . import integrators
from .compile import to_heyoka
from ..precision import Precision, parse_precision

METHODS = ("auto", "closed-form", "fundamental-matrix")

#: Bits the transport works above the run's precision, at least (the closed form's margin).
GUARD_BITS = 10


def transport_precision(precision: Precision) -> Precision:
    """The precision the transport runs at: the cheapest of the ladder with >= bits + GUARD_BITS.

    double (53) -> long (64 where the platform's long double is x87's 80-bit, else quad),
    long -> quad (113), quad and MPFR at b bits -> MPFR at b + GUARD_BITS.
    """
    long = parse_precision("long")
    if precision.bits + GUARD_BITS <= long.bits and np.finfo(np.longdouble).nmant + 1 == long.bits:
        return long
    quad = parse_precision("quad")
    if precision.bits + GUARD_BITS <= quad.bits:
        return quad
    return parse_precision(f"mp:{precision.bits + GUARD_BITS}")


def chaplygin_integrals(model: Model, precision: Precision, params: dict, thetas, w2, w3, method: str = "auto"):
    """(omega2, omega3) carried back to theta_ref: Chaplygin's two first integrals at each point.

    ``thetas``, ``w2``, ``w3``: sequences of equal length at the run's precision; ``params``:
    name -> value at the run's precision.  ``method``: ``"fundamental-matrix"`` (the transport),
    ``"closed-form"`` (needs ``model.chaplygin.closed_form``) or ``"auto"``: the transport, and
    the closed form at any theta outside the model's domain where the model has one (see the
    module docstring).  Returns two arrays of the run's precision.
    """
    if method not in METHODS:
        raise ValueError(f"method={method!r}; allowed: {', '.join(METHODS)}")
    if method == "closed-form":
        if model.chaplygin.closed_form is None:
            raise ValueError(f"{model.name!r} has no closed form of Chaplygin's integrals")
        return _closed_form(model, precision, params, thetas, w2, w3)
    thetas = thetas if isinstance(thetas, np.ndarray) else precision.array(list(thetas))
    w2, w3 = np.asarray(w2), np.asarray(w3)
    move = np.ones(len(thetas), dtype=bool)
    if method == "auto" and model.chaplygin.closed_form is not None:
        lo, hi = _domain(model.domain, precision)
        with np.errstate(invalid="ignore"):  # a NaN theta goes to the transport, which gives NaN
            move = ((thetas > lo) & (thetas < hi)) | (thetas != thetas)
        c1, c2 = _transported(model, precision, params, thetas[move], w2[move], w3[move])
    else:
        c1, c2 = _transported(model, precision, params, thetas, w2, w3)
    if move.all():
        return c1, c2
    out1, out2 = thetas.copy(), thetas.copy()  # of the run's dtype (and MPFR precision)
    out1[move], out2[move] = c1, c2
    rest = ~move
    out1[rest], out2[rest] = _closed_form(model, precision, params, thetas[rest], w2[rest], w3[rest])
    return out1, out2


@lru_cache(maxsize=None)
def _domain(domain, precision: Precision) -> tuple:
    return precision.number(domain.theta_min), precision.number(domain.theta_max)


class _Transport:
    """The transport of one Chaplygin system at one precision: its constants, and the key (this
    object) and build of its integrator for :func:`integrators.borrowed` (one JIT per system and
    precision, for the life of the process)."""

    def __init__(self, system, parameters: tuple, precision: Precision):
        """``parameters``: the model's (name, symbol) pairs in ``par[i]`` order."""
        one, zero = precision.number(1), precision.number(0)
        used = [i for i, (_, symbol) in enumerate(parameters) if system.matrix.has(symbol)]
        self.precision = precision
        self.ref = precision.number(system.theta_ref)
        self.identity = precision.array([one, zero, zero, one])
        self.parameter_names = tuple(name for name, _ in parameters[: max(used) + 1 if used else 0])
        self._equations = _transport_system(system.matrix, tuple(symbol for _, symbol in parameters))

    def build(self):
        zero = self.precision.number(0)
        return hy.taylor_adaptive(list(self._equations), self.identity, pars=self.precision.array(
            [zero] * len(self.parameter_names)), time=self.ref, tol=zero, **self.precision.integrator_kwargs())


@lru_cache(maxsize=None)
def _transport(system, parameters: tuple, precision: Precision) -> _Transport:
    return _Transport(system, parameters, precision)


def _transported(model, precision, params, thetas, w2, w3, tp=None):
    """Phi(theta)^-1 w at the transport precision, rounded once to ``precision``.

    Thetas a fixed-exponent transport cannot reach (its Taylor coefficients overflow within
    ~1e-200 of a singular end: cot(theta)'s n-th derivative ~ theta^-(n+1)) are transported again
    by MPFR at the same bits, whose exponent range does not overflow.
    """
    tp = tp or transport_precision(precision)
    up = lambda values: _convert(values, precision, tp)  # noqa: E731 - exact: tp holds every value
    phi, reached = _fundamental(model, tp, {k: up([v])[0] for k, v in params.items()}, up(thetas), partial=not tp.is_mpfr)
    p11, p12, p21, p22 = phi.T
    a, b = up(w2), up(w3)
    det = p11 * p22 - p12 * p21
    c1, c2 = _convert((p22 * a - p12 * b) / det, tp, precision), _convert((p11 * b - p21 * a) / det, tp, precision)
    if not reached.all():
        missed = ~reached
        c1[missed], c2[missed] = _transported(model, precision, params, thetas[missed], w2[missed], w3[missed],
                                              parse_precision(f"mp:{tp.bits}"))
    return c1, c2


def fundamental_matrices(model: Model, precision: Precision, params: dict, thetas) -> np.ndarray:
    """Phi(theta) with Phi(theta_ref) = identity at each theta, at ``precision``: rows (p11, p12, p21, p22)."""
    return _fundamental(model, precision, params, precision.array(list(thetas)))[0]


def _fundamental(model, precision, params, thetas, partial: bool = False) -> tuple:
    """(Phi at each theta, which thetas were reached).  ``partial``: where the transport stops (its
    Taylor coefficients overflow near a singular end) the thetas beyond get NaN and False;
    otherwise it raises."""
    tr = _transport(model.chaplygin, tuple((p.name, p.symbol) for p in model.parameters), precision)
    ref, identity = tr.ref, tr.identity
    pars = precision.array([params[name] for name in tr.parameter_names])
    distinct, owner = np.unique(thetas, return_inverse=True)  # sorted ascending; NaNs last
    found = np.empty((len(distinct), 4), dtype=identity.dtype)
    found[:] = identity  # theta == theta_ref
    reached = np.ones(len(distinct), dtype=bool)
    above, below = distinct > ref, distinct < ref
    for where in (np.flatnonzero(above), np.flatnonzero(below)[::-1]):  # outwards from theta_ref
        if not len(where):
            continue
        grid = np.concatenate([np.array([ref]), distinct[where]])
        with integrators.borrowed(tr, tr.build, ref, identity, pars) as ta:
            res = ta.propagate_grid(grid)
        rows = res[-1]
        if len(rows) != len(grid):
            if not partial:
                raise RuntimeError(f"the Chaplygin transport stopped early ({res[0]}) on its way to theta = {grid[-1]}")
            missed = where[max(len(rows) - 1, 0):]
            reached[missed] = False
            with np.errstate(invalid="ignore"):
                found[missed] = distinct[missed, None] * ((ref - ref) / (ref - ref))  # NaN of the dtype
            where = where[: max(len(rows) - 1, 0)]
            rows = rows[: len(where) + 1]
        found[where] = rows[1:]
    unordered = ~(above | below | (distinct == ref))
    found[unordered] = distinct[unordered, None]  # a NaN theta gives a NaN matrix
    owner = owner.reshape(-1)
    return found[owner], reached[owner]


@lru_cache(maxsize=None)
def _transport_system(matrix, parameter_symbols: tuple):
    """dPhi/dtheta = A(theta) Phi with theta as heyoka's time variable, parameters as par[i]."""
    variables = hy.make_vars("p11", "p12", "p21", "p22")
    mapping = {theta: hy.time}
    mapping.update({s: hy.par[i] for i, s in enumerate(parameter_symbols)})
    A = [[to_heyoka(matrix[i, j], mapping, compact=True) for j in range(2)] for i in range(2)]
    P = [[variables[0], variables[1]], [variables[2], variables[3]]]
    rhs = [A[i][0] * P[0][j] + A[i][1] * P[1][j] for i in range(2) for j in range(2)]
    return tuple(zip(variables, rhs))


def _convert(values, source: Precision, target: Precision) -> np.ndarray:
    """``values`` (at ``source``) at ``target``: exact upwards, rounded to nearest downwards."""
    values = np.asarray(values)
    if source == target:
        return values
    if target.name == "double":
        return values.astype(float)  # from long: the x87 value rounded to nearest by the hardware
    if target.name == "long":
        if source.name == "double":
            return values.astype(np.longdouble)
        return target.array(list(values))  # from quad: through its 36 digits (Precision.number)
    if target.name == "quad":
        if source.name in ("double", "long"):
            return np.array([hy.real128(v) for v in values])
        # heyoka's real -> real128 conversion does not round to nearest; MPFR rounds to 113 bits first
        return np.array([hy.real(v, target.bits) for v in values]).astype(hy.real128)
    return np.array([hy.real(v, target.bits) for v in values])  # MPFR: exact up, to nearest down


def _closed_form(model, precision, params, thetas, w2, w3):
    c1, c2 = [], []
    with mpmath.workprec(precision.bits + GUARD_BITS):
        pm = {k: precision.to_mpf(v) for k, v in params.items()}
        for th, a, b in zip(thetas, w2, w3):
            x1, x2 = model.chaplygin.closed_form(precision.to_mpf(th), precision.to_mpf(a), precision.to_mpf(b), pm)
            c1.append(precision.number(x1))
            c2.append(precision.number(x2))
    return precision.array(c1), precision.array(c2)
