"""Linear stability of steady motions, exactly: the threshold spin rate (issue 4, part 1).

For a steady motion (thetadot = 0, constant rates) of a body of revolution on the plane,
phiddot and psiddot carry a factor thetadot and thetaddot is even in thetadot, so the
Jacobian of the reduced system X = (theta, thetadot, phidot, psidot) has the shape

    [[0, 1, 0, 0], [a, 0, c, d], [0, e, 0, 0], [0, f, 0, 0]]

and its characteristic polynomial is lambda^2 (lambda^2 + w2), w2 = -(a + c e + d f).
The double zero belongs to the two-parameter family of steady motions (a perturbation
can move the body to a neighbouring member); the motion is linearly stable (oscillatory)
when w2 > 0, and the threshold is w2 = 0.  The shape is checked, not assumed.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import mpmath
import sympy as sp

from models import get_model
from models.symbols import phidot, psidot, theta, thetadot

MOTIONS = {
    "disk": ("diameter-spin", "straight-line"),
    "sliding-disk": ("diameter-spin",),
    "ring": ("diameter-spin", "straight-line"),
    "hurricane": ("precession",),
}
OMEGA = sp.Symbol("Omega", positive=True)


@dataclass(frozen=True)
class Threshold:
    model: str
    motion: str
    params: dict  # name -> decimal string
    name: str  # phidot0 | psidot0
    value: Optional[mpmath.mpf]  # None: no threshold (stable, or unstable, for every rate)
    closed_form: Optional[str]
    method: str
    w2: str  # the stability coefficient as a function of the rate (text)


def stability_coefficient(model, steady: dict):
    """w2 at a steady state given as {theta, phidot, psidot} expressions (thetadot = 0)."""
    X = [theta, thetadot, phidot, psidot]
    F = [thetadot] + list(model.accelerations)
    J = sp.Matrix([[sp.diff(f, x) for x in X] for f in F])
    at = {**steady, thetadot: 0}
    Js = J.subs(at)
    zero_pattern = [(0, 0), (0, 2), (0, 3), (1, 1), (2, 0), (2, 2), (2, 3), (3, 0), (3, 2), (3, 3)]
    for i, j in zero_pattern:
        if sp.simplify(Js[i, j]) != 0:
            raise RuntimeError(f"unexpected Jacobian entry ({i}, {j}) = {Js[i, j]}: not a steady motion of this shape")
    a, c, d, e, f = Js[1, 0], Js[1, 2], Js[1, 3], Js[2, 1], Js[3, 1]
    return -(a + c * e + d * f)


def _params(model, values: dict) -> dict:
    out = {}
    for p in model.parameters:
        v = values.get(p.name, p.default)
        out[p.symbol] = sp.nsimplify(v) if isinstance(v, str) else sp.sympify(v)
    return out


def to_record(t: Threshold, nonlinear=None) -> dict:
    """The JSON object of ``python -m verify threshold --format json``; ``nonlinear`` is (tilt, (lo, hi))."""
    return {
        "model": t.model,
        "motion": t.motion,
        "params": t.params,
        "threshold": {"name": t.name, "value": None if t.value is None else mpmath.nstr(t.value, 20, strip_zeros=False)},
        "closed_form": t.closed_form,
        "method": t.method,
        "bracket": None if not nonlinear or nonlinear[1] is None else {
            "tilt": nonlinear[0], "low": mpmath.nstr(nonlinear[1][0], 12), "high": mpmath.nstr(nonlinear[1][1], 12),
            "method": f"bisection on the rate; theta perturbed by the tilt, grows = leaves the domain or moves more than "
                      f"{GROWTH} x the tilt within 10 s (double, derived equations)"},
    }


def threshold(name: str, motion: str, params: Optional[dict] = None, dps: int = 30) -> Threshold:
    """The critical rate of ``motion`` for model ``name`` (parameters as decimal strings)."""
    if name not in MOTIONS:
        raise ValueError(f"model {name!r} has no threshold study; allowed: {', '.join(MOTIONS)}")
    if motion not in MOTIONS[name]:
        raise ValueError(f"motion {motion!r} for {name!r}; allowed: {', '.join(MOTIONS[name])}")
    model = get_model(name)
    params = dict(params or {})
    unknown = set(params) - set(model.parameter_names)
    if unknown:
        raise ValueError(f"unknown parameter {sorted(unknown)[0]!r}; allowed: {', '.join(model.parameter_names)}")
    from verify.integrate import resolve_parameters
    from verify.precision import parse_precision

    resolve_parameters(model, params, parse_precision("double"))  # validates ranges
    subs = _params(model, params)
    shown = {p.name: str(sp.N(subs[p.symbol], 20)) for p in model.parameters}
    if motion in ("diameter-spin", "straight-line") and name in ("disk", "sliding-disk"):
        steady = {theta: sp.pi / 2, phidot: OMEGA, psidot: 0} if motion == "diameter-spin" else \
                 {theta: sp.pi / 2, phidot: 0, psidot: OMEGA}
        return _closed(name, motion, model, steady, subs, shown, dps)
    if name == "ring" and motion == "straight-line":
        h = model.parameter("h").symbol
        steady = {theta: sp.acot(h), phidot: 0, psidot: OMEGA}
        return _closed(name, motion, model, steady, subs, shown, dps)
    if name == "ring" and motion == "diameter-spin":
        return _ring_diameter(model, subs, shown, dps)
    return _hurricane_precession(model, subs, shown, dps)


def _closed(name, motion, model, steady, subs, shown, dps) -> Threshold:
    w2 = sp.simplify(stability_coefficient(model, steady))
    roots = sp.solve(sp.Eq(w2, 0), OMEGA)
    if len(roots) != 1:
        raise RuntimeError(f"{name} {motion}: w2 = {w2} has roots {roots}")
    crit = sp.simplify(roots[0])
    with mpmath.workdps(dps):
        value = mpmath.mpf(sp.N(crit.subs(subs), dps + 10))
    rate = "phidot0" if motion == "diameter-spin" else "psidot0"
    return Threshold(name, motion, shown, rate, value, f"{rate}^2 = {sp.sstr(sp.simplify(crit**2))}",
                     "linearisation of the derived equations (sympy), closed form", sp.sstr(w2))


def _ring_diameter(model, subs, shown, dps) -> Threshold:
    """theta0(phidot0) is the root of row 1 with psidot = 0 (Eq. 62); w2 along that branch."""
    th0 = sp.Symbol("theta0")
    steady = {theta: th0, phidot: OMEGA, psidot: 0}
    w2 = stability_coefficient(model, steady).subs(subs)
    row1 = model.accelerations[0].subs({thetadot: 0, psidot: 0, phidot: OMEGA}).subs(subs).subs(theta, th0)
    f_row = sp.lambdify((th0, OMEGA), sp.numer(sp.together(row1)), "mpmath")
    f_w2 = sp.lambdify((th0, OMEGA), w2, "mpmath")
    h = float(subs[model.parameter("h").symbol])

    def branch(rate):
        lo = mpmath.acot(mpmath.mpf(h))
        return mpmath.findroot(lambda t: f_row(t, rate), (lo, mpmath.pi / 2 - mpmath.mpf("1e-9")), solver="anderson")

    with mpmath.workdps(dps):
        g = lambda rate: f_w2(branch(rate), rate)
        # bracket the sign change of w2 on a grid of rates, then refine
        rates = [mpmath.mpf(r) for r in (5, 10, 15, 20, 25, 30, 40, 60, 100)]
        signs = [(r, g(r)) for r in rates]
        pair = next(((a, b) for (a, fa), (b, fb) in zip(signs, signs[1:]) if fa * fb < 0), None)
        if pair is None:
            raise RuntimeError(f"ring diameter spin: w2 does not change sign on {rates}: {[float(v) for _, v in signs]}")
        value = mpmath.findroot(g, pair, solver="anderson")
    return Threshold("ring", "diameter-spin", shown, "phidot0", value, None,
                     "linearisation of the derived equations along the Eq. 62 branch; root by mpmath", "numeric")


def _hurricane_precession(model, subs, shown, dps) -> Threshold:
    """Steady precession psidot = phidot = Omega, cos(theta0) = (I3 - g/Omega^2)/(I1 - I3) (Eqs. 70-72)."""
    I1, I3 = model.parameter("I1").symbol, model.parameter("I3").symbol
    g = model.parameter("g").symbol
    C = sp.Symbol("C")
    steady = {theta: sp.acos(C), phidot: OMEGA, psidot: OMEGA}
    w2 = sp.simplify(stability_coefficient(model, steady).subs(C, (I3 - g / OMEGA**2) / (I1 - I3)))
    w2n = sp.lambdify(OMEGA, w2.subs(subs), "mpmath")
    low = sp.sqrt(g / I3).subs(subs)  # cos(theta0) = 0: the upper ball touches the plane
    with mpmath.workdps(dps):
        grid = [mpmath.mpf(sp.N(low, dps)) * (1 + mpmath.mpf(i) / 20) for i in range(1, 200)]
        vals = [w2n(r) for r in grid]
        pair = next(((a, b) for a, b, fa, fb in zip(grid, grid[1:], vals, vals[1:]) if fa * fb < 0), None)
        if pair is None:
            verdict = "stable" if all(v > 0 for v in vals) else "unstable"
            return Threshold("hurricane", "precession", shown, "phidot0", None, None,
                             f"linearisation along Eq. 72: w2 has one sign, linearly {verdict} for every rate from the "
                             f"slow-spin limit sqrt(g/I3) = {mpmath.nstr(grid[0] / (1 + mpmath.mpf(1) / 20), 12)} to 10 times it",
                             "numeric")
        value = mpmath.findroot(w2n, pair, solver="anderson")
    return Threshold("hurricane", "precession", shown, "phidot0", value, None,
                     "linearisation of the derived equations along Eq. 72; root by mpmath", "numeric")


# --- confirmation by the full nonlinear equations ----------------------------------------

GROWTH = 1000  # a run "grows" when theta leaves its steady value by more than GROWTH x the tilt


def steady_state(name: str, motion: str, rate, params: dict) -> dict:
    """The steady motion at ``rate`` as decimal strings (theta, phidot, psidot), 30 digits."""
    model = get_model(name)
    subs = _params(model, params)
    pv = {p.name: mpmath.mpf(sp.N(subs[p.symbol], 40)) for p in model.parameters}
    with mpmath.workdps(30):
        rate = mpmath.mpf(rate)
        if name in ("disk", "sliding-disk"):
            th, phd, psd = mpmath.pi / 2, (rate if motion == "diameter-spin" else 0), (rate if motion == "straight-line" else 0)
        elif motion == "straight-line":
            th, phd, psd = mpmath.acot(pv["h"]), 0, rate
        elif name == "ring":
            row1 = model.accelerations[0].subs({thetadot: 0, psidot: 0}).subs(subs)
            f = sp.lambdify((theta, phidot), sp.numer(sp.together(row1)), "mpmath")
            th = mpmath.findroot(lambda t: f(t, rate), (mpmath.acot(pv["h"]), mpmath.pi / 2 - mpmath.mpf("1e-9")),
                                 solver="anderson")
            phd, psd = rate, 0
        else:
            th = mpmath.acos((pv["I3"] - pv["g"] / rate**2) / (pv["I1"] - pv["I3"]))
            phd = psd = rate
        return {"theta": mpmath.nstr(th, 30), "phidot": mpmath.nstr(mpmath.mpf(phd), 30),
                "psidot": mpmath.nstr(mpmath.mpf(psd), 30)}


def grows(name, motion, rate, tilt, params, t_end="10") -> bool:
    """Perturb theta alone by ``tilt`` (rates kept: the body moves onto a neighbouring member of the
    family) and report whether theta leaves its steady value by more than GROWTH x tilt, or the
    run leaves the model's domain, within ``t_end``."""
    from verify.integrate import solve

    state = steady_state(name, motion, rate, params)
    th0 = mpmath.mpf(state["theta"])
    state["theta"] = mpmath.nstr(th0 + mpmath.mpf(tilt), 30)
    sol = solve(name, t_end, state, params, n_eval=401)
    if sol.outcome != "ok":
        return True
    dev = max(abs(float(v) - float(th0)) for v in sol["theta"])
    return dev > GROWTH * float(tilt)


def bracket(name: str, motion: str, tilt: str, params=None, iterations: int = 25, t_end: str = "10"):
    """Bisect the rate between growth and no growth, starting from [lin/2, 2 lin]."""
    params = dict(params or {})
    lin = threshold(name, motion, params).value
    if lin is None:
        return None
    lo, hi = lin / 2, lin * 2
    if not grows(name, motion, lo, tilt, params, t_end) or grows(name, motion, hi, tilt, params, t_end):
        raise RuntimeError(f"{name} {motion}: no sign change of the growth test on [{lo}, {hi}] at tilt {tilt}")
    for _ in range(iterations):
        mid = (lo + hi) / 2
        if grows(name, motion, mid, tilt, params, t_end):
            lo = mid
        else:
            hi = mid
    return lo, hi
