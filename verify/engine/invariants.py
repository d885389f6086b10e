"""Invariants along a run, evaluated in the run's precision from the model's expressions.

* closed-form invariants (energy, Jellett, Routh, cyclic momenta): one compiled cfunc;
* Chaplygin's two integrals of a rolling body of revolution: (omega2, omega3) carried back
  to ``theta_ref`` along the linear ODE d(w)/d(theta) = A(theta) w, either in closed form
  (the disk: Legendre functions via mpmath, at the run's bits) or through the fundamental
  matrix of that ODE, integrated by heyoka in theta at the run's precision.
"""
from __future__ import annotations

import math
import threading
from dataclasses import dataclass, replace
from functools import cmp_to_key, lru_cache

import heyoka as hy
import mpmath
import numpy as np
import sympy as sp

from models.base import Model
from models.symbols import STATE, theta

from .compile import CompiledModel, to_heyoka
from ..precision import Precision


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
        intermediates).  It can be far above |I(0)|: on the README's run the disk
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
        the disk's energy is 0.006 of its term scale on the README's run and 1e-5 to 1e-13
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
    was as good as its precision allows (0.16 eps on the README's quad run, where the
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
    """The drifts of ``values`` (see :class:`InvariantTrace`); differences in the run's precision."""
    diffs = [abs(float(v - values[0])) for v in values]
    worst = max(diffs) if diffs else 0.0
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
    return max(f(*[float(v) for v in col], *pars) for col in y.T)


@lru_cache(maxsize=None)
def _scale_function(model: Model, inv_scale: sp.Expr):
    return sp.lambdify(list(STATE) + [p.symbol for p in model.parameters], inv_scale, modules="math")


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
    """The invariants of a run (and the normal force), evaluated on first request and kept.

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


# --- Chaplygin's integrals --------------------------------------------------------------

def chaplygin_integrals(model: Model, precision: Precision, params: dict, thetas, w2, w3, method: str = "auto"):
    """(omega2, omega3) carried back to theta_ref: Chaplygin's two first integrals.

    ``method`` is ``"closed-form"`` (needs ``model.chaplygin.closed_form``),
    ``"fundamental-matrix"`` or ``"auto"`` (closed form where the model has one).
    """
    ch = model.chaplygin
    if method == "auto":
        method = "closed-form" if ch.closed_form is not None else "fundamental-matrix"
    if method == "closed-form":
        return _closed_form(model, precision, params, thetas, w2, w3)
    if method != "fundamental-matrix":
        raise ValueError(f"method={method!r}; allowed: auto, closed-form, fundamental-matrix")
    phis = fundamental_matrices(model, precision, params, thetas)
    p11, p12, p21, p22 = (np.array([m[i] for m in phis]) for i in range(4))
    det = p11 * p22 - p12 * p21
    return (p22 * w2 - p12 * w3) / det, (p11 * w3 - p21 * w2) / det


def _closed_form(model, precision, params, thetas, w2, w3):
    c1, c2 = [], []
    with mpmath.workprec(precision.bits + 10):
        pm = {k: precision.to_mpf(v) for k, v in params.items()}
        for th, a, b in zip(thetas, w2, w3):
            x1, x2 = model.chaplygin.closed_form(precision.to_mpf(th), precision.to_mpf(a), precision.to_mpf(b), pm)
            c1.append(precision.number(x1))
            c2.append(precision.number(x2))
    return precision.array(c1), precision.array(c2)


@lru_cache(maxsize=None)
def _transport_system(model: Model):
    """The ODE dPhi/dtheta = A(theta) Phi with theta as heyoka's time variable."""
    variables = hy.make_vars("p11", "p12", "p21", "p22")
    mapping = {theta: hy.time}
    mapping.update({p.symbol: hy.par[i] for i, p in enumerate(model.parameters)})
    A = [[to_heyoka(model.chaplygin.matrix[i, j], mapping) for j in range(2)] for i in range(2)]
    P = [[variables[0], variables[1]], [variables[2], variables[3]]]
    rhs = [A[i][0] * P[0][j] + A[i][1] * P[1][j] for i in range(2) for j in range(2)]
    return list(zip(variables, rhs))


def fundamental_matrices(model: Model, precision: Precision, params: dict, thetas) -> list:
    """Phi(theta) with Phi(theta_ref) = identity, for each theta, as (p11, p12, p21, p22)."""
    ref = precision.number(model.chaplygin.theta_ref)
    one, zero = precision.number(1), precision.number(0)
    used = [i for i, p in enumerate(model.parameters) if model.chaplygin.matrix.has(p.symbol)]
    pars = precision.array(list(params.values())[: max(used) + 1 if used else 0])
    order = sorted(range(len(thetas)), key=cmp_to_key(lambda i, j: int(bool(thetas[i] > thetas[j])) - int(bool(thetas[i] < thetas[j]))))
    found = [None] * len(thetas)
    for side in (1, -1):
        idx = [i for i in order if (thetas[i] > ref if side > 0 else thetas[i] < ref)]
        if side < 0:
            idx = idx[::-1]
        if not idx:
            continue
        grid, owners = [], []  # distinct theta values and the indices that share each
        for i in idx:
            if grid and not (thetas[i] != grid[-1]):
                owners[-1].append(i)
            else:
                grid.append(thetas[i])
                owners.append([i])
        ta = hy.taylor_adaptive(_transport_system(model), precision.array([one, zero, zero, one]), pars=pars,
                                time=ref, tol=zero, **precision.integrator_kwargs())
        res = ta.propagate_grid(precision.array([ref] + grid))
        rows = res[-1]
        if len(rows) != len(grid) + 1:
            raise RuntimeError(f"the Chaplygin transport stopped early ({res[0]})")
        for row, group in zip(rows[1:], owners):
            for i in group:
                found[i] = tuple(row)
    for i, f in enumerate(found):
        if f is None:  # theta == theta_ref
            found[i] = (one, zero, zero, one)
    return found
