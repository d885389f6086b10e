"""Benchmark: the cost of a `trajectory` run against a bare heyoka integrator and scipy.

Prints ratios measured in one run (the machines are shared and noisy: compare ratios,
not seconds).  Usage: ``python benchmarks/bench_trajectory.py [MODEL] [T_END]``.

* suite overhead: ``verify.solve`` (segments keeping phi, psi, x, y small, grid output,
  invariants along the run) against ``taylor_adaptive.propagate_until`` on the same
  compiled equations, with and without the same terminal events (domain ends, loss of
  contact), all warm (derivation and JIT cached; constructing an integrator from the
  cache is part of every run);
* scipy's DOP853 at its tightest working tolerance (rtol = atol = 1e-13, below that it
  warns and stalls), with the right-hand side compiled by heyoka's cfunc so that only
  the integrator differs; final-state error of each against a quad run.
"""
from __future__ import annotations

import sys
import time

import heyoka as hy
import numpy as np

from models import get_model
from verify import solve
from verify.engine.compile import compile_model
from verify.engine.single import resolve_parameters, resolve_state
from verify.precision import parse_precision
from verify.standard import STANDARD_STATES


def best_of(f, repeat=5):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main(name="disk", t_end="10"):
    from scipy.integrate import solve_ivp

    p = parse_precision("double")
    model = get_model(name)
    compiled = compile_model(model, p)
    pars = resolve_parameters(model, {}, p)
    y0 = resolve_state(model, STANDARD_STATES[name], p)
    T = float(t_end)
    parr = compiled.system_pars(p.array(pars.values()))

    ref = solve(name, t_end, STANDARD_STATES[name], precision="quad", n_eval=2)
    ref_final = np.array([float(v) for v in ref.y[:, -1]])

    solve(name, t_end, STANDARD_STATES[name], n_eval=2)  # warm
    t_suite, sol = best_of(lambda: solve(name, t_end, STANDARD_STATES[name], n_eval=2))

    def bare():
        ta = hy.taylor_adaptive(list(compiled.system), y0, pars=parr)
        ta.propagate_until(T)
        return ta

    bare()
    t_bare, ta = best_of(bare)

    def bare_events():
        ta = hy.taylor_adaptive(list(compiled.system), y0, pars=parr, t_events=compiled.t_events())
        ta.propagate_until(T)
        return ta

    bare_events()
    t_events, _ = best_of(bare_events)

    rhs = hy.cfunc([r for _, r in compiled.system], list(compiled.variables))
    out = np.empty(8)

    def f(t, y):
        rhs(y, pars=parr, outputs=out)
        return out.copy()

    def dop():
        return solve_ivp(f, (0, T), y0, method="DOP853", rtol=1e-13, atol=1e-13)

    t_dop, d = best_of(dop, repeat=1)

    err = lambda y: np.max(np.abs(np.asarray(y, float) - ref_final))
    print(f"model {name}, t_end {t_end} s, standard state {STANDARD_STATES[name]}")
    print(f"  heyoka bare       {t_bare * 1e3:9.2f} ms  steps {ta.step_counter if hasattr(ta, 'step_counter') else '-'}"
          f"  final error {err(ta.state):.2e}")
    print(f"  heyoka + events   {t_events * 1e3:9.2f} ms  (the same domain and contact events as solve)")
    print(f"  verify.solve      {t_suite * 1e3:9.2f} ms  steps {sol.steps}  final error {err(sol.y[:, -1]):.2e}")
    print(f"  scipy DOP853      {t_dop * 1e3:9.2f} ms  rhs calls {d.nfev}  final error {err(d.y[:, -1]):.2e}")
    print(f"ratios: solve / (bare + events) = {t_suite / t_events:.2f};  events / bare = {t_events / t_bare:.2f};"
          f"  solve / bare = {t_suite / t_bare:.2f};  DOP853 / solve = {t_dop / t_suite:.0f};"
          f"  DOP853 / bare = {t_dop / t_bare:.0f}")


if __name__ == "__main__":
    main(*sys.argv[1:])
