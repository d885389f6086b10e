"""The paper's 'effective Lagrangian' for the hurricane balls (Eq. 96).

Holonomic by construction: psi = phi is imposed, the centre of mass moves only
vertically (x, y fixed).  The state keeps the common eight components; psidot must equal
phidot at the start and psi follows phi.  The printed potential -g cos(theta) is shifted
by the constant g so that, as for every model, the potential is zero on the plane
(z_C = a (1 + cos theta)).
"""
from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .base import Domain, Model
from .build import energy_invariant, invariant
from .common import GRAVITY, inertia_parameters
from .lagrange import euler_lagrange
from .paper import eq96_lagrangian
from .symbols import g, phi, phidot, phiddot, psidot, theta, thetadot, thetaddot

_I1, _I3 = inertia_parameters(sp.Rational(7, 5), sp.Rational(2, 5), "2 m a^2")
PARAMETERS = (_I1, _I3, GRAVITY)
I1, I3 = _I1.symbol, _I3.symbol
DOMAIN = Domain(sp.Integer(0), sp.pi / 2, "upright", "upper_ball_contact")


@lru_cache(maxsize=None)
def model(equations: str = "derived") -> Model:
    if equations != "derived":
        raise ValueError(f"equations={equations!r} for effective; allowed: 'derived' (Euler-Lagrange of Eq. 96)")
    L = eq96_lagrangian(I1, I3)
    acc, energy, p = euler_lagrange(L, ((theta, thetadot, thetaddot), (phi, phidot, phiddot)))
    potential = g * (1 + sp.cos(theta))
    kinetic = sp.simplify(energy - g * sp.cos(theta))
    return Model(
        name="effective",
        title="hurricane balls, the paper's effective Lagrangian (psi = phi)",
        equations="derived",
        source="Euler-Lagrange equations of paper Eq. 96",
        parameters=PARAMETERS,
        accelerations=(acc[thetaddot], acc[phiddot], acc[phiddot]),
        velocity_xy=(sp.Integer(0), sp.Integer(0)),
        invariants=(
            energy_invariant(kinetic, potential, "2 m a^2"),
            invariant("p_phi", p[phi], "momentum conjugate to the cyclic phi"),
        ),
        domain=DOMAIN,
        constraints=(("psidot - phidot", psidot - phidot, "the effective Lagrangian imposes psidot = phidot"),),
        units="2 m a^2",
    )
