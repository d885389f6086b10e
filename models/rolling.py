"""One derivation for every body of revolution on a horizontal plane (paper Eqs. 5-12, 73).

Newton-Euler about the centre of mass C, per unit mass (``I <- I/M``), lengths in units
of the body's scale: with ``r_P`` the vector from C to the contact point P and ``F`` the
contact force,

    M a_C = F - M g Z                                   (paper Eq. 6)
    I omega_dot + Omega x (I omega) = r_P x F            (paper Eq. 5)

The contact law closes the system:

* ``rolling`` (no slip): ``v_C = -omega x r_P`` (paper Eq. 7), so
  ``a_C = -(omega_dot x r_P + omega x r_P_dot) + Omega x v_C`` with derivatives of the
  1-2-3 components, and ``F`` is eliminated (the general form of Eqs. 8 and 73);
* ``smooth`` (no friction): ``F = N Z``; with no horizontal force and no horizontal
  momentum the centre of mass moves only vertically, ``a_C = z_C'' Z``.

``r_P = (0, r2(theta), r3(theta))`` in 1-2-3 components; the body is symmetric about e3,
so the inertia is ``diag(I1, I1, I3)`` in that frame (paper Eq. 4).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from .symbols import (
    ACCELERATIONS, g, omega_body, omega_body_dot, omega_frame, phi, phidot, psidot,
    theta, thetadot, time_derivative, to_inertial,
    vertical_in_frame,
)


@dataclass(frozen=True)
class Derivation:
    """Everything one derivation yields for one body (all sympy)."""

    rows: sp.Matrix  # Newton-Euler rows, LHS - RHS, 1-2-3 components; zero on solutions
    accelerations: tuple  # (thetaddot, phiddot, psiddot)
    velocity_cm: sp.Matrix  # 1-2-3 components
    velocity_xy: tuple  # inertial horizontal components of v_C
    height_cm: sp.Expr  # z_C, the height of C above the plane
    vertical_acceleration: sp.Expr  # a_C . Z, second derivatives left symbolic
    horizontal_acceleration: tuple | None  # (a_C . X, a_C . Y), second derivatives left symbolic; None if smooth
    kinetic: sp.Expr
    potential: sp.Expr
    normal_force: sp.Expr  # N / (M g)
    chaplygin_matrix: sp.Matrix | None  # A(theta) with d(omega2, omega3)/dtheta = A w


def _simplify(expr):
    # Rational simplification only: trigonometric simplification costs seconds per
    # body and buys heyoka nothing.
    return sp.factor_terms(sp.cancel(sp.together(expr)))


def newton_euler(inertia, w, wdot, Om, r, force) -> tuple:
    """(rows, accelerations): paper Eq. 5 about C, I omega_dot + Omega x (I omega) = r_P x F, in 1-2-3
    components (LHS - RHS, expanded), solved for (thetaddot, phiddot, psiddot); ``force`` is F / M with
    the accelerations left as symbols wherever the contact law puts them."""
    rows = (inertia * wdot + Om.cross(inertia * w) - r.cross(force)).applyfunc(sp.expand)
    solution = sp.solve(list(rows), list(ACCELERATIONS), dict=True)
    if len(solution) != 1:
        raise RuntimeError("the Newton-Euler rows did not give unique accelerations")
    return rows, tuple(_simplify(solution[0][q]) for q in ACCELERATIONS)


@lru_cache(maxsize=None)
def derive(I1: sp.Expr, I3: sp.Expr, r2: sp.Expr, r3: sp.Expr, contact: str = "rolling") -> Derivation:
    """Derive the equations of motion of a body of revolution on the plane.

    Parameters
    ----------
    I1, I3 : sympy expressions
        Transverse and axial moments of inertia about C, per unit mass, in units of L^2.
    r2, r3 : sympy expressions of theta
        The 1-2-3 components of r_P = CP (paper Eqs. 7, 47, 63).
    contact : {"rolling", "smooth"}
        No slip (paper Eq. 7) or a frictionless plane.
    """
    if contact not in ("rolling", "smooth"):
        raise ValueError(f"contact={contact!r}; allowed: 'rolling', 'smooth'")
    w, wdot, Om = omega_body(), omega_body_dot(), omega_frame()
    Z = vertical_in_frame()
    r = sp.Matrix([0, r2, r3])
    inertia = sp.diag(I1, I1, I3)
    height = sp.simplify(-r.dot(Z))

    if contact == "rolling":
        v = -w.cross(r)
        v_dot_components = -(wdot.cross(r) + w.cross(r.applyfunc(time_derivative)))
        a = v_dot_components + Om.cross(v)
    else:
        v = time_derivative(height) * Z
        a = time_derivative(time_derivative(height)) * Z
    force = a + g * Z  # F / M
    rows, acc = newton_euler(inertia, w, wdot, Om, r, force)
    on_shell = dict(zip(ACCELERATIONS, acc))

    kinetic = sp.Rational(1, 2) * (w.dot(inertia * w) + v.dot(v))
    potential = g * height
    a_vertical = sp.expand(a.dot(Z))
    normal = _simplify(1 + a_vertical.subs(on_shell) / g)
    if contact == "rolling":
        v_in = to_inertial(v)
        vxy = (_simplify(v_in[0]), _simplify(v_in[1]))
        chaplygin = _chaplygin_matrix(w, wdot, on_shell)
        a_horizontal = _horizontal_in_fixed_frame(a)
    else:
        vxy = (sp.Integer(0), sp.Integer(0))
        chaplygin = None
        a_horizontal = None  # no friction: F = N Z, nothing horizontal to ask of the plane
    return Derivation(rows, acc, v, vxy, height, a_vertical, a_horizontal, kinetic, potential, normal, chaplygin)


def _horizontal_in_fixed_frame(a) -> tuple:
    """(a . X, a . Y) of a vector given in 1-2-3 components, exactly and without expanding.

    The horizontal plane is spanned by e1 = (cos phi, sin phi, 0) and h = cos(theta) e2 -
    sin(theta) e3 = (-sin phi, cos phi, 0) (Z = sin(theta) e2 + cos(theta) e3, paper Fig. 1), so
    the horizontal part of ``a`` is a1 e1 + (a2 cos theta - a3 sin theta) h.  Since gravity is
    vertical, these over g are the horizontal contact force F_h / (M g) (paper Eq. 6).
    """
    along_e1 = a[0]
    along_h = a[1] * sp.cos(theta) - a[2] * sp.sin(theta)
    return (along_e1 * sp.cos(phi) - along_h * sp.sin(phi), along_e1 * sp.sin(phi) + along_h * sp.cos(phi))


def _chaplygin_matrix(w, wdot, on_shell) -> sp.Matrix:
    """A(theta) such that d(omega2, omega3)/dt = thetadot A(theta) (omega2, omega3).

    Rows 2 and 3 of the rolling equations contain neither thetaddot nor gravity, and
    every term on their right-hand side carries one factor thetadot (see the module
    docstring), which is what makes (omega2, omega3) a linear ODE in theta.
    """
    w2, w3 = sp.symbols("omega2 omega3", real=True)
    s, c = sp.sin(theta), sp.cos(theta)
    rates = {phidot: w2 / s, psidot: w3 - w2 * c / s}
    per_dtheta = [sp.cancel(wdot[i].subs(on_shell) / thetadot) for i in (1, 2)]
    per_dtheta = [sp.cancel(e.subs(rates)) for e in per_dtheta]
    A = sp.Matrix(2, 2, lambda i, j: _simplify(sp.diff(per_dtheta[i], (w2, w3)[j])))
    for i in range(2):
        rest = sp.simplify(sp.cancel(per_dtheta[i] - A[i, 0] * w2 - A[i, 1] * w3))
        if rest != 0 or A[i, :].has(thetadot, w2, w3, phidot, psidot):
            raise RuntimeError("the rows without thetaddot are not linear in (omega2, omega3)")
    return A
