"""What a couple does on the disk's centre-of-mass-at-rest family, in closed form (sympy; item 1 of the
package docstring)."""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from models import disk
from models.dissipative import dissipative_disk, law as get_law, work_rate
from models.rolling import derive
from models.symbols import phidot, psidot, theta, thetadot


theta0 = sp.Symbol("theta0", positive=True)


@dataclass(frozen=True)
class FamilyLaw:
    """What the couple does on the disk's centre-of-mass-at-rest family, in closed form.

    Every expression is derived from the model (the energy and row 1 of the derived
    equations, the velocity of C, the couple's work rate); nothing is typed in.
    """

    law: str
    exponent: int  # n of the couple
    phidot_squared: sp.Expr  # phidot^2 on the family (paper Eq. 45)
    energy: sp.Expr  # E(theta) on the family, per m R^2
    power: sp.Expr  # dissipated power on the family, >= 0
    rate: sp.Expr  # dtheta/dt = -power / (dE/dtheta)
    rate_coefficient: sp.Expr  # A in dtheta/dt ~ -A theta^m
    rate_exponent: sp.Rational  # m
    phidot_exponent: sp.Rational  # r in phidot ~ theta^r
    p: sp.Rational  # theta ~ (t0 - t)^p
    q: sp.Rational  # phidot ~ (t0 - t)^q
    time_to_singularity: sp.Expr  # t0 from theta0 (symbol theta0)
    turns_to_singularity: sp.Expr  # turns of phi from theta0 to theta = 0

    @property
    def finite_time(self) -> bool:
        return _finite(self.time_to_singularity)

    @property
    def finite_turns(self) -> bool:
        return _finite(self.turns_to_singularity)


def _finite(expr: sp.Expr) -> bool:
    return not expr.has(sp.oo, -sp.oo, sp.zoo, sp.nan, sp.Integral)


def _family_substitution():
    """psidot on the cm-at-rest family: v_C = 0 at thetadot = 0, solved from the derived v_C."""
    d = derive(disk.k, 2 * disk.k, disk.R2, disk.R3, "rolling")
    eqs = [e for e in d.velocity_cm.subs(thetadot, 0) if e != 0]
    sol = sp.solve(eqs, psidot, dict=True)
    if len(sol) != 1:
        raise RuntimeError("v_C = 0 does not fix psidot uniquely")
    return {thetadot: 0, psidot: sol[0][psidot]}


@lru_cache(maxsize=None)
def family_law(name: str) -> FamilyLaw:
    """Closed-form laws of the ``name`` couple on the cm-at-rest family (module docstring, item 1)."""
    lw = get_law(name)
    model = dissipative_disk(name)
    fam = _family_substitution()
    P2 = sp.Symbol("P2", positive=True)
    row = sp.numer(sp.together(model.accelerations[0].subs(fam)))  # thetaddot = 0 on a steady motion
    roots = sp.solve(sp.expand(row).subs(phidot, sp.sqrt(P2)), P2)
    if len(roots) != 1:
        raise RuntimeError(f"row 1 on the family gives {len(roots)} values of phidot^2")
    phidot2 = sp.simplify(roots[0])
    on = lambda e: sp.simplify(e.subs(fam).subs(phidot, sp.sqrt(phidot2)))
    energy, power = on(model.energy), on(work_rate(name))
    rate = sp.simplify(-power / sp.diff(energy, theta))
    A, m = _leading(-rate)
    _, r = _leading(sp.sqrt(phidot2))
    p = 1 / (1 - m)
    per_dtheta = 1 / (-rate)  # dt per unit fall of theta
    t0 = _integral_from_zero(per_dtheta)
    turns = sp.simplify(_integral_from_zero(sp.sqrt(phidot2) * per_dtheta) / (2 * sp.pi))
    return FamilyLaw(name, lw.exponent, phidot2, energy, power, rate, A, m, r, p, p * r, t0, turns)


def _integral_from_zero(expr) -> sp.Expr:
    """int_0^theta0 expr d(theta), through u = sin(theta) (0 < theta < pi/2; sympy's own
    route through heurisch takes tens of seconds on these integrands)."""
    u = sp.Symbol("u", positive=True)
    integrand = sp.expand_trig(sp.simplify(expr / sp.cos(theta)))
    integrand = sp.simplify(integrand.subs(sp.cos(theta), sp.sqrt(1 - u ** 2)).subs(sp.sin(theta), u))
    if integrand.has(theta):
        raise RuntimeError(f"cannot write {expr} d(theta) in u = sin(theta)")
    return sp.simplify(sp.integrate(integrand, (u, 0, sp.sin(theta0))))


def _leading(expr):
    """(A, m) with expr ~ A theta^m as theta -> 0+: m = lim theta d(log expr)/d(theta), A = lim expr / theta^m."""
    m = sp.limit(sp.simplify(theta * sp.diff(sp.log(expr), theta)), theta, 0, "+")
    A = sp.simplify(sp.limit(sp.simplify(expr / theta ** m), theta, 0, "+"))
    if not m.is_Rational or A.has(theta) or not _finite(A) or A == 0:
        raise RuntimeError(f"no leading power of theta in {expr}")
    return A, m
