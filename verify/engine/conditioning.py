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
from .problem import max_step
from .single import resolve_parameters, resolve_state
from ..precision import parse_precision


def _variational(model, t_eval, state, params, equations, with_params: bool):
    """Phi (and d y/d p) on ``t_eval`` from heyoka's order-1 variational equations (double, compact mode).

    Returns ``(blocks, names, par_values)``: per time of ``t_eval`` the n x len(names) matrix of
    derivatives of the state with respect to ``names`` (the state variables, then the runtime
    parameters "p<k>" when ``with_params``), and the parameter values in double.
    """
    prec = parse_precision("double")
    if isinstance(model, str):
        model = get_model(model, equations)
    pars = resolve_parameters(model, params, prec)
    y0 = resolve_state(model, state, prec)
    compiled = compile_model(model, prec)
    wrt = hy.var_args.vars | hy.var_args.params if with_params else hy.var_args.vars
    vsys = hy.var_ode_sys(list(compiled.system), wrt, order=1)
    par_values = compiled.parameter_vector(pars)
    ta = hy.taylor_adaptive(vsys, y0, pars=par_values, compact_mode=True)
    times = np.asarray(t_eval, dtype=float)
    grid = np.concatenate([[0.0], times]) if times[0] > 0 else times
    outcome, _, _, _, _, rows = ta.propagate_grid(grid, max_delta_t=float(max_step(y0, pars, prec)))
    if outcome != hy.taylor_outcome.time_limit:
        raise RuntimeError(f"the variational run of {model.name} stopped early: {outcome}")
    names = [str(v) for v in vsys.vargs]
    sl, n = ta.get_vslice(order=1), len(y0)
    blocks = [row[sl].reshape(n, len(names)) for row in rows[-len(times):]]
    return blocks, names, par_values


def transition_matrix(model, state, params, t_end, precision="double"):
    """Phi(t_end, 0) = d y(t_end) / d y(0), an n x n array at ``precision``, from one run of the
    order-1 variational equations (compact mode at every precision: they are 72 equations).

    ``state`` and ``params`` as for :func:`verify.engine.single.solve` (``model`` a name or a
    Model); ``t_end`` a number at ``precision``.  Steps are capped by
    :func:`verify.engine.problem.max_step`; a run that does not reach ``t_end`` raises
    ``RuntimeError``.
    """
    prec = parse_precision(precision)
    if isinstance(model, str):
        model = get_model(model)
    pars = resolve_parameters(model, params, prec)
    y0 = resolve_state(model, state, prec)
    compiled = compile_model(model, prec)
    vsys = hy.var_ode_sys(list(compiled.system), hy.var_args.vars, order=1)
    kwargs = prec.integrator_kwargs()
    kwargs["compact_mode"] = True
    ta = hy.taylor_adaptive(vsys, y0, pars=compiled.parameter_vector(pars), **kwargs)
    outcome = ta.propagate_until(t_end, max_delta_t=max_step(y0, pars, prec))[0]
    if outcome != hy.taylor_outcome.time_limit:
        raise RuntimeError(f"the variational run of {model.name} stopped with {outcome}")
    n = len(y0)
    return ta.state[ta.get_vslice(order=1)].reshape(n, n)


def transition_norms(model, t_eval, state=None, params=None, equations="derived") -> np.ndarray:
    """max-row-sum norm of Phi(t, 0) at each time of ``t_eval`` (double precision)."""
    blocks, _, _ = _variational(model, t_eval, state, params, equations, with_params=False)
    return np.array([np.abs(m).sum(axis=1).max() for m in blocks])


def sensitivities(model, t_eval, state=None, params=None, equations="derived") -> tuple:
    """How errors in the start and in the parameters reach each component at each time.

    Returns ``(R, P)``, arrays of shape ``(len(t_eval), 8)`` in STATE_NAMES order:

    * ``R[t, i] = sum_j |d y_i(t) / d y_j(0)|`` -- row sums of the state-transition matrix:
      an error of size e in every component at time 0 (or, to first order, at any earlier
      time of a run whose |Phi| grows monotonically) becomes at most ``R e`` in y_i;
    * ``P[t, i] = sum_k |d y_i(t) / d p_k| |p_k|`` -- a relative error e in every parameter
      (a rounded 1/4, 0.4344, ...) becomes at most ``P e`` in y_i.

    From heyoka's order-1 variational equations with respect to the state and the runtime
    parameters (double, compact mode).
    """
    blocks, names, par_values = _variational(model, t_eval, state, params, equations, with_params=True)
    is_par = [re.fullmatch(r"p(\d+)", v) for v in names]  # heyoka names par[k] "p<k>" in vargs
    state_cols = [j for j, m in enumerate(is_par) if m is None]
    par_cols = [(j, int(m.group(1))) for j, m in enumerate(is_par) if m is not None]
    R = [np.abs(m[:, state_cols]).sum(axis=1) for m in blocks]
    P = [sum((np.abs(m[:, j]) * abs(float(par_values[k])) for j, k in par_cols), np.zeros(m.shape[0])) for m in blocks]
    return np.array(R), np.array(P)
