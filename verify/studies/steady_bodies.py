"""Linear stability of the steady motions of any body of revolution: the threshold rates (issue 32, part 3).

The steady motions are :mod:`models.steady_bodies` (row 1 at thetadot = 0).  Linearised about one, with
theta = theta0 + small and the rates of the cyclic angles perturbed, the reduced system (theta, thetadot,
phidot, psidot) has the Jacobian [[0, 1, 0, 0], [a, 0, c, d], [0, e, 0, 0], [0, f, 0, 0]] (the zeros are
what :func:`models.steady_bodies.row1` checks: phiddot, psiddot vanish at thetadot = 0 and thetaddot is
even in it) and the characteristic polynomial lambda^2 (lambda^2 + w2), w2 = -(a + c e + d f) -- the
double zero is the two-parameter family of steady motions, i.e. Chaplygin's two linear integrals
(:mod:`verify.studies.thresholds` for the paper's bodies).  The motion is linearly stable (oscillatory)
while w2 > 0.  For every body w2 is a quadratic form in the rates plus a gravity term,

    w2 = q11(theta0) phidot^2 + q12(theta0) phidot psidot + q22(theta0) psidot^2 + l(theta0) g,

checked on the model (:func:`stability_form`), so that each motion's threshold is one equation:

* ``straight-line`` (phidot = 0 at theta_s): psidot0^2 = -g l/q22, closed form (sympy);
* ``diameter-spin`` on the line theta0 = theta_s (psidot = 0): phidot0^2 = -g l/q11, closed form;
* ``diameter-spin`` on a branch phidot^2 = -g delta/alpha: w2 = g (l - q11 delta/alpha), zero where
  q11 delta - l alpha = 0, a root in theta0 by mpmath at 45 digits, then phidot0;
* ``sleeping`` at theta0 = 0 (or pi, the body turned over): u'' = A u + i B u' in the complex tilt
  u = theta exp(i phi) (:func:`sleeping_form`, whose form is checked), stable while B^2 > 4A, closed
  form in omega3;
* the family at a fixed theta0 (:func:`family`): with psidot from row 1, phidot^2 w2 is a quadratic in
  phidot^2, closed form.

``python -m verify.studies.steady_bodies [BODY ...]`` prints the table of docs/bodies.md.
"""
from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict, dataclass
from functools import lru_cache
from typing import Optional

import mpmath
import sympy as sp

from models import get_model
from models.bodies import load, shipped
from models.steady_bodies import (
    DPS,
    domain,
    is_spin_line,
    mp,
    parameter_values,
    row1,
    sleeping_ends,
    spin_rate_squared,
    straight_line_angles,
    turned_over,
)
from models.symbols import g, phidot, psidot, theta, thetadot

from .thresholds import OMEGA3

#: Significant digits of a printed threshold (the computation carries DPS = 45).
DIGITS = 30
_RATE = sp.Symbol("Omega", positive=True)


@dataclass(frozen=True)
class Record:
    """One steady motion of a body and its linear stability threshold.

    ``value`` is the critical rate as a decimal string (``DIGITS`` significant digits), None where the
    motion keeps one stability for every rate (``stable`` = "every rate" or "no rate"); otherwise ``stable``
    says on which side of ``value`` the motion is stable ("above" or "below").  ``theta0`` is the steady
    tilt (on a branch: the tilt at the threshold), ``theta0_exact`` its closed form where sympy has one.
    """

    body: str
    motion: str  # straight-line | diameter-spin | sleeping
    branch: str  # where the motion lies: "theta0 = theta_s", "theta0(phidot0) on (lo, hi)", "theta0 = 0"
    theta0: str
    theta0_exact: Optional[str]
    rate: str  # psidot0 | phidot0 | phidot+psidot | psidot-phidot (omega3 at theta0 = 0 or pi)
    value: Optional[str]
    stable: str  # above | below | every rate | no rate
    closed_form: Optional[str]
    method: str
    params: dict  # name -> the value used, 20 digits

    def as_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class Form:
    """w2 = q11 phidot^2 + q12 phidot psidot + q22 psidot^2 + l g at thetadot = 0 (expressions of theta)."""

    w2: sp.Expr
    q11: sp.Expr
    q12: sp.Expr
    q22: sp.Expr
    l: sp.Expr
    s: sp.Expr  # c e + d f: with the rates kept, a tilt moves the body to a member displaced by -s tilt / w2


def _model(model):
    return get_model(model) if isinstance(model, str) else model


@lru_cache(maxsize=None)
def stability_form(model) -> Form:
    """The stability coefficient of ``model`` and its coefficients (module docstring).

    The quadratic form is read off by differentiation and checked at five points of the domain with
    arbitrary rates, g and the default parameters, at 45 digits: w2 minus the form must vanish to 1e-35 of
    the terms' size (a rational function that is not the form differs from it at almost every point).
    """
    row1(model)  # the zero pattern of the Jacobian
    F1, F2, F3 = model.accelerations
    at = {thetadot: 0}
    a, c, d = (sp.diff(F1, x).subs(at) for x in (theta, phidot, psidot))
    e, f = (sp.diff(F, thetadot).subs(at) for F in (F2, F3))
    w2 = -(a + c * e + d * f)
    zero = {phidot: 0, psidot: 0, g: 0}
    q11, q22 = (sp.diff(w2, x, 2).subs(zero) / 2 for x in (phidot, psidot))
    q12 = sp.diff(w2, phidot, psidot).subs(zero)
    l_ = sp.diff(w2, g).subs(zero)
    form = Form(w2, q11, q12, q22, l_, c * e + d * f)
    subs = parameter_values(model)
    names = (theta, phidot, psidot, g)
    lhs = sp.lambdify(names, w2.subs(subs), "mpmath")
    rhs = sp.lambdify(names, (q11 * phidot**2 + q12 * phidot * psidot + q22 * psidot**2 + l_ * g).subs(subs), "mpmath")
    with mpmath.workdps(DPS):
        lo, hi = domain(model, {})
        for i, (ph, ps, gv) in enumerate(((3, -7, 980), (-11, 2, 9.81), (0.5, 13, 100), (17, 0, 1), (-2, -19, 3000))):
            th = lo + (hi - lo) * mpmath.mpf(2 * i + 1) / 11
            x, y = lhs(th, ph, ps, gv), rhs(th, ph, ps, gv)
            if abs(x - y) > mpmath.mpf(10) ** -35 * (1 + abs(x) + abs(y)):
                raise RuntimeError(f"{model.name}: w2 is not a quadratic form in the rates plus a gravity term "
                                   f"(at theta = {mpmath.nstr(th, 8)}: {mpmath.nstr(x, 12)} against {mpmath.nstr(y, 12)})")
    return form


def _shown(model, subs) -> dict:
    return {p.name: str(sp.N(subs[p.symbol], 20)) for p in model.parameters}


def _side(coefficient, constant) -> tuple:
    """(critical rate^2 or None, stable side) of w2 = coefficient rate^2 + constant (numbers)."""
    if coefficient != 0 and -constant / coefficient > 0:
        return -constant / coefficient, "above" if coefficient > 0 else "below"
    if coefficient == 0 and constant == 0:
        raise RuntimeError("w2 vanishes identically along the motion: no linear verdict")
    positive = coefficient > 0 or (coefficient == 0 and constant > 0)
    return None, "every rate" if positive else "no rate"


def _line(model, motion, theta_s, value_s, subs, shown) -> Record:
    """A line theta0 = theta_s (straight line: rate psidot; diameter spin: rate phidot): a closed form where
    theta_s has one (``theta_s`` a sympy root), else the numbers at ``value_s`` (mpmath, 45 digits)."""
    form = stability_form(model)
    rate = "psidot0" if motion == "straight-line" else "phidot0"
    q = form.q22 if motion == "straight-line" else form.q11
    with mpmath.workdps(DPS):
        if theta_s is None:
            q_s, l_s = (sp.lambdify(theta, e.subs(subs), "mpmath")(value_s) for e in (q, form.l * g))
            value, stable = _side(q_s, l_s)
            th = mpmath.nstr(value_s, DIGITS)
            return Record(model.name, motion, f"theta0 = {th} at every rate", th, None, rate,
                          None if value is None else mpmath.nstr(mpmath.sqrt(value), DIGITS), stable, None,
                          f"linearisation of the model's equations at theta0 = {th}, the root of delta by mpmath "
                          f"(no closed form): {rate}^2 = -g l/q at 45 digits", shown)
    at = {theta: theta_s}
    crit2 = sp.simplify((-g * form.l / q).subs(at))
    with mpmath.workdps(DPS):
        value, stable = _side(mp(q.subs(at), subs), mp((form.l * g).subs(at), subs))
        text = None if value is None else mpmath.nstr(mpmath.sqrt(value), DIGITS)
        exact = mp(crit2, subs) if value is not None else None
        if exact is not None and abs(exact - value) > mpmath.mpf(10) ** (8 - DPS) * abs(value):
            raise RuntimeError(f"{model.name} {motion}: the closed form {crit2} gives {exact}, the numbers {value}")
        th = mpmath.nstr(mp(theta_s, subs), DIGITS)
    w2_line = (form.q22 * _RATE**2 if motion == "straight-line" else form.q11 * _RATE**2) + form.l * g
    return Record(model.name, motion, f"theta0 = {sp.sstr(theta_s)} at every rate", th, sp.sstr(theta_s), rate, text,
                  stable, None if value is None else f"{rate}^2 = {sp.sstr(crit2)}",
                  f"linearisation of the model's equations at theta0 = {sp.sstr(theta_s)} (sympy): w2 = "
                  f"{sp.sstr(sp.simplify(w2_line.subs(at)))} with {rate} = Omega; closed form", shown)


def _branch_records(model, subs, shown) -> list:
    """The psidot = 0 branches phidot^2 = -g delta/alpha > 0 and where w2 changes sign on them (numeric)."""
    form, r = stability_form(model), row1(model)
    speed2 = spin_rate_squared(model, {p.name: subs[p.symbol] for p in model.parameters})
    crit = sp.lambdify(theta, (form.q11 * r.delta - form.l * r.alpha).subs(subs), "mpmath")
    w2b = sp.lambdify(theta, (form.q11 * (-g * r.delta / r.alpha) + form.l * g).subs(subs), "mpmath")
    alpha = sp.lambdify(theta, r.alpha.subs(subs), "mpmath")
    out = []
    with mpmath.workdps(DPS):
        lo, hi = domain(model, subs)
        n = 1999  # odd: pi/2 is not a grid point of (0, pi) or (0, pi/2), where alpha and delta may vanish together
        grid = [lo + (hi - lo) * mpmath.mpf(i) / n for i in range(1, n)]
        valid = [abs(alpha(t)) > mpmath.mpf(10) ** -20 and speed2(t) > 0 for t in grid]
        runs, start = [], None
        for i, ok in enumerate(valid + [False]):
            if ok and start is None:
                start = i
            elif not ok and start is not None:
                runs.append((start, i - 1))
                start = None
        for i0, i1 in runs:
            if i1 - i0 < 2:
                continue
            pts = grid[i0:i1 + 1]
            span = f"theta0(phidot0) with phidot0^2 = -g delta/alpha, theta0 in ({mpmath.nstr(pts[0], 6)}, {mpmath.nstr(pts[-1], 6)})"
            vals = [crit(t) for t in pts]
            roots = [mpmath.findroot(crit, (a, b), solver="anderson")
                     for a, b, fa, fb in zip(pts, pts[1:], vals, vals[1:]) if fa * fb < 0]
            if not roots:
                stable = "every rate" if w2b(pts[len(pts) // 2]) > 0 else "no rate"
                out.append(Record(model.name, "diameter-spin", span, "-", None, "phidot0", None, stable, None,
                                  "linearisation along the branch (sympy rows, mpmath at 45 digits): w2 keeps one sign",
                                  shown))
                continue
            for t0 in roots:
                eps = mpmath.mpf(10) ** -12
                up = (speed2(t0 + eps) - speed2(t0 - eps)) * (w2b(t0 + eps) - w2b(t0 - eps)) > 0
                out.append(Record(model.name, "diameter-spin", span, mpmath.nstr(t0, DIGITS), None, "phidot0",
                                  mpmath.nstr(mpmath.sqrt(speed2(t0)), DIGITS), "above" if up else "below", None,
                                  "linearisation along the branch: w2 = g (l - q11 delta/alpha) = 0 where q11 delta = "
                                  "l alpha, root in theta0 by mpmath at 45 digits, then phidot0^2 = -g delta/alpha",
                                  shown))
    return out


def _at_zero(expr, order: int = 0):
    """The ``order``-th derivative at theta = 0 of sin(theta) ``expr``, whose limit it is (``order`` = 0) or gives
    (order 1: lim expr = d(sin(theta) expr)/d(theta) at 0 when sin(theta) expr vanishes there): a rational
    function of sin, cos (and the profile's square roots) evaluated at 0 where it is finite; a series otherwise."""
    k = sp.cancel(sp.sin(theta) * expr)
    value = sp.diff(k, theta, order).subs(theta, 0) if order else k.subs(theta, 0)
    if value.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
        value = sp.series(k, theta, 0, order + 1).removeO().coeff(theta, order) * sp.factorial(order)
    return sp.simplify(value)


@lru_cache(maxsize=None)
def sleeping_form(body) -> tuple:
    """(A, B) of the tilt equation u'' = A u + i B u' at theta = 0, u = theta exp(i phi), omega3 held.

    The form of :func:`verify.studies.thresholds.sleeping_coefficients`, reached by derivatives instead of a
    series of the whole rows (about a second for an ellipsoid instead of some forty): with psidot = omega3 -
    phidot cos(theta), row 1 vanishes at theta = 0 and is even in thetadot, so its first order in the tilt
    is theta d(thetaddot)/d(theta) at theta = thetadot = 0, which must be theta (phidot^2 + A - B phidot).
    The two other conditions are checked on the thetadot-coefficients of the other rows: theta phiddot /
    thetadot -> B - 2 phidot (the imaginary part of the tilt equation) and d(omega3)/dt = O(tilt^2).
    ``body`` is a model or a :class:`models.steady_bodies.TurnedOver`.
    """
    spin = {psidot: OMEGA3 - phidot * sp.cos(theta)}
    F1, F2, F3 = (F.subs(spin) for F in body.accelerations)
    if sp.cancel(F1.subs(thetadot, 0).subs(theta, 0)) != 0:
        raise RuntimeError(f"{body.name}: thetaddot does not vanish at theta = 0: not a sleeping motion")
    tilt = sp.cancel(sp.diff(F1, theta).subs(thetadot, 0).subs(theta, 0))
    P = sp.Poly(tilt, phidot)
    if P.degree() != 2 or sp.simplify(P.coeff_monomial(phidot**2) - 1) != 0:
        raise RuntimeError(f"{body.name}: thetaddot/theta at theta = 0 is {tilt}: not phidot^2 + A - B phidot")
    A, B = sp.factor(P.coeff_monomial(1)), sp.factor(-P.coeff_monomial(phidot))
    az = _at_zero(sp.diff(F2, thetadot).subs(thetadot, 0))
    if sp.simplify(az - (B - 2 * phidot)) != 0:
        raise RuntimeError(f"{body.name}: theta phiddot/thetadot at theta = 0 is {az}, not B - 2 phidot")
    spin_rate = (sp.diff(F3, thetadot) + sp.diff(F2, thetadot) * sp.cos(theta)).subs(thetadot, 0) - phidot * sp.sin(theta)
    if _at_zero(spin_rate) != 0 or _at_zero(spin_rate, 1) != 0:
        raise RuntimeError(f"{body.name}: omega3 is not held to first order in the tilt at theta = 0")
    return A, B


def _sleeping(model, end, subs, shown) -> Record:
    """Sleeping at theta0 = end (0: the model; pi: the model turned over), closed form in omega3."""
    body = model if end == 0 else turned_over(model)
    A, B = sleeping_form(body)
    disc = sp.factor(sp.simplify(B**2 - 4 * A))
    rate = "phidot+psidot" if end == 0 else "psidot-phidot"
    roots = [sp.simplify(x) for x in sp.solve(sp.Eq(disc.subs(OMEGA3, _RATE), 0), _RATE)]
    f = sp.lambdify(OMEGA3, disc.subs(subs), "mpmath")
    with mpmath.workdps(DPS):
        values = sorted((mp(x, subs), x) for x in roots if mp(sp.im(x), subs) == 0 and mp(x, subs) > 0)
        if len(values) > 1:
            raise RuntimeError(f"{model.name} sleeping at {end}: B^2 - 4A = {disc} has roots {roots}")
        if values:
            v, x = values[0]
            stable = "above" if f(2 * v) > 0 else "below"
            text, closed = mpmath.nstr(v, DIGITS), f"({rate})^2 = {sp.sstr(sp.factor(x**2))}"
        else:
            stable, text, closed = ("every rate" if f(1) > 0 else "no rate"), None, None
    turned = "" if end == 0 else " of the body turned over (e3 -> -e3, omega3 -> -omega3)"
    return Record(model.name, "sleeping", f"theta0 = {sp.sstr(end)}", mpmath.nstr(mp(end, subs), DIGITS),
                  sp.sstr(end), rate, text, stable, closed,
                  f"linearisation in the complex tilt u = theta exp(i phi) at theta = 0{turned} (sympy): "
                  f"u'' = A u + i B u', stable while B^2 - 4A = {sp.sstr(disc)} > 0", shown)


def thresholds(model, params: Optional[dict] = None) -> list:
    """Every steady motion of ``model`` with a stability threshold: a list of :class:`Record`.

    Parameters
    ----------
    model : Model or str
        A body's model (``models.bodies.model_of``, ``models.body_of_revolution``) or a name such as
        ``"body:rounded-coin"``; any model whose equations have the structure :func:`stability_form` checks.
    params : dict, optional
        Parameter overrides as decimal strings (``{"half_thickness": "0.4344"}``), read exactly.

    Returns
    -------
    list of Record
        Straight-line rolling at each root of delta, the diameter spin on each line and branch, and
        sleeping at each end of the domain where the contact lies on the axis.
    """
    model = _model(model)
    subs = parameter_values(model, params)
    shown = _shown(model, subs)
    values = {p.name: subs[p.symbol] for p in model.parameters}
    out = []
    for exact, value in straight_line_angles(model, values):
        out.append(_line(model, "straight-line", exact, value, subs, shown))
        if is_spin_line(model, exact if exact is not None else value, values):
            out.append(_line(model, "diameter-spin", exact, value, subs, shown))
    out.extend(_branch_records(model, subs, shown))
    for end in sleeping_ends(model, values):
        out.append(_sleeping(model, end, subs, shown))
    return out


@dataclass(frozen=True)
class Family:
    """The family at a fixed theta0: phidot^2 w2 = p4 phidot^4 + p2 phidot^2 + p0 with psidot from row 1."""

    theta0: str
    p4: str
    p2: str
    p0: str
    critical: tuple  # the phidot0 > 0 where w2 changes sign, decimal strings
    stable_at: tuple  # for each interval between them (from phidot0 -> 0 up), whether w2 > 0 there


def family(model, theta0, params: Optional[dict] = None) -> Family:
    """Stability along the family at ``theta0`` (a decimal string or number), closed form in phidot^2.

    With psidot = (p phidot^2 + s)/phidot, p = -alpha/beta, s = -g delta/beta (row 1), the form of
    :func:`stability_form` gives phidot^2 w2 = p4 phidot^4 + p2 phidot^2 + p0 with p4 = q11 + q12 p + q22 p^2,
    p2 = (q12 + 2 q22 p) s + l g, p0 = q22 s^2; its roots in phidot^2 > 0 are the thresholds.
    """
    model = _model(model)
    subs = parameter_values(model, params)
    form, r = stability_form(model), row1(model)
    with mpmath.workdps(DPS):
        th = mpmath.mpf(theta0)
        q11, q12, q22, l_, a, b, d = (sp.lambdify(theta, e.subs(subs), "mpmath")(th)
                                      for e in (form.q11, form.q12, form.q22, form.l, r.alpha, r.beta, r.delta))
        gv = mp(g, subs)
        p, s = -a / b, -gv * d / b
        p4, p2, p0 = q11 + q12 * p + q22 * p**2, (q12 + 2 * q22 * p) * s + l_ * gv, q22 * s**2
        if p4 == 0:
            roots = [] if p2 == 0 or -p0 / p2 <= 0 else [-p0 / p2]
        else:
            disc = p2**2 - 4 * p4 * p0
            roots = [] if disc < 0 else [(-p2 - sgn * mpmath.sqrt(disc)) / (2 * p4) for sgn in (-1, 1)]
        crit = sorted(mpmath.sqrt(x) for x in roots if x > 0)
        edges = [mpmath.mpf(0)] + crit + [None]
        probe = [(lo + hi) / 2 if hi is not None else 2 * lo + 1 for lo, hi in zip(edges, edges[1:])]
        stable = tuple(bool(p4 * x**4 + p2 * x**2 + p0 > 0) for x in probe)
        return Family(mpmath.nstr(th, DIGITS), *(mpmath.nstr(x, DIGITS) for x in (p4, p2, p0)),
                      tuple(mpmath.nstr(x, DIGITS) for x in crit), stable)


def stability_coefficient(model, state: dict, params: Optional[dict] = None):
    """w2 at a steady state {theta, phidot, psidot} (decimal strings or numbers), an mpmath number at 45
    digits; refused if row 1 does not vanish there to 1e-30 of its terms."""
    model = _model(model)
    subs = parameter_values(model, params)
    r = row1(model)
    names = (theta, phidot, psidot)
    with mpmath.workdps(DPS):
        x = [mpmath.mpf(state[k]) for k in ("theta", "phidot", "psidot")]
        terms = [sp.lambdify(names, e.subs(subs), "mpmath")(*x) for e in
                 (r.alpha * phidot**2, r.beta * phidot * psidot, r.delta * g)]
        if abs(sum(terms)) > mpmath.mpf(10) ** -30 * (1 + sum(abs(t) for t in terms)):
            raise ValueError(f"{model.name}: {state} is not a steady motion (row 1 = {mpmath.nstr(sum(terms), 8)})")
        return sp.lambdify(names, stability_form(model).w2.subs(subs), "mpmath")(*x)


def table(records) -> str:
    """The records as the Markdown table of docs/bodies.md (15 significant digits, as the suite prints)."""
    rows = ["| body | motion | theta0 | rate | threshold | stable | closed form |", "|---|---|---|---|---|---|---|"]
    for rec in records:
        value = "none" if rec.value is None else mpmath.nstr(mpmath.mpf(rec.value), 15)
        theta0 = rec.theta0_exact or (rec.theta0 if rec.theta0 == "-" else mpmath.nstr(mpmath.mpf(rec.theta0), 12))
        rows.append(f"| {rec.body} | {rec.motion} | {theta0} | {rec.rate} | {value} | {rec.stable} | "
                    f"{rec.closed_form or ('-' if rec.value is None else 'numeric')} |")
    return "\n".join(rows)


def main(argv=None) -> int:
    """``python -m verify.studies.steady_bodies [BODY ...] [--param NAME=VALUE] [--format json]``."""
    # a curve body (models.profile_curve) is left out of the default: sympy's analysis of its trigonometric
    # polynomials ran for more than ten minutes on the egg; name it to run it
    default = [n for n in shipped() if load(n).kind != "curve"]
    parser = argparse.ArgumentParser(prog="python -m verify.studies.steady_bodies", description=main.__doc__)
    parser.add_argument("bodies", nargs="*", help=f"shipped bodies (default: {', '.join(default)}; a curve body such "
                                                  "as egg only by name: slow)")
    parser.add_argument("--param", action="append", default=[], metavar="NAME=VALUE")
    parser.add_argument("--format", choices=("table", "json"), default="table")
    args = parser.parse_args(argv)
    params = dict(p.split("=", 1) for p in args.param)
    records = []
    for name in args.bodies or default:
        records.extend(thresholds(get_model(name if name.startswith("body:") else f"body:{name}"), params))
    print(json.dumps([r.as_dict() for r in records], indent=1) if args.format == "json" else table(records))
    return 0


if __name__ == "__main__":
    sys.exit(main())
