"""Long-run energy error: the exponent of t^a over many starts, for solve, solve(high_accuracy=True) and plain heyoka."""
from __future__ import annotations

import heyoka as hy
import numpy as np

from models import get_model

from ..engine.compile import compile_model
from ..engine.single import solve
from ..precision import parse_precision
from ..standard import STANDARD_STATES
from .sizes import _size

ENERGY_LABELS = ("suite", "suite_high_accuracy", "plain")


def energy_starts(n: int) -> list:
    """n starts near the disk's standard state: theta = 1.200, 1.205, ... (phidot 1, psidot 10)."""
    return [dict(STANDARD_STATES["disk"], theta=f"{1.2 + 0.005 * k:.3f}") for k in range(n)]


def energy_growth(quick: bool, progress, n_starts: int = None, t_end: float = None) -> dict:
    """Relative energy error against time over many starts, with the spread of the fitted exponent.

    For each start: :func:`verify.solve` (default, and with heyoka's high-accuracy mode:
    compensated summation), and a plain heyoka integrator on the compiled system (no events, no
    step cap, the angles unbounded), the energy read at 40 log-spaced times.  Fits of
    log(error) against log(t) from t = 10 s: per start (of its running maximum: a single run's
    error crosses zero), summarised by the median and the interquartile range; and of the RMS over
    the starts, with a 90 % bootstrap interval (the starts resampled, fixed seed).
    """
    n_starts = n_starts or _size("energy_starts", quick)
    T = t_end or _size("energy_t_end", quick)
    times = np.geomspace(1.0, T, 40)
    grid = ["0"] + [f"{v:.6f}" for v in times]  # E(0) first
    model = get_model("disk")
    prec = parse_precision("double")
    compiled = compile_model(model, prec)
    errors = {k: [] for k in ENERGY_LABELS}
    steps = []
    for k, state in enumerate(energy_starts(n_starts)):
        progress(f"  energy: start {k + 1}/{n_starts}, {T:g} s")
        for label, ha in (("suite", False), ("suite_high_accuracy", True)):
            sol = solve("disk", repr(T), state, t_eval=grid, high_accuracy=ha)
            e = np.array([float(v) for v in sol.invariants["energy"].values])
            errors[label].append(np.abs(e[1:] - e[0]) / abs(e[0]))
            steps.append(sol.steps)
        y0 = np.array(sol.y[:, 0], dtype=float)
        ta = hy.taylor_adaptive(list(compiled.system), y0, pars=compiled.parameter_vector(sol.params))
        res = ta.propagate_grid(np.concatenate([[0.0], times]))
        ys = np.ascontiguousarray(np.array(res[-1]).T)
        vals = compiled.invariant_function(ys, pars=np.ascontiguousarray(np.repeat(
            compiled.parameter_vector(sol.params, for_function=True)[:, None], ys.shape[1], axis=1)))[0]
        errors["plain"].append(np.abs(vals[1:] - vals[0]) / abs(vals[0]))
    fit = times >= 10.0
    logt = np.log(times[fit])

    def slope(r):
        return float(np.polyfit(logt, np.log(np.maximum(r[fit], 1e-300)), 1)[0])

    rng = np.random.default_rng(20261124)
    resamples = rng.integers(0, n_starts, size=(_size("bootstrap", quick), n_starts))
    out = {"times": times.tolist(), "steps_per_run": int(np.median(steps)), "starts": n_starts, "t_end": T,
           "start_thetas": [s["theta"] for s in energy_starts(n_starts)], "fit_from": 10.0,
           "bootstrap_resamples": int(resamples.shape[0]), "rms": {}, "exponent": {}, "exponent_interval_90": {},
           "exponent_per_start": {}, "per_start_median": {}, "per_start_quartiles": {}}
    for label, errs in errors.items():
        errs = np.array(errs)
        rms = np.sqrt(np.mean(errs ** 2, axis=0))
        out["rms"][label] = rms.tolist()
        out["exponent"][label] = round(slope(rms), 4)
        boot = [slope(np.sqrt(np.mean(errs[idx] ** 2, axis=0))) for idx in resamples]
        out["exponent_interval_90"][label] = [round(float(np.percentile(boot, 5)), 4),
                                              round(float(np.percentile(boot, 95)), 4)]
        per = np.array([slope(np.maximum.accumulate(e)) for e in errs])
        out["exponent_per_start"][label] = [round(float(v), 3) for v in per]
        out["per_start_median"][label] = round(float(np.median(per)), 4)
        out["per_start_quartiles"][label] = [round(float(np.percentile(per, 25)), 4),
                                             round(float(np.percentile(per, 75)), 4)]
    ha, de = np.array(out["exponent_per_start"]["suite_high_accuracy"]), np.array(out["exponent_per_start"]["suite"])
    out["starts_high_accuracy_below_default"] = int(np.sum(ha < de))
    return out
