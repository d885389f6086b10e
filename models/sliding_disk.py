"""Thin disk on a perfectly smooth plane: the contact force is vertical (Olsson's case).

With no horizontal force and no initial horizontal momentum, the centre of mass moves
only vertically; x, y stay at their initial values.  Integrals: energy, the vertical
angular momentum about C (gravity and N exert no torque about Z) and the spin omega3
(the torque r_P x N Z is perpendicular to e3).
"""
from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .base import Domain, Parameter
from .build import invariant, rolling_model
from .common import GRAVITY
from .symbols import omega_body, vertical_in_frame

k = sp.Symbol("k", positive=True)
PARAMETERS = (
    Parameter("k", k, sp.Rational(1, 4), "I1/(m R^2) with I3 = 2 I1; 1/4 disk, 1/2 hoop", lower=0.0, upper=0.5),
    GRAVITY,
)
DOMAIN = Domain(sp.Integer(0), sp.pi, "lies_flat", "lies_flat")


@lru_cache(maxsize=None)
def model(equations: str = "derived"):
    if equations != "derived":
        raise ValueError(f"equations={equations!r} for sliding-disk; allowed: 'derived'")
    w = omega_body()
    L = sp.Matrix([k * w[0], k * w[1], 2 * k * w[2]])
    extra = (
        invariant("p_phi", L.dot(vertical_in_frame()), "vertical angular momentum about C, L . Z"),
        invariant("p_psi", 2 * k * w[2], "axial angular momentum I3 omega3"),
    )
    return rolling_model(
        "sliding-disk", "thin disk on a frictionless plane", PARAMETERS, k, 2 * k, sp.Integer(-1), sp.Integer(0),
        DOMAIN, unit="m R^2", contact="smooth", extra_invariants=extra,
    )
