"""Benchmarks: accuracy for the time spent, long-run energy error, sweep throughput, JIT cost.

``python -m verify bench`` (and the last stage of ``python -m verify report``) measures, in
one run, and writes ``reports/BENCHMARKS.md``, ``reports/benchmarks.json`` and two figures.
Everything is reported as measured on this machine and as *ratios measured in the same run*
(the machines are shared and noisy; compare ratios, not seconds).  Nothing here passes or
fails: the targets of the issue are printed beside the measured figures.

* **Work against precision.**  The final state of a reference case (certified digits, see
  :mod:`verify.reference`) is computed by heyoka at double (several tolerances), long, quad
  and MPFR, by scipy's ``solve_ivp`` (DOP853, Radau, LSODA; right-hand side and Jacobian
  compiled by heyoka's ``cfunc``, so only the integrator differs) down to their tightest
  working tolerances, and by mpmath's ``odefun`` (Taylor series in Python) on a short run.
  Error = max_i |y_i - ref_i| / max_i |ref_i| of the 8-component final state.  heyoka runs
  bare (``propagate_until`` on the compiled system, no events) from an integrator built once
  and reset before each timed run -- building one costs ~20 ms even from the in-memory JIT
  cache (the Taylor decomposition is redone), more than a 1 s run of the disk, and is
  measured under "compile cost"; this measures integrators, not the suite's bookkeeping
  (``benchmarks/bench_trajectory.py`` measures that).
* **Long-run energy error.**  8 starts near the disk's standard state, about 10^6 Taylor steps
  each, by :func:`verify.solve` (phi, psi, x, y kept out of the error control) and by a plain
  heyoka integrator; the RMS over the starts of the relative energy error at log-spaced times
  is fitted to t^a.
* **Sweep throughput.**  N trajectories of 10 s of the disk (8-dimensional, double): a plain
  loop reusing one integrator, batch mode (SIMD lanes), heyoka's ensemble over threads (scalar
  and batch), and a scipy DOP853 loop on a subset.
* **Compile cost.**  Fresh processes with an empty heyoka disk cache, then again with the cache
  it left, for the disk at double (default and compact mode), quad and MPFR.
"""
from __future__ import annotations

import io
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import heyoka as hy
import mpmath
import numpy as np
import sympy as sp

from models import get_model
from models.symbols import STATE, STATE_NAMES

from .engine.compile import compile_model
from .engine.single import max_step, resolve_parameters, resolve_state, solve
from .precision import parse_precision
from .provenance import write_atomic

#: (quick, full) sizes; quick is for the tests and for trying the command.
SIZES = {
    "sweep_n": (64, 1024), "scipy_sweep_n": (2, 8), "energy_starts": (2, 8), "energy_t_end": (40.0, 3400.0),
    "odefun_dps": ((15,), (15, 25)), "repeats": (1, 3),
}
TARGETS = {"dop853_speedup": 200.0, "energy_exponent": 0.55, "sweep_per_second": 3000.0}
WORK_CASE = "disk-standard-1"  # 1 s: short enough for Radau and the Python integrators
LONG_CASE = "ring-standard-10"  # 10 s: heyoka against DOP853 on a longer run
ODEFUN_GRID_INDEX = 2  # odefun stops at grid[2] = 0.0625 s of WORK_CASE (dps 25 costs ~50 s there)


@dataclass(frozen=True)
class Attempt:
    """One integrator at one setting: wall time and final-state error against the reference."""

    method: str
    setting: str
    seconds: float
    error: float
    work: int  # steps (heyoka) or right-hand-side evaluations (scipy, mpmath)
    t_end: str

    def to_record(self) -> dict:
        return {"method": self.method, "setting": self.setting, "seconds": float(f"{self.seconds:.4g}"),
                "error": float(f"{self.error:.3e}"), "work": self.work, "t_end": self.t_end}


def _size(name: str, quick: bool):
    return SIZES[name][0 if quick else 1]


def _timed(f, repeats: int):
    """(best wall time of ``repeats`` calls, the last result)."""
    best, out = math.inf, None
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


# --- work against precision ------------------------------------------------------------------

class ReferenceProblem:
    """A reference case as an initial-value problem, with its certified values on the grid."""

    def __init__(self, name: str):
        from .reference import load_set

        self.record = load_set(names=[name])[0]
        self.model = get_model(self.record["model"]["name"])
        self.params = {k: sp.Rational(v["exact"]) for k, v in self.record["model"]["parameters"].items()}

    def reference(self, index: int = -1) -> tuple:
        """(values as mpf, the reference floor: max abs_error / max |value|) at a grid index."""
        with mpmath.workprec(320):
            vals = [mpmath.mpf(self.record["state"][n]["value"][index]) for n in STATE_NAMES]
            errs = [mpmath.mpf(self.record["state"][n]["abs_error"][index]) for n in STATE_NAMES]
            return vals, float(max(errs) / max(abs(v) for v in vals))

    def error(self, y, index: int = -1) -> float:
        """max_i |y_i - ref_i| / max_i |ref_i| (y in any precision: compared exactly)."""
        vals, _ = self.reference(index)
        with mpmath.workprec(320):
            num = max(abs(_to_mpf(a) - b) for a, b in zip(y, vals))
            return float(num / max(abs(v) for v in vals))

    def t(self, index: int = -1) -> str:
        return self.record["grid"][index]

    def start(self, precision):
        prec = parse_precision(precision)
        pars = resolve_parameters(self.model, self.params, prec)
        y0 = resolve_state(self.model, self.record["initial_state"], prec)
        return prec, pars, y0


def _to_mpf(x):
    """The exact value of a double, long double, real128, real or mpf (inside a wide workprec)."""
    if isinstance(x, mpmath.mpf):
        return x
    if isinstance(x, (float, np.floating)):
        p, q = x.as_integer_ratio()
        return mpmath.mpf(p) / q
    return mpmath.mpf(str(x))


def heyoka_attempt(problem: ReferenceProblem, precision: str, tol=None, repeats: int = 1, index: int = -1) -> Attempt:
    """Bare heyoka (compiled system, no events) from the case's start to grid[index]."""
    prec, pars, y0 = problem.start(precision)
    compiled = compile_model(problem.model, prec)
    kw = prec.integrator_kwargs()
    if tol is not None:
        kw["tol"] = prec.number(tol)
    parr = compiled.system_pars(prec.array(pars.values()))
    t_end = prec.number(problem.t(index))
    h_max = max_step(y0, pars, prec)
    ta = hy.taylor_adaptive(list(compiled.system), y0, pars=parr, **kw)  # construction outside the timing

    def run():
        ta.time = prec.zero()
        ta.state[:] = y0
        out = ta.propagate_until(t_end, max_delta_t=h_max)
        if out[0] != hy.taylor_outcome.time_limit:
            raise RuntimeError(f"heyoka {precision} stopped with {out[0]}")
        return ta, int(out[3])

    seconds, (ta, steps) = _timed(run, repeats)
    label = "eps" if tol is None else f"{tol:g}"
    return Attempt(f"heyoka {prec.name}", f"tol {label}", seconds, problem.error(list(ta.state), index),
                   steps, problem.t(index))


def _compiled_rhs(problem: ReferenceProblem):
    """f(t, y) and its Jacobian as numpy callables built from heyoka cfuncs (double)."""
    prec, pars, y0 = problem.start("double")
    compiled = compile_model(problem.model, prec)
    exprs = [r for _, r in compiled.system]
    variables = list(compiled.variables)
    parr = np.ascontiguousarray(compiled.system_pars(prec.array(pars.values())))
    rhs = hy.cfunc(exprs, variables)
    jac = hy.cfunc([hy.diff(e, v) for e in exprs for v in variables], variables)
    n = len(variables)
    out, jout = np.empty(n), np.empty(n * n)
    p_rhs, p_jac = parr[: rhs.nparams], parr[: jac.nparams]  # each cfunc takes exactly its own count

    def f(t, y):
        rhs(np.ascontiguousarray(y), pars=p_rhs, outputs=out)
        return out.copy()

    def j(t, y):
        jac(np.ascontiguousarray(y), pars=p_jac, outputs=jout)
        return jout.reshape(n, n).copy()

    return f, j, np.array(y0, dtype=float)


def scipy_attempts(problem: ReferenceProblem, method: str, tolerances, use_jac: bool, repeats: int = 1) -> list:
    from scipy.integrate import solve_ivp

    f, jac, y0 = _compiled_rhs(problem)
    T = float(problem.t())
    out = []
    for tol in tolerances:
        kw = {"jac": jac} if use_jac else {}

        def run():
            sol = solve_ivp(f, (0.0, T), y0, method=method, rtol=tol, atol=tol, **kw)
            if sol.status != 0:
                raise RuntimeError(f"{method} at {tol:g}: {sol.message}")
            return sol

        try:
            seconds, sol = _timed(run, repeats)
        except RuntimeError as err:
            out.append(Attempt(f"scipy {method}", f"rtol=atol {tol:g}", math.nan, math.nan, 0, problem.t()))
            print(f"  {err}", file=sys.stderr)
            continue
        out.append(Attempt(f"scipy {method}", f"rtol=atol {tol:g}", seconds, problem.error(sol.y[:, -1]),
                           int(sol.nfev), problem.t()))
    return out


def odefun_attempts(problem: ReferenceProblem, dps_values, index: int = ODEFUN_GRID_INDEX) -> list:
    """mpmath.odefun (Taylor series in Python) from the start to grid[index], at each dps."""
    model = problem.model
    syms = list(STATE) + [p.symbol for p in model.parameters]
    rhs_exprs = [r for _, r in model.rhs()]
    f_mp = sp.lambdify(syms, rhs_exprs, "mpmath")
    out = []
    for dps in dps_values:
        with mpmath.workdps(dps):
            y0 = [mpmath.mpf(problem.record["initial_state"][n]) for n in STATE_NAMES]
            pv = [mpmath.mpf(sp.N(problem.params[p.name], dps + 10)) for p in model.parameters]
            calls = [0]

            def F(t, y):
                calls[0] += 1
                return f_mp(*y, *pv)

            t_end = mpmath.mpf(problem.t(index))
            t0 = time.perf_counter()
            sol = mpmath.odefun(F, 0, y0)
            y = sol(t_end)
            seconds = time.perf_counter() - t0
            err = problem.error(y, index)
        out.append(Attempt("mpmath odefun", f"dps {dps}", seconds, err, calls[0], problem.t(index)))
    return out


def work_precision(quick: bool, progress) -> dict:
    repeats = _size("repeats", quick)
    p = ReferenceProblem(WORK_CASE)
    attempts = []
    progress("  work-precision: heyoka")
    for tol in (1e-6, 1e-9, 1e-12, None):
        attempts.append(heyoka_attempt(p, "double", tol, repeats))
    for prec in ("long", "quad") + (() if quick else ("mp:96", "mp:128")):
        attempts.append(heyoka_attempt(p, prec, None, 1 if prec != "long" else repeats))
    progress("  work-precision: scipy")
    attempts += scipy_attempts(p, "DOP853", (1e-6, 1e-8, 1e-10, 1e-12, 1e-13), False, repeats)
    attempts += scipy_attempts(p, "LSODA", (1e-6, 1e-8, 1e-10, 1e-12) if not quick else (1e-8,), True, 1)
    attempts += scipy_attempts(p, "Radau", (1e-6, 1e-8, 1e-10) if not quick else (1e-6,), True, 1)
    progress("  work-precision: mpmath odefun (short run) against heyoka quad on the same run")
    short = odefun_attempts(p, _size("odefun_dps", quick))
    short.append(heyoka_attempt(p, "quad", None, 1, index=ODEFUN_GRID_INDEX))
    short.append(heyoka_attempt(p, "double", None, repeats, index=ODEFUN_GRID_INDEX))
    longer = None
    if not quick:
        progress("  work-precision: 10 s ring, heyoka double against DOP853")
        q = ReferenceProblem(LONG_CASE)
        longer = [heyoka_attempt(q, "double", tol, repeats) for tol in (1e-9, 1e-12, None)]
        longer += scipy_attempts(q, "DOP853", (1e-10, 1e-12, 1e-13), False, repeats)
        longer_floor = q.reference()[1]
    return {"case": WORK_CASE, "t_end": p.t(), "reference_floor": p.reference()[1], "attempts": attempts,
            "short": short, "short_t_end": p.t(ODEFUN_GRID_INDEX), "short_floor": p.reference(ODEFUN_GRID_INDEX)[1],
            "long_case": LONG_CASE if longer else None, "long": longer or [],
            "long_floor": longer_floor if longer else None}


def same_accuracy_speedup(attempts: list, fast: str = "heyoka double", slow: str = "scipy DOP853") -> dict:
    """t_slow / t_fast at equal accuracy: the slow method's most accurate attempt against the
    fastest attempt of ``fast`` that is at least as accurate."""
    slow_runs = [a for a in attempts if a.method == slow and math.isfinite(a.error)]
    fast_runs = [a for a in attempts if a.method == fast and math.isfinite(a.error)]
    if not slow_runs or not fast_runs:
        return {}
    best_slow = min(slow_runs, key=lambda a: a.error)
    good = [a for a in fast_runs if a.error <= best_slow.error] or [min(fast_runs, key=lambda a: a.error)]
    match = min(good, key=lambda a: a.seconds)
    tightest = min(fast_runs, key=lambda a: a.error)
    return {"slow": best_slow.to_record(), "fast": match.to_record(), "speedup": best_slow.seconds / match.seconds,
            "tightest_fast": tightest.to_record(), "speedup_tightest": best_slow.seconds / tightest.seconds,
            "accuracy_ratio_tightest": best_slow.error / tightest.error if tightest.error > 0 else math.inf}


# --- long-run energy error ---------------------------------------------------------------------

def energy_growth(quick: bool, progress) -> dict:
    """RMS relative energy error against time over several starts: the suite (default and with
    heyoka's high-accuracy mode, compensated summation) and a plain integrator with the angles unbounded."""
    from .standard import STANDARD_STATES

    n_starts, T = _size("energy_starts", quick), _size("energy_t_end", quick)
    times = np.geomspace(1.0, T, 40)
    grid = [f"{v:.6f}" for v in times]
    model = get_model("disk")
    prec = parse_precision("double")
    compiled = compile_model(model, prec)
    errors = {"suite": [], "suite_high_accuracy": [], "plain": []}
    steps = []
    for k in range(n_starts):
        state = dict(STANDARD_STATES["disk"], theta=f"{1.2 + 0.01 * k:.2f}")
        progress(f"  energy: start {k + 1}/{n_starts}, {T:g} s")
        for label, ha in (("suite", False), ("suite_high_accuracy", True)):
            sol = solve("disk", repr(T), state, t_eval=["0"] + grid, high_accuracy=ha)  # E(0) first
            e = np.array([float(v) for v in sol.invariants["energy"].values])
            errors[label].append(np.abs(e[1:] - e[0]) / abs(e[0]))
            steps.append(sol.steps)
        pars = resolve_parameters(model, {}, prec)
        y0 = resolve_state(model, state, prec)
        ta = hy.taylor_adaptive(list(compiled.system), y0, pars=compiled.system_pars(prec.array(pars.values())))
        res = ta.propagate_grid(np.concatenate([[0.0], times]), max_delta_t=float(max_step(y0, pars, prec)))
        ys = np.ascontiguousarray(np.array(res[-1]).T)
        vals = compiled.invariant_function(ys, pars=np.ascontiguousarray(np.repeat(
            compiled.function_pars(prec.array(pars.values()))[:, None], ys.shape[1], axis=1)))[0]
        errors["plain"].append(np.abs(vals[1:] - vals[0]) / abs(vals[0]))
    fit = times >= 10.0
    slope = lambda r: float(np.polyfit(np.log(times[fit]), np.log(np.maximum(r[fit], 1e-300)), 1)[0])  # noqa: E731
    out = {"times": times.tolist(), "steps_per_run": int(np.median(steps)), "starts": n_starts, "t_end": T,
           "fit_from": 10.0, "rms": {}, "exponent": {}, "exponent_per_start": {}}
    for label, errs in errors.items():
        rms = np.sqrt(np.mean(np.array(errs) ** 2, axis=0))
        out["rms"][label] = rms.tolist()
        out["exponent"][label] = slope(rms)
        out["exponent_per_start"][label] = [round(slope(np.maximum.accumulate(e)), 3) for e in errs]
    return out


# --- sweep throughput ----------------------------------------------------------------------------

def _sweep_states(n: int) -> np.ndarray:
    """n disk starts (theta in [1.0, 1.4], phidot in [-2, 2], psidot in [5, 15]), a fixed pseudo-random set."""
    rng = np.random.default_rng(20261123)
    y = np.zeros((8, n))
    y[0] = rng.uniform(1.0, 1.4, n)
    y[4] = rng.uniform(-2, 2, n)
    y[5] = rng.uniform(5, 15, n)
    return y


def sweep_throughput(quick: bool, progress) -> dict:
    """Trajectories per second of the disk, full (8-dimensional) and reduced (theta, thetadot, phidot,
    psidot: what a stability sweep needs), by loop, batch lanes, ensembles, and scipy's DOP853."""
    from .studies.maps import reduced_system

    n, T = _size("sweep_n", quick), 10.0
    model = get_model("disk")
    prec = parse_precision("double")
    compiled = compile_model(model, prec)
    full_pars = compiled.system_pars(prec.array(resolve_parameters(model, {}, prec).values()))
    ys = _sweep_states(n)
    _, reduced, _, n_model = reduced_system("disk")
    reduced_pars = np.concatenate([full_pars[:n_model], [1.0]])  # + the maps' 'alive' factor, 1
    out = {"trajectories": n, "t_end": T, "threads": os.cpu_count() or 1, "systems": {}}
    for label, system, pars, states in (("full 8-dim", list(compiled.system), full_pars, ys),
                                        ("reduced 4-dim", list(reduced), reduced_pars, ys[[0, 3, 4, 5]])):
        progress(f"  sweep: {n} trajectories of {T:g} s, {label}")
        out["systems"][label] = _throughput(system, np.ascontiguousarray(pars), np.ascontiguousarray(states), T,
                                            _size("scipy_sweep_n", quick))
    progress("  sweep: the reduced system at looser tolerances")
    out["tolerances"] = _throughput_by_tolerance(list(reduced), np.ascontiguousarray(reduced_pars),
                                                 np.ascontiguousarray(ys[[0, 3, 4, 5]]), T)
    return out


def _batch_integrator(system, pars, ys, bs: int, **kwargs):
    """A batch integrator of ``bs`` lanes for ``system``, every lane with the parameters ``pars``."""
    return hy.taylor_adaptive_batch(system, np.ascontiguousarray(ys[:, :bs]),
                                    pars=np.ascontiguousarray(np.repeat(pars[:, None], bs, axis=1)), **kwargs)


def _ensemble_of_batches(tb, ys, T: float) -> tuple:
    """(seconds, final states) of every whole batch of the columns of ``ys`` to time T, batches on threads."""
    bs = tb.batch_size
    m = ys.shape[1] // bs

    def gen(tc, b):
        tc.set_time(0.0)
        tc.state[:] = ys[:, b * bs:(b + 1) * bs]
        return tc

    seconds, res = _timed(lambda: hy.ensemble_propagate_until_batch(tb, T, m, gen), 1)
    return seconds, np.hstack([r[0].state for r in res])


def _throughput_by_tolerance(system, pars, ys, T: float, tolerances=(None, 1e-12, 1e-9, 1e-6)) -> list:
    """The best mode (batch lanes in an ensemble) at looser tolerances: what the issue's 3,000/s would
    cost in accuracy. Each row's error is the largest final-state difference to the run at eps."""
    bs = hy.recommended_simd_size()
    rows, at_eps = [], None
    for tol in tolerances:
        tb = _batch_integrator(system, pars, ys, bs, **({} if tol is None else {"tol": tol}))
        seconds, final = _ensemble_of_batches(tb, ys, T)
        at_eps = final if at_eps is None else at_eps
        rows.append({"tol": "eps" if tol is None else f"{tol:g}", "order": int(tb.order), "lanes": bs,
                     "per_second": float(f"{final.shape[1] / seconds:.4g}"),
                     "max_difference_to_eps": float(f"{np.max(np.abs(final - at_eps)):.2e}")})
    return rows


def _throughput(system, pars, ys, T: float, k_scipy: int) -> dict:
    n = ys.shape[1]
    results, agree, finals = {}, {}, {}
    ta = hy.taylor_adaptive(system, ys[:, 0], pars=pars)

    def loop():
        out = np.empty_like(ys)
        for i in range(n):
            ta.time = 0.0
            ta.state[:] = ys[:, i]
            ta.propagate_until(T)
            out[:, i] = ta.state
        return out

    results["loop"], ref = _timed(loop, 1)

    def gen_scalar(tc, i):
        tc.time = 0.0
        tc.state[:] = ys[:, i]
        return tc

    results["ensemble"], ens = _timed(lambda: hy.ensemble_propagate_until(ta, T, n, gen_scalar), 1)
    finals["ensemble"] = np.array([r[0].state for r in ens]).T
    for bs in sorted({hy.recommended_simd_size(), 2 * hy.recommended_simd_size()}):
        m = n // bs
        tb = _batch_integrator(system, pars, ys, bs)

        def batch_loop():
            out = np.empty_like(ys[:, : m * bs])
            for b in range(m):
                tb.set_time(0.0)
                tb.state[:] = ys[:, b * bs:(b + 1) * bs]
                tb.propagate_until(T)
                out[:, b * bs:(b + 1) * bs] = tb.state
            return out

        results[f"batch{bs}"], finals[f"batch{bs}"] = _timed(batch_loop, 1)
        results[f"ensemble_batch{bs}"], finals[f"ensemble_batch{bs}"] = _ensemble_of_batches(tb, ys, T)
    for name, fin in finals.items():
        agree[name] = float(np.max(np.abs(fin - ref[:, : fin.shape[1]])))
    from scipy.integrate import solve_ivp

    rhs = hy.cfunc([r for _, r in system], [v for v, _ in system])
    buf = np.empty(len(system))
    p_rhs = pars[: rhs.nparams]

    def f(t, y):
        rhs(np.ascontiguousarray(y), pars=p_rhs, outputs=buf)
        return buf.copy()

    t_dop, _ = _timed(lambda: [solve_ivp(f, (0, T), ys[:, i], method="DOP853", rtol=1e-10, atol=1e-10)
                               for i in range(k_scipy)], 1)
    per_second = {}
    for name, sec in results.items():
        bs = int(name.rsplit("batch", 1)[1]) if "batch" in name else 1
        per_second[name] = (n // bs) * bs / sec
    per_second["scipy_dop853"] = k_scipy / t_dop
    return {"seconds": {k2: float(f"{v:.4g}") for k2, v in results.items()},
            "per_second": {k2: float(f"{v:.4g}") for k2, v in per_second.items()},
            "ratio_to_loop": {k2: float(f"{v / per_second['loop']:.3g}") for k2, v in per_second.items()},
            "max_difference_to_loop": {k2: float(f"{v:.2e}") for k2, v in agree.items()}, "scipy_subset": k_scipy}


# --- the stability map ---------------------------------------------------

def stability_map_speed(quick: bool, progress) -> dict:
    """The report's 100 x 100 map of the disk's diameter spin (10^4 runs of 10 s), timed alone."""
    from .studies.maps import stability_map
    from .studies.thresholds import threshold

    n = 10 if quick else 100
    lin = float(threshold("disk", "diameter-spin").value)
    rates, tilts = np.linspace(0.5 * lin, 1.5 * lin, n), np.logspace(-6, -1, n)
    stability_map("disk", "diameter-spin", rates=rates[:4], tilts=tilts[:2])  # warm: JIT, sympy
    progress(f"  stability map: disk diameter spin, {n * n} trajectories of 10 s")
    smap = stability_map("disk", "diameter-spin", rates=rates, tilts=tilts)
    return {"trajectories": smap.n_trajectories, "t_end": smap.t_end, "wall_seconds": round(smap.wall_seconds, 2),
            "per_second": round(smap.n_trajectories / smap.wall_seconds), "batch_size": smap.batch_size,
            "threads": smap.threads, "target_seconds": 10.0}


# --- compile cost ---------------------------------------------------------------------------------

_COMPILE_SCRIPT = r"""
import json, resource, sys, time
t0 = time.perf_counter()
import heyoka as hy
t_import = time.perf_counter() - t0
from models import get_model
from verify.engine.compile import compile_model
from verify.precision import parse_precision
t0 = time.perf_counter()
model = get_model("disk")
t_derive = time.perf_counter() - t0
out = {"import": t_import, "derive": t_derive}
for label, precision, compact in json.loads(sys.argv[1]):
    prec = parse_precision(precision)
    c = compile_model(model, prec)
    kw = prec.integrator_kwargs(); kw["compact_mode"] = compact
    t0 = time.perf_counter()
    hy.taylor_adaptive(list(c.system), [1.2, 0, 0, 0, 1, 10, 0, 0] if precision == "double" else
                       prec.array(["1.2", 0, 0, 0, 1, 10, 0, 0]), pars=prec.array([prec.number("0.25"), prec.number(980)]), **kw)
    first = time.perf_counter() - t0
    t0 = time.perf_counter()
    hy.taylor_adaptive(list(c.system), [1.2, 0, 0, 0, 1, 10, 0, 0] if precision == "double" else
                       prec.array(["1.2", 0, 0, 0, 1, 10, 0, 0]), pars=prec.array([prec.number("0.25"), prec.number(980)]), **kw)
    out[label] = {"first": first, "again_in_process": time.perf_counter() - t0}
out["max_rss_mib"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps(out))
"""
COMPILE_CASES = (("double default", "double", False), ("double compact", "double", True),
                 ("quad compact", "quad", True), ("mp:128 compact", "mp:128", True))


def compile_cost(quick: bool, progress) -> dict:
    cases = COMPILE_CASES[:2] if quick else COMPILE_CASES
    root = Path(__file__).resolve().parent.parent
    with tempfile.TemporaryDirectory(prefix="heyoka-cache-") as cache:
        env = dict(os.environ, HEYOKA_CACHE_DIR=cache, PYTHONPATH=str(root))
        runs = {}
        for label in ("empty disk cache", "warm disk cache"):
            progress(f"  compile cost: fresh process, {label}")
            res = subprocess.run([sys.executable, "-c", _COMPILE_SCRIPT, json.dumps(cases)], env=env, cwd=root,
                                 capture_output=True, text=True, check=True)
            runs[label] = json.loads(res.stdout.strip().splitlines()[-1])
    return {"cases": [c[0] for c in cases], "runs": runs}


# --- all of it -----------------------------------------------------------------------------------

def machine() -> dict:
    info = {"platform": platform.platform(), "processor": platform.machine(), "cpus": os.cpu_count(),
            "python": platform.python_version(), "heyoka": hy.__version__,
            "simd_size": hy.recommended_simd_size()}
    try:
        model = [line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                 if line.startswith("model name")]
        info["cpu"] = model[0] if model else "unknown"
    except OSError:
        info["cpu"] = "unknown"
    return info


def run_benchmarks(quick: bool = False, progress=None) -> dict:
    t0 = time.monotonic()

    def say(text):
        if progress:
            progress(f"{text} [{time.monotonic() - t0:.0f} s]")

    results = {"machine": machine(), "quick": quick, "targets": TARGETS}
    wp = work_precision(quick, say)
    results["work_precision"] = {**{k: v for k, v in wp.items() if k not in ("attempts", "short", "long")},
                                 "attempts": [a.to_record() for a in wp["attempts"]],
                                 "short": [a.to_record() for a in wp["short"]],
                                 "long": [a.to_record() for a in wp["long"]],
                                 "same_accuracy": same_accuracy_speedup(wp["attempts"]),
                                 "same_accuracy_long": same_accuracy_speedup(wp["long"]) if wp["long"] else {}}
    results["energy"] = energy_growth(quick, say)
    results["sweep"] = sweep_throughput(quick, say)
    results["stability_map"] = stability_map_speed(quick, say)
    results["compile"] = compile_cost(quick, say)
    results["wall_seconds"] = round(time.monotonic() - t0, 1)
    return results


def write_benchmarks(results: dict, out: Path) -> None:
    out = Path(out)
    # everything is rendered before the first file is replaced: a rendering error leaves the old set whole
    files = {Path("figures") / "bench-work-precision.png": render_work_precision(results),
             Path("figures") / "bench-energy.png": render_energy(results),
             Path("benchmarks.json"): json.dumps(results, indent=2) + "\n",
             Path("BENCHMARKS.md"): render_markdown(results)}
    for name, data in files.items():
        write_atomic(out / name, data)


# --- rendering ---------------------------------------------------------------------------------

def render_markdown(r: dict) -> str:
    m, wp, e, s, c = r["machine"], r["work_precision"], r["energy"], r["sweep"], r["compile"]
    lines = [
        "# Benchmarks",
        "",
        "Generated by `python -m verify bench` (the last stage of `make report`). Timings depend on the machine and",
        "its load, so this file and `benchmarks.json` change from run to run; compare the *ratios*, measured in one run.",
        "Nothing here is a pass/fail test; the issue's targets are printed beside the measured figures.",
        "",
        f"Machine: {m['cpu']} ({m['processor']}), {m['cpus']} cores, SIMD batch size {m['simd_size']}; {m['platform']}; "
        f"Python {m['python']}, heyoka {m['heyoka']}. Benchmark wall time {r['wall_seconds']} s"
        + (" (quick sizes)." if r["quick"] else "."),
        "",
        "## Work against precision",
        "",
        f"Final state of the reference case `{wp['case']}` at t = {wp['t_end']} s against its certified digits",
        f"(error = max |y_i - ref_i| / max |ref_i|; the reference itself is good to {wp['reference_floor']:.1e}).",
        "heyoka runs bare (compiled system, no events); scipy gets the right-hand side and the Jacobian compiled by",
        "heyoka's cfunc. Time is the best of repeated runs where a run is short.",
        "",
        "| method | setting | seconds | final error | steps / rhs calls | time / heyoka double at eps |",
        "|---|---|---:|---:|---:|---:|",
    ]
    base = next((a["seconds"] for a in wp["attempts"] if a["method"] == "heyoka double" and a["setting"] == "tol eps"), None)
    lines += [_attempt_row(a, base, wp["reference_floor"]) for a in wp["attempts"]]
    sa = wp.get("same_accuracy") or {}
    if sa:
        lines += ["", f"**heyoka double against DOP853 at the same accuracy** (target: at least "
                      f"{TARGETS['dop853_speedup']:g}x): DOP853's most accurate run ({sa['slow']['setting']}, error "
                      f"{sa['slow']['error']:.1e}) takes {sa['speedup']:.0f}x the time of the fastest heyoka double run at "
                      f"least as accurate ({sa['fast']['setting']}, error {sa['fast']['error']:.1e}); heyoka at its "
                      f"tightest ({sa['tightest_fast']['setting']}) is {sa['speedup_tightest']:.0f}x faster and "
                      f"{sa['accuracy_ratio_tightest']:.0f}x more accurate."]
    if wp.get("long"):
        sal = wp["same_accuracy_long"]
        lines += ["", f"On the 10 s case `{wp['long_case']}` (reference good to {wp['long_floor']:.1e}):", "",
                  "| method | setting | seconds | final error | steps / rhs calls |", "|---|---|---:|---:|---:|"]
        lines += [f"| {a['method']} | {a['setting']} | {a['seconds']:.4g} | {a['error']:.2e} | {a['work']} |" for a in wp["long"]]
        if sal:
            lines += ["", f"Same accuracy: DOP853 ({sal['slow']['setting']}) / heyoka double ({sal['fast']['setting']}) = "
                          f"{sal['speedup']:.0f}x; at heyoka's tightest: {sal['speedup_tightest']:.0f}x faster, "
                          f"{sal['accuracy_ratio_tightest']:.0f}x more accurate."]
    lines += ["", f"**mpmath odefun** (Taylor series in Python) on the first {wp['short_t_end']} s of the same case, "
                  f"against heyoka on the same run (reference good to {wp['short_floor']:.1e}):", "",
              "| method | setting | seconds | final error | steps / rhs calls |", "|---|---|---:|---:|---:|"]
    lines += [f"| {a['method']} | {a['setting']} | {a['seconds']:.4g} | {a['error']:.2e} | {a['work']} |" for a in wp["short"]]
    q = next((a for a in wp["short"] if a["method"] == "heyoka quad"), None)
    od = [a for a in wp["short"] if a["method"] == "mpmath odefun"]
    if q and od:
        lines += ["", "odefun / heyoka quad: " + ", ".join(f"{a['setting']}: {a['seconds'] / q['seconds']:.0f}x the time "
                                                           f"at error {a['error']:.1e} (quad: {q['error']:.1e})" for a in od)]
    labels = {"suite": "verify.solve (phi, psi, x, y kept out of the error control)",
              "suite_high_accuracy": "verify.solve with heyoka's high-accuracy mode (compensated summation)",
              "plain": "plain heyoka integrator (angles unbounded)"}
    lines += ["", "![work against precision](figures/bench-work-precision.png)", "",
              "## Long-run energy error", "",
              f"{e['starts']} starts near the disk's standard state, {e['t_end']:g} s each (about {e['steps_per_run']:,} "
              f"Taylor steps per run), relative energy error at 40 log-spaced times, RMS over the starts, fitted to t^a "
              f"from t = {e['fit_from']:g} s; the last column fits each start's running maximum (a single run is noisy).", "",
              "| integrator | fitted exponent a (RMS) | RMS error at the end | a per start (running max) |",
              "|---|---:|---:|---|"]
    for key, text in labels.items():
        lines.append(f"| {text} | {e['exponent'][key]:.3f} | {e['rms'][key][-1]:.2e} | "
                     f"{', '.join(f'{v:.2f}' for v in e['exponent_per_start'][key])} |")
    lines += ["", f"Brouwer's law is a = 0.5 (round-off as an unbiased random walk); the target is a <= "
                  f"{TARGETS['energy_exponent']} over 10^6 steps; a secular drift gives a = 1.", "",
              "![energy error](figures/bench-energy.png)", "", "## Sweep throughput", "",
              f"{s['trajectories']} disk trajectories of {s['t_end']:g} s (double, tolerance eps; starts theta in "
              f"[1.0, 1.4], phidot in [-2, 2], psidot in [5, 15]), {s['threads']} threads for the ensembles, for the full "
              "8-dimensional system and for the reduced one (theta, thetadot, phidot, psidot: all a stability sweep "
              "needs); scipy's DOP853 (rtol = atol = 1e-10, right-hand side compiled) on a subset.", "",
              "| system | mode | trajectories per second | x plain loop | max difference of the final state to the loop |",
              "|---|---|---:|---:|---:|"]
    best = 0.0
    for system, res in s["systems"].items():
        for k, v in res["per_second"].items():
            diff = res["max_difference_to_loop"].get(k, 0.0 if k == "loop" else None)
            mode = f"{k} ({res['scipy_subset']} runs)" if k == "scipy_dop853" else k
            shown = "-" if diff is None else f"{diff:.1e}"
            lines.append(f"| {system} | {mode} | {v:,.1f} | {res['ratio_to_loop'][k]} | {shown} |")
            if k != "scipy_dop853":
                best = max(best, v)
    lines += ["", f"Best heyoka mode: {best:,.0f} trajectories of {s['t_end']:g} s per second (target: "
                  f"{TARGETS['sweep_per_second']:,.0f}). Lanes and threads give the loop's results up to round-off "
                  "amplified by the flow's conditioning (last column; the ensemble of scalar integrators is the loop, "
                  "bit for bit). Each of these runs takes ~3,000 Taylor steps of order 20: the cost is the steps, not "
                  "the bookkeeping.", ""]
    if s.get("tolerances"):
        lines += [f"The best mode (reduced system, {s['tolerances'][0]['lanes']} lanes a batch, ensemble) at looser "
                  "tolerances; heyoka lowers the Taylor order with the tolerance. The last column is what the speed "
                  "costs: the largest final-state difference to the run at eps.", "",
                  "| tolerance | order | trajectories per second | max difference to eps |", "|---|---:|---:|---:|"]
        lines += [f"| {t['tol']} | {t['order']} | {t['per_second']:,.0f} | {t['max_difference_to_eps']:.1e} |"
                  for t in s["tolerances"]]
        lines += [""]
    lines += [
              "## Stability map", "",
              f"The report's map of the disk's spin about a vertical diameter, {r['stability_map']['trajectories']:,} "
              f"trajectories of {r['stability_map']['t_end']:g} s (reduced system, batch size "
              f"{r['stability_map']['batch_size']}, ensemble on {r['stability_map']['threads']} threads, run alone): "
              f"{r['stability_map']['wall_seconds']} s, {r['stability_map']['per_second']:,} trajectories per second "
              f"(target: under {r['stability_map']['target_seconds']:g} s). Most of its runs are near-steady or leave "
              "early, so they take fewer steps than the sweep above. `python benchmarks/bench_map.py` compares it with "
              "a scalar loop and plain batch mode.", "",
              "## Compile cost", "",
              "Fresh Python processes: first with an empty heyoka disk cache (`HEYOKA_CACHE_DIR` a new folder), then a "
              "second process with the cache the first one left. 'again' is a second integrator in the same process "
              "(heyoka's in-memory cache).", "",
              "| integrator | empty disk cache (s) | warm disk cache (s) | again in the same process (s) |",
              "|---|---:|---:|---:|"]
    cold, warm = c["runs"]["empty disk cache"], c["runs"]["warm disk cache"]
    for label in c["cases"]:
        lines.append(f"| {label} | {cold[label]['first']:.3f} | {warm[label]['first']:.3f} | {cold[label]['again_in_process']:.4f} |")
    lines += ["", f"Also per fresh process: `import heyoka` {cold['import']:.2f} s; deriving the disk's equations "
                  f"(sympy) {cold['derive']:.2f} s; peak memory {cold['max_rss_mib']:.0f} MiB.", ""]
    return "\n".join(lines)


def _attempt_row(a: dict, base, floor: float) -> str:
    err = f"{a['error']:.2e}" if math.isfinite(a["error"]) else "failed"
    if math.isfinite(a["error"]) and a["error"] < floor:
        err = f"< {floor:.0e} (the reference's own)"
    ratio = f"{a['seconds'] / base:.3g}" if base and math.isfinite(a["seconds"]) else "-"
    return f"| {a['method']} | {a['setting']} | {a['seconds']:.4g} | {err} | {a['work']} | {ratio} |"


def render_work_precision(r: dict) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    wp = r["work_precision"]
    fig, ax = plt.subplots(figsize=(7.5, 5))
    floor = wp["reference_floor"]
    methods = []
    for a in wp["attempts"]:
        if a["method"] not in methods:
            methods.append(a["method"])
    for mname in methods:
        pts = [a for a in wp["attempts"] if a["method"] == mname and math.isfinite(a["error"])]
        if not pts:
            continue
        pts.sort(key=lambda a: a["seconds"])
        ax.loglog([a["seconds"] for a in pts], [max(a["error"], floor) for a in pts], "o-", label=mname)
    ax.axhline(floor, color="grey", ls=":", lw=1, label="reference's certified accuracy")
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("final-state error (relative, max norm)")
    ax.set_title(f"work against precision: {wp['case']}, t = {wp['t_end']} s")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    return _png(fig)


def render_energy(r: dict) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    e = r["energy"]
    t = np.array(e["times"])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, text in (("suite", "verify.solve"), ("suite_high_accuracy", "verify.solve, high accuracy"),
                      ("plain", "plain heyoka")):
        ax.loglog(t, e["rms"][key], label=f"{text}: t^{e['exponent'][key]:.2f}")
    guide = e["rms"]["suite_high_accuracy"][-1] * np.sqrt(t / t[-1])
    ax.loglog(t, guide, "k:", lw=1, label="t^0.5 (Brouwer)")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("relative energy error (RMS over starts)")
    ax.set_title(f"disk, about {e['steps_per_run']:,} steps per run")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    return _png(fig)


def _png(fig) -> bytes:
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.tight_layout()
    fig.savefig(buf, format="png", dpi=100, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()
