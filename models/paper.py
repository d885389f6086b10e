"""The paper's equations of motion, transcribed exactly as printed (not corrected).

Each function returns the three rows ``LHS - RHS`` in the paper's own symbols, with the
paper's Eq. 16 for omega where a row is written in omega_dot.  Where these differ from
:mod:`models.rolling`, the difference is a finding of the suite, pinned in the tests.
"""
from __future__ import annotations

import sympy as sp

from .symbols import (
    g, omega_body_dot, phidot, phiddot, psidot, psiddot, theta, thetadot, thetaddot,
)

s, c = sp.sin(theta), sp.cos(theta)


def eq17_rhs(I1, I3) -> sp.Matrix:
    """Eq. 17, right-hand side."""
    return sp.Matrix([
        -(psidot * (1 + I3) + phidot * (1 + I3 - I1) * c) * phidot * s - g * c,
        thetadot * (psidot * I3 + phidot * (I3 - I1) * c),
        phidot * thetadot * s,
    ])


def eq17_rows(I1, I3) -> sp.Matrix:
    """Eq. 17: the thin disk or hoop, general I1, I3."""
    wd = omega_body_dot()
    lhs = sp.Matrix([(I1 + 1) * wd[0], I1 * wd[1], (I3 + 1) * wd[2]])
    return lhs - eq17_rhs(I1, I3)


def eq18_rows(k) -> sp.Matrix:
    """Eq. 18: the thin disk or hoop with I1 = k, I3 = 2k."""
    wd = omega_body_dot()
    lhs = sp.Matrix([(k + 1) * wd[0], k * wd[1], (2 * k + 1) * wd[2]])
    rhs = sp.Matrix([
        -(psidot * (2 * k + 1) + phidot * (k + 1) * c) * phidot * s - g * c,
        k * thetadot * (2 * psidot + phidot * c),
        phidot * thetadot * s,
    ])
    return lhs - rhs


def eq50_middle_lhs(I1, I3, h) -> sp.Matrix:
    """Eq. 50, the middle (explicit) form of the LHS."""
    return sp.Matrix([
        (I1 + 1 + h**2) * thetaddot,
        (I1 + h**2) * (phiddot * s + phidot * c * thetadot) - h * (psiddot + phiddot * c - phidot * s * thetadot),
        (I3 + 1) * (psiddot + phiddot * c - phidot * s * thetadot) - h * (phiddot * s + phidot * c * thetadot),
    ])


def eq50_rhs(I1, I3, h) -> sp.Matrix:
    """Eq. 50, the RHS."""
    return sp.Matrix([
        -phidot * psidot * ((1 + I3) * s + h * c)
        - phidot**2 * (s * c * (1 + I3 - I1 - h**2) + h * sp.cos(2 * theta))
        - g * (c - h * s),
        thetadot * (psidot * I3 + phidot * ((I3 - I1 - h**2) * c - h * s)),
        phidot * thetadot * (s + h * c),
    ])


def eq50_rows(I1, I3, h) -> sp.Matrix:
    """Eq. 50: the thick ring or coin; the middle (explicit) LHS equated to the RHS."""
    return eq50_middle_lhs(I1, I3, h) - eq50_rhs(I1, I3, h)


def eq50_omega_lhs(I1, I3, h) -> sp.Matrix:
    """Eq. 50, first LHS (in omega_dot), to check against the middle form."""
    wd = omega_body_dot()
    return sp.Matrix([
        (I1 + 1 + h**2) * wd[0],
        (I1 + h**2) * wd[1] - h * wd[2],
        (I3 + 1) * wd[2] - h * wd[1],
    ])


def eq81_lhs(I1, I3) -> sp.Matrix:
    """Eq. 81: the hurricane balls' LHS ("Mathematica finds the LHS")."""
    return sp.Matrix([
        thetaddot * (I1 + 2 * c + 2),
        s * (phiddot * (I1 + c + 1) - psiddot * (c + 1)) + phidot * thetadot * (I1 * c + (1 + c) ** 2),
        phiddot * (I3 * c + c**2 - 1) - phidot * thetadot * s * (I3 + c + 1) + psiddot * (I3 - c**2 + 1),
    ])


def eq80_rhs(I1, I3) -> sp.Matrix:
    """Eq. 80: the hurricane balls' RHS ("Mathematica finds the RHS")."""
    return sp.Matrix([
        s * (g + phidot**2 * ((I1 - I3 + 1) * c + 1) - phidot * psidot * (I3 + c + 1) + thetadot**2),
        thetadot * (psidot * (I3 + c**2 + c) - phidot * c * (I1 - I3 + c + 1)),
        thetadot * s * c * (phidot - psidot),
    ])


def eq80_81_rows(I1, I3) -> sp.Matrix:
    """Eqs. 80 = 81 for the hurricane balls."""
    return eq81_lhs(I1, I3) - eq80_rhs(I1, I3)


def eq86_lagrangian(I1, I3) -> sp.Expr:
    """Eq. 86: the hurricane-ball gyroscope, tildes dropped: I1 <- I1 + 4, g <- 2 g."""
    return (
        sp.Rational(1, 2) * (I1 + 4) * (phidot**2 * s**2 + thetadot**2)
        + sp.Rational(1, 2) * I3 * (phidot * c + psidot) ** 2
        - 2 * g * c
    )


def eq96_lagrangian(I1, I3) -> sp.Expr:
    """Eq. 96: the paper's 'effective Lagrangian' for the hurricane balls (psi = phi)."""
    return (
        sp.Rational(1, 2) * I1 * (phidot**2 * s**2 + thetadot**2)
        + sp.Rational(1, 2) * I3 * phidot**2 * (c + 1) ** 2
        + sp.Rational(1, 2) * s**2 * thetadot**2
        - g * c
    )
