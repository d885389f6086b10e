"""The friction each motion of the report needs, mu_req = |F_h| / N, and where a spinning coin starts to slip.

Four parts, each a report job (:mod:`verify.report.jobs`):

* **figure runs** (:func:`verify.report.figure_friction.figure_rows`, each run read by
  :func:`run_friction` here): every run a caption's figure shows, its largest mu_req on the run's
  own output grid and when, and where N <= 0 if the run loses contact.  The runs are the claims'
  own (:mod:`verify.claims.simulations`), matched to their trajectories by their samples;
* **reference cases** (:func:`reference_rows`): every case of the reference set, in double on a
  grid of :data:`REFERENCE_POINTS` points;
* **steady families** (:func:`steady_rows`): mu_req along each family as a function of theta,
  two ways: the friction cfunc of the engine on the steady state, and the closed form
  :func:`closed_form`, agreeing to :func:`agreement_bound`;
* **slip on the spin-down**: the tilt at which mu_req reaches mu = :data:`MU_LEVELS` along the
  quasi-steady families (:func:`family_slip`), and along the dissipative drift and in the
  dissipative runs of :mod:`verify.studies.dissipation` with the engine's ``slips`` event
  (:mod:`verify.studies.spindown_slip`, whose :func:`transported_slip` and :func:`slip_runs`
  the report's jobs take from here).

The closed form on a steady motion, the engine's cfunc on it and the bound they agree to are
:mod:`verify.studies.steady_friction`'s.
"""
from __future__ import annotations

from functools import lru_cache

import mpmath
import numpy as np
import sympy as sp

from models import get_model
from models.steady import exact_parameters, steady_state
from models import symbols as sym

from ..engine.single import solve
from ..precision import parse_precision
from ..reference.cases import cases
from .spindown import _psidot_ratio
from .spindown_slip import MU_LEVELS
from .spindown_slip import slip_runs, transported_slip  # noqa: F401 (re-exported: the report's friction jobs)
from .steady_friction import (AGREEMENT_FACTOR, BANDS, CFUNC_PRECISIONS, DPS, agreement_bound, band, cfunc_value,
                              circle, closed_form)
from .summary import RING_PARAMS

#: Output points of a reference case's run read for mu_req (the cases' own grids have 41 to 101).
REFERENCE_POINTS = 20001
#: theta of the spin-down families' table (decimal strings); a family with no steady motion at
#: a theta says so.
FAMILY_THETAS = ("1.2", "1", "0.5", "0.3", "0.1", "1e-2", "1e-4", "1e-8")
#: Rates of the steady motions of models/steady.py in the table.
STEADY_RATES = {("disk", "diameter-spin"): ("10", "40"), ("disk", "straight-line"): ("10", "40"),
                ("ring", "straight-line"): ("10", "40"), ("ring", "diameter-spin"): ("5", "9", "20", "40"),
                ("hurricane", "precession"): ("30", "40", "80")}


# --- the steady families: two ways -------------------------------------------------------

def _values(model: str, params: dict) -> dict:
    m = get_model(model)
    subs = exact_parameters(m, params)
    with mpmath.workdps(DPS + 10):  # not mpmath's default 15 digits
        return {p.name: mpmath.mpf(sp.N(subs[p.symbol], DPS + 10)) for p in m.parameters}


def steady_point(model: str, family: str, theta, phidot, psidot, values: dict, label: str) -> dict:
    """One steady state: mu_req by the closed form and by the cfunc in each precision, the
    circle of C, and the disagreement in units of eps S (:func:`agreement_bound`)."""
    with mpmath.workdps(DPS):
        closed = closed_form(model, theta, phidot, psidot, values)
        c = circle(model, theta, phidot, psidot, values)
        row = {"model": model, "family": family, "at": label, "theta": mpmath.nstr(theta, 12),
               "phidot": mpmath.nstr(phidot, 12), "psidot": mpmath.nstr(psidot, 12),
               "rho_C": mpmath.nstr(c["rho_C"], 8), "Omega_C": mpmath.nstr(c["Omega_C"], 8),
               "mu_closed": mpmath.nstr(closed, 10), "band": band(closed), "cfunc": {}}
        for precision in CFUNC_PRECISIONS:
            eps = parse_precision(precision).eps
            normal, mu = cfunc_value(model, theta, phidot, psidot, values, precision)
            scale = agreement_bound(phidot, psidot, values["g"], 1.0) / AGREEMENT_FACTOR
            diff = abs(mu - closed)
            row["cfunc"][precision] = {
                "mu": mpmath.nstr(mu, 10), "normal": mpmath.nstr(normal, 10),
                "difference_in_eps_scale": f"{float(diff / (eps * scale)):.3g}",
                "agrees": bool(diff <= agreement_bound(phidot, psidot, values["g"], eps))}
    return row


def spindown_family_rows(model: str, family: str, params: dict, thetas=FAMILY_THETAS) -> list:
    """The spin-down family (:mod:`verify.studies.spindown`'s construction, :func:`family_state`)
    at each theta; a theta with no steady motion of the family is a row saying so."""
    values = _values(model, params)
    rows = []
    for th in thetas:
        with mpmath.workdps(DPS):
            x = mpmath.mpf(th)
            state = family_state(model, family, x, values)
            if state is None:
                rows.append({"model": model, "family": family, "at": f"theta = {th}", "theta": th, "none": True})
                continue
            rows.append(steady_point(model, family, x, *state, values, f"theta = {th}"))
    return rows


def steady_motion_rows(model: str, motion: str, params: dict, rates) -> list:
    """The steady motions of :mod:`models.steady` at the given rates."""
    values = _values(model, params)
    rows = []
    for rate in rates:
        s = steady_state(model, motion, rate, params)
        with mpmath.workdps(DPS):
            rows.append(steady_point(model, motion, mpmath.mpf(s["theta"]), mpmath.mpf(s["phidot"]),
                                     mpmath.mpf(s["psidot"]), values, f"rate {rate}"))
    return rows


def steady_rows() -> dict:
    """Every steady family the report shows: the spin-down families of the disk and of the paper's
    printed ring (as the spin-down table), and the steady motions of models/steady.py."""
    families = []
    for model in ("disk", "ring"):
        params = dict(RING_PARAMS) if model == "ring" else {}
        for family in ("cm-at-rest", "zero-vertical-spin"):
            families += spindown_family_rows(model, family, params)
    motions = []
    for (model, motion), rates in STEADY_RATES.items():
        params = dict(RING_PARAMS) if model == "ring" else {}
        motions += steady_motion_rows(model, motion, params, rates)
    return {"bands": [label for _, label in BANDS], "agreement_factor": AGREEMENT_FACTOR,
            "cfunc_precisions": list(CFUNC_PRECISIONS), "mu_levels": list(MU_LEVELS),
            "spindown": families, "motions": motions,
            "family_slip": [family_slip("disk", "cm-at-rest", {}), family_slip("disk", "zero-vertical-spin", {}),
                            family_slip("ring", "zero-vertical-spin", dict(RING_PARAMS))]}


# --- slip on the quasi-steady families ----------------------------------------------------

#: The scan of a family for the roots of mu_req(theta) = mu: theta from FAMILY_SCAN_LOW to
#: pi/2 (exclusive), evenly in log theta below 0.1 and in theta above, then each bracketed
#: root refined by mpmath's Illinois method to 30 digits.
FAMILY_SCAN_LOW = "1e-8"
FAMILY_SCAN_POINTS = (60, 90)


def _scan_thetas() -> list:
    low, mid, top = mpmath.mpf(FAMILY_SCAN_LOW), mpmath.mpf("0.1"), mpmath.pi / 2
    n_log, n_lin = FAMILY_SCAN_POINTS
    logs = [low * (mid / low) ** (mpmath.mpf(i) / n_log) for i in range(n_log)]
    return logs + [mid + (top - mid) * mpmath.mpf(i) / n_lin for i in range(n_lin)]


@lru_cache(maxsize=None)
def _family_row(model: str, family: str):
    """(f, ratio): the numerator of row 1 on the family, f(theta, phidot, *params), and
    psidot / phidot there, as mpmath functions (the construction of
    :func:`verify.studies.spindown.spindown`, lambdified once for a scan)."""
    m = get_model(model)
    ratio = _psidot_ratio(m, family)
    row = m.accelerations[0].subs({sym.thetadot: 0, sym.psidot: ratio * sym.phidot})
    syms = [p.symbol for p in m.parameters]
    return (sp.lambdify([sym.theta, sym.phidot] + syms, sp.numer(sp.together(row)), "mpmath"),
            sp.lambdify([sym.theta] + syms, ratio, "mpmath"))


def family_state(model: str, family: str, th, values: dict):
    """(phidot, psidot) of the spin-down family at ``th`` (mpmath), or None where it has no steady
    motion: row 1 is linear in phidot^2 on the family, phidot^2 = -f(0) / (f(1) - f(0)), at
    DPS + 10 + log10(1/theta) digits as :func:`verify.studies.spindown.spindown` (which the
    tests compare it with)."""
    f, ratio = _family_row(model, family)
    args = [values[p.name] for p in get_model(model).parameters]
    with mpmath.workdps(DPS + 10 + max(0, int(-mpmath.log10(th)))):
        f0, f1 = f(th, 0, *args), f(th, 1, *args)
        square = -f0 / (f1 - f0)
        if square <= 0:
            return None
        rate = mpmath.sqrt(square)
        return +rate, rate * ratio(th, *args)


def family_mu(model: str, family: str, values: dict):
    """theta -> mu_req (closed form) on the spin-down family, or None where the family has no steady motion."""
    def mu(th):
        state = family_state(model, family, th, values)
        if state is None:
            return None
        with mpmath.workdps(DPS):
            return closed_form(model, th, *state, values)
    return mu


def family_slip(model: str, family: str, params: dict) -> dict:
    """Where mu_req(theta) = mu on a spin-down family, for each of :data:`MU_LEVELS`.

    Every root in the scanned range (:func:`_scan_thetas`) is listed, in decreasing theta (the
    order a spin-down meets them); a coin on the family slips where mu_req first exceeds mu
    coming down from its start, so which root matters depends on where it starts.  The largest
    mu_req of the scan and where are given too (no root for any mu above it).
    """
    values = _values(model, params)
    mu = family_mu(model, family, values)
    thetas = _scan_thetas()
    with mpmath.workdps(DPS):
        points = [(th, mu(th)) for th in thetas]
    points = [(th, m) for th, m in points if m is not None]
    if not points:
        return {"model": model, "family": family, "none": True}
    i_max = max(range(len(points)), key=lambda i: points[i][1])
    roots = {}
    for level in MU_LEVELS:
        target = mpmath.mpf(level)
        found = []
        for (a, fa), (b, fb) in zip(points, points[1:]):
            if (fa - target) * (fb - target) < 0:
                with mpmath.workdps(30):
                    r = mpmath.findroot(lambda t: mu(t) - target, (a, b), solver="illinois")
                found.append(mpmath.nstr(r, 10))
        roots[level] = sorted(found, key=float, reverse=True)
    return {"model": model, "family": family, "params": {k: str(v) for k, v in params.items()},
            "scan": {"points": len(points), "theta_low": mpmath.nstr(points[0][0], 6),
                     "theta_high": mpmath.nstr(points[-1][0], 10)},
            "max_mu": mpmath.nstr(points[i_max][1], 8), "theta_at_max": mpmath.nstr(points[i_max][0], 8),
            "roots": roots}


# --- the figure runs and the reference cases -----------------------------------------------

def run_friction(sol) -> dict:
    """The largest mu_req of a trajectory on its output grid and when, and where it loses contact.

    ``contact_lost_t``: the first output time with N <= 0 (the run's own ``contact_lost`` event
    time where the run stopped there); mu_req is NaN from there on (meaningless without
    contact), so its maximum is over the points with N > 0.  None without rolling contact.
    """
    mu = sol.friction_required
    base = {"model": sol.model, "outcome": sol.outcome, "t_end": f"{float(sol.t[-1]):.6g}", "points": len(sol.t)}
    if mu is None:
        return {**base, "rolling": False}
    mu = np.asarray(mu, float)
    normal = np.asarray(sol.normal_force, float)
    t = np.asarray(sol.t, float)
    lost = np.nonzero(~(normal > 0))[0]
    finite = np.isfinite(mu)
    if len(lost):  # after the first loss of contact the rolling solution is not physical (Fig. 12 runs on)
        finite[lost[0]:] = False
    i = int(np.nanargmax(np.where(finite, mu, -np.inf))) if finite.any() else None
    contact_t = None
    if sol.outcome == "event:contact_lost":
        contact_t = float(sol.t_events["contact_lost"]) if "contact_lost" in (sol.t_events or {}) else float(t[-1])
    elif len(lost):
        contact_t = float(t[lost[0]])
    return {**base, "rolling": True, "mu_max": None if i is None else f"{mu[i]:.4g}",
            "t_mu_max": None if i is None else f"{t[i]:.6g}", "band": band(mu[i]) if i is not None else "-",
            "normal_min": f"{np.nanmin(normal):.4g}", "contact_lost_t": None if contact_t is None else f"{contact_t:.6g}",
            "points_without_contact": int(len(lost))}


def reference_rows(names=None) -> list:
    """mu_req along every reference case, run in double on REFERENCE_POINTS points."""
    rows = []
    for c in cases():
        if names is not None and c.name not in names:
            continue
        sol = solve(c.model, c.t_end, dict(c.state), c.exact_params, n_eval=REFERENCE_POINTS)
        rows.append({"case": c.name, "source": c.source, "kind": c.kind, **run_friction(sol)})
    return rows
