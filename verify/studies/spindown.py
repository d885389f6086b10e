"""Exact steady spin-down motions (thetadot = 0) of the disk and the ring.

Two families, each fixing psidot in terms of phidot at a given theta:

* ``cm-at-rest``: v_C = 0, i.e. psidot = -phidot (cos(theta) - h sin(theta)) (h = 0 for the disk:
  omega3 = 0, the family on which the paper's Eq. 45 holds exactly);
* ``zero-vertical-spin``: omega . Z = phidot + psidot cos(theta) = 0.

On either family row 1 of the derived equations (thetaddot = 0) is linear in phidot^2, so
phidot^2 = -f(0) / (f(1) - f(0)) with f the thetaddot numerator as a function of phidot^2:
exact, evaluated with mpmath at 50 digits.  The paper's formulas (Eq. 45 disk, Eq. 61 ring)
are compared with it.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import mpmath
import sympy as sp

from models import get_model
from models.symbols import STATE, omega_body, phi, phidot, psidot, theta, thetadot, time_derivative, to_inertial

FAMILIES = ("cm-at-rest", "zero-vertical-spin")
MODELS = ("disk", "ring")
DPS = 50
# phidot^2 = -f(0) / (f(1) - f(0)) with f(1) - f(0) ~ theta f(0): the difference loses
# log10(1/theta) digits, so the working precision is DPS + 10 + log10(1/theta) digits (at a fixed
# DPS + 10, theta = 1e-60 lost all of them: ZeroDivisionError).  THETA_MIN bounds that growth
# (1060 digits at most, milliseconds); it is not a limit of the method.
THETA_MIN = "1e-1000"


@dataclass(frozen=True)
class SpinDown:
    model: str
    family: str
    theta: mpmath.mpf
    params: dict
    phidot: mpmath.mpf
    psidot: mpmath.mpf
    energy: mpmath.mpf
    paper_source: str
    paper_phidot: mpmath.mpf
    values: dict = None  # parameter values as mpmath numbers at the working precision

    @property
    def relative_error(self):
        if self.paper_phidot is None:  # a body with no closed form (body_spindown)
            return None
        with mpmath.workdps(DPS + 10):  # not at mpmath's global precision
            return self.paper_phidot / self.phidot - 1


def _psidot_ratio(model, family):
    h = model.parameter("h").symbol if model.name == "ring" else sp.Integer(0)
    if family == "cm-at-rest":
        return -(sp.cos(theta) - h * sp.sin(theta))
    return -1 / sp.cos(theta)


def spindown(name: str, theta_value: str, family: str = "cm-at-rest", params=None) -> SpinDown:
    if name not in MODELS:
        raise ValueError(f"model {name!r} has no spin-down study; allowed: {', '.join(MODELS)}")
    if family not in FAMILIES:
        raise ValueError(f"unknown family {family!r}; allowed: {', '.join(FAMILIES)}")
    model = get_model(name)
    params = dict(params or {})
    from verify.engine.single import resolve_parameters  # lazy: heyoka (0.4 s): bad input answers first
    from verify.precision import parse_precision  # lazy: as the line above

    resolve_parameters(model, params, parse_precision("double"))  # names and ranges
    from .thresholds import check_reading  # lazy: as the line above

    check_reading(params, "spin-down study")
    with mpmath.workdps(DPS + 10):
        try:
            th = mpmath.mpf(theta_value)
        except (ValueError, TypeError):
            raise ValueError(f"--theta {theta_value!r} is not a number") from None
        top = mpmath.pi / 2
        if not (mpmath.isfinite(th) and 0 < th < top):
            raise ValueError(f"--theta {theta_value} is outside (0, pi/2): the spin-down families need a leaning body")
        if th < mpmath.mpf(THETA_MIN):
            raise ValueError(f"--theta {theta_value} is below {THETA_MIN}; allowed: {THETA_MIN} <= theta < pi/2 (the "
                             "working precision grows as log10(1/theta) digits)")
        digits = DPS + 10 + max(0, int(mpmath.ceil(-mpmath.log10(th))))
    with mpmath.workdps(digits):
        th = mpmath.mpf(theta_value)
        pv = {p.name: mpmath.mpf(sp.N(sp.nsimplify(params[p.name]) if p.name in params else p.default, digits))
              for p in model.parameters}
        ratio = _psidot_ratio(model, family)
        row = model.accelerations[0].subs({thetadot: 0, psidot: ratio * phidot})
        syms = [theta, phidot] + [p.symbol for p in model.parameters]
        f = sp.lambdify(syms, sp.numer(sp.together(row)), "mpmath")
        args = [pv[p.name] for p in model.parameters]
        f0, f1 = f(th, 0, *args), f(th, 1, *args)
        P = -f0 / (f1 - f0)
        if P <= 0:
            raise ValueError(f"no steady {family} motion of the {name} at theta = {theta_value} (phidot^2 = {mpmath.nstr(P, 5)})")
        rate = mpmath.sqrt(P)
        r = sp.lambdify([theta] + [p.symbol for p in model.parameters], ratio, "mpmath")(th, *args)
        psi_rate = r * rate
        state = {theta: th, phidot: rate, psidot: psi_rate}
        E = sp.lambdify(list(STATE) + [p.symbol for p in model.parameters], model.energy, "mpmath")(
            *[state.get(s, mpmath.mpf(0)) for s in STATE], *args)
        g = pv["g"]
        if name == "disk":
            paper, source = mpmath.sqrt(g / (pv["k"] * mpmath.sin(th))), "Eq. 45"
        else:
            paper = mpmath.sqrt(g * (1 - pv["h"]) / ((pv["h"] ** 2 + pv["I1"]) * th))
            source = "Eq. 61"
        shown = {k: mpmath.nstr(v, 20) for k, v in pv.items()}
        return SpinDown(name, family, th, shown, rate, psi_rate, E, source, paper, pv)


def body_spindown(model, theta_value: str, family: str = "cm-at-rest", params=None) -> SpinDown:
    """The steady spin-down state of any body of revolution at ``theta_value`` (a decimal string in its domain).

    The families generalise: with thetadot = 0, omega = phidot Z + psidot e3 = (0, phidot sin(theta), phidot cos(theta)
    + psidot) in the 1-2-3 frame and v_C = -omega x r_P, r_P = (0, r2, r3) (paper Eq. 7), so C is at rest exactly where
    omega is parallel to r_P: psidot = phidot (r3 sin(theta) - r2 cos(theta))/r2 (the disk's -cos(theta), r2 = -1,
    r3 = 0; the ring's -(cos(theta) - h sin(theta)), r3 = -h); ``zero-vertical-spin`` is psidot = -phidot/cos(theta)
    for every body.  On either, row 1 (:func:`models.steady_bodies.row1`: alpha phidot^2 + beta phidot psidot + delta g)
    gives phidot^2 = -delta g/(alpha + beta ratio), at the working precision of :func:`spindown`.  A second route
    checks the state: the model's own v_C (its ``velocity_xy``) must vanish on ``cm-at-rest``, and its thetaddot at the
    state, to 1e-40 of the terms.  The paper's closed form is shown where the body is the disk's (a point rim of
    radius 1 with I3 = 2 I1: Eq. 45, k = I1) or the ring's (two rims of radius 1: Eq. 61, h = half_thickness);
    elsewhere ``paper_source`` and ``paper_phidot`` are None.
    """
    from models.bodies import contact_vector, resolve  # lazy: only for a body (0.1 s)
    from models.steady_bodies import row1  # lazy: as the line above

    if family not in FAMILIES:
        raise ValueError(f"unknown family {family!r}; allowed: {', '.join(FAMILIES)}")
    body = resolve(model.name.removeprefix("body:"))
    params = dict(params or {})
    with mpmath.workdps(DPS + 10):
        try:
            th = mpmath.mpf(theta_value)
        except (ValueError, TypeError):
            raise ValueError(f"--theta {theta_value!r} is not a number") from None
        lo, hi = (mpmath.mpf(sp.N(e, DPS + 10)) for e in (model.domain.theta_min, model.domain.theta_max))
        if not (mpmath.isfinite(th) and lo < th < hi):
            raise ValueError(f"--theta {theta_value} is outside the domain of {model.name}: "
                             f"{mpmath.nstr(lo, 6)} < theta < {mpmath.nstr(hi, 6)}")
        if th < mpmath.mpf(THETA_MIN):
            raise ValueError(f"--theta {theta_value} is below {THETA_MIN}; allowed: {THETA_MIN} <= theta (the working "
                             "precision grows as log10(1/theta) digits)")
        digits = DPS + 10 + max(0, int(mpmath.ceil(-mpmath.log10(th))))
    _, _, r2, r3 = contact_vector(body)
    ratio = (r3 * sp.sin(theta) - r2 * sp.cos(theta)) / r2 if family == "cm-at-rest" else -1 / sp.cos(theta)
    r = row1(model)
    symbols = [p.symbol for p in model.parameters]
    with mpmath.workdps(digits):
        th = mpmath.mpf(theta_value)
        pv = {p.name: mpmath.mpf(sp.N(sp.nsimplify(params[p.name]) if p.name in params else p.default, digits))
              for p in model.parameters}
        args = [pv[p.name] for p in model.parameters]
        at = lambda e: sp.lambdify([theta] + symbols, e, "mpmath")(th, *args)  # noqa: E731
        den = r2 if family == "cm-at-rest" else sp.cos(theta)
        if at(den) == 0:
            raise ValueError(f"no steady {family} family of {model.name} at theta = {theta_value} "
                             f"({'the contact is on the axis' if family == 'cm-at-rest' else 'cos(theta) = 0'})")
        k = at(ratio)
        alpha, beta, delta, gv = at(r.alpha), at(r.beta), at(r.delta), pv["g"]
        P = -delta * gv / (alpha + beta * k)
        if not P > 0:
            raise ValueError(f"no steady {family} motion of {model.name} at theta = {theta_value} "
                             f"(phidot^2 = {mpmath.nstr(P, 5)})")
        rate = mpmath.sqrt(P)
        state = {theta: th, phidot: rate, psidot: k * rate}
        values = [state.get(q, mpmath.mpf(0)) for q in STATE] + args
        f = lambda e: sp.lambdify(list(STATE) + symbols, e, "mpmath")(*values)  # noqa: E731
        checks = [model.accelerations[0]] + (list(model.velocity_xy) if family == "cm-at-rest" else [])
        for e in checks:  # the second route: the model's own thetaddot and v_C at the state
            if abs(f(e)) > mpmath.mpf(10) ** -40 * (1 + rate * rate * (1 + abs(k)) + gv):
                raise RuntimeError(f"{model.name}: the {family} state at theta = {theta_value} is not steady by the "
                                   f"model's own equations ({e} = {mpmath.nstr(f(e), 8)})")
        E = f(model.energy)
        paper, source = _paper_closed_form(body, pv, th)
        shown = {n: mpmath.nstr(v, 20) for n, v in pv.items()}
        return SpinDown(model.name, family, th, shown, rate, k * rate, E, source, paper, pv)


def _paper_closed_form(body, pv: dict, th) -> tuple:
    """(phidot, 'Eq. 45' or 'Eq. 61') where the body is the paper's disk or ring (:func:`body_spindown`), else (None, None)."""
    profile = body.values
    if body.kind == "point-rim" and profile.get("radius") == 1 and pv["I3"] == 2 * pv["I1"]:
        return mpmath.sqrt(pv["g"] / (pv["I1"] * mpmath.sin(th))), "Eq. 45"
    if body.kind == "two-rims" and profile.get("radius") == 1:
        h = pv["half_thickness"]
        return mpmath.sqrt(pv["g"] * (1 - h) / ((h ** 2 + pv["I1"]) * th)), "Eq. 61"
    return None, None


def to_record(s: SpinDown) -> dict:
    d = lambda x: None if x is None else mpmath.nstr(x, 20, strip_zeros=False)  # noqa: E731
    return {"model": s.model, "family": s.family, "theta": d(s.theta), "params": s.params,
            "phidot": d(s.phidot), "psidot": d(s.psidot), "energy": d(s.energy),
            "paper_formula": s.paper_source, "paper_phidot": d(s.paper_phidot), "relative_error": d(s.relative_error)}


# --- what diverges and what vanishes along a family ---------------------------------------

@lru_cache(maxsize=None)
def _quantity_functions(name: str):
    """Numeric functions (theta, phidot, psidot, *params) -> |omega|, |v_C|, |v_P|, N/(Mg), w2.

    v_P is the velocity of the geometric contact point over the floor: v_C plus the rate of
    the horizontal part of r_P = CP (thetadot = 0 on the family).  w2 is the stability
    coefficient of the reduced Jacobian (verify/studies/thresholds/linear.py), valid on steady motions.
    """
    from .thresholds import jacobian_entries  # lazy: heyoka (0.5 s), as in spindown()

    model = get_model(name)
    r2 = -1
    r3 = -model.parameter("h").symbol if name == "ring" else 0
    steady = {thetadot: 0}
    w = omega_body()
    omega = sp.sqrt(sum(c**2 for c in w)).subs(steady)
    vc = [e.subs(steady) for e in model.velocity_xy]
    rp = to_inertial(sp.Matrix([0, r2, r3]))
    vp = [(vc[i] + time_derivative(rp[i]).subs(steady)) for i in range(2)]
    a, c, d, e, f = jacobian_entries(model, {})
    exprs = [omega, sp.sqrt(vc[0] ** 2 + vc[1] ** 2), sp.sqrt(vp[0] ** 2 + vp[1] ** 2),
             model.normal_force.subs(steady), -(a + c * e + d * f)]
    syms = [theta, phi_symbol(), phidot, psidot] + [p.symbol for p in model.parameters]
    return sp.lambdify(syms, exprs, "mpmath")


def phi_symbol():
    return phi


def family_quantities(s: SpinDown) -> dict:
    """|omega|, centre-of-mass speed, contact-point speed, N/(Mg) and w2 at a steady state (50 digits)."""
    model = get_model(s.model)
    f = _quantity_functions(s.model)
    with mpmath.workdps(DPS + 10):
        args = [s.values[p.name] for p in model.parameters]
        omega, vc, vp, normal, w2 = f(s.theta, 0, s.phidot, s.psidot, *args)
    return {"omega": omega, "v_cm": vc, "v_contact": vp, "normal_force": normal, "w2": w2}


# --- precision: integrating the families near theta -> 0 -----------------------------------

PRECISIONS = ("double", "quad", "mp:160")
REFERENCE = "mp:256"
TURNS = 5


@dataclass(frozen=True)
class PrecisionRun:
    label: str
    precision: str
    theta0: str
    steps: int
    t_end: str
    theta_error: float  # |theta(T) - theta_ref(T)| / theta0
    omega3_error: float  # |omega3(T) - omega3_ref(T)| / |phidot0|
    omega3_scale: float  # |omega3| / |phidot| on the state (0 on the cm-at-rest family of the disk)
    cm_drift: float  # |x, y of C at T - reference| in units of R
    energy_drift: float  # max |E(t) - E(0)| / |E(0)| (InvariantTrace.max_rel_drift)


def _omega3(y):
    return y[5] + y[4] * mpmath.cos(y[0])


def precision_runs(label: str, state: dict, precisions=PRECISIONS, turns: int = TURNS) -> list:
    """Integrate ``state`` (decimal strings, disk) for ``turns`` turns of phi at every precision and
    compare the final state with a reference at REFERENCE; one PrecisionRun per precision."""
    from verify.engine.single import solve  # lazy: heyoka (0.4 s), as in spindown()

    with mpmath.workdps(80):
        t_end = mpmath.nstr(2 * mpmath.pi * turns / abs(mpmath.mpf(state["phidot"])), 40)
    ref = solve("disk", t_end, state, precision=REFERENCE, n_eval=2)
    with mpmath.workdps(80):
        yr = [ref.precision.to_mpf(v) for v in ref.y[:, -1]]
        y0 = [mpmath.mpf(state.get(n, "0")) for n in ("theta", "phi", "psi", "thetadot", "phidot", "psidot")]
        scale = abs(_omega3(y0) / y0[4])
    out = []
    for p in precisions:
        sol = solve("disk", t_end, state, precision=p, n_eval=2)
        with mpmath.workdps(80):
            y = [sol.precision.to_mpf(v) for v in sol.y[:, -1]]
            out.append(PrecisionRun(
                label, p, state["theta"], sol.steps, t_end,
                float(abs(y[0] - yr[0]) / y0[0]), float(abs(_omega3(y) - _omega3(yr)) / abs(y0[4])), float(scale),
                float(mpmath.sqrt((y[6] - yr[6]) ** 2 + (y[7] - yr[7]) ** 2)),
                float(sol.invariants["energy"].max_rel_drift)))
    return out


def family_state(theta_value: str, family: str) -> dict:
    s = spindown("disk", theta_value, family)
    return {"theta": theta_value, "phidot": mpmath.nstr(s.phidot, 45), "psidot": mpmath.nstr(s.psidot, 45)}
