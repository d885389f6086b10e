"""Hurricane-ball gyroscope: the bottom of the lower ball held fixed (paper Eqs. 83-90).

Holonomic.  Derived from the vectors: the centre of mass sits d = 2a e3 above the pivot,
T = 1/2 omega.I.omega + 1/2 |omega x d|^2, V = g z_C (per 2 m a^2, g <- g/a).  The paper's
Eq. 86 (tildes dropped: I1 <- I1 + 4, g <- 2g) is the second source.  phi and psi are
cyclic: p_phi and p_psi are conserved (Eqs. 87-88).
"""
from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .base import Domain, Model
from .build import energy_invariant, invariant
from .common import GRAVITY, inertia_parameters
from .lagrange import euler_lagrange
from .paper import eq86_lagrangian
from .symbols import (
    g, omega_body, phi, phidot, phiddot, psi, psidot, psiddot, theta, thetadot, thetaddot,
    to_inertial, vertical_in_frame,
)

_I1, _I3 = inertia_parameters(sp.Rational(7, 5), sp.Rational(2, 5), "2 m a^2")
PARAMETERS = (_I1, _I3, GRAVITY)
I1, I3 = _I1.symbol, _I3.symbol
DOMAIN = Domain(sp.Integer(0), sp.pi, "upright", "hanging")
COORDINATES = ((theta, thetadot, thetaddot), (phi, phidot, phiddot), (psi, psidot, psiddot))
PIVOT_TO_CM = sp.Matrix([0, 0, 2])


def lagrangian_from_vectors() -> sp.Expr:
    w = omega_body()
    v = w.cross(PIVOT_TO_CM)
    T = sp.Rational(1, 2) * (I1 * (w[0] ** 2 + w[1] ** 2) + I3 * w[2] ** 2 + v.dot(v))
    return T - g * PIVOT_TO_CM.dot(vertical_in_frame())


@lru_cache(maxsize=None)
def model(equations: str = "derived") -> Model:
    if equations == "derived":
        L, source = lagrangian_from_vectors(), "derived: Lagrangian of the body about the fixed pivot"
    elif equations == "paper":
        L, source = eq86_lagrangian(I1, I3), "paper Eq. 86 as printed (tildes dropped)"
    else:
        raise ValueError(f"equations={equations!r} for gyroscope; allowed: 'derived', 'paper'")
    acc, energy, p = euler_lagrange(L, COORDINATES)
    v = to_inertial(omega_body().cross(PIVOT_TO_CM))
    kinetic = sp.simplify(energy - 2 * g * sp.cos(theta))
    return Model(
        name="gyroscope",
        title="hurricane-ball gyroscope about a fixed pivot",
        equations=equations,
        source=source,
        parameters=PARAMETERS,
        accelerations=(acc[thetaddot], acc[phiddot], acc[psiddot]),
        velocity_xy=(sp.simplify(v[0]), sp.simplify(v[1])),
        invariants=(
            energy_invariant(kinetic, 2 * g * sp.cos(theta), "2 m a^2"),
            invariant("p_phi", p[phi], "momentum conjugate to the cyclic phi (Eq. 88)"),
            invariant("p_psi", p[psi], "momentum conjugate to the cyclic psi (Eq. 87)"),
        ),
        domain=DOMAIN,
        units="2 m a^2",
    )
