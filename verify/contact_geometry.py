"""The numbers the scorer (and the animation) need from the contact geometry, in numpy only (no sympy, no heyoka).

The forms of a run and the conversion between them are defined in :mod:`verify.frames`, which
builds them symbolically from :mod:`models`; this module holds the numeric parts the scorer
uses, so that ``from verify.scoring import score`` needs only numpy and mpmath:

* the columns of the forms and :func:`detect`;
* :func:`frame`, :func:`matrix_from_quaternion`, :func:`b_to_euler` (form (b) -> (a)),
  :func:`rotation_defect`;
* :data:`CONTACT` and :func:`contact_point`: the height and the constrained velocity of the
  contact point along a form (b) run, with r_P = r2 e2 + r3 e3 from C to P (paper Eqs. 7, 47, 63);
* :data:`ENERGY`: the energy of a form (a) state of every model the reference set holds.

Every function here is tested against the sympy expressions it stands for
(``tests/test_score_light.py``: random states, agreement to 1e-14 relative); the energies and the
radii are written as ``sympy.lambdify`` prints the models' expressions, term by term in the same
order, so that the light scorer's numbers are the very doubles the symbolic path gave.
"""
from __future__ import annotations

import numpy as np
from numpy import cos, sin

STATE_NAMES = ("theta", "phi", "psi", "thetadot", "phidot", "psidot", "x", "y")  # models.catalogue.STATE_NAMES
EULER = ("t",) + STATE_NAMES
MATRIX_ENTRIES = tuple(f"R{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3))
QUATERNION = ("qw", "qx", "qy", "qz")
MOTION = ("x", "y", "z", "vx", "vy", "vz", "wx", "wy", "wz")
MATRIX = ("t",) + MATRIX_ENTRIES + MOTION
QUATERNION_FORM = ("t",) + QUATERNION + MOTION
BOTH = ("t",) + MATRIX_ENTRIES + QUATERNION + MOTION
#: the rotation given both ways (as ``reference --export`` writes it): R is read, q must agree at t = 0
FORMS = {"euler": EULER, "matrix": MATRIX, "quaternion": QUATERNION_FORM, "matrix+quaternion": BOTH}


def _disk_radii(th, p):
    """Disk of radius 1 (paper Eq. 7): r_P = -e2."""
    return -1, 0


def _ring_radii(th, p):
    """Ring, the centre of mass h below the rim's plane (paper Eq. 47): r_P = -e2 - h e3."""
    return -1, -p["h"]


def _hurricane_radii(th, p):
    """Hurricane balls on the lower ball (paper Eq. 63): r_P = -sin(theta) e2 - (1 + cos(theta)) e3."""
    return -sin(th), -cos(th) - 1


#: model -> (r2(theta, params), r3(theta, params), contact): r_P = r2 e2 + r3 e3 from C to the contact
#: point; 'rolling' (P at rest) or 'smooth' (only P's vertical velocity vanishes).
CONTACT = {"disk": (_disk_radii, "rolling"), "ring": (_ring_radii, "rolling"),
           "hurricane": (_hurricane_radii, "rolling"), "sliding-disk": (_disk_radii, "smooth")}
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


def frame(th, ph) -> tuple:
    """(e1, e2, e3), each of shape (3, n) (paper Fig. 1)."""
    s, c, sp_, cp = np.sin(th), np.cos(th), np.sin(ph), np.cos(ph)
    z = np.zeros_like(th)
    return (np.array([cp, sp_, z]), np.array([-sp_ * c, cp * c, s]), np.array([sp_ * s, -cp * s, c]))


def rotation_from_euler(th, ph, ps) -> np.ndarray:
    """R = Rz(phi) Rx(theta) Rz(psi) of shape (3, 3, n), body to inertial (columns b1, b2, e3).

    Not used by :func:`verify.scoring.score` (which reads R from the run); it is the numeric
    twin of :func:`verify.frames.rotation_matrix` for a tool that writes form (b) without sympy.
    """
    th, ph, ps = np.broadcast_arrays(*(np.asarray(a, float) for a in (th, ph, ps)))
    ct, st, cf, sf, cs, ss = np.cos(th), np.sin(th), np.cos(ph), np.sin(ph), np.cos(ps), np.sin(ps)
    return np.array([[cf * cs - sf * ct * ss, -cf * ss - sf * ct * cs, sf * st],
                     [sf * cs + cf * ct * ss, -sf * ss + cf * ct * cs, -cf * st],
                     [st * ss, st * cs, ct]])


def matrix_from_quaternion(qw, qx, qy, qz) -> np.ndarray:
    """R (shape (3, 3, n)) of the quaternion, normalised: its norm's defect is reported apart."""
    n = np.sqrt(qw ** 2 + qx ** 2 + qy ** 2 + qz ** 2)
    w, x, y, z = qw / n, qx / n, qy / n, qz / n
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def b_to_euler(columns: dict) -> tuple:
    """(form (a) as a dict of arrays, R of shape (3, 3, n), omega of shape (3, n)) from form (b)'s columns.

    theta = atan2(hypot(R13, R23), R33), phi = atan2(R13, -R23), psi = atan2(R31, R32); then
    thetadot = w . e1, phidot = (w . e2) / sin theta, psidot = w . e3 - phidot cos theta (paper Eq. 16).
    """
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


def contact_vector(model: str, th, ph, params: dict) -> np.ndarray:
    """r_P = r2 e2 + r3 e3 in inertial components, shape (3, n) (paper Eqs. 7, 47, 63).

    Parameters
    ----------
    model : str
        One of :data:`BODIES_ON_PLANE`.
    th, ph : array_like
        theta and phi.
    params : dict
        The model's parameters by name (the ring's ``h``).
    """
    radii, _ = CONTACT[model]
    th = np.asarray(th, float)
    r2, r3 = radii(th, params)
    r2 = np.broadcast_to(r2, th.shape)
    r3 = np.broadcast_to(r3, th.shape)
    _, e2, e3 = frame(th, np.asarray(ph, float))
    return r2 * e2 + r3 * e3


def contact_point(model: str, columns: dict, state: dict, w: np.ndarray, params: dict) -> tuple:
    """(height of P, velocity of P that the constraints require to vanish) along a form (b) run.

    The height is P's z (lengths in the model's unit); the velocity is v_C + omega x r_P (paper
    Eq. 7), all three components rolling, its vertical component on the smooth plane (the body
    may slide there).  Returned as arrays: height (n,), |velocity| (n,).
    """
    r_p = contact_vector(model, state["theta"], state["phi"], params)
    height = np.asarray(columns["z"], float) + r_p[2]
    v = np.array([columns["vx"], columns["vy"], columns["vz"]], float) + np.cross(w, r_p, axis=0)
    speed = np.abs(v[2]) if CONTACT[model][1] == "smooth" else np.sqrt((v * v).sum(axis=0))
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


# The energies per M L^2 of a form (a) state (potential zero on the plane), as sympy.lambdify prints
# ``models.get_model(name).energy`` (same terms, same order: the same doubles).  Arguments: the eight
# state components, then the parameters in the model's order.

def _energy_disk(theta, phi, psi, thetadot, phidot, psidot, x, y, k, g):
    return (g*sin(theta) + (1/2)*k*phidot**2*sin(theta)**2 + (1/2)*k*thetadot**2 + k*(phidot*cos(theta) + psidot)**2
            + (1/2)*thetadot**2 + (1/2)*(-phidot*cos(theta) - psidot)**2)


def _energy_ring(theta, phi, psi, thetadot, phidot, psidot, x, y, I1, I3, h, g):
    return ((1/2)*I1*phidot**2*sin(theta)**2 + (1/2)*I1*thetadot**2 + (1/2)*I3*(phidot*cos(theta) + psidot)**2
            + g*(h*cos(theta) + sin(theta)) + (1/2)*h**2*thetadot**2 + (1/2)*thetadot**2
            + (1/2)*(h*phidot*sin(theta) - phidot*cos(theta) - psidot)**2)


def _energy_hurricane(theta, phi, psi, thetadot, phidot, psidot, x, y, I1, I3, g):
    return ((1/2)*I1*phidot**2*sin(theta)**2 + (1/2)*I1*thetadot**2 + (1/2)*I3*(phidot*cos(theta) + psidot)**2
            + g*(cos(theta) + 1) + (1/2)*thetadot**2*(-cos(theta) - 1)**2 + (1/2)*thetadot**2*sin(theta)**2
            + (1/2)*(-phidot*(-cos(theta) - 1)*sin(theta) - (phidot*cos(theta) + psidot)*sin(theta))**2)


def _energy_sliding_disk(theta, phi, psi, thetadot, phidot, psidot, x, y, k, g):
    return (g*sin(theta) + (1/2)*k*phidot**2*sin(theta)**2 + (1/2)*k*thetadot**2 + k*(phidot*cos(theta) + psidot)**2
            + (1/2)*thetadot**2*sin(theta)**2*cos(theta)**2 + (1/2)*thetadot**2*cos(theta)**4)


def _energy_gyroscope(theta, phi, psi, thetadot, phidot, psidot, x, y, I1, I3, g):
    return ((1/2)*I1*phidot**2*sin(theta)**2 + (1/2)*I1*thetadot**2 + (1/2)*I3*phidot**2*cos(theta)**2
            + I3*phidot*psidot*cos(theta) + (1/2)*I3*psidot**2 + 2*g*cos(theta) + 2*phidot**2*sin(theta)**2
            + 2*thetadot**2)


def _energy_effective(theta, phi, psi, thetadot, phidot, psidot, x, y, I1, I3, g):
    return ((1/2)*I1*phidot**2*sin(theta)**2 + (1/2)*I1*thetadot**2 - 1/2*I3*phidot**2*sin(theta)**2
            + I3*phidot**2*cos(theta) + I3*phidot**2 + g*(cos(theta) + 1) + (1/2)*thetadot**2*sin(theta)**2)


#: model -> (energy(theta, ..., y, *parameters), the parameters' names in order).
ENERGY = {"disk": (_energy_disk, ("k", "g")), "ring": (_energy_ring, ("I1", "I3", "h", "g")),
          "hurricane": (_energy_hurricane, ("I1", "I3", "g")), "sliding-disk": (_energy_sliding_disk, ("k", "g")),
          "gyroscope": (_energy_gyroscope, ("I1", "I3", "g")), "effective": (_energy_effective, ("I1", "I3", "g"))}


def energy(model: str, state: dict, params: dict) -> np.ndarray:
    """E per M L^2 of a form (a) state (a dict of arrays by state name) with ``params`` by name."""
    if model not in ENERGY:
        raise ValueError(f"no numeric energy for model {model!r}; known: {', '.join(ENERGY)}")
    f, names = ENERGY[model]
    return f(*[state[n] for n in STATE_NAMES], *[params[p] for p in names])
