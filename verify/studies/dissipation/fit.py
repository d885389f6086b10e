"""Exponents, t0 and turns fitted on a run without knowing t0, against the predictions (item 4 of the
package docstring)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import sympy as sp


from .family import family_law
from .prediction import Prediction, _secants
from .protocol import A_MAX, FIT_TOP
from .work_run import WorkRun


@dataclass(frozen=True)
class ExponentFit:
    """Exponents, t0 and turns fitted on a run, against the predictions.

    ``slope_rate`` (s) and ``slope_phidot`` (r) are least-squares slopes of log|dtheta/dt| and
    log phidot against log theta over the window (secants between samples); p = 1/(1 - s),
    q = p r.  ``*_transported`` are the same fits on the transported prediction's levels.
    ``t0`` is the intercept of t = t0 - B theta^(1/p) over the lower half (in log theta) of
    the window; ``turns`` = phi / 2 pi observed down to theta_stop (or, if the run broke down
    above it, to the window's foot) + the family law's remainder from there to theta = 0.

    Tolerances (on |p - p_predicted|, |q - q_predicted|): a least-squares slope is a
    positively weighted mean of the slopes between neighbouring points, so |s - m| is at most
    the largest |local slope - m| in the window.  The local slopes are those of the
    transported drift (the exact family law has O(theta^2) terms, the omega3 it picks up
    O(theta^1/2) ones) plus what the drift's adiabatic picture leaves out, allowed A_MAX
    (measured: <= 2e-4 at a = A_MAX, falling like a^2, 1e-5 below a = 1e-4).  The interval
    for s (and r) is mapped exactly to p = 1/(1 - s) and q = p r.
    """

    window: tuple  # (theta_low, theta_high)
    points: int
    slope_rate: float
    slope_phidot: float
    slope_rate_transported: float
    slope_phidot_transported: float
    p: float
    q: float
    p_predicted: sp.Rational
    q_predicted: sp.Rational
    p_tolerance: float
    q_tolerance: float
    t0: float
    turns: float
    turns_observed: float  # phi / 2 pi up to turns_reference_theta
    turns_remainder: float  # family law, from turns_reference_theta to theta = 0
    turns_reference_theta: float  # theta_stop, or the window's foot if the run broke down above it
    breakdown_theta: float  # first secant where phidot is 10% below the transported drift (nan: none)

    @property
    def p_ok(self) -> bool:
        return abs(self.p - float(self.p_predicted)) <= self.p_tolerance

    @property
    def q_ok(self) -> bool:
        return abs(self.q - float(self.q_predicted)) <= self.q_tolerance

    @property
    def t0_finite(self) -> bool:
        """theta reaches 0 at a finite time: the fitted p > 0 and t0 came out finite."""
        return self.p > 0 and math.isfinite(self.t0)

    @property
    def turns_finite(self) -> bool:
        """int phidot dt converges at t0: phidot ~ (t0 - t)^q with q > -1."""
        return self.q > -1 and math.isfinite(self.turns)

    @property
    def matches_transported(self) -> bool:
        """The run's slopes equal the transported drift's over the same window within A_MAX."""
        return (abs(self.slope_rate - self.slope_rate_transported) <= A_MAX
                and abs(self.slope_phidot - self.slope_phidot_transported) <= A_MAX)


def secants(run: WorkRun):
    """(theta_mid, |dtheta/dt|, phidot) between consecutive samples, theta_mid the geometric mean:
    secant slopes, which average over the nutation."""
    return _secants(run.t, run["theta"], run["phi"])


def fit_window(pred: Prediction) -> tuple:
    """(theta_low, FIT_TOP): down to where the predicted a(theta) reaches A_MAX (or theta_stop)."""
    grid = np.geomspace(FIT_TOP, float(pred.levels[-1]), 4000)
    inside = grid[pred.adiabatic_parameter(grid) <= A_MAX]
    if len(inside) == 0:
        raise ValueError(f"c = {float(pred.c):g} is too large: the drift is not adiabatic (a > {A_MAX:g}) "
                         f"anywhere below theta = {FIT_TOP}")
    return float(inside[-1]), FIT_TOP


def _ols(x, y) -> float:
    return float(np.polyfit(x, y, 1)[0])


def _window_slopes(mid, rate, phd, lo, hi):
    sel = (mid >= lo) & (mid <= hi) & (rate > 0) & (phd > 0)
    x = np.log(mid[sel])
    return x, np.log(rate[sel]), np.log(phd[sel])


def fit_exponents(run: WorkRun, pred: Prediction) -> ExponentFit:
    """Fit p, q, t0 and the turns on ``run`` (sampled at ``pred``'s level times) over :func:`fit_window`."""
    lo, hi = fit_window(pred)
    x, lr, lp = _window_slopes(*secants(run), lo, hi)
    if len(x) < 4:
        raise ValueError(f"only {len(x)} samples in the fit window [{lo:.3g}, {hi:.3g}]; the run is too short")
    s, r = _ols(x, lr), _ols(x, lp)
    xt, lrt, lpt = _window_slopes(*pred.secant_table(), lo, hi)
    p = 1.0 / (1.0 - s)
    q = p * r
    p_tol, q_tol = _tolerances(pred, xt, lrt, lpt)
    t0 = _fit_t0(run, p, lo, hi)
    breakdown = _breakdown(run, pred)
    ref = _turns_reference(run, lo, breakdown)
    observed = float(run["phi"][ref]) / (2 * math.pi)
    rest = float(pred.family_remainder(float(run["theta"][ref]))[1])
    return ExponentFit((lo, hi), len(x), s, r, _ols(xt, lrt), _ols(xt, lpt), p, q, pred.p, pred.q, p_tol, q_tol,
                       t0, observed + rest, observed, rest, float(run["theta"][ref]), breakdown)


def _turns_reference(run: WorkRun, lo: float, breakdown: float) -> int:
    """The sample the turns are counted to: theta_stop if the run got there without breaking
    down, otherwise the foot of the fit window (the last sample the law is trusted at)."""
    if run.outcome == "event:theta_stop" and math.isnan(breakdown):
        return len(run.t) - 1
    return int(np.nonzero(np.asarray(run["theta"], float) >= lo)[0][-1])


def _tolerances(pred: Prediction, x, lrate, lphd):
    """(p_tol, q_tol) from the transported drift's local slopes in the window (see ExponentFit)."""
    fl = family_law(pred.law)
    m, r_inf = float(fl.rate_exponent), float(fl.phidot_exponent)
    ds = float(np.max(np.abs(np.diff(lrate) / np.diff(x) - m))) + A_MAX
    dr = float(np.max(np.abs(np.diff(lphd) / np.diff(x) - r_inf))) + A_MAX
    p_inf, q_inf = float(fl.p), float(fl.q)
    ps = [1.0 / (1.0 - (m + e)) for e in (-ds, ds)]
    qs = [pp * (r_inf + e) for pp in ps for e in (-dr, dr)]
    return max(abs(v - p_inf) for v in ps), max(abs(v - q_inf) for v in qs)


def _fit_t0(run: WorkRun, p: float, lo: float, hi: float) -> float:
    """t0 from t = t0 - B theta^(1/p) on the samples in the lower half (in log theta) of the window."""
    th, t = np.asarray(run["theta"], float), np.asarray(run.t, float)
    sel = (th >= lo) & (th <= math.sqrt(lo * hi))
    if sel.sum() < 2:
        return math.nan
    A = np.vstack([np.ones(int(sel.sum())), -th[sel] ** (1.0 / p)]).T
    (t0, _), *_ = np.linalg.lstsq(A, t[sel], rcond=None)
    return float(t0)


def _breakdown(run: WorkRun, pred: Prediction) -> float:
    """The first secant theta where phidot is 10% below the transported drift's (nan: never)."""
    mid, _, phd = secants(run)
    pmid, _, pphd = pred.secant_table()
    expected = np.exp(np.interp(-np.log(mid), -np.log(pmid), np.log(pphd)))
    bad = np.nonzero(phd < 0.9 * expected)[0]
    return float(mid[bad[0]]) if len(bad) else math.nan
