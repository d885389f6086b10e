"""Steady motions of any body of revolution, read off its own equations (issue 32, part 3).

A steady motion has thetadot = 0 and constant rates.  In the equations the suite derives for every body
(:func:`models.rolling.derive`, paper Eqs. 5-8 and 73) phiddot and psiddot carry a factor thetadot (the two
rows without thetaddot, which give Chaplygin's linear integrals; the paper's Eqs. 17-18, 50 and 80-81 show
it for its bodies) and thetaddot is even in thetadot, so thetadot = 0 with any theta0, phidot, psidot is
steady exactly where row 1 vanishes (the ring's Eq. 57 is this):

    alpha(theta0) phidot^2 + beta(theta0) phidot psidot + delta(theta0) g = 0        (row 1 at thetadot = 0)

with no psidot^2 term (with phidot = 0 the 1-2-3 frame does not turn, and a spin about e3 exerts no
couple) and delta proportional to r2 cos(theta) - r3 sin(theta), the slope of the height of C.  All of it is
checked on the model's own expressions (:func:`row1`), not assumed.  The motions:

* the family: theta0 and phidot != 0 given, psidot = -(alpha phidot^2 + delta g)/(beta phidot)
  (the paper's Eqs. 42-45 for the disk, 55-58 for the ring and 70-72 for the hurricane balls are members);
* ``straight-line``, phidot = 0 and any psidot: at a root theta_s of delta inside the domain, where r_P is
  vertical -- the disk upright, the ring at cot^-1 h (paper Eqs. 30-32; after Eq. 61), the rounded coin
  and the ellipsoids on their equator;
* ``diameter-spin``, psidot = 0: omega = phidot Z, the body turns about the vertical through the contact
  point (paper Eqs. 34-41, 62).  Either a branch phidot^2 = -g delta(theta0)/alpha(theta0) (the ring's
  Eq. 62) or, where alpha vanishes with delta (a body symmetric about its mid-plane, upright), the line
  theta0 = theta_s at every rate (the disk's, Eqs. 34-41);
* ``sleeping``: theta0 = 0 or pi, at an end of the domain where delta vanishes (the contact on the axis:
  the spheres, the ellipsoids), any omega3.  Euler angles are singular there; theta0 = pi is theta0 = 0
  of the body turned over (:func:`turned_over`).

Stability is :mod:`verify.studies.steady_bodies`.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Optional

import mpmath
import sympy as sp

from .symbols import g, phidot, psidot, theta, thetadot

#: Working digits of every numeric step here (parameters, roots): beyond the 30 the thresholds print.
DPS = 45


@dataclass(frozen=True)
class Row1:
    """Row 1 at thetadot = 0 as numerator / denominator, numerator = alpha phidot^2 + beta phidot psidot + delta g."""

    alpha: sp.Expr
    beta: sp.Expr
    delta: sp.Expr
    denominator: sp.Expr


@lru_cache(maxsize=None)
def row1(model) -> Row1:
    """The steady condition of ``model`` (module docstring), with the structure that makes it one checked.

    Raises
    ------
    RuntimeError
        If phiddot or psiddot do not vanish at thetadot = 0, thetaddot is not even in thetadot, or row 1's
        numerator has a monomial other than phidot^2, phidot psidot and g: then thetadot = 0 is not a
        two-parameter family of steady motions and nothing below applies.
    """
    F1, F2, F3 = model.accelerations
    for label, F in (("phiddot", F2), ("psiddot", F3)):
        if sp.cancel(F.subs(thetadot, 0)) != 0:
            raise RuntimeError(f"{model.name}: {label} does not vanish at thetadot = 0")
    if sp.cancel(sp.diff(F1, thetadot).subs(thetadot, 0)) != 0:
        raise RuntimeError(f"{model.name}: thetaddot is not even in thetadot")
    num, den = sp.fraction(sp.together(F1.subs(thetadot, 0)))
    poly = sp.Poly(sp.expand(num), phidot, psidot, g)
    extra = set(poly.as_dict()) - {(2, 0, 0), (1, 1, 0), (0, 0, 1)}
    if extra:
        raise RuntimeError(f"{model.name}: row 1 at thetadot = 0 has monomials {sorted(extra)} of (phidot, psidot, g)")
    alpha, beta, delta = (poly.coeff_monomial(m) for m in (phidot**2, phidot * psidot, g))
    return Row1(sp.factor_terms(alpha), sp.factor_terms(beta), sp.factor_terms(delta), den)


def parameter_values(model, params: Optional[dict] = None) -> dict:
    """symbol -> exact value: ``params`` (decimal strings read by ``sp.nsimplify`` as in :mod:`models.steady`,
    or exact numbers) over the model's defaults; an unknown name is refused naming the allowed ones."""
    params = dict(params or {})
    unknown = sorted(set(params) - set(model.parameter_names))
    if unknown:
        raise ValueError(f"unknown parameter {unknown[0]!r} for {model.name}; allowed: {', '.join(model.parameter_names)}")
    out = {}
    for p in model.parameters:
        v = params.get(p.name, p.default)
        out[p.symbol] = sp.nsimplify(v) if isinstance(v, str) else sp.sympify(v)
    return out


def mp(expr, subs: dict):
    """``expr`` with ``subs`` as an mpmath number at the working precision (evaluated exactly by sympy at DPS + 10)."""
    return mpmath.mpf(sp.N(sp.sympify(expr).subs(subs), DPS + 10))


def domain(model, subs: dict) -> tuple:
    """The model's open domain (theta_min, theta_max) as mpmath numbers."""
    return mp(model.domain.theta_min, subs), mp(model.domain.theta_max, subs)


def _numeric_roots(f, lo, hi, n: int = 2000) -> list:
    """Roots of f (mpmath) where it changes sign on a grid of n cells strictly inside (lo, hi), refined by bisection
    to the working precision (anderson where it converges)."""
    grid = [lo + (hi - lo) * mpmath.mpf(i) / n for i in range(1, n)]
    vals = [f(t) for t in grid]
    roots = []
    for (a, fa), (b, fb) in zip(zip(grid, vals), zip(grid[1:], vals[1:])):
        if fa == 0:
            roots.append(a)
        elif fa * fb < 0:
            roots.append(mpmath.findroot(f, (a, b), solver="anderson"))
    return roots


def straight_line_angles(model, params: Optional[dict] = None) -> list:
    """The roots theta_s of delta strictly inside the domain: [(exact sympy root or None, mpmath value)].

    sympy's ``solve`` gives them exactly (``pi/2``, ``atan(1/half_thickness)``); a scan for sign changes of
    delta on 2000 cells of the domain at the parameters must find the same number (it would see a root
    ``solve`` missed), and where ``solve`` cannot, the scan's roots are returned without a closed form.
    """
    subs = parameter_values(model, params)
    delta = row1(model).delta
    with mpmath.workdps(DPS):
        lo, hi = domain(model, subs)
        f = sp.lambdify(theta, delta.subs(subs), "mpmath")
        scanned = _numeric_roots(f, lo, hi)
        try:
            exact = sp.solve(delta, theta)
        except NotImplementedError:
            return [(None, r) for r in scanned]
        numbers = ((r, sp.N(r.subs(subs), DPS + 10)) for r in exact)
        inside = sorted(((r, mpmath.mpf(v)) for r, v in numbers if v.is_real), key=lambda rv: rv[1])
        inside = [(r, v) for r, v in inside if lo < v < hi and not (mpmath.almosteq(v, lo, 1e-30) or
                                                                   mpmath.almosteq(v, hi, 1e-30))]
        if len(inside) != len(scanned) or any(abs(v - s) > mpmath.mpf(10) ** (10 - DPS) for (_, v), s in zip(inside, scanned)):
            raise RuntimeError(f"{model.name}: sympy's roots of delta {[v for _, v in inside]} and the scan's {scanned} "
                               "disagree")
        return inside


def is_spin_line(model, theta_s, params: Optional[dict] = None) -> bool:
    """Whether alpha vanishes at the straight-line angle ``theta_s`` too: then theta0 = theta_s is steady with
    psidot = 0 at every phidot (the diameter spin of a body symmetric about its mid-plane).  Exactly for a
    sympy root; for an mpmath one, to 1e-30 of alpha's size over the domain."""
    subs = parameter_values(model, params)
    alpha = row1(model).alpha.subs(subs)
    if not isinstance(theta_s, mpmath.mpf):
        return sp.simplify(alpha.subs(theta, theta_s)) == 0
    f = sp.lambdify(theta, alpha, "mpmath")
    with mpmath.workdps(DPS):
        lo, hi = domain(model, subs)
        size = max(abs(f(lo + (hi - lo) * mpmath.mpf(i) / 7)) for i in range(1, 7))
        return abs(f(theta_s)) < mpmath.mpf(10) ** -30 * size


def sleeping_ends(model, params: Optional[dict] = None) -> list:
    """The ends 0 and pi of the domain where delta vanishes (exactly, at the parameters): where the body can sleep."""
    subs = parameter_values(model, params)
    delta = row1(model).delta.subs(subs)
    out = []
    for end in (model.domain.theta_min, model.domain.theta_max):
        if end in (sp.Integer(0), sp.pi) and sp.simplify(delta.subs(theta, end)) == 0:
            out.append(end)
    return out


@dataclass(frozen=True)
class TurnedOver:
    """The equations of a body described with e3 reversed: enough for the linearisation at theta = 0.

    Turning the body frame by pi about e1 maps the 3-1-3 angles to phi' = phi + pi, theta' = pi - theta,
    psi' = -psi - pi (Rz(psi) Rx(pi) = Rx(pi) Rz(-psi), Rx(theta + pi) = Rz(pi) Rx(pi - theta) Rz(-pi)), so
    thetaddot' = -thetaddot, phiddot' = phiddot, psiddot' = -psiddot at (pi - theta, -thetadot, phidot,
    -psidot), and omega3' = -omega3: theta = pi of the body is theta' = 0 of this one.  The contact vector
    becomes (0, r2(pi - theta), -r3(pi - theta)) (the tests compare it with a derivation of that body).
    """

    name: str
    accelerations: tuple


@lru_cache(maxsize=None)
def turned_over(model) -> TurnedOver:
    """The equations of ``model`` turned over (:class:`TurnedOver`)."""
    flip = {theta: sp.pi - theta, thetadot: -thetadot, psidot: -psidot}
    F1, F2, F3 = (F.subs(flip, simultaneous=True) for F in model.accelerations)
    return TurnedOver(f"{model.name} turned over", (-F1, F2, -F3))


def family_psidot(model, theta0, rate, params: Optional[dict] = None):
    """psidot of the family member at (theta0, phidot = rate != 0): row 1 solved, an mpmath number."""
    subs = parameter_values(model, params)
    r = row1(model)
    with mpmath.workdps(DPS):
        th, w = mpmath.mpf(theta0), mpmath.mpf(rate)
        a, b, d = (sp.lambdify(theta, e.subs(subs), "mpmath")(th) for e in (r.alpha, r.beta, r.delta))
        return -(a * w**2 + d * mp(g, subs)) / (b * w)


def spin_rate_squared(model, params: Optional[dict] = None):
    """theta -> phidot^2 = -g delta/alpha on the psidot = 0 branch (mpmath; negative where there is none)."""
    subs = parameter_values(model, params)
    r = row1(model)
    ratio = sp.lambdify(theta, (-g * r.delta / r.alpha).subs(subs), "mpmath")
    return ratio


def spin_branch_angle(model, rate, guess, params: Optional[dict] = None):
    """theta0 of the psidot = 0 branch at phidot = ``rate``: the root of alpha rate^2 + delta g nearest ``guess``."""
    subs = parameter_values(model, params)
    r = row1(model)
    f = sp.lambdify((theta, phidot), (r.alpha * phidot**2 + r.delta * g).subs(subs), "mpmath")
    with mpmath.workdps(DPS):
        w = mpmath.mpf(rate)
        return mpmath.findroot(lambda t: f(t, w), mpmath.mpf(guess))


def steady_state(model, motion: str, rate, theta0, params: Optional[dict] = None, branch: bool = False) -> dict:
    """The steady motion at ``rate`` as 36-digit decimal strings (theta, phidot, psidot).

    Parameters
    ----------
    model
        A body's model.
    motion : {"straight-line", "diameter-spin", "sleeping", "family"}
        phidot = 0, psidot = rate at theta0; phidot = rate, psidot = 0 at theta0 (``branch``: theta0 is only
        a guess, the branch's angle at the rate is solved for); theta0 (0 or pi) with phidot = 0 and
        omega3 = psidot = rate (the caller adds the tilt); phidot = rate with psidot from row 1.
    rate, theta0
        Decimal strings or numbers.
    """
    with mpmath.workdps(DPS):
        w, th = mpmath.mpf(rate), mpmath.mpf(theta0)
        if motion == "straight-line":
            phd, psd = mpmath.mpf(0), w
        elif motion == "diameter-spin":
            th = spin_branch_angle(model, w, th, params) if branch else th
            phd, psd = w, mpmath.mpf(0)
        elif motion == "sleeping":
            phd, psd = mpmath.mpf(0), w
        elif motion == "family":
            phd, psd = w, family_psidot(model, th, w, params)
        else:
            raise ValueError(f"motion {motion!r}; allowed: straight-line, diameter-spin, sleeping, family")
        return {"theta": mpmath.nstr(th, 36), "phidot": mpmath.nstr(phd, 36), "psidot": mpmath.nstr(psd, 36)}


__all__ = ["DPS", "Row1", "TurnedOver", "domain", "family_psidot", "is_spin_line", "parameter_values", "row1",
           "sleeping_ends", "spin_branch_angle", "spin_rate_squared", "steady_state", "straight_line_angles",
           "turned_over"]
