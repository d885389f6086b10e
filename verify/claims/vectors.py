"""Vector algebra shared by the claims: the paper's symbols as sympy objects (m = R = 1)."""
from __future__ import annotations

from functools import lru_cache

import sympy as sp

from models.symbols import (
    phi, psi, theta,
    time_derivative,
)

E1, E2, E3 = sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0]), sp.Matrix([0, 0, 1])
s, c = sp.sin(theta), sp.cos(theta)


def same(a, b) -> bool:
    """Exact identity of two scalar or vector expressions (sympy)."""
    a, b = sp.Matrix([a]) if not isinstance(a, sp.MatrixBase) else a, sp.Matrix([b]) if not isinstance(b, sp.MatrixBase) else b
    return all(sp.simplify(sp.expand_trig(sp.expand(x - y))) == 0 for x, y in zip(a, b))


@lru_cache(maxsize=None)
def euler_angles_omega():
    """omega and Omega from the rotation matrices, independent of Eqs. 13-16.

    R = Rz(phi) Rx(theta) Rz(psi) maps body to inertial; the body rate in inertial axes is
    the axial vector of R' R^T; its components along e1, e2, e3 (the columns of
    Rz(phi) Rx(theta)) are what Eq. 16 calls omega.
    """
    def Rz(a):
        return sp.Matrix([[sp.cos(a), -sp.sin(a), 0], [sp.sin(a), sp.cos(a), 0], [0, 0, 1]])

    def Rx(a):
        return sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])

    def axial(W):
        return sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])

    frame = Rz(phi) * Rx(theta)  # columns e1, e2, e3 in inertial components
    body = frame * Rz(psi)
    w_in = axial((body.applyfunc(time_derivative) * body.T).applyfunc(sp.simplify))
    W_in = axial((frame.applyfunc(time_derivative) * frame.T).applyfunc(sp.simplify))
    to123 = lambda v: (frame.T * v).applyfunc(sp.simplify)
    return frame, to123(w_in), to123(W_in)
