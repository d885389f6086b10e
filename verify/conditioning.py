"""The conditioning of the flow: the state-transition matrix from the variational equations.

The error of a run at precision eps is, to first order, a sum of local errors carried
forward by the flow, so its size is about eps * sqrt(steps) * |Phi(t, 0)| * |y| where
Phi = d y(t) / d y(0) (HEYOKA.md: |Phi| ~ 1e3 by t = 0.5, ~1e4 by t = 10 for typical
disk motions).  Computed in double, compact mode (order-1 variational equations of the
eight-dimensional system).
"""
from __future__ import annotations

import re

import heyoka as hy
import numpy as np

from models import get_model

from .compile import compile_model
from .integrate import max_step, resolve_parameters, resolve_state
from .precision import parse_precision


def transition_norms(model, t_eval, state=None, params=None, equations="derived") -> np.ndarray:
    """max-row-sum norm of Phi(t, 0) at each time of ``t_eval`` (double precision)."""
    prec = parse_precision("double")
    if isinstance(model, str):
        model = get_model(model, equations)
    pars = resolve_parameters(model, params, prec)
    y0 = resolve_state(model, state, prec)
    compiled = compile_model(model, prec)
    vsys = hy.var_ode_sys(list(compiled.system), hy.var_args.vars, order=1)
    ta = hy.taylor_adaptive(vsys, y0, pars=compiled.system_pars(prec.array(pars.values())), compact_mode=True)
    grid = np.concatenate([[0.0], np.asarray(t_eval, dtype=float)]) if float(t_eval[0]) > 0 else np.asarray(t_eval, float)
    res = ta.propagate_grid(grid, max_delta_t=float(max_step(y0, pars, prec)))
    sl = ta.get_vslice(order=1)
    n = len(y0)
    norms = [np.abs(row[sl].reshape(n, n)).sum(axis=1).max() for row in res[-1]]
    return np.array(norms[-len(t_eval):])


def sensitivities(model, t_eval, state=None, params=None, equations="derived") -> tuple:
    """How errors in the start and in the parameters reach each component at each time.

    Returns ``(R, P)``, arrays of shape ``(len(t_eval), 8)`` in STATE_NAMES order:

    * ``R[t, i] = sum_j |d y_i(t) / d y_j(0)|`` -- row sums of the state-transition matrix:
      an error of size e in every component at time 0 (or, to first order, at any earlier
      time of a run whose |Phi| grows monotonically) becomes at most ``R e`` in y_i;
    * ``P[t, i] = sum_k |d y_i(t) / d p_k| |p_k|`` -- a relative error e in every parameter
      (a rounded 1/4, 0.4344, ...) becomes at most ``P e`` in y_i.

    From heyoka's order-1 variational equations with respect to the state and the runtime
    parameters (double, compact mode); ``t_eval`` must be increasing and positive.
    """
    prec = parse_precision("double")
    if isinstance(model, str):
        model = get_model(model, equations)
    pars = resolve_parameters(model, params, prec)
    y0 = resolve_state(model, state, prec)
    compiled = compile_model(model, prec)
    vsys = hy.var_ode_sys(list(compiled.system), hy.var_args.vars | hy.var_args.params, order=1)
    par_values = compiled.system_pars(prec.array(pars.values()))
    ta = hy.taylor_adaptive(vsys, y0, pars=par_values, compact_mode=True)
    grid = np.concatenate([[0.0], np.asarray(t_eval, dtype=float)])
    res = ta.propagate_grid(grid, max_delta_t=float(max_step(y0, pars, prec)))
    if res[0] != hy.taylor_outcome.time_limit:
        raise RuntimeError(f"the variational run of {model.name} stopped early: {res[0]}")
    n = len(y0)
    names = [str(v) for v in vsys.vargs]
    is_par = [re.fullmatch(r"p(\d+)", v) for v in names]  # heyoka names par[k] "p<k>" in vargs
    state_cols = [j for j, m in enumerate(is_par) if m is None]
    par_cols = [(j, int(m.group(1))) for j, m in enumerate(is_par) if m is not None]
    sl = ta.get_vslice(order=1)
    R, P = [], []
    for row in res[-1][1:]:
        m = row[sl].reshape(n, len(names))
        R.append(np.abs(m[:, state_cols]).sum(axis=1))
        P.append(sum((np.abs(m[:, j]) * abs(float(par_values[k])) for j, k in par_cols), np.zeros(n)))
    return np.array(R), np.array(P)
