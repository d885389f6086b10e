"""The two documented forms of a state, and the exact conversion between them.

Form (a), ``euler``: the suite's own state (paper Fig. 1, :mod:`models.symbols`)

    t, theta, phi, psi, thetadot, phidot, psidot, x, y

3-1-3 Euler angles (phi about Z, theta about the line of nodes e1, psi about the symmetry
axis e3), their rates, and (x, y) the horizontal position of the centre of mass C.

Form (b), ``matrix`` or ``quaternion``: what a general multibody engine reports

    t, R11 .. R33 (or qw, qx, qy, qz), x, y, z, vx, vy, vz, wx, wy, wz

* ``R`` maps body to inertial components, with the body's symmetry axis its third column:
  ``R = Rz(phi) Rx(theta) Rz(psi)``, so column 3 is e3 and columns 1, 2 are e1, e2 turned
  by psi about e3 (``b1 = cos psi e1 + sin psi e2``, ``b2 = -sin psi e1 + cos psi e2``);
  ``Rij`` is row i, column j.  The quaternion (scalar first) is the same rotation,
  ``q = qz(phi) qx(theta) qz(psi)``; q and -q are the same rotation and both are accepted.
* ``x, y, z`` the centre of mass in the inertial frame, Z up, the plane at z = 0;
  ``vx, vy, vz`` its velocity; ``wx, wy, wz`` the angular velocity in *inertial* components.

(b) -> (a) is exact up to rounding: theta = atan2(hypot(R13, R23), R33),
phi = atan2(R13, -R23), psi = atan2(R31, R32) (both in (-pi, pi]: compared modulo 2 pi), and
with e1, e2, e3 from those angles thetadot = w . e1, phidot = (w . e2) / sin theta,
psidot = w . e3 - phidot cos theta (omega = (thetadot, phidot sin theta, phidot cos theta +
psidot) in (e1, e2, e3), paper Eq. 16).  z, vx, vy, vz carry what (a) leaves implicit, the
constraints: the contact point P = C + r_P (r_P = r2(theta) e2 + r3(theta) e3, paper Eqs. 7,
47, 63) must be at height 0 and, rolling, at rest (v_C + omega x r_P = 0, Eq. 7); on the
smooth plane only its vertical velocity must vanish.  A run in form (b) is scored on
those too.

Form (b) is defined for the bodies on the plane: ``disk``, ``ring``, ``hurricane``,
``sliding-disk``.  (The gyroscope turns about a fixed pivot and the effective model imposes
psi = phi; neither has a contact on the plane, and their runs are read in form (a) only.)

The numeric parts (the columns, :func:`detect`, (b) -> (a), the contact point, the rotation's
defect) live in :mod:`verify.contact_geometry`, numpy only, so that scoring needs no sympy; they
are re-exported here and tested against the expressions of this module.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from models import disk, get_model, hurricane, ring
from models.symbols import STATE, STATE_NAMES, frame_vectors, omega_body, phi, psi, theta, thetadot, to_inertial

from .contact_geometry import (BOTH, EULER, FORMS, MATRIX, MATRIX_ENTRIES, MOTION, QUATERNION,  # noqa: F401
                               QUATERNION_FORM, b_to_euler, contact_point, detect, frame, matrix_from_quaternion,
                               rotation_defect)


def _contact_geometry():
    return {"disk": (disk.R2, disk.R3, "rolling"), "ring": (ring.R2, ring.R3, "rolling"),
            "hurricane": (hurricane.R2, hurricane.R3, "rolling"),
            "sliding-disk": (sp.Integer(-1), sp.Integer(0), "smooth")}


#: model -> (r2, r3, contact): r_P = r2 e2 + r3 e3 from C to the contact point.
CONTACT = _contact_geometry()
BODIES_ON_PLANE = tuple(CONTACT)


def rotation_matrix() -> sp.Matrix:
    """R = Rz(phi) Rx(theta) Rz(psi), body to inertial (columns b1, b2, e3)."""
    def rz(a):
        return sp.Matrix([[sp.cos(a), -sp.sin(a), 0], [sp.sin(a), sp.cos(a), 0], [0, 0, 1]])

    rx = sp.Matrix([[1, 0, 0], [0, sp.cos(theta), -sp.sin(theta)], [0, sp.sin(theta), sp.cos(theta)]])
    return rz(phi) * rx * rz(psi)


def quaternion() -> tuple:
    """(qw, qx, qy, qz) of qz(phi) qx(theta) qz(psi)."""
    c, s = sp.cos(theta / 2), sp.sin(theta / 2)
    return (c * sp.cos((phi + psi) / 2), s * sp.cos((phi - psi) / 2), s * sp.sin((phi - psi) / 2),
            c * sp.sin((phi + psi) / 2))


def contact_vector(model: str) -> sp.Matrix:
    """r_P in inertial components (paper Eqs. 7, 47, 63)."""
    r2, r3, _ = CONTACT[model]
    _, e2, e3 = frame_vectors()
    return r2 * e2 + r3 * e3


@lru_cache(maxsize=None)
def from_euler_expressions(model: str) -> dict:
    """Form (b)'s columns (but t) as sympy expressions of the state and the model's parameters."""
    if model not in CONTACT:
        raise ValueError(f"form (b) is defined for {', '.join(BODIES_ON_PLANE)}; not for {model!r}")
    m = get_model(model)
    R = rotation_matrix()
    out = {f"R{i + 1}{j + 1}": R[i, j] for i in range(3) for j in range(3)}
    out.update(zip(QUATERNION, quaternion()))
    height = -contact_vector(model)[2]  # C above the plane: P = C + r_P is at z = 0
    w = to_inertial(omega_body())
    vx, vy = m.velocity_xy
    out.update({"x": STATE[6], "y": STATE[7], "z": sp.simplify(height),
                "vx": vx, "vy": vy, "vz": sp.diff(height, theta) * thetadot,
                "wx": w[0], "wy": w[1], "wz": w[2]})
    return out


@lru_cache(maxsize=None)
def _lambdified(model: str, module: str):
    m = get_model(model)
    exprs = from_euler_expressions(model)
    args = list(STATE) + [p.symbol for p in m.parameters]
    return {k: sp.lambdify(args, e, modules=module) for k, e in exprs.items()}


def euler_to_b(model: str, state: dict, params: dict, module: str = "numpy") -> dict:
    """Form (b) from form (a): ``state`` maps state names to values (arrays or mpf), ``params`` names to values.

    ``module`` 'numpy' (float arrays) or 'mpmath' (at the caller's mpmath precision).
    """
    m = get_model(model)
    args = [state[n] for n in STATE_NAMES] + [params[p.name] for p in m.parameters]
    out = {}
    for k, f in _lambdified(model, module).items():
        v = f(*args)
        out[k] = np.broadcast_to(v, np.shape(state["theta"])).astype(float) if module == "numpy" else v
    return out
