"""The conditioning of the flow: the state-transition matrix from the variational equations.

The error of a run at precision eps is, to first order, a sum of local errors carried
forward by the flow, so its size is about eps * sqrt(steps) * |Phi(t, 0)| * |y| where
Phi = d y(t) / d y(0) (HEYOKA.md: |Phi| ~ 1e3 by t = 0.5, ~1e4 by t = 10 for typical
disk motions).  Computed in double, compact mode (order-1 variational equations of the
eight-dimensional system).
"""
from __future__ import annotations

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
