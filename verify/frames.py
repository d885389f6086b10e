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
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from models import get_model
from models.symbols import STATE, STATE_NAMES, omega_body, phi, psi, theta, thetadot, to_inertial

EULER = ("t",) + STATE_NAMES
MATRIX_ENTRIES = tuple(f"R{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3))
QUATERNION = ("qw", "qx", "qy", "qz")
MOTION = ("x", "y", "z", "vx", "vy", "vz", "wx", "wy", "wz")
MATRIX = ("t",) + MATRIX_ENTRIES + MOTION
QUATERNION_FORM = ("t",) + QUATERNION + MOTION
BOTH = ("t",) + MATRIX_ENTRIES + QUATERNION + MOTION
#: the rotation given both ways (as ``reference --export`` writes it): R is read, q must agree at t = 0
FORMS = {"euler": EULER, "matrix": MATRIX, "quaternion": QUATERNION_FORM, "matrix+quaternion": BOTH}


def _contact_geometry():
    from models import disk, hurricane, ring

    return {"disk": (disk.R2, disk.R3, "rolling"), "ring": (ring.R2, ring.R3, "rolling"),
            "hurricane": (hurricane.R2, hurricane.R3, "rolling"),
            "sliding-disk": (sp.Integer(-1), sp.Integer(0), "smooth")}


#: model -> (r2, r3, contact): r_P = r2 e2 + r3 e3 from C to the contact point.
CONTACT = _contact_geometry()
BODIES_ON_PLANE = tuple(CONTACT)


def detect(columns) -> str:
    """The form whose columns are exactly ``columns`` (any order); ``ValueError`` naming the difference."""
    have = set(columns)
    for name, cols in FORMS.items():
        if have == set(cols):
            return name
    best = min(FORMS, key=lambda n: len(have ^ set(FORMS[n])))
    missing = [c for c in FORMS[best] if c not in have]
    extra = sorted(have - set(FORMS[best]))
    raise ValueError(f"columns {sorted(have)} are none of the documented forms (nearest: {best}; missing "
                     f"{missing or '-'}, unknown {extra or '-'}); allowed: "
                     + "; ".join(f"{n}: {', '.join(c)}" for n, c in FORMS.items()))


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
    from models.symbols import frame_vectors

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


def matrix_from_quaternion(qw, qx, qy, qz) -> np.ndarray:
    """R (shape (3, 3, n)) of the quaternion, normalised: its norm's defect is reported apart."""
    n = np.sqrt(qw ** 2 + qx ** 2 + qy ** 2 + qz ** 2)
    w, x, y, z = qw / n, qx / n, qy / n, qz / n
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def b_to_euler(columns: dict) -> tuple:
    """(form (a) as a dict of arrays, R of shape (3, 3, n), omega of shape (3, n)) from form (b)'s columns."""
    if "R11" not in columns:
        R = matrix_from_quaternion(*(columns[c] for c in QUATERNION))
    else:
        R = np.array([[columns[f"R{i}{j}"] for j in (1, 2, 3)] for i in (1, 2, 3)])
    th = np.arctan2(np.hypot(R[0, 2], R[1, 2]), R[2, 2])
    ph = np.arctan2(R[0, 2], -R[1, 2])
    ps = np.arctan2(R[2, 0], R[2, 1])
    w = np.array([columns["wx"], columns["wy"], columns["wz"]])
    e1, e2, e3 = frame(th, ph)
    thd = np.einsum("in,in->n", w, e1)
    phd = np.einsum("in,in->n", w, e2) / np.sin(th)
    psd = np.einsum("in,in->n", w, e3) - phd * np.cos(th)
    state = {"theta": th, "phi": ph, "psi": ps, "thetadot": thd, "phidot": phd, "psidot": psd,
             "x": np.asarray(columns["x"], float), "y": np.asarray(columns["y"], float)}
    return state, R, w


def frame(th, ph) -> tuple:
    """(e1, e2, e3), each of shape (3, n) (paper Fig. 1)."""
    s, c, sp_, cp = np.sin(th), np.cos(th), np.sin(ph), np.cos(ph)
    z = np.zeros_like(th)
    return (np.array([cp, sp_, z]), np.array([-sp_ * c, cp * c, s]), np.array([sp_ * s, -cp * s, c]))


@lru_cache(maxsize=None)
def _radii(model: str):
    m = get_model(model)
    r2, r3, _ = CONTACT[model]
    args = [theta] + [p.symbol for p in m.parameters]
    return sp.lambdify(args, r2, "numpy"), sp.lambdify(args, r3, "numpy")


def contact_point(model: str, columns: dict, state: dict, w: np.ndarray, params: dict) -> tuple:
    """(height of P, velocity of P that the constraints require to vanish) along a form (b) run.

    The height is P's z (lengths in the model's unit); the velocity is v_C + omega x r_P,
    all three components rolling, its vertical component on the smooth plane (the body may
    slide there).  Returned as arrays: height (n,), |velocity| (n,).
    """
    m = get_model(model)
    values = [params[p.name] for p in m.parameters]
    f2, f3 = _radii(model)
    th = state["theta"]
    r2 = np.broadcast_to(f2(th, *values), th.shape)
    r3 = np.broadcast_to(f3(th, *values), th.shape)
    _, e2, e3 = frame(th, state["phi"])
    r_p = r2 * e2 + r3 * e3
    height = np.asarray(columns["z"], float) + r_p[2]
    v = np.array([columns["vx"], columns["vy"], columns["vz"]], float) + np.cross(w, r_p, axis=0)
    speed = np.abs(v[2]) if CONTACT[model][2] == "smooth" else np.sqrt((v * v).sum(axis=0))
    return height, speed


def rotation_defect(R: np.ndarray, columns: dict) -> np.ndarray:
    """How far the run's orientation is from a rotation: max |R^T R - I| entry and |det R - 1|, or
    | |q| - 1 |; with both given, also the largest entry of R(q) - R."""
    norm = None
    if "qw" in columns:
        norm = np.abs(np.sqrt(sum(np.asarray(columns[c], float) ** 2 for c in QUATERNION)) - 1)
        if "R11" not in columns:
            return norm
    gram = np.einsum("kin,kjn->ijn", R, R) - np.eye(3)[:, :, None]
    det = np.linalg.det(np.moveaxis(R, 2, 0))
    defect = np.maximum(np.abs(gram).max(axis=(0, 1)), np.abs(det - 1))
    if norm is not None:  # both given: they must be the same rotation
        other = matrix_from_quaternion(*(columns[c] for c in QUATERNION))
        defect = np.maximum(defect, np.maximum(norm, np.abs(other - R).max(axis=(0, 1))))
    return defect
