"""Work against precision: the final state of a reference case (agreeing digits) by heyoka at every precision,
scipy's solve_ivp and mpmath's odefun, error against time."""
from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass

import heyoka as hy
import mpmath
import numpy as np
import sympy as sp

from models import get_model
from models.symbols import STATE, STATE_NAMES

from ..engine.compile import compile_model
from ..engine.single import max_step, resolve_parameters, resolve_state
from ..precision import parse_precision
from ..reference import load_set
from .sizes import _size
from .timing import _timed

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


class ReferenceProblem:
    """A reference case as an initial-value problem, with its agreed values on the grid."""

    def __init__(self, name: str):
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
    parr = compiled.parameter_vector(pars)
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
    parr = np.ascontiguousarray(compiled.parameter_vector(pars))
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
    from scipy.integrate import solve_ivp  # lazy: scipy is optional (the bench extra, pyproject.toml)

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
