"""Exact steady spin-down motions (thetadot = 0) of the disk and the ring (issue 4, part 2, begun).

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

import mpmath
import sympy as sp

from models import get_model
from models.symbols import STATE, phidot, psidot, theta, thetadot

FAMILIES = ("cm-at-rest", "zero-vertical-spin")
MODELS = ("disk", "ring")
DPS = 50


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

    @property
    def relative_error(self):
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
    from verify.integrate import resolve_parameters
    from verify.precision import parse_precision

    resolve_parameters(model, params, parse_precision("double"))  # names and ranges
    with mpmath.workdps(DPS + 10):
        try:
            th = mpmath.mpf(theta_value)
        except (ValueError, TypeError):
            raise ValueError(f"--theta {theta_value!r} is not a number") from None
        top = mpmath.pi / 2
        if not (mpmath.isfinite(th) and 0 < th < top):
            raise ValueError(f"--theta {theta_value} is outside (0, pi/2): the spin-down families need a leaning body")
        pv = {p.name: mpmath.mpf(sp.N(sp.nsimplify(params[p.name]) if p.name in params else p.default, DPS + 10))
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
        return SpinDown(name, family, th, shown, rate, psi_rate, E, source, paper)


def to_record(s: SpinDown) -> dict:
    d = lambda x: mpmath.nstr(x, 20, strip_zeros=False)
    return {"model": s.model, "family": s.family, "theta": d(s.theta), "params": s.params,
            "phidot": d(s.phidot), "psidot": d(s.psidot), "energy": d(s.energy),
            "paper_formula": s.paper_source, "paper_phidot": d(s.paper_phidot), "relative_error": d(s.relative_error)}
