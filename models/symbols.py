"""The symbols every model is written in, and the paper's frame conventions (Fig. 1).

Conventions
-----------
3-1-3 Euler angles (phi, theta, psi).  In the inertial frame (X, Y, Z with Z up)

* ``e1 = (cos phi, sin phi, 0)`` is the line of nodes (always horizontal),
* ``e2 = (-sin phi cos theta, cos phi cos theta, sin theta)``,
* ``e3 = (sin phi sin theta, -cos phi sin theta, cos theta)`` is the symmetry axis,

so that ``Z = sin(theta) e2 + cos(theta) e3``.  The 1-2-3 frame turns with
``Omega = (thetadot, phidot sin theta, phidot cos theta)`` and the body with
``omega = Omega + psidot e3`` (paper Eqs. 13-16).  ``theta = pi/2`` is the disk upright.

The state of every model is ``theta, phi, psi, thetadot, phidot, psidot, x, y`` with
``x, y`` the horizontal position of the centre of mass in the inertial frame.
"""
from __future__ import annotations

import sympy as sp

from .catalogue import STATE_NAMES

theta, phi, psi, thetadot, phidot, psidot, x, y = sp.symbols(STATE_NAMES, real=True)
STATE = (theta, phi, psi, thetadot, phidot, psidot, x, y)

#: Second derivatives, the unknowns of every derivation.
thetaddot, phiddot, psiddot = sp.symbols("thetaddot phiddot psiddot", real=True)
ACCELERATIONS = (thetaddot, phiddot, psiddot)

#: Gravity g/L (L = R for disk and ring, a for the hurricane balls), in s^-2.
g = sp.Symbol("g", positive=True)


def frame_vectors():
    """Inertial components of (e1, e2, e3) as sympy column vectors (paper Fig. 1)."""
    s, c, sp_, cp = sp.sin(theta), sp.cos(theta), sp.sin(phi), sp.cos(phi)
    e1 = sp.Matrix([cp, sp_, 0])
    e2 = sp.Matrix([-sp_ * c, cp * c, s])
    e3 = sp.Matrix([sp_ * s, -cp * s, c])
    return e1, e2, e3


def vertical_in_frame():
    """The upward unit vector Z in 1-2-3 components: (0, sin theta, cos theta)."""
    return sp.Matrix([0, sp.sin(theta), sp.cos(theta)])


def omega_frame():
    """Angular velocity of the 1-2-3 frame, Omega (paper Eq. 14)."""
    return sp.Matrix([thetadot, phidot * sp.sin(theta), phidot * sp.cos(theta)])


def omega_body():
    """Angular velocity of the body, omega = Omega + psidot e3 (paper Eq. 16)."""
    return omega_frame() + sp.Matrix([0, 0, psidot])


def time_derivative(expr):
    """d/dt of an expression in (theta, phi, psi, rates), second derivatives left symbolic."""
    return (
        sp.diff(expr, theta) * thetadot
        + sp.diff(expr, phi) * phidot
        + sp.diff(expr, psi) * psidot
        + sp.diff(expr, thetadot) * thetaddot
        + sp.diff(expr, phidot) * phiddot
        + sp.diff(expr, psidot) * psiddot
    )


def omega_body_dot():
    """Componentwise time derivative of omega in the 1-2-3 frame."""
    return omega_body().applyfunc(time_derivative)


def to_inertial(v):
    """Inertial components of a vector given in 1-2-3 components."""
    e1, e2, e3 = frame_vectors()
    return v[0] * e1 + v[1] * e2 + v[2] * e3
