"""Hurricane balls: two equal spheres (radius a) glued at a point (paper Eqs. 63-82).

I = 2 m a^2 diag(I1, I1, I3) with I1 = 7/5, I3 = 2/5 (Eq. 64); the lower ball touches the
plane, r_P = -sin(theta) e2 - (1 + cos(theta)) e3 (Eq. 63), until the upper ball touches
it at theta = pi/2.  The lower ball is a sphere whose centre lies on the symmetry axis:
a Routh sphere, which has Jellett's and Routh's integrals in closed form.
"""
from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import sympy as sp

from .base import Domain
from .build import invariant, paper_variant, rolling_model
from .common import AXIAL_BOUND, GRAVITY, inertia_parameters
from .paper import eq80_81_rows
from .symbols import omega_body, theta

_I1, _I3 = inertia_parameters(sp.Rational(7, 5), sp.Rational(2, 5), "2 m a^2")
PARAMETERS = (_I1, _I3, GRAVITY)
I1, I3 = _I1.symbol, _I3.symbol
R2, R3 = -sp.sin(theta), -(1 + sp.cos(theta))
DOMAIN = Domain(sp.Integer(0), sp.pi / 2, "upright", "upper_ball_contact")


def closed_form_integrals():
    """Jellett's J = L . r_P and Routh's R = omega3 sqrt(I1 I3 + I1 r2^2 + I3 r3^2)."""
    w = omega_body()
    jellett = I1 * w[1] * R2 + I3 * w[2] * R3
    routh = w[2] * sp.sqrt(I1 * I3 + I1 * R2**2 + I3 * R3**2)
    return (
        invariant("jellett", jellett, "Jellett's integral L_C . r_P (angular momentum about C along CP)"),
        invariant("routh", routh, "Routh's integral omega3 sqrt(I1 I3 + I1 r2^2 + I3 r3^2)"),
    )


@lru_cache(maxsize=None)
def model(equations: str = "derived"):
    derived = rolling_model(
        "hurricane", "hurricane balls rolling without slipping", PARAMETERS, I1, I3, R2, R3, DOMAIN,
        unit="2 m a^2", extra_invariants=closed_form_integrals(),
    )
    derived = replace(derived, relations=(AXIAL_BOUND,))
    if equations == "derived":
        return derived
    return paper_variant(derived, eq80_81_rows(I1, I3), "paper Eqs. 80 = 81 as printed", I1, I3, R2, R3)
