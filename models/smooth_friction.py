"""A body of revolution sliding on the plane under the smooth friction law (the tippe top's law).

Newton-Euler about C as in :mod:`models.rolling` and :mod:`models.coulomb` (per unit mass, lengths
in units of the body's scale):

    a_C = F - g Z,          F = N Z + F_h                              (paper Eq. 6)
    I omega_dot + Omega x (I omega) = r_P x F                          (paper Eq. 5)
    F_h = -mu N u / sqrt(|u|^2 + eps^2),   u = v_C + omega x r_P       (the smooth law)

with the height constraint z_C = -r_P . Z, so that N = g + z_C'' carries thetaddot and is
eliminated by substitution (as in :func:`models.coulomb.derive_sliding`); the three rotational rows
are linear in the accelerations and solved for them (:func:`models.rolling.newton_euler`).  ``eps``
is the slip scale: for |u| >> eps the law is Coulomb's -mu N u/|u|, for |u| << eps it is viscous,
-(mu N / eps) u.  It is smooth everywhere, u = 0 included: unlike exact Coulomb friction there is
no sticking and no switch, so one system of ODEs covers the whole motion.

The state
---------
The eight components of every model, then the slip's Cartesian components in the horizontal frame
(e1, h) of :mod:`models.coulomb` (h = Z x e1 = cos(theta) e2 - sin(theta) e3),
``slip_e1`` and ``slip_h`` (u = slip_e1 e1 + slip_h h), then the work ``work``:

* Cartesian, not polar (Coulomb's speed and direction): the law is regular at u = 0 in them, and
  the slip of a rolling-like motion hovers near 0, where the polar direction's rate (1/s) is stiff;
* in (e1, h), not inertial (x, y): the rows then hold phi only in the centre of mass's velocity
  x', y' (phi is cyclic), as Coulomb's beta = alpha - phi keeps it out.  With
  du/dt = d1 e1 + d2 h (d1, d2 below) and de1/dt = phidot h, dh/dt = -phidot e1:
  slip_e1' = d1 + phidot slip_h, slip_h' = d2 - phidot slip_e1;
* W = int mu N |u|^2 / sqrt(|u|^2 + eps^2) dt, the work done against friction, a quadrature:
  dE/dt = F . u_C-velocities = F_h . u (N Z . u = 0, u being horizontal) = -dW/dt, so E + W is
  conserved.  The state ``work`` is W / g (per unit mass: W over M g, a length; 0 to a few R on the
  tippe top), not W: heyoka's error control is relative to the largest state component, and W itself
  reaches thousands (g = 980) where the rates are a hundred, which loosened the control of the rates
  and let E + W drift by 900 eps in 6000 steps on one run; W / g stays below the rates.

Jellett's integral
------------------
For a sphere profile (r_P = c e3 - R Z, c the centre's height above C) lambda = L_C . r_P is
conserved under any force applied at P, so under this law too: dL_C/dt = r_P x F is normal to
r_P, and dr_P/dt = c omega x e3 (Z is fixed), so d lambda/dt = c L_C . (omega x e3)
= c e3 . (L_C x omega), and for an axisymmetric body L_C = I1 omega + (I3 - I1) omega3 e3 gives
L_C x omega = (I3 - I1) omega3 e3 x omega, normal to e3.  It is the rolling model's ``jellett``
invariant (:func:`models.bodies._sphere_integrals`), which holds the rates and not v_C; Routh's
integral needs rolling and is not conserved here.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from . import get_model
from .base import Parameter
from .coulomb import FRICTION, contact_kinematics, mu
from .rolling import _simplify, newton_euler
from .symbols import (
    ACCELERATIONS, STATE, g, phi, phidot, theta,
    time_derivative,
)

slip_e1, slip_h, work = sp.symbols("slip_e1 slip_h work", real=True)
eps = sp.Symbol("eps", positive=True)
#: mu / sqrt(|u|^2 + eps^2): the law's factor, a symbol while deriving (the rows are rational in it).
_q = sp.Symbol("q", nonnegative=True)
SLIP_SCALE = Parameter("eps", eps, sp.Integer(1), "slip scale of the smooth friction law, in L/s (Coulomb for |u| >> eps)",
                       lower=0.0, lower_inclusive=False, upper=None)

#: The state of the smooth-law model: the eight, the slip in (e1, h), the work over g.
STATE_NAMES = ("theta", "phi", "psi", "thetadot", "phidot", "psidot", "x", "y", "slip_e1", "slip_h", "work")
SMOOTH_STATE = STATE + (slip_e1, slip_h, work)


@dataclass(frozen=True)
class SmoothSliding:
    """The smooth-law equations of one body (sympy, in :data:`SMOOTH_STATE`, the rolling model's parameters,
    ``mu`` and ``eps``).

    Attributes
    ----------
    rhs : tuple
        d/dt of each of :data:`SMOOTH_STATE`, in that order.
    energy, kinetic : sp.Expr
        E (kinetic + potential, per unit mass, potential zero with C on the plane) and its kinetic part.
    normal_force : sp.Expr
        N / (M g) on shell.
    friction_force : tuple
        F_h / (M g) along (e1, h) on shell.
    height : sp.Expr
        z_C(theta), the height of C.
    cm_velocity_xy : tuple
        (x', y') of C.
    painleve_margin : sp.Expr
        det(d rows / d accelerations) over its value without friction: the rows jam where it reaches 0
        (as :func:`models.coulomb.painleve_margin`, with mu |u| / sqrt(|u|^2 + eps^2) <= mu for mu).
    """

    rhs: tuple
    energy: sp.Expr
    kinetic: sp.Expr
    normal_force: sp.Expr
    friction_force: tuple
    height: sp.Expr
    cm_velocity_xy: tuple
    painleve_margin: sp.Expr


def law_factor() -> sp.Expr:
    """mu / sqrt(|u|^2 + eps^2), so that F_h = -(this) N u."""
    return mu / sp.sqrt(slip_e1 ** 2 + slip_h ** 2 + eps ** 2)


@lru_cache(maxsize=None)
def derive_smooth(I1: sp.Expr, I3: sp.Expr, r2: sp.Expr, r3: sp.Expr) -> SmoothSliding:
    """The smooth-law sliding equations of a body of revolution with r_P = (0, r2(theta), r3(theta))
    (paper Eqs. 5-7 with F_h = -mu N u / sqrt(|u|^2 + eps^2))."""
    w, wdot, Om, Z, r, inertia, height, zdot, zddot = contact_kinematics(I1, I3, r2, r3)

    s, c = sp.sin(theta), sp.cos(theta)
    slip = sp.Matrix([slip_e1, slip_h * c, -slip_h * s])  # u in 1-2-3 components (h = (0, cos, -sin))
    normal = g + zddot  # N / M
    force = normal * Z - _q * normal * slip  # F / M
    rows, acc = newton_euler(inertia, w, wdot, Om, r, force)
    on_shell = dict(zip(ACCELERATIONS, acc))
    jac = rows.jacobian(list(ACCELERATIONS))
    det = sp.expand(jac.det())
    margin = _simplify(det / det.subs(_q, 0))

    spin = w.cross(r)  # omega x r_P: its vertical part is -z_C', its horizontal part (c1, c2) in (e1, h)
    if sp.simplify(spin.dot(Z) + zdot) != 0:
        raise RuntimeError("the contact point's vertical velocity is not -z_C'; r_P is not a contact of the plane")
    c1 = spin[0]
    c2 = spin[1] * c - spin[2] * s
    v1, v2 = slip_e1 - c1, slip_h - c2  # C's horizontal velocity along (e1, h)
    # du/dt along (e1, h): a_C,h + d/dt(c1 e1 + c2 h)  (models.coulomb.derive_sliding)
    d1 = -_q * normal * slip_e1 + time_derivative(c1) - phidot * c2
    d2 = -_q * normal * slip_h + time_derivative(c2) + phidot * c1
    d1, d2 = (sp.expand(d.subs(on_shell)) for d in (d1, d2))
    normal_on_shell = _simplify(normal.subs(on_shell) / g)

    law = law_factor()
    xdot = v1 * sp.cos(phi) - v2 * sp.sin(phi)
    ydot = v1 * sp.sin(phi) + v2 * sp.cos(phi)
    rhs = (STATE[3], STATE[4], STATE[5], *acc, xdot, ydot,
           _simplify(d1) + phidot * slip_h, _simplify(d2) - phidot * slip_e1,
           _q * normal_on_shell * (slip_e1 ** 2 + slip_h ** 2))  # d(W/g)/dt
    rhs = tuple(sp.sympify(e).subs(_q, law) for e in rhs)
    kinetic = sp.Rational(1, 2) * (w.dot(inertia * w) + v1 ** 2 + v2 ** 2 + zdot ** 2)
    friction = tuple((-_q * normal_on_shell * u).subs(_q, law) for u in (slip_e1, slip_h))
    return SmoothSliding(rhs, kinetic + g * height, kinetic, normal_on_shell.subs(_q, law), friction, height,
                         (xdot, ydot), margin.subs(_q, law))


def body(name: str):
    """(rolling model, smooth-law equations, parameters with ``mu`` and ``eps`` last) of a shipped body file
    ``body:NAME`` or ``NAME`` (:mod:`models.bodies`: the same contact vector as its rolling model)."""
    from .bodies import contact_vector, load  # lazy: models.bodies (0.12 s) only for a body

    name = name if name.startswith("body:") else f"body:{name}"
    rolling = get_model(name)
    I1, I3, r2, r3 = contact_vector(load(name[len("body:"):]))
    return rolling, derive_smooth(I1, I3, r2, r3), rolling.parameters + (FRICTION, SLIP_SCALE)


def body_model(body_object):
    """(rolling model, smooth-law equations, parameters) of a :class:`models.bodies.Body` (a file not shipped)."""
    from .bodies import contact_vector, model_of  # lazy: models.bodies (0.12 s) only for a body

    rolling = model_of(body_object)
    I1, I3, r2, r3 = contact_vector(body_object)
    return rolling, derive_smooth(I1, I3, r2, r3), rolling.parameters + (FRICTION, SLIP_SCALE)


__all__ = ["SLIP_SCALE", "SMOOTH_STATE", "STATE_NAMES", "SmoothSliding", "body", "body_model", "derive_smooth",
           "eps", "law_factor", "slip_e1", "slip_h", "work"]
