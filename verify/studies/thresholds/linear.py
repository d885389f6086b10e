"""Linear stability of steady motions, exactly: the threshold spin rate (paper Eqs. 32, 41, 62, 70-72, 95).

For a steady motion (thetadot = 0, constant rates) of a body of revolution on the plane,
phiddot and psiddot carry a factor thetadot and thetaddot is even in thetadot, so the
Jacobian of the reduced system X = (theta, thetadot, phidot, psidot) has the shape

    [[0, 1, 0, 0], [a, 0, c, d], [0, e, 0, 0], [0, f, 0, 0]]

and its characteristic polynomial is lambda^2 (lambda^2 + w2), w2 = -(a + c e + d f).
The double zero belongs to the two-parameter family of steady motions (a perturbation
can move the body to a neighbouring member); the motion is linearly stable (oscillatory)
when w2 > 0, and the threshold is w2 = 0.  The shape is checked, not assumed.  The sleeping
motion (theta = 0) is linearised in the complex tilt instead (:func:`sleeping_coefficients`).
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Optional

import mpmath
import sympy as sp

from models import get_model
from models.steady import MOTIONS, exact_parameters, steady_state
from models.symbols import phidot, psidot, theta, thetadot

from ...engine.single import resolve_parameters
from ...mathtext import latex, symbol_latex
from ...precision import parse_precision

OMEGA = sp.Symbol("Omega", positive=True)


@dataclass(frozen=True)
class Threshold:
    """The critical rate of one steady motion of one model: ``value`` (None: no threshold), its closed form
    where there is one, how it was found, and w2 as a function of the rate."""

    model: str
    motion: str
    params: dict  # name -> decimal string
    name: str  # phidot0 | psidot0
    value: Optional[mpmath.mpf]  # None: no threshold (stable, or unstable, for every rate)
    closed_form: Optional[str]
    method: str
    w2: str  # the stability coefficient as a function of the rate (text)
    closed_form_tex: Optional[str] = None  # closed_form in LaTeX (without dollars), for the report


def jacobian_entries(model, steady: dict) -> tuple:
    """(a, c, d, e, f) of the reduced Jacobian at a steady state {theta, phidot, psidot} (thetadot = 0).

    The zero pattern of the module docstring is checked, not assumed.
    """
    X = [theta, thetadot, phidot, psidot]
    F = [thetadot] + list(model.accelerations)
    J = sp.Matrix([[sp.diff(f, x) for x in X] for f in F])
    at = {**steady, thetadot: 0}
    Js = J.subs(at)
    zero_pattern = [(0, 0), (0, 2), (0, 3), (1, 1), (2, 0), (2, 2), (2, 3), (3, 0), (3, 2), (3, 3)]
    for i, j in zero_pattern:
        if sp.simplify(Js[i, j]) != 0:
            raise RuntimeError(f"unexpected Jacobian entry ({i}, {j}) = {Js[i, j]}: not a steady motion of this shape")
    return Js[1, 0], Js[1, 2], Js[1, 3], Js[2, 1], Js[3, 1]


def stability_coefficient(model, steady: dict):
    """w2 at a steady state given as {theta, phidot, psidot} expressions (thetadot = 0)."""
    a, c, d, e, f = jacobian_entries(model, steady)
    return -(a + c * e + d * f)


def check_reading(params: dict, study: str) -> None:
    """Input validation: every parameter given as a decimal string must be read by the studies
    (``sp.nsimplify``, below and in spindown.py) as the number typed, to 15 digits.  nsimplify
    reads 1e-300 as 0 (and then divides by it) and 0.1111111111 as 1/9; such values are refused,
    naming what they would become."""
    tiny = sp.Rational(1, 10**15)
    for name, value in params.items():
        if not isinstance(value, str):
            continue
        try:
            exact = sp.Rational(value.strip())
        except (TypeError, ValueError, sp.SympifyError):
            continue  # not a decimal: resolve_parameters names it
        read = sp.nsimplify(value)
        if read != exact and (exact == 0 or abs((read - exact) / exact) > tiny):
            raise ValueError(f"parameter {name}={value}: the {study} would read it as {read} (sympy's nsimplify); allowed: "
                             "a value it keeps to 15 digits (magnitude above ~1e-30; a repeating decimal to 16 digits)")


def threshold(name: str, motion: str, params: Optional[dict] = None, dps: int = 30) -> Threshold:
    """The critical rate of ``motion`` for model ``name`` (parameters as decimal strings).

    Computed once per (name, motion, params, dps) in a process: the sympy linearisation costs
    0.1-2 s, and the brackets, the scan and the ring's comparison each ask for it again.
    """
    key = params_key(params)
    if key is None:
        return _threshold(name, motion, params, dps)
    t = _threshold_memo(name, motion, key, dps)
    return replace(t, params=dict(t.params))  # the caller's own dict, as from a fresh computation


def params_key(params: Optional[dict]):
    """``params`` as a hashable key that tells 1, 1.0 and "1" apart, or None if a value is not hashable."""
    try:
        key = tuple(sorted((k, type(v).__name__, v) for k, v in (params or {}).items()))
        hash(key)
    except TypeError:
        return None
    return key


@lru_cache(maxsize=None)
def _threshold_memo(name: str, motion: str, key: tuple, dps: int) -> Threshold:
    return _threshold(name, motion, {k: v for k, _, v in key}, dps)


def _threshold(name: str, motion: str, params: Optional[dict], dps: int) -> Threshold:
    if name not in MOTIONS:
        raise ValueError(f"model {name!r} has no threshold study; allowed: {', '.join(MOTIONS)}")
    if motion not in MOTIONS[name]:
        raise ValueError(f"motion {motion!r} for {name!r}; allowed: {', '.join(MOTIONS[name])}")
    model = get_model(name)
    params = dict(params or {})
    unknown = set(params) - set(model.parameter_names)
    if unknown:
        raise ValueError(f"unknown parameter {sorted(unknown)[0]!r}; allowed: {', '.join(model.parameter_names)}")
    values = resolve_parameters(model, params, parse_precision("double"))  # validates ranges
    check_reading(params, "threshold study")
    if name == "hurricane" and motion == "precession" and not values["I1"] > values["I3"]:
        # Eq. 72, cos(theta0) = (I3 - g/Omega^2)/(I1 - I3), is scanned from the slow-spin limit
        # sqrt(g/I3) upwards: that branch lies in 0 < theta0 < pi/2 only for I1 > I3.
        raise ValueError(f"hurricane precession with I1={values['I1']:g}, I3={values['I3']:g}: the Eq. 72 branch this "
                         "study scans (rates above sqrt(g/I3)) needs I1 > I3; allowed: I3 < I1")
    subs = exact_parameters(model, params)
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
    if motion == "sleeping":
        return _sleeping(name, model, subs, shown, dps)
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
                     "linearisation of the derived equations (sympy), closed form", sp.sstr(w2),
                     f"{symbol_latex(rate)}^2 = {latex(sp.simplify(crit**2))}")


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


OMEGA3 = sp.Symbol("omega3", real=True)


@lru_cache(maxsize=None)  # ~2 s of sympy series; a Model is hashable and never changes
def sleeping_coefficients(model) -> tuple:
    """(A, B) of the tilt equation u'' = A u + i B u' near theta = 0, u = theta exp(i phi).

    Euler angles are singular at theta = 0, so the sleeping state is linearised in the
    complex tilt u instead: with omega3 = psidot + phidot cos(theta) held (its rate is
    O(theta^2), checked) and theta = eps a, thetadot = eps b, the derived accelerations
    must take the form

        thetaddot = theta (phidot^2 + A - B phidot) + O(eps^2)
        theta phiddot + 2 thetadot phidot = B thetadot + O(eps),

    which are the real and imaginary parts of u'' = A u + i B u'.  The form is checked,
    not assumed.  u ~ exp(i s t) gives s^2 - B s + A = 0: the sleeping state is stable
    (both s real) when B^2 - 4 A > 0.
    """
    # Dummies: a body's own parameter may be called a (the ellipsoid's semi-axis) and would be taken for these
    eps, a, b = (sp.Dummy(n, positive=True) for n in ("epsilon", "a", "b"))
    spin = {psidot: OMEGA3 - phidot * sp.cos(theta)}
    small = {theta: eps * a, thetadot: eps * b}
    F1, F2, F3 = [e.subs(spin) for e in model.accelerations]
    tilt = sp.expand(sp.simplify(sp.series(F1.subs(small), eps, 0, 2).removeO() / (eps * a)))
    P = sp.Poly(tilt, phidot)
    if P.degree() != 2 or sp.simplify(P.coeff_monomial(phidot**2) - 1) != 0 or tilt.has(a, b, eps):
        raise RuntimeError(f"thetaddot/theta near theta = 0 is {tilt}: not of the form phidot^2 + A - B phidot")
    A = sp.simplify(P.coeff_monomial(1))
    B = sp.simplify(-P.coeff_monomial(phidot))
    azimuth = sp.series(F2.subs(small), eps, 0, 1).removeO()
    if sp.simplify(azimuth - (b / a) * (B - 2 * phidot)) != 0:
        raise RuntimeError(f"phiddot near theta = 0 is {azimuth}: not (thetadot/theta)(B - 2 phidot)")
    spin_rate = (F3 + F2 * sp.cos(theta) - phidot * thetadot * sp.sin(theta)).subs(small)
    if sp.simplify(sp.series(spin_rate, eps, 0, 2).removeO()) != 0:
        raise RuntimeError("omega3 is not conserved to first order in the tilt near theta = 0")
    return A, B


def _sleeping(name, model, subs, shown, dps) -> Threshold:
    A, B = sleeping_coefficients(model)
    disc = sp.simplify(B**2 - 4 * A)
    roots = [r for r in sp.solve(sp.Eq(disc.subs(OMEGA3, OMEGA), 0), OMEGA)]
    if len(roots) != 1:
        raise RuntimeError(f"{name} sleeping: B^2 - 4A = {disc} has roots {roots} in omega3 > 0")
    crit = sp.simplify(roots[0])
    with mpmath.workdps(dps):
        value = mpmath.mpf(sp.N(crit.subs(subs), dps + 10))
    return Threshold(name, "sleeping", shown, "phidot+psidot", value,
                     f"(phidot+psidot)^2 = {sp.sstr(sp.factor(crit**2))}",
                     "linearisation of the derived equations in the complex tilt u = theta exp(i phi) at theta = 0 "
                     f"(sympy): u'' = A u + i B u', A = {sp.sstr(A)}, B = {sp.sstr(B)}; stable while B^2 > 4A",
                     sp.sstr(disc),
                     f"(\\dot{{\\phi}} + \\dot{{\\psi}})^2 = {latex(sp.factor(crit**2))}")


# --- the steady state and the linearisation's coefficients, numerically (shared by the confirmations) -----

@lru_cache(maxsize=None)
def _exact_memo(name: str, key: tuple) -> dict:
    """The parameters of :func:`params_key`'s ``key`` as the exact numbers the study reads them as."""
    model = get_model(name)
    subs = exact_parameters(model, {k: v for k, _, v in key})
    return {p.name: subs[p.symbol] for p in model.parameters}


def steady_at(name, motion, rate, params) -> dict:
    """:func:`models.steady.steady_state` with the parameters read (``sp.nsimplify``, ~40 ms for the
    ring's three) once per set: handed on as the exact numbers it reads them as, every parameter
    given, so its result is the same dict."""
    key = params_key(params)
    return steady_state(name, motion, rate, params if key is None else _exact_memo(name, key))


@lru_cache(maxsize=None)
def linear_coefficients(name: str, motion: str, key: tuple):
    """Numeric functions of the steady state giving the linearised theta dynamics (``key``: the parameters'
    sorted items; see :func:`verify.studies.thresholds.growth.linear_deviation`)."""
    model = get_model(name)
    subs = exact_parameters(model, dict(key))
    if motion == "sleeping":
        A, B = sleeping_coefficients(model)
        return sp.lambdify(OMEGA3, (A.subs(subs), B.subs(subs)), "mpmath")
    entries = jacobian_entries(model, {})
    entries = [e.subs(subs) for e in entries]
    return sp.lambdify((theta, phidot, psidot), entries, "mpmath")
