"""mu_req = |F_h| / N on a steady motion, two ways: the closed form and the engine's friction cfunc on the state.

The bound the two agree to (:func:`agreement_bound`), and the bands a required friction is read
against (:func:`band`), serve the friction section (:mod:`verify.studies.friction`) and the slip on
the spin-down (:mod:`verify.studies.spindown_slip`).

The closed form on a steady motion
----------------------------------
On a steady motion theta, phidot, psidot are constant, so the body's configuration turns
rigidly about the vertical at Omega_C = phidot (phi is the only angle of the frame e1, e2,
e3 that moves; psi turns the body about its symmetry axis, which carries C).  With the contact
point r_P = CP = r2 e2 + r3 e3 and omega = (0, phidot sin theta, phidot cos theta + psidot) in
(e1, e2, e3) (thetadot = 0), no slip gives v_C = -omega x r_P = (r2 omega3 - r3 omega2) e1:
horizontal, of constant size, turning with e1 at phidot.  So C moves on a circle of radius
rho_C = |r2 omega3 - r3 omega2| / |phidot| at the rate Omega_C = phidot, its acceleration is
horizontal, M Omega_C^2 rho_C towards the centre, and N = M g (paper Eq. 6: no vertical
acceleration of C).  Hence

    mu_req = Omega_C^2 rho_C / g = |phidot| |r2 omega3 - r3 omega2| / g,

with r2 = -1, r3 = 0 (disk), r2 = -1, r3 = -h (ring), r2 = -sin theta, r3 = -(1 + cos theta)
(hurricane balls; lengths in units of the ball radius), the contact geometry of the paper
(docs/models.md).  It reads neither the equations of motion nor a_C: only the steady state and
the no-slip condition.  On the centre-of-mass-at-rest family (the paper's Eq. 45 for the disk)
r2 omega3 = r3 omega2, so rho_C = 0 and mu_req = 0 at every theta: a coin exactly on that
family needs no friction at all.
"""
from __future__ import annotations

import math

import mpmath
import numpy as np

from models import get_model
from models.symbols import STATE_NAMES

from ..engine import invariants
from ..engine.compile import compile_model
from ..precision import parse_precision

#: The bands the report reads mu_req against (see :func:`band`): 0.2 to 0.5 for a coin on
#: glass and up to about 1 for rubber on wood, as the task that asked for this section states
#: them; order-of-magnitude values, not measured for these bodies and cited to no source.
BANDS = (("0.2", "<= 0.2"), ("0.5", "0.2-0.5"), ("1", "0.5-1"), (None, "> 1"))
#: Working digits of the closed form and of the steady states.
DPS = 50
#: The precisions the cfunc is evaluated in, against the closed form.
CFUNC_PRECISIONS = ("double", "quad")
#: |cfunc - closed form| <= AGREEMENT_FACTOR eps (1 + phidot (|phidot| + |psidot|) / g): see
#: :func:`agreement_bound`.
AGREEMENT_FACTOR = 64


def band(mu) -> str:
    """The band of :data:`BANDS` a required friction falls in ('-' for NaN or None)."""
    if mu is None or not math.isfinite(float(mu)):
        return "-"
    for top, words in BANDS:
        if top is None or float(mu) <= float(top):
            return words
    raise AssertionError("unreachable")


def contact_geometry(model: str, theta, values: dict) -> tuple:
    """(r2, r3) of r_P = CP = r2 e2 + r3 e3 for the body (the paper's contact point; docs/models.md)."""
    if model == "disk":
        return -1, 0
    if model == "ring":
        return -1, -values["h"]
    if model == "hurricane":
        return -mpmath.sin(theta), -(1 + mpmath.cos(theta))
    raise ValueError(f"no rolling contact geometry for {model!r}; allowed: disk, ring, hurricane")


def closed_form(model: str, theta, phidot, psidot, values: dict, geometry=None):
    """mu_req on the steady motion (theta, phidot, psidot): |phidot| |r2 omega3 - r3 omega2| / g
    (module docstring), at mpmath's working precision.  ``geometry``: (r2, r3) in place of the
    body's, for negative controls."""
    r2, r3 = geometry if geometry is not None else contact_geometry(model, theta, values)
    omega2 = phidot * mpmath.sin(theta)
    omega3 = phidot * mpmath.cos(theta) + psidot
    return abs(phidot) * abs(r2 * omega3 - r3 * omega2) / values["g"]


def circle(model: str, theta, phidot, psidot, values: dict) -> dict:
    """Omega_C and rho_C of the circle C runs on (module docstring)."""
    r2, r3 = contact_geometry(model, theta, values)
    speed = abs(r2 * (phidot * mpmath.cos(theta) + psidot) - r3 * phidot * mpmath.sin(theta))
    return {"Omega_C": phidot, "rho_C": speed / abs(phidot) if phidot else mpmath.mpf(0)}


def cfunc_value(model: str, theta, phidot, psidot, values: dict, precision: str) -> tuple:
    """(N/(Mg), mu_req) from the engine's friction cfunc at the state rounded to ``precision``."""
    prec = parse_precision(precision)
    m = get_model(model)
    compiled = compile_model(m, prec)
    state = {"theta": theta, "phidot": phidot, "psidot": psidot}
    y = prec.array([prec.number(mpmath.nstr(state[n], DPS)) if n in state else prec.zero() for n in STATE_NAMES])
    pars = {p.name: prec.number(mpmath.nstr(values[p.name], DPS)) for p in m.parameters}
    y = np.ascontiguousarray(y.reshape(8, 1))
    mu = invariants.friction_required(compiled, y, pars)
    normal = invariants.evaluate(compiled, y, pars)[1]
    return prec.to_mpf(normal[0]), prec.to_mpf(mu[0])


def agreement_bound(phidot, psidot, g, eps) -> float:
    """The bound on |cfunc - closed form| on a steady state: AGREEMENT_FACTOR eps S, with
    S = 1 + |phidot| (|phidot| + |psidot|) / g.

    Why that scale: the state is rounded to the precision (eps relative in each rate), and mu is
    linear in omega3 = phidot cos theta + psidot, so rounding moves it by about
    eps |phidot| (|phidot| + |psidot|) / g; the cfunc forms F_h from the accelerations, whose
    terms (g, phidot^2, phidot psidot, over g) cancel to zero on a steady motion, adding eps
    times their size.  The factor 64 covers the few hundred operations of the cfunc; it is the
    same empirical allowance tests/test_friction_required.py uses, not a derived constant (the
    measured worst case is in the report's table, in units of eps S).
    """
    return AGREEMENT_FACTOR * eps * (1 + abs(float(phidot)) * (abs(float(phidot)) + abs(float(psidot))) / float(g))
