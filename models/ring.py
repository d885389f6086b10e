"""Thick ring or coin rolling on one rim (paper Eqs. 47-62).

r_P = -e2 - h e3 (paper Fig. 7), valid for 0 < theta < pi/2: at theta = pi/2 the contact
switches to the other rim.  Defaults are the paper's in-hand ring: R = 3.66 cm,
half-thickness h = 1.59 cm, wall w = 0.5 cm (text after Eq. 62), as exact rationals.
"""
from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .base import Domain, Parameter
from .build import paper_variant, rolling_model
from .common import AXIAL_BOUND, GRAVITY, inertia_parameters
from .paper import eq50_rows

_R, _H, _W = sp.Rational(366, 100), sp.Rational(159, 100), sp.Rational(1, 2)
I3_DEFAULT = (1 + (1 - _W / _R) ** 2) / 2  # annulus about its axis
I1_DEFAULT = (3 * (1 + (1 - _W / _R) ** 2) + (2 * _H / _R) ** 2) / 12  # about a diameter
H_DEFAULT = _H / _R

_I1, _I3 = inertia_parameters(I1_DEFAULT, I3_DEFAULT, "m R^2")
h = sp.Symbol("h", nonnegative=True)
PARAMETERS = (
    _I1, _I3,
    Parameter("h", h, H_DEFAULT, "half-thickness of the ring in units of R", lower=0.0, lower_inclusive=True),
    GRAVITY,
)
I1, I3 = _I1.symbol, _I3.symbol
R2, R3 = sp.Integer(-1), -h
DOMAIN = Domain(sp.Integer(0), sp.pi / 2, "lies_flat", "rim_switch")


@lru_cache(maxsize=None)
def model(equations: str = "derived"):
    derived = rolling_model(
        "ring", "thick ring or coin rolling on one rim", PARAMETERS, I1, I3, R2, R3, DOMAIN,
        unit="m R^2", theta_ref=sp.pi / 4,
    )
    from dataclasses import replace

    derived = replace(derived, relations=(AXIAL_BOUND,))
    if equations == "derived":
        return derived
    return paper_variant(derived, eq50_rows(I1, I3, h), "paper Eq. 50 as printed (explicit middle form)", I1, I3, R2, R3)
