"""Thin disk or hoop rolling without slipping (paper Eqs. 4-46).

I1 = k, I3 = 2k in units of m R^2 (k = 1/4 disk, 1/2 hoop); r_P = -e2 (paper Eq. 7).
"""
from __future__ import annotations

from functools import lru_cache

import mpmath
import sympy as sp

from .base import Domain, Parameter
from .build import paper_variant, rolling_model
from .common import GRAVITY
from .paper import eq18_rows

k = sp.Symbol("k", positive=True)
PARAMETERS = (
    Parameter("k", k, sp.Rational(1, 4), "I1/(m R^2) with I3 = 2 I1; 1/4 disk, 1/2 hoop; at most 1/2 (all mass on the rim)",
              lower=0.0, upper=0.5),
    GRAVITY,
)
R2, R3 = sp.Integer(-1), sp.Integer(0)
DOMAIN = Domain(sp.Integer(0), sp.pi, "lies_flat", "lies_flat")


def chaplygin_closed_form(theta, omega2, omega3, params):
    """Chaplygin's integrals of the rolling disk in closed form (Legendre functions).

    Rows 2 and 3 of Eq. 17 with I3 = 2k give ``(2k+1) d(omega3)/d(theta) = omega2`` and
    ``d(sin(theta) omega2)/d(theta) = 2 sin(theta) omega3``, so with x = cos(theta)
    ``(1 - x^2) w'' - 2 x w' - lam w = 0``, lam = 2/(2k+1): Legendre's equation with
    nu(nu+1) = -lam.  Its even and odd solutions about x = 0 are

        w_e = 2F1(a, b; 1/2; x^2),   w_o = x 2F1(a + 1/2, b + 1/2; 3/2; x^2),

    a + b = 1/2, a b = lam/4.  With omega3 = A w_e + B w_o the constants are the values
    at theta = pi/2: omega3(pi/2) = A, omega2(pi/2) = -(2k+1) B.  Returned as
    (chaplygin_1, chaplygin_2) = (omega2, omega3) transported to theta = pi/2, the same
    numbers the transport of :mod:`verify.engine.chaplygin` computes.

    All arguments are mpmath numbers.  It works at the caller's precision plus 2 log2(1/|sin(theta)|)
    bits: near theta = 0 and pi (x^2 -> 1, the singular point of 2F1, where w_e and w_o grow like
    log(sin(theta)) and their derivatives like 1/sin(theta)^2) forming (A, B) cancels about that many
    bits (measured: ~20 at theta = 1e-6, ~45 at 1e-12; without the extra bits the result at 1e-12
    was NaN in double).  At sin(theta) = 0 the basis is singular and the division fails.
    """
    s = mpmath.sin(theta)
    extra = 2 * max(0, -mpmath.mag(s)) if s else 0
    with mpmath.extraprec(extra):
        return _legendre_integrals(theta, omega2, omega3, params["k"])


def _legendre_integrals(theta, omega2, omega3, kk):
    lam = 2 / (2 * kk + 1)
    root = mpmath.sqrt(mpmath.mpc(1 - 4 * lam)) / 4
    a, b = mpmath.mpf(1) / 4 + root, mpmath.mpf(1) / 4 - root
    x = mpmath.cos(theta)
    s = mpmath.sin(theta)
    z = x * x
    F = lambda p, q, r: mpmath.hyp2f1(p, q, r, z)  # noqa: E731
    half = mpmath.mpf(1) / 2
    we = F(a, b, half)
    wo = x * F(a + half, b + half, 3 * half)
    dwe = 4 * a * b * x * F(a + 1, b + 1, 3 * half)  # d/dx
    ap, bp = a + half, b + half
    dwo = F(ap, bp, 3 * half) + x * 2 * x * (ap * bp / (3 * half)) * F(ap + 1, bp + 1, 5 * half)
    f = 2 * kk + 1
    # [omega3, omega2] = [[we, wo], [-f s dwe, -f s dwo]] [A, B]
    m11, m12, m21, m22 = we, wo, -f * s * dwe, -f * s * dwo
    det = m11 * m22 - m12 * m21
    A = (omega3 * m22 - m12 * omega2) / det
    B = (m11 * omega2 - m21 * omega3) / det
    return mpmath.re(-f * B), mpmath.re(A)


@lru_cache(maxsize=None)
def model(equations: str = "derived"):
    derived = rolling_model(
        "disk", "thin disk or hoop rolling without slipping", PARAMETERS, k, 2 * k, R2, R3, DOMAIN,
        unit="m R^2", theta_ref=sp.pi / 2, chaplygin_closed_form=chaplygin_closed_form,
    )
    if equations == "derived":
        return derived
    return paper_variant(derived, eq18_rows(k), "paper Eq. 18 as printed", k, 2 * k, R2, R3)
