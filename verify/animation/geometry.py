"""Where each drawn body is: orientation, contact vector, centre-of-mass height (numpy only).

Conventions of :mod:`models.symbols` and :mod:`verify.frames`: 3-1-3 Euler angles, the body
turned by ``R = Rz(phi) Rx(theta) Rz(psi)`` (body to inertial; columns b1, b2, e3 with e3 the
symmetry axis), Z up, the plane at z = 0.  Lengths in the body's unit: the disk's or ring's
radius R, the hurricane ball's radius a.

The contact vector from the centre of mass C to the contact point P is
``r_P = r2(theta) e2 + r3(theta) e3`` (paper Eqs. 7, 47, 63):

=============  ===================  ======================  ============================
body           r2                   r3                      z_C = -(r2 sin + r3 cos)
=============  ===================  ======================  ============================
disk, hoop     -1                   0                       sin(theta)            (Eq. 7)
ring           -1                   -h                      sin(theta) + h cos(theta) (Eq. 47)
hurricane      -sin(theta)          -(1 + cos(theta))       1 + cos(theta)        (Eq. 63)
=============  ===================  ======================  ============================

P = C + r_P is on the plane because e2 and e3 have heights sin(theta) and cos(theta).  The
gyroscope (paper Eqs. 83-86) has no contact: the bottom of its lower ball, r_B = -2 e3 from
C, is held at a fixed pivot.
"""
from __future__ import annotations

import numpy as np

from ..contact_geometry import CONTACT
from .errors import AnimationError

#: Which body each drawable model is.  The effective model (paper Eq. 96) is left out: it
#: imposes psi = phi and fixes x, y, so no rolling body moves as it says.
DRAWN_MODELS = {
    "disk": "disk", "sliding-disk": "disk", "disk+moffatt": "disk", "disk+contact-rate": "disk",
    "disk+coulomb": "disk",
    "ring": "ring", "ring+air-drag": "ring", "ring+rolling-friction": "ring", "ring+coulomb": "ring",
    "hurricane": "hurricane", "gyroscope": "gyroscope",
}
#: The parameters a body's drawing reads (others are accepted and ignored).
REQUIRED_PARAMS = {"disk": ("k",), "ring": ("h",), "hurricane": (), "gyroscope": (), "revolution": ()}
#: The ring's wall (inner radius 1 - w) where the run does not give ``w``: the paper's ring,
#: w = 0.5 cm of R = 3.66 cm (text after Eq. 62).
RING_WALL_DEFAULT = 0.5 / 3.66
#: Distance from C to the gyroscope's pivot along -e3 (paper: r_B = (0, 0, -2a)).
PIVOT_DISTANCE = 2.0


#: The prefix of a body of revolution's models (``body:NAME``, ``body:NAME+coulomb``, ``body:NAME+smooth``):
#: drawn from the body file's profile (:mod:`verify.animation.revolution`).
BODY_PREFIX = "body:"


def body_kind(model: str) -> str:
    """The body drawn for ``model``: 'disk', 'ring', 'hurricane', 'gyroscope', or 'revolution' (a body file's).

    Raises
    ------
    AnimationError
        ``model`` is not drawable (one line naming it and the drawable models).
    """
    if isinstance(model, str) and model.startswith(BODY_PREFIX) and len(model) > len(BODY_PREFIX):
        return "revolution"
    if model not in DRAWN_MODELS:
        raise AnimationError(f"cannot animate model {model!r}; allowed: {', '.join(DRAWN_MODELS)}, or body:NAME "
                             "(a body file's)")
    return DRAWN_MODELS[model]


def body_name(model: str) -> str:
    """NAME of a body model ``body:NAME``, ``body:NAME+coulomb`` or ``body:NAME+smooth``."""
    return model[len(BODY_PREFIX):].split("+", 1)[0]


def checked_params(model: str, params) -> dict:
    """``params`` as floats, with the ones the drawing reads present and in range."""
    kind = body_kind(model)
    out = {}
    for name, value in dict(params or {}).items():
        try:
            out[name] = float(value)
        except (TypeError, ValueError):
            raise AnimationError(f"parameter {name}={value!r} of {model!r} is not a number; allowed: floats") from None
    missing = [name for name in REQUIRED_PARAMS[kind] if name not in out]
    if missing:
        raise AnimationError(f"model {model!r} needs parameter(s) {', '.join(missing)} to be drawn; "
                             f"given: {', '.join(out) or 'none'}")
    if kind == "disk" and not 0 < out["k"] <= 0.5:
        raise AnimationError(f"disk parameter k={out['k']!r}; allowed: 0 < k <= 1/2")
    if kind == "ring" and not out["h"] >= 0:
        raise AnimationError(f"ring parameter h={out['h']!r}; allowed: h >= 0")
    if kind == "ring" and not 0 < out.get("w", RING_WALL_DEFAULT) <= 1:
        raise AnimationError(f"ring parameter w={out['w']!r}; allowed: 0 < w <= 1")
    return out


def frame(theta, phi) -> tuple:
    """(e1, e2, e3), each of shape theta.shape + (3,) (paper Fig. 1, :func:`models.symbols.frame_vectors`)."""
    theta, phi = np.asarray(theta, float), np.asarray(phi, float)
    s, c, sp, cp = np.sin(theta), np.cos(theta), np.sin(phi), np.cos(phi)
    zero = np.zeros_like(theta)
    return (np.stack([cp, sp, zero], -1), np.stack([-sp * c, cp * c, s], -1), np.stack([sp * s, -cp * s, c], -1))


def rotation(theta, phi, psi) -> np.ndarray:
    """R = Rz(phi) Rx(theta) Rz(psi), body to inertial, shape theta.shape + (3, 3).

    Its columns are b1 = cos(psi) e1 + sin(psi) e2, b2 = -sin(psi) e1 + cos(psi) e2 and e3
    (:func:`verify.frames.rotation_matrix`).
    """
    e1, e2, e3 = frame(theta, phi)
    cs, ss = np.cos(psi)[..., None], np.sin(psi)[..., None]
    return np.stack([cs * e1 + ss * e2, -ss * e1 + cs * e2, e3], -1)


def contact_radii(kind: str, theta, params: dict) -> tuple:
    """(r2, r3) of r_P = r2 e2 + r3 e3 (paper Eqs. 7, 47, 63); arrays of theta's shape.

    The scorer's numbers (:data:`verify.contact_geometry.CONTACT`): one definition of each body's contact."""
    if kind not in ("disk", "ring", "hurricane"):
        raise AnimationError(f"body {kind!r} has no contact on the plane; allowed: disk, ring, hurricane")
    theta = np.asarray(theta, float)
    r2, r3 = CONTACT[kind][0](theta, params)
    return np.broadcast_to(r2, theta.shape).astype(float), np.broadcast_to(r3, theta.shape).astype(float)


def centre_height(kind: str, theta, params: dict) -> np.ndarray:
    """z_C = -(r2 sin(theta) + r3 cos(theta)): the contact point is on the plane z = 0.

    For the gyroscope, the height of C above its pivot, 2 cos(theta) (paper Eq. 85).
    """
    theta = np.asarray(theta, float)
    if kind == "gyroscope":
        return PIVOT_DISTANCE * np.cos(theta)
    r2, r3 = contact_radii(kind, theta, params)
    return -(r2 * np.sin(theta) + r3 * np.cos(theta))


def centre(kind: str, theta, x, y, params: dict, pivot_height: float = 0.0) -> np.ndarray:
    """The centre of mass C (shape theta.shape + (3,)); the gyroscope's pivot at ``pivot_height``."""
    z = centre_height(kind, theta, params) + (pivot_height if kind == "gyroscope" else 0.0)
    return np.stack([np.asarray(x, float), np.asarray(y, float), z], -1)


def contact_point(kind: str, theta, phi, x, y, params: dict) -> np.ndarray:
    """P = C + r_P (shape theta.shape + (3,)); its height is 0 up to rounding."""
    _, e2, e3 = frame(theta, phi)
    r2, r3 = contact_radii(kind, theta, params)
    return centre(kind, theta, x, y, params) + r2[..., None] * e2 + r3[..., None] * e3


def pivot_point(theta, phi, x, y, pivot_height: float) -> np.ndarray:
    """The gyroscope's pivot C - 2 e3 (fixed while the run is right; shape theta.shape + (3,))."""
    _, _, e3 = frame(theta, phi)
    return centre("gyroscope", theta, x, y, {}, pivot_height) - PIVOT_DISTANCE * e3


def gyroscope_pivot_height(theta) -> float:
    """The stand under the gyroscope's pivot: high enough that no ball reaches the floor.

    Relative to the pivot the lower ball's lowest point is at cos(theta) - 1 and the upper
    ball's at 3 cos(theta) - 1; the stand is the largest depth over the run plus 0.25.
    """
    c = np.cos(np.asarray(theta, float))
    return float(max(np.max(1 - c), np.max(1 - 3 * c), 0.0)) + 0.25
