"""Where a spinning coin starts to slip on its dissipative spin-down: two routes to each mu of :data:`MU_LEVELS`.

* route 1, :func:`transported_slip`: along the quasi-steady drift the dissipation study predicts
  (:mod:`verify.studies.dissipation.prediction`: steady motions, Eq. 45's family for the disk, with
  omega3 transported from THETA0), mu_req by the closed form of :mod:`verify.studies.steady_friction`
  reaches mu at a theta found by Brent's method;
* route 2, :func:`slip_runs`: the damped run itself (``disk+<law>``) with the engine's ``slips`` event,
  switched on shortly before route 1's slip time, its mu_req checked below mu up to there.

Both are report jobs (``friction/slip/<law>``, through :mod:`verify.studies.friction`).
"""
from __future__ import annotations

import math
from functools import lru_cache

import mpmath
import numpy as np
import sympy as sp

from models import disk
from models.dissipative import c as c_symbol, dissipative_disk
from models import symbols as sym

from ..engine.single import solve, through_grid
from ..engine.validation import InvalidStart
from .dissipation import STUDY_C, THETA0, THETA_STOP, level_grid, predict
from .dissipation.prediction import transport_system
from .spindown import spindown
from .steady_friction import closed_form

#: The friction coefficients at which the spin-down's slip is located.
MU_LEVELS = ("0.1", "0.2", "0.3", "0.5", "1")


@lru_cache(maxsize=None)
def _transported_row(law: str):
    """Row 1 of the dissipative disk at thetadot = 0 with psidot = omega3 - phidot cos theta, as
    an mpmath function of (theta, phidot, omega3, k, g, c): its root in phidot is the steady rate
    at (theta, omega3) the transported drift follows (:mod:`verify.studies.dissipation.prediction`)."""
    w3 = sp.Symbol("omega3", real=True)
    psidot = w3 - sym.phidot * sp.cos(sym.theta)
    row = dissipative_disk(law).accelerations[0].subs({sym.thetadot: 0, sym.psidot: psidot})
    return sp.lambdify([sym.theta, sym.phidot, w3, disk.k, sym.g, c_symbol], sp.numer(sp.together(row)), "mpmath")


def transported_point(law: str, th: float, pars: list) -> dict:
    """The transported drift at ``th`` (from THETA0, omega3 = 0 there): omega3, the time, the
    steady phidot at (theta, omega3), and mu_req by the closed form (N = M g, quasi-steady)."""
    run = through_grid(("dissipation transport", law), transport_system(law), [0.0, 0.0, 0.0], pars,
                       [float(THETA0), th])
    if not run.reached:
        raise RuntimeError(f"the transported drift stopped before theta = {th} ({run.outcome})")
    th = float(th)
    omega3, t, _ = (float(v) for v in run.rows[-1])
    k, g, c = (mpmath.mpf(float(v)) for v in pars)
    row = _transported_row(law)
    with mpmath.workdps(30):
        x = mpmath.mpf(th)
        rate = mpmath.findroot(lambda p: row(x, p, omega3, k, g, c), mpmath.sqrt(g / (k * mpmath.sin(x))))
        mu = closed_form("disk", x, rate, omega3 - rate * mpmath.cos(x), {"g": g})
    return {"theta": th, "omega3": omega3, "t": t, "phidot": float(rate), "mu": float(mu)}


def transported_slip(law: str, c=None) -> dict:
    """Route 1 of the spin-down's slip: where mu_req reaches each of MU_LEVELS along the drift the
    dissipation study predicts (steady motions with omega3 transported from THETA0; its theta is
    the same for both laws, only its clock depends on the couple).  ``c``: the couple's
    coefficient, default the study's (:data:`~verify.studies.dissipation.STUDY_C`).

    The levels of the study's grid bracket each crossing; Brent's method refines it to a relative
    1e-13 in theta (the drift is integrated in double).
    """
    from scipy.optimize import brentq  # lazy: scipy is optional (the test and bench extras, pyproject.toml)

    c = STUDY_C[law] if c is None else c
    pred = predict(law, c)
    pars = [float(pred.params[n]) for n in ("k", "g", "c")]
    levels = [float(THETA0)] + [float(v) for v in level_grid(float(THETA0), float(THETA_STOP))]
    points = [transported_point(law, th, pars) if th < float(THETA0) else
              {"theta": th, "mu": 0.0, "t": 0.0} for th in levels]
    out = []
    for level in MU_LEVELS:
        target = float(level)
        bracket = next(((a, b) for a, b in zip(points, points[1:]) if a["mu"] < target <= b["mu"]), None)
        if bracket is None:
            out.append({"mu": level, "theta": None})
            continue
        th = brentq(lambda x: transported_point(law, x, pars)["mu"] - target, bracket[1]["theta"], bracket[0]["theta"],
                    xtol=1e-300, rtol=1e-13)
        p = transported_point(law, th, pars)
        out.append({"mu": level, "theta": f"{th:.10g}", "t": f"{p['t']:.10g}", "omega3": f"{p['omega3']:.6g}",
                    "phidot": f"{p['phidot']:.6g}", "adiabatic": f"{float(pred.adiabatic_parameter(th)):.2g}"})
    return {"law": law, "c": c, "t0_transported": f"{pred.t0_transported:.10g}",
            "t0_family": mpmath.nstr(pred.t0_family, 10), "levels": out}


#: Output points of the run without the slip event, on which its mu_req is checked to stay below mu.
PLAIN_POINTS = 2001
#: The slip event is switched on this long before the drift's slip time, relative to it (or at
#: most (t0 - that time) before, whichever is shorter).
EVENT_LEAD = 1e-3


def slip_runs(law: str, drift: dict) -> dict:
    """Route 2: the dissipative run of the study (``disk+<law>`` at its coefficient, from the exact
    Eq. 45 state at THETA0) with the engine's ``slips`` event, for each of MU_LEVELS.

    The event's function (the horizontal accelerations) makes every step dearer, and the run
    needs about 2e6 steps to the last slip, so the event is on only near each slip: one run
    without it (``solve``, friction None, and without the domain and contact events: it must end
    ``ok``, with N > 0 on its grid) passes through a switch time for each mu, shortly
    before the slip time ``drift`` (route 1) predicts -- EVENT_LEAD of it, at most t0 minus it
    --, and from its state there a run with ``friction=mu`` goes on until ``slips``.  The
    prediction only decides where the event is switched on; it cannot hide an earlier slip: the
    run without the event has its mu_req checked below mu up to each switch time on its output
    grid (PLAIN_POINTS points plus the switch times; ``plain_max``), and a state that already
    needs mu is refused by ``solve`` (reported).  Each leg's state at the event is the last
    column of its run; its mu_req (the engine's cfunc on it) equals mu to the event's precision.
    """
    c = drift["c"]  # the drift's coefficient: the same couple
    model = f"disk+{law}"
    t0 = float(drift["t0_transported"])
    predicted = {x["mu"]: float(x["t"]) for x in drift["levels"] if x.get("t")}
    switch = {m: t - min(EVENT_LEAD * t, t0 - t) for m, t in predicted.items()}
    s = spindown("disk", THETA0, "cm-at-rest")
    start = {"theta": THETA0, "phidot": mpmath.nstr(s.phidot, 45), "psidot": mpmath.nstr(s.psidot, 45)}
    grid = sorted(set(np.linspace(0.0, max(switch.values()), PLAIN_POINTS).tolist()) | set(switch.values()))
    # without the terminal events (a third of the cost of a step): the run must end "ok" inside the
    # domain, and N > 0 is checked on its grid (normal_min) instead
    plain = solve(model, repr(grid[-1]), start, {"c": c}, t_eval=grid, events=False)
    t = np.asarray(plain.t, float)
    need = np.asarray(plain.friction_required, float)
    normal_min = float(np.min(np.asarray(plain.normal_force, float)))
    if plain.outcome != "ok" or not normal_min > 0:
        raise RuntimeError(f"the {model} run without events ended {plain.outcome}, min N/(Mg) {normal_min:.6g}")
    legs = []
    for level in MU_LEVELS:
        leg = {"mu": level}
        if level not in switch:
            legs.append({**leg, "outcome": "no slip predicted before t0"})
            continue
        i = int(np.searchsorted(t, switch[level]))
        if i >= len(t) or t[i] != switch[level]:
            legs.append({**leg, "outcome": f"the run without the event ended at t = {t[-1]:.10g} ({plain.outcome})"})
            continue
        leg["switch"] = f"{switch[level]:.10g}"
        leg["plain_max"] = f"{float(np.nanmax(need[:i + 1])):.6g}"
        try:
            sol = solve(model, repr(t0 * (1 + 1e-6) - switch[level]), [float(v) for v in plain.y[:, i]], {"c": c},
                        friction=level, n_eval=2)
        except InvalidStart as err:
            legs.append({**leg, "outcome": f"refused: {err.reason}"})
            continue
        leg["event_steps"] = int(sol.steps)
        if sol.outcome != "event:slips":
            legs.append({**leg, "outcome": sol.outcome, "t_end": f"{switch[level] + float(sol.t[-1]):.10g}",
                         "theta_end": f"{float(sol['theta'][-1]):.6g}"})
            continue
        y = sol.y[:, -1]
        th, phd, psd = float(y[0]), float(y[4]), float(y[5])
        legs.append({**leg, "outcome": sol.outcome, "t": f"{switch[level] + float(sol.t_events['slips']):.10g}",
                     "theta": f"{th:.10g}", "thetadot": f"{float(y[3]):.4g}", "phidot": f"{phd:.6g}",
                     "omega3": f"{psd + phd * math.cos(th):.6g}",
                     "mu_at_event": f"{float(sol.friction_required[-1]):.12g}"})
    return {"law": law, "c": c, "theta0": THETA0, "plain_steps": int(plain.steps), "plain_outcome": plain.outcome,
            "plain_normal_min": f"{normal_min:.8g}", "legs": legs}
