"""The friction each motion of the report needs, mu_req = |F_h| / N, and where a spinning coin starts to slip.

Four parts, each a report job (:mod:`verify.report.jobs`):

* **figure runs** (:func:`figure_rows`): every run a caption's figure shows, its largest mu_req
  on the run's own output grid and when, and where N <= 0 if the run loses contact.  The runs
  are the claims' own (:mod:`verify.claims.simulations`): the claims of one figure are
  evaluated with the trajectories their ``run`` makes recorded, and each run a figure shows is
  matched to its trajectory by its samples (:func:`recorded_runs`);
* **reference cases** (:func:`reference_rows`): every case of the reference set, in double on a
  grid of :data:`REFERENCE_POINTS` points;
* **steady families** (:func:`steady_rows`): mu_req along each family as a function of theta,
  two ways: the friction cfunc of the engine on the steady state, and the closed form
  :func:`closed_form` (below), agreeing to :func:`agreement_bound`;
* **slip on the spin-down** (:func:`family_slip`, :func:`slip_runs`): the tilt at which mu_req
  reaches mu = :data:`MU_LEVELS` along the quasi-steady families, and in the dissipative runs
  of :mod:`verify.studies.dissipation` with the engine's ``slips`` event.

The closed form on a steady motion
----------------------------------
On a steady motion theta, phidot, psidot are constant, so the body's configuration turns
rigidly about the vertical at Omega_C = phidot (phi is the only angle of the frame e1, e2,
e3 that moves; psi turns the body about its symmetry axis, which carries C).  With the contact
point r_P = CP = r2 e2 + r3 e3 and omega = (0, phidot sin theta, phidot cos theta + psidot) in
(e1, e2, e3) (thetadot = 0), no slip gives v_C = -omega x r_P = (r2 omega3 - r3 omega2) e1:
horizontal, of constant size, turning with e1 at phidot.  So C moves on a circle of radius
rho_C = |r2 omega3 - r3 omega2| / |phidot| at the rate Omega_C = phidot, its acceleration is
horizontal, M Omega_C^2 rho_C towards the centre, and N = M g (paper Eq. 6: no vertical
acceleration of C).  Hence

    mu_req = Omega_C^2 rho_C / g = |phidot| |r2 omega3 - r3 omega2| / g,

with r2 = -1, r3 = 0 (disk), r2 = -1, r3 = -h (ring), r2 = -sin theta, r3 = -(1 + cos theta)
(hurricane balls; lengths in units of the ball radius), the contact geometry of the paper
(docs/models.md).  It reads neither the equations of motion nor a_C: only the steady state and
the no-slip condition.  On the centre-of-mass-at-rest family (the paper's Eq. 45 for the disk)
r2 omega3 = r3 omega2, so rho_C = 0 and mu_req = 0 at every theta: a coin exactly on that
family needs no friction at all.
"""
from __future__ import annotations

import math
from functools import lru_cache

import mpmath
import numpy as np
import sympy as sp

from models import get_model
from models.steady import steady_state
from models.symbols import STATE_NAMES

#: The friction coefficients at which the spin-down's slip is located.
MU_LEVELS = ("0.1", "0.2", "0.3", "0.5", "1")
#: The bands the report reads mu_req against (see :func:`band`): 0.2 to 0.5 for a coin on
#: glass and up to about 1 for rubber on wood, as the task that asked for this section states
#: them; order-of-magnitude values, not measured for these bodies and cited to no source.
BANDS = (("0.2", "<= 0.2"), ("0.5", "0.2-0.5"), ("1", "0.5-1"), (None, "> 1"))
#: Output points of a reference case's run read for mu_req (the cases' own grids have 41 to 101).
REFERENCE_POINTS = 20001
#: Working digits of the closed form and of the steady states.
DPS = 50
#: theta of the spin-down families' table (decimal strings); a family with no steady motion at
#: a theta says so.
FAMILY_THETAS = ("1.2", "1", "0.5", "0.3", "0.1", "1e-2", "1e-4", "1e-8")
#: Rates of the steady motions of models/steady.py in the table.
STEADY_RATES = {("disk", "diameter-spin"): ("10", "40"), ("disk", "straight-line"): ("10", "40"),
                ("ring", "straight-line"): ("10", "40"), ("ring", "diameter-spin"): ("5", "9", "20", "40"),
                ("hurricane", "precession"): ("30", "40", "80")}
#: The precisions the cfunc is evaluated in, against the closed form.
CFUNC_PRECISIONS = ("double", "quad")
#: |cfunc - closed form| <= AGREEMENT_FACTOR eps (1 + phidot (|phidot| + |psidot|) / g): see
#: :func:`agreement_bound`.
AGREEMENT_FACTOR = 64


def band(mu) -> str:
    """The band of :data:`BANDS` a required friction falls in ('-' for NaN or None)."""
    if mu is None or not math.isfinite(float(mu)):
        return "-"
    for top, words in BANDS:
        if top is None or float(mu) <= float(top):
            return words
    raise AssertionError("unreachable")


# --- the steady families: two ways -------------------------------------------------------

def contact_geometry(model: str, theta, values: dict) -> tuple:
    """(r2, r3) of r_P = CP = r2 e2 + r3 e3 for the body (the paper's contact point; docs/models.md)."""
    if model == "disk":
        return -1, 0
    if model == "ring":
        return -1, -values["h"]
    if model == "hurricane":
        return -mpmath.sin(theta), -(1 + mpmath.cos(theta))
    raise ValueError(f"no rolling contact geometry for {model!r}; allowed: disk, ring, hurricane")


def closed_form(model: str, theta, phidot, psidot, values: dict, geometry=None):
    """mu_req on the steady motion (theta, phidot, psidot): |phidot| |r2 omega3 - r3 omega2| / g
    (module docstring), at mpmath's working precision.  ``geometry``: (r2, r3) in place of the
    body's, for negative controls."""
    r2, r3 = geometry if geometry is not None else contact_geometry(model, theta, values)
    omega2 = phidot * mpmath.sin(theta)
    omega3 = phidot * mpmath.cos(theta) + psidot
    return abs(phidot) * abs(r2 * omega3 - r3 * omega2) / values["g"]


def circle(model: str, theta, phidot, psidot, values: dict) -> dict:
    """Omega_C and rho_C of the circle C runs on (module docstring)."""
    r2, r3 = contact_geometry(model, theta, values)
    speed = abs(r2 * (phidot * mpmath.cos(theta) + psidot) - r3 * phidot * mpmath.sin(theta))
    return {"Omega_C": phidot, "rho_C": speed / abs(phidot) if phidot else mpmath.mpf(0)}


def cfunc_value(model: str, theta, phidot, psidot, values: dict, precision: str) -> tuple:
    """(N/(Mg), mu_req) from the engine's friction cfunc at the state rounded to ``precision``."""
    from verify.engine import invariants
    from verify.engine.compile import compile_model
    from verify.precision import parse_precision

    prec = parse_precision(precision)
    m = get_model(model)
    compiled = compile_model(m, prec)
    state = {"theta": theta, "phidot": phidot, "psidot": psidot}
    y = prec.array([prec.number(mpmath.nstr(state[n], DPS)) if n in state else prec.zero() for n in STATE_NAMES])
    pars = {p.name: prec.number(mpmath.nstr(values[p.name], DPS)) for p in m.parameters}
    y = np.ascontiguousarray(y.reshape(8, 1))
    mu = invariants.friction_required(compiled, y, pars)
    normal = invariants.evaluate(compiled, y, pars)[1]
    return prec.to_mpf(normal[0]), prec.to_mpf(mu[0])


def agreement_bound(phidot, psidot, g, eps) -> float:
    """The bound on |cfunc - closed form| on a steady state: AGREEMENT_FACTOR eps S, with
    S = 1 + |phidot| (|phidot| + |psidot|) / g.

    Why that scale: the state is rounded to the precision (eps relative in each rate), and mu is
    linear in omega3 = phidot cos theta + psidot, so rounding moves it by about
    eps |phidot| (|phidot| + |psidot|) / g; the cfunc forms F_h from the accelerations, whose
    terms (g, phidot^2, phidot psidot, over g) cancel to zero on a steady motion, adding eps
    times their size.  The factor 64 covers the few hundred operations of the cfunc; it is the
    same empirical allowance tests/test_friction_required.py uses, not a derived constant (the
    measured worst case is in the report's table, in units of eps S).
    """
    return AGREEMENT_FACTOR * eps * (1 + abs(float(phidot)) * (abs(float(phidot)) + abs(float(psidot))) / float(g))


def _values(model: str, params: dict) -> dict:
    from models.steady import exact_parameters

    m = get_model(model)
    subs = exact_parameters(m, params)
    with mpmath.workdps(DPS + 10):  # not mpmath's default 15 digits
        return {p.name: mpmath.mpf(sp.N(subs[p.symbol], DPS + 10)) for p in m.parameters}


def steady_point(model: str, family: str, theta, phidot, psidot, values: dict, label: str) -> dict:
    """One steady state: mu_req by the closed form and by the cfunc in each precision, the
    circle of C, and the disagreement in units of eps S (:func:`agreement_bound`)."""
    from verify.precision import parse_precision

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
    from .summary import RING_PARAMS

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
    from models.symbols import phidot, psidot, theta, thetadot

    from .spindown import _psidot_ratio

    m = get_model(model)
    ratio = _psidot_ratio(m, family)
    row = m.accelerations[0].subs({thetadot: 0, psidot: ratio * phidot})
    syms = [p.symbol for p in m.parameters]
    return (sp.lambdify([theta, phidot] + syms, sp.numer(sp.together(row)), "mpmath"),
            sp.lambdify([theta] + syms, ratio, "mpmath"))


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
    from verify.engine.single import solve
    from verify.reference.cases import cases

    rows = []
    for c in cases():
        if names is not None and c.name not in names:
            continue
        sol = solve(c.model, c.t_end, dict(c.state), c.exact_params, n_eval=REFERENCE_POINTS)
        rows.append({"case": c.name, "source": c.source, "kind": c.kind, **run_friction(sol)})
    return rows


# --- slip on the dissipative spin-down: the quasi-steady drift and the damped run ----------

@lru_cache(maxsize=None)
def _transported_row(law: str):
    """Row 1 of the dissipative disk at thetadot = 0 with psidot = omega3 - phidot cos theta, as
    an mpmath function of (theta, phidot, omega3, k, g, c): its root in phidot is the steady rate
    at (theta, omega3) the transported drift follows (:mod:`verify.studies.dissipation.prediction`)."""
    from models import disk
    from models.dissipative import c as c_symbol, dissipative_disk
    from models.symbols import g, phidot, psidot, theta, thetadot

    w3 = sp.Symbol("omega3", real=True)
    row = dissipative_disk(law).accelerations[0].subs({thetadot: 0, psidot: w3 - phidot * sp.cos(theta)})
    return sp.lambdify([theta, phidot, w3, disk.k, g, c_symbol], sp.numer(sp.together(row)), "mpmath")


def transported_point(law: str, th: float, pars: list) -> dict:
    """The transported drift at ``th`` (from THETA0, omega3 = 0 there): omega3, the time, the
    steady phidot at (theta, omega3), and mu_req by the closed form (N = M g, quasi-steady)."""
    from verify.engine.single import through_grid

    from .dissipation import THETA0
    from .dissipation.prediction import transport_system

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
    from scipy.optimize import brentq

    from .dissipation import STUDY_C, THETA0, THETA_STOP, level_grid, predict

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
    from verify.engine.single import solve
    from verify.engine.validation import InvalidStart

    from .dissipation import THETA0
    from .spindown import spindown

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
