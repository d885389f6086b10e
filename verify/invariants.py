"""Invariants along a run, evaluated in the run's precision from the model's expressions.

* closed-form invariants (energy, Jellett, Routh, cyclic momenta): one compiled cfunc;
* Chaplygin's two integrals of a rolling body of revolution: (omega2, omega3) carried back
  to ``theta_ref`` along the linear ODE d(w)/d(theta) = A(theta) w, either in closed form
  (the disk: Legendre functions via mpmath, at the run's bits) or through the fundamental
  matrix of that ODE, integrated by heyoka in theta at the run's precision.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cmp_to_key, lru_cache

import heyoka as hy
import mpmath
import numpy as np
import sympy as sp

from models.base import Model
from models.symbols import STATE, theta

from .compile import CompiledModel, to_heyoka
from .precision import Precision


@dataclass(frozen=True)
class InvariantTrace:
    """One conserved quantity along a run.

    ``max_rel_drift`` is max_t |I(t) - I(0)| / scale, with scale the largest value along
    the run of the sum of the absolute values of the terms of I (so it stays meaningful
    when I is near zero, and measures drift against the magnitudes actually rounded); for
    Chaplygin's integrals the scale is |c1(0)| + |c2(0)|.  If the scale is zero the drift
    is absolute and ``scale`` is reported as 0.
    """

    name: str
    values: np.ndarray
    scale: float
    max_rel_drift: float

    @property
    def initial(self):
        return self.values[0]

    @property
    def final(self):
        return self.values[-1]


def trace(name: str, values: np.ndarray, scale: float) -> InvariantTrace:
    diffs = [abs(float(v - values[0])) for v in values]
    worst = max(diffs) if diffs else 0.0
    return InvariantTrace(name, values, scale, worst / scale if scale > 0 else worst)


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
    pars = np.ascontiguousarray(np.repeat(compiled.function_pars(precision.array(params.values()))[:, None], n, axis=1))
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
    model = compiled.model
    out = {}
    for inv in model.invariants:
        out[inv.name] = trace(inv.name, values[inv.name], scale_over(model, inv.scale, y, params))
    if model.chaplygin is not None:
        c1, c2 = values["chaplygin_1"], values["chaplygin_2"]
        scale = abs(float(c1[0])) + abs(float(c2[0]))
        out["chaplygin_1"] = trace("chaplygin_1", c1, scale)
        out["chaplygin_2"] = trace("chaplygin_2", c2, scale)
    return out


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
