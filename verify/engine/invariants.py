"""Invariants along a run, evaluated in the run's precision from the model's expressions.

* closed-form invariants (energy, Jellett, Routh, cyclic momenta): one compiled cfunc;
* Chaplygin's two integrals of a rolling body of revolution: (omega2, omega3) carried back
  to ``theta_ref`` along the linear ODE d(w)/d(theta) = A(theta) w (:mod:`.chaplygin`).

Everything is vectorised over the output grid (a run's invariants on its 101 default points
cost a fraction of a millisecond in double), with the semantics the per-point loops had.
"""
from __future__ import annotations

import math
import threading
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
import sympy as sp
from sympy.printing.numpy import NumPyPrinter

from models.base import Model
from models.symbols import STATE

from .chaplygin import chaplygin_integrals
from .compile import CompiledModel, friction_function


#: The relative drift is NaN where |I(0)| <= NEGLIGIBLE_INITIAL * eps * term scale: see
#: :class:`InvariantTrace`.
NEGLIGIBLE_INITIAL = 10


@dataclass(frozen=True)
class InvariantTrace:
    """One conserved quantity I along a run, and its drift three ways.

    Attributes
    ----------
    values : ndarray
        I on the output grid, in the run's precision.
    term_scale : float
        The largest value along the run of the sum of the absolute values of the terms of I
        expanded (``Invariant.scale``, ``models.build.additive_scale``); for Chaplygin's
        integrals |c1(0)| + |c2(0)|.  It bounds what rounding does to I: an error of eps
        relative in each state component, or in each operation evaluating I, moves I by at
        most about eps times this times the degree of the terms.  It is an upper bound on
        the magnitudes actually rounded (the cfunc evaluates I unexpanded, often on smaller
        intermediates).  It can be far above |I(0)|: on the Python page's run (docs/python.md: theta = 1.2, psidot = 10, 2 s) the disk
        dips to theta = 0.25 with phidot = -237, psidot = 250, where the expanded terms of
        (phidot cos theta + psidot)^2 are ~6e4 and cancel, and |E(0)| is 0.006 of it.
    eps : float
        The run's machine epsilon, 2^(1 - bits).
    max_abs_drift : float
        max_t |I(t) - I(0)|, in I's units (each difference taken in the run's precision).
    max_rel_drift : float
        max_abs_drift / |I(0)|: exactly the relative drift, how much of I's own value was
        lost.  NaN (never an absolute number in its place) where |I(0)| <=
        NEGLIGIBLE_INITIAL * eps * term_scale, I(0) = 0 included: I(0) is then within ten
        rounding units of the magnitudes I is made of, so by that bound it cannot be told
        from zero at the run's precision (a p_phi that is zero in exact arithmetic rounds to
        about eps times its terms) and a ratio to it means nothing.  The rule uses eps, not a
        fixed fraction such as 1e-3 of the term scale, because the bound is pessimistic:
        the disk's energy is 0.006 of its term scale on that run and 1e-5 to 1e-13
        of it on the Fig. 6 and spin-down states, and E(0) is right to about 1 eps in all of
        them (at theta = 1e-6 in double it is 563 eps term scale: kept).
    initial_value : optional
        I(0) where the output grid does not start at t = 0 (``solve(t_eval=...)`` returns only
        the requested times, while the drifts are still taken against the start); None when
        ``values[0]`` is I(0).
    max_drift_vs_terms : float
        max_abs_drift / term_scale (NaN if term_scale is 0), the cancellation-aware figure:
        the drift against the magnitudes the integrator and the evaluation of I round, so it
        is the figure Brouwer's eps sqrt(N) argument bounds (tests/test_conservation.py), and
        it stays defined where I(0) is negligible.  Never above max_rel_drift (|I(0)| <=
        term_scale by the triangle inequality), smaller by the factor |I(0)| / term_scale.
    max_drift_vs_terms_in_eps : float (property)
        max_drift_vs_terms / eps.

    Both ratios are kept because they answer different questions: ``max_rel_drift`` is
    what a user of the value I loses; ``max_drift_vs_terms`` (in eps) is whether the run
    was as good as its precision allows (0.16 eps on that run in quad, where the
    relative drift is 5.2e-33 = 27 eps).
    """

    name: str
    values: np.ndarray
    term_scale: float
    eps: float
    max_abs_drift: float
    max_rel_drift: float
    max_drift_vs_terms: float
    initial_value: object = None

    @property
    def initial(self):
        return self.values[0] if self.initial_value is None else self.initial_value

    @property
    def final(self):
        return self.values[-1]

    @property
    def max_drift_vs_terms_in_eps(self) -> float:
        return self.max_drift_vs_terms / self.eps

    @property
    def initial_negligible(self) -> bool:
        """|I(0)| <= NEGLIGIBLE_INITIAL * eps * term_scale: the relative drift is undefined (NaN)."""
        return _negligible(abs(float(self.initial)), self.term_scale, self.eps)


def _negligible(initial_magnitude: float, term_scale: float, eps: float) -> bool:
    return initial_magnitude <= NEGLIGIBLE_INITIAL * eps * term_scale


def trace(name: str, values: np.ndarray, term_scale: float, eps: float) -> InvariantTrace:
    """The drifts of ``values`` (see :class:`InvariantTrace`); differences in the run's precision.

    Each I(t) - I(0) is taken in the values' own dtype (double, long double, heyoka's real128
    or real) and then rounded to double, as ``float()`` of it would be.
    """
    values = np.asarray(values)
    worst = _python_max(np.abs(_to_double(values - values[0]))) if len(values) else 0.0
    i0 = abs(float(values[0])) if len(values) else 0.0
    rel = math.nan if _negligible(i0, term_scale, eps) else worst / i0
    vs_terms = worst / term_scale if term_scale > 0 else math.nan
    return InvariantTrace(name, values, float(term_scale), float(eps), worst, rel, vs_terms)


def scale_over(model: Model, inv_scale: sp.Expr, y: np.ndarray, params: dict) -> float:
    """The largest value of a scale expression along the run (in double: it is a magnitude).

    The rounding error of an invariant is relative to the magnitude of its terms, which
    can grow far above their initial size during a run (a disk near flat spins fast).
    """
    f = _scale_function(model, inv_scale)
    pars = [float(params[p.name]) for p in model.parameters]
    y = _to_double(np.asarray(y))
    return _python_max(np.broadcast_to(np.asarray(f(*y, *pars), dtype=float), (y.shape[1],)))


class _LibmPowPrinter(NumPyPrinter):
    """numpy code that gives the bits ``lambdify(modules="math")`` gave: x**n as libm's pow(x, n).

    numpy's ``x**2`` is x*x (correctly rounded), glibc's pow(x, 2.0) is not always (about one
    square in 1,300 differs in the last bit); ``numpy.float_power`` calls pow().  The scale is a
    magnitude and either would do, but the published term scales were made with pow().
    """

    def _print_Pow(self, expr, rational=False):
        if expr.exp.is_Integer and expr.exp > 1:
            return f"numpy.float_power({self._print(expr.base)}, {float(expr.exp)!r})"
        return super()._print_Pow(expr, rational=rational)


@lru_cache(maxsize=None)
def _scale_function(model: Model, inv_scale: sp.Expr):
    return sp.lambdify(list(STATE) + [p.symbol for p in model.parameters], inv_scale, modules="numpy",
                       printer=_LibmPowPrinter)


def _to_double(values: np.ndarray) -> np.ndarray:
    """Each value rounded to the nearest double, as ``float(v)`` (one cast for every dtype of the ladder)."""
    if values.dtype == np.float64:
        return values
    with np.errstate(invalid="ignore"):  # a NaN casts to NaN, as float() gives it, without numpy's warning
        return values.astype(float)


def _python_max(values: np.ndarray) -> float:
    """max() of the values as Python's builtin gives it: a NaN after the first value is passed over
    (no later value compares greater than it), a NaN first stays."""
    if math.isnan(values[0]):
        return float(values[0])
    return float(np.nanmax(values))


def evaluate(compiled: CompiledModel, y: np.ndarray, params: dict) -> dict:
    """Closed-form invariants, the normal force and Chaplygin's integrals at every column of y."""
    model, precision = compiled.model, compiled.precision
    n = y.shape[1]
    pars = np.ascontiguousarray(np.repeat(compiled.parameter_vector(params, for_function=True)[:, None], n, axis=1))
    out = compiled.invariant_function(np.ascontiguousarray(y), pars=pars)
    result = {inv.name: out[i] for i, inv in enumerate(model.invariants)}
    j = compiled.n_invariants
    normal = None
    if compiled.has_normal_force:
        normal, j = out[j], j + 1
    if model.chaplygin is not None:
        w2, w3 = out[j], out[j + 1]
        c1, c2 = chaplygin_integrals(model, precision, params, y[0], w2, w3)
        result["chaplygin_1"], result["chaplygin_2"] = c1, c2
    return result, normal


def friction_required(compiled: CompiledModel, y: np.ndarray, params: dict):
    """mu_req = |F_h| / N at every column of y in the run's precision; NaN where N <= 0; None without rolling contact."""
    friction = friction_function(compiled.model, compiled.precision)
    if friction is None:
        return None
    n = y.shape[1]
    names = compiled.model.parameter_names[:friction.n_pars]
    vector = compiled.precision.array([params[name] for name in names])
    pars = np.ascontiguousarray(np.repeat(vector[:, None], n, axis=1))
    normal, mu = friction.function(np.ascontiguousarray(y), pars=pars)
    return np.where(normal > 0, mu, np.full_like(mu, math.nan))


def traces(compiled: CompiledModel, values: dict, y: np.ndarray, params: dict) -> dict:
    model, eps = compiled.model, compiled.precision.eps
    out = {}
    for inv in model.invariants:
        out[inv.name] = trace(inv.name, values[inv.name], scale_over(model, inv.scale, y, params), eps)
    if model.chaplygin is not None:
        c1, c2 = values["chaplygin_1"], values["chaplygin_2"]
        scale = abs(float(c1[0])) + abs(float(c2[0]))
        out["chaplygin_1"] = trace("chaplygin_1", c1, scale, eps)
        out["chaplygin_2"] = trace("chaplygin_2", c2, scale, eps)
    return out


class OnDemand:
    """The invariants of a run (and the normal force, and apart the required friction), evaluated on first request and kept.

    Holds the run's states on its whole output grid, t = 0 included, so the drifts cover every
    output of the run whatever part of it is returned; ``drop_start`` removes t = 0 from the
    returned values (``solve(t_eval=...)`` without 0) while the drifts stay taken against I(0).
    ``normal`` is N/(Mg) where the caller already has it (the failure guard computed it).
    Thread-safe: the first request evaluates, later ones read.
    """

    def __init__(self, compiled: CompiledModel, y: np.ndarray, params: dict, drop_start: bool, normal=None):
        self._compiled, self._y, self._params, self._drop = compiled, y, params, drop_start
        self._normal = normal
        self._traces = None
        self._friction = None  # (values,) once evaluated: the values may be None
        self._lock = threading.Lock()

    def __getstate__(self):  # a Trajectory stays picklable (process pools): the lock is not
        state = dict(self.__dict__)
        del state["_lock"]
        return state

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._lock = threading.Lock()

    def _start(self, values):
        return values if values is None or not self._drop else values[1:]

    @property
    def normal_force(self):
        if self._normal is None and self._compiled.has_normal_force and self._traces is None:
            self._evaluate()
        return self._start(self._normal)

    @property
    def friction_required(self):
        """mu_req = |F_h| / N on the grid (NaN where N <= 0), or None without rolling contact."""
        if self._friction is None:
            with self._lock:
                if self._friction is None:
                    self._friction = (friction_required(self._compiled, self._y, self._params),)
        return self._start(self._friction[0])

    @property
    def traces(self) -> dict:
        if self._traces is None:
            self._evaluate()
        return self._traces

    def _evaluate(self) -> None:
        with self._lock:
            if self._traces is not None:
                return
            values, normal = evaluate(self._compiled, self._y, self._params)
            found = traces(self._compiled, values, self._y, self._params)
            if self._drop:
                found = {n: replace(tr, values=tr.values[1:], initial_value=tr.values[0]) for n, tr in found.items()}
            if self._normal is None:
                self._normal = normal
            self._traces = found
