"""One law's study as a JSON-ready record (results.json's ``studies.dissipation``)."""
from __future__ import annotations

import math

import mpmath
import sympy as sp


from .protocol import A_MAX
from .study import LawStudy


def _d(x, digits: int = 12) -> str:
    """A decimal string (mpmath, sympy, float)."""
    if isinstance(x, mpmath.mpf):
        return mpmath.nstr(x, digits, strip_zeros=False)
    if isinstance(x, sp.Basic):
        return str(x)
    x = float(x)
    return repr(x) if not math.isfinite(x) else f"{x:.{digits}g}"


def to_record(s: LawStudy) -> dict:
    """One law's study as a JSON-ready dict; numbers as decimal strings.  Byte-reproducible:
    the run's wall time (``s.run.wall_seconds``) is left out, for timing.json."""
    fl, pr, run, fit = s.family, s.prediction, s.run, s.fit
    return {
        "law": s.law,
        "couple_exponent": fl.exponent,
        "c": _d(pr.c),
        "params": {k: _d(v) for k, v in pr.params.items()},
        "theta0": _d(pr.theta0),
        "family": {
            "phidot_squared": str(fl.phidot_squared), "energy": str(fl.energy), "power": str(fl.power),
            "dtheta_dt": str(fl.rate), "leading": f"-({fl.rate_coefficient}) theta^({fl.rate_exponent})",
            "p": str(fl.p), "q": str(fl.q), "time_to_singularity": str(fl.time_to_singularity),
            "turns_to_singularity": str(fl.turns_to_singularity),
            "finite_time": fl.finite_time, "finite_turns": fl.finite_turns,
        },
        "predicted": {
            "t0_family": _d(pr.t0_family), "turns_family": _d(pr.turns_family),
            "t0_transported": _d(pr.t0_transported), "turns_transported": _d(pr.turns_transported),
            "omega3_at_singularity_transported": _d(pr.omega3_final),
        },
        "run": {
            "precision": run.precision, "outcome": run.outcome, "steps": run.steps, "t_end": _d(run.t[-1]),
            "theta_end": _d(run["theta"][-1]), "turns_end": _d(float(run["phi"][-1]) / (2 * math.pi)),
            "energy_balance": _d(run.balance, 4), "energy_balance_eps": _d(run.balance_in_eps, 4),
            "energy_balance_bound_eps": _d(run.balance_bound_in_eps, 4), "energy_balance_ok": run.balance_ok,
        },
        "fit": {
            "window": [_d(fit.window[0], 6), _d(fit.window[1], 6)], "points": fit.points,
            "adiabatic_bound": _d(A_MAX, 3),
            "slope_rate": _d(fit.slope_rate, 8), "slope_rate_transported": _d(fit.slope_rate_transported, 8),
            "slope_phidot": _d(fit.slope_phidot, 8), "slope_phidot_transported": _d(fit.slope_phidot_transported, 8),
            "matches_transported": fit.matches_transported,
            "p": _d(fit.p, 8), "p_predicted": str(fit.p_predicted), "p_tolerance": _d(fit.p_tolerance, 3),
            "p_ok": fit.p_ok,
            "q": _d(fit.q, 8), "q_predicted": str(fit.q_predicted), "q_tolerance": _d(fit.q_tolerance, 3),
            "q_ok": fit.q_ok,
            "t0": _d(fit.t0), "t0_finite": fit.t0_finite,
            "turns": _d(fit.turns), "turns_observed": _d(fit.turns_observed), "turns_remainder": _d(fit.turns_remainder),
            "turns_reference_theta": _d(fit.turns_reference_theta, 6),
            "turns_finite": fit.turns_finite,
            "breakdown_theta": _d(fit.breakdown_theta, 4),
        },
    }
