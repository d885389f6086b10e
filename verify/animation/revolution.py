"""Any body of revolution drawn from its meridian profile (a body file, :mod:`models.bodies`).

A body file gives a convex meridian profile (rho, zeta): rho the distance from the axis e3, zeta the
height along e3 above the centre of mass C, lengths in the body's unit L (:mod:`models.profiles`).
Revolving the profile about e3 gives the drawn surface; the body is placed with the body file's own
contact vector r_P = r2(theta) e2 + r3(theta) e3 (the same sympy expressions the model is derived
from, :func:`models.profiles.vector`, evaluated here by numpy), so C is at height
z_C = -(r2 sin(theta) + r3 cos(theta)) and the drawn surface touches the plane at P.

The meridian of each kind, from the axis below C to the axis above it (vertices on the true surface):

=============  ==============================================================================
kind           meridian
=============  ==============================================================================
point-rim      the flat disk rho in [0, radius], zeta = 0 (a hoop, I3 = radius^2: the band
               rho in [(1 - HOOP_BAND) radius, radius])
two-rims       the cylinder |zeta| <= half_thickness, rho <= radius; hollow (inner radius
               sqrt(2 I3 - radius^2), the uniform annular cylinder of that I3) where
               0 < 2 I3 - radius^2 < radius^2: the paper's ring comes out with its wall w
sphere         rho = radius sin(s), zeta = centre_height - radius cos(s), s in [0, pi]
torus-rim      the bottom face, the lower rounding arc, the band, the upper arc, the top face
ellipse        rho = a sin(s), zeta = centre_height - c cos(s), s in [0, pi]
=============  ==============================================================================

**The drawn mesh touches the plane, to its resolution.** Every vertex is on the true surface and the
surface is convex, so the flat faces lie inside the body and the drawn body is never below the plane
(its lowest point is a vertex: a face's lowest point is one of its corners).  The contact point P, at
azimuth beta* and meridian point m*, is within ``2 rho_max sin(pi / (2 M))`` (half the azimuthal
chord at the widest parallel, M meridians) plus half the longest meridian arc between samples of a
vertex v; the plane is a support plane of a surface whose point P is on it, so z(v) <= |v - P|.
Hence 0 <= lowest drawn point <= :func:`resolution` (tests/test_animate_bodies.py checks it at every
frame of a run, and that a mesh placed with another contact fails it).

**The tippe top's stem.** A sphere whose centre is above C (``centre_height > 0``, the centre of
mass below the centre: a tippe top, or Routh's loaded ball) gets a stem on the axis on the side
opposite the ball's bottom (+e3), so that a turn-over shows.  The stem is *drawn only*: the model is
the ball, which rests on its top point when inverted, so the part of the stem that would be below
the floor is cut off at the floor each frame (:func:`stem_quads`) and the panel says so.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .errors import AnimationError
from .geometry import body_name
from .shapes import HOOP_BAND, Mesh

#: Meridians of a drawn body (its azimuthal resolution) and samples along a curved piece of profile.
MERIDIANS = 32
CURVE_SAMPLES = 16
#: Straight pieces of profile are cut into this many faces (only the lighting sees it).
FLAT_SAMPLES = 3
#: The stem, in units of the sphere's radius: radius, and length beyond the sphere.
STEM_RADIUS = 0.12
STEM_LENGTH = 0.7
STEM_SIDES = 12


@dataclass(frozen=True)
class Profile:
    """A body of revolution ready to draw: its name, profile ``kind``, the profile's numbers as floats
    (the run's where it overrides the file's), and I1, I3 (per unit mass, L^2)."""

    name: str
    kind: str
    values: tuple  # ((field, float), ...) in the kind's order
    I1: float
    I3: float

    @property
    def numbers(self) -> dict:
        return dict(self.values)

    @property
    def stem(self) -> bool:
        """Whether a stem is drawn: a sphere with its centre above C (module docstring)."""
        return self.kind == "sphere" and self.numbers["centre_height"] > 0


@dataclass(frozen=True)
class Meridian:
    """The profile's points (rho, zeta) from the axis below C to the axis above it (or an open curve:
    a hoop's band), with ``arc_max`` the longest arc of the true profile between consecutive points and
    ``upper`` the flag of each segment on the stem's side (zeta above the sphere's centre)."""

    rho: np.ndarray
    zeta: np.ndarray
    arc_max: float
    upper: np.ndarray


def profile_of(body, params=None) -> Profile:
    """The :class:`Profile` of ``body`` (a :class:`models.bodies.Body`) with the run's parameters
    ``params`` (profile fields, I1, I3 by name; others ignored), checked.

    Raises
    ------
    AnimationError
        A length that is not positive, or a relation of the kind broken (one line).
    """
    from models.profiles import FIELDS, RELATIONS  # lazy: sympy (0.25 s): bodies of revolution only

    if body.kind == "curve":
        raise AnimationError(f"body {body.name!r}: kind = 'curve' is not drawn yet; allowed kinds: "
                             f"{', '.join(k for k in FIELDS if k != 'curve')} (a curve's mesh from r(s), z(s) is not built)")
    params = dict(params or {})
    numbers = {}
    for field, exact in body.profile:
        value = params.get(field, exact)
        try:
            numbers[field] = float(value)
        except (TypeError, ValueError):
            raise AnimationError(f"body {body.name!r}: {field}={value!r}; allowed: a number") from None
    for field in FIELDS[body.kind]:
        if field != "centre_height" and not numbers[field] > 0 and not (field == "half_thickness" and numbers[field] == 0):
            raise AnimationError(f"body {body.name!r}: {field}={numbers[field]!r}; allowed: a length > 0")
    for text, rule in RELATIONS.get(body.kind, ()):
        if not rule(numbers):
            raise AnimationError(f"body {body.name!r}: {numbers}; allowed: {text}")
    inertia = [float(params.get(n, v)) for n, v in (("I1", body.I1), ("I3", body.I3))]
    return Profile(body.name, body.kind, tuple((f, numbers[f]) for f in FIELDS[body.kind]), *inertia)


def profile_for(model: str, body, params) -> Profile:
    """The :class:`Profile` of a run of ``model`` (``body:NAME...``): of ``body`` if given, else of the shipped
    body file NAME."""
    if body is None:
        from models.bodies import InvalidBody, load, shipped  # lazy: sympy (0.25 s): bodies of revolution only

        name = body_name(model)
        if name not in shipped():
            raise AnimationError(f"model {model!r}: no shipped body {name!r}; allowed: {', '.join(shipped())}, or give "
                                 "the run's body (AnimationRun(body=models.bodies.load(FILE)))")
        try:
            body = load(name)
        except InvalidBody as err:
            raise AnimationError(str(err)) from None
    return profile_of(body, params)


@lru_cache(maxsize=None)
def _vector_function(kind: str):
    """numpy (theta, *fields) -> (r2, r3) of :func:`models.profiles.vector`: the model's own expressions."""
    import sympy as sp  # lazy: sympy (0.25 s): bodies of revolution only

    from models.profiles import FIELDS, vector  # lazy: as sympy above
    from models.symbols import theta  # lazy: as sympy above

    symbols = {f: sp.Symbol(f, real=True) for f in FIELDS[kind]}
    r2, r3 = vector(kind, symbols)
    return sp.lambdify((theta, *symbols.values()), (r2, r3), "numpy")


def contact_radii(profile: Profile, theta) -> tuple:
    """(r2, r3) of r_P = r2 e2 + r3 e3 at ``theta`` (arrays of theta's shape), by the body file's formula."""
    theta = np.asarray(theta, float)
    r2, r3 = _vector_function(profile.kind)(theta, *(v for _, v in profile.values))
    return np.broadcast_to(r2, theta.shape).astype(float), np.broadcast_to(r3, theta.shape).astype(float)


def centre_height(profile: Profile, theta) -> np.ndarray:
    """z_C = -(r2 sin(theta) + r3 cos(theta)): the contact point on the plane z = 0."""
    theta = np.asarray(theta, float)
    r2, r3 = contact_radii(profile, theta)
    return -(r2 * np.sin(theta) + r3 * np.cos(theta))


def _arc(rho0, zeta0, radius, a0, a1, n):
    a = np.linspace(a0, a1, n + 1)
    return rho0 + radius * np.cos(a), zeta0 + radius * np.sin(a), abs(a1 - a0) / n * radius


def _segment(p, q, n):
    s = np.linspace(0.0, 1.0, n + 1)
    return p[0] + (q[0] - p[0]) * s, p[1] + (q[1] - p[1]) * s, float(np.hypot(q[0] - p[0], q[1] - p[1])) / n


def _joined(pieces, touching) -> tuple:
    """One meridian from pieces (rho, zeta, arc); its arc bound is the longest of the ``touching`` pieces,
    those where the contact point can lie (the flat faces of a rounded coin touch only at theta = 0)."""
    rho, zeta, arcs = [], [], [0.0]
    for (r, z, arc), touches in zip(pieces, touching):
        start = 1 if rho else 0  # each piece begins where the last ended
        rho.append(r[start:])
        zeta.append(z[start:])
        if touches:
            arcs.append(arc)
    return np.concatenate(rho), np.concatenate(zeta), max(arcs)


def meridian(profile: Profile, samples: int = CURVE_SAMPLES) -> Meridian:
    """The profile's points (module docstring), ``samples`` per curved piece (half as many on a quarter arc)."""
    v = profile.numbers
    flat = FLAT_SAMPLES
    if profile.kind == "point-rim":
        R = v["radius"]
        inner = (1 - HOOP_BAND) * R if profile.I3 >= R * R * (1 - 1e-12) else 0.0
        rho, zeta, _ = _segment((inner, 0.0), (R, 0.0), flat)
        arc = 0.0  # the contact is the rim point, a vertex of the meridian
    elif profile.kind == "two-rims":
        R, h = v["radius"], v["half_thickness"]
        hole = 2 * profile.I3 - R * R
        inner = float(np.sqrt(hole)) if 0 < hole < R * R else 0.0
        corners = [(inner, -h), (R, -h), (R, h), (inner, h)] + ([(inner, -h)] if inner > 0 else [])
        rho, zeta, arc = _joined([_segment(p, q, flat) for p, q in zip(corners, corners[1:])], [False] * len(corners))
        # the contact is a rim corner (radius, -+half_thickness), a vertex of the meridian: no arc term
    elif profile.kind == "sphere":
        R, c = v["radius"], v["centre_height"]
        rho, zeta, arc = _arc(0.0, c, R, -np.pi / 2, np.pi / 2, samples)
    elif profile.kind == "torus-rim":
        R, h, t = v["radius"], v["half_thickness"], v["tube_radius"]
        quarter = max(samples // 2, 2)
        pieces = [_segment((0.0, -h), (R - t, -h), flat), _arc(R - t, -(h - t), t, -np.pi / 2, 0.0, quarter)]
        touching = [False, True]
        if h - t > 0:  # the band touches at theta = pi/2 only, all along its length
            pieces.append(_segment((R, -(h - t)), (R, h - t), flat))
            touching.append(True)
        pieces += [_arc(R - t, h - t, t, 0.0, np.pi / 2, quarter), _segment((R - t, h), (0.0, h), flat)]
        touching += [True, False]
        rho, zeta, arc = _joined(pieces, touching)
    elif profile.kind == "ellipse":
        a, c, z0 = v["a"], v["c"], v["centre_height"]
        s = np.linspace(0.0, np.pi, samples + 1)
        rho, zeta = a * np.sin(s), z0 - c * np.cos(s)
        arc = max(a, c) * np.pi / samples  # the speed |d(rho, zeta)/ds| is at most max(a, c)
    else:
        raise AnimationError(f"profile kind {profile.kind!r} cannot be drawn; allowed: point-rim, two-rims, sphere, "
                             "torus-rim, ellipse")
    rho = np.maximum(np.asarray(rho, float), 0.0)
    zeta = np.asarray(zeta, float)
    middle = (zeta[:-1] + zeta[1:]) / 2
    upper = middle > v["centre_height"] if profile.stem else np.zeros(len(middle), bool)
    return Meridian(rho, zeta, float(arc), upper)


def mesh(profile: Profile, meridians: int = MERIDIANS, samples: int = CURVE_SAMPLES) -> tuple:
    """(Mesh, upper): the surface of revolution in the body frame (b1, b2, e3; origin C) and the flag of
    the quads on the stem's side.  The mark is the strip of quads of the meridian centred on b1."""
    m = meridian(profile, samples)
    a = np.linspace(0, 2 * np.pi, meridians + 1) - np.pi / meridians  # strip 0 centred on b1
    c, s = np.cos(a), np.sin(a)

    def point(j, i):  # j: azimuths (meridians + 1,), i: profile index
        return np.stack([m.rho[i] * c[j], m.rho[i] * s[j], np.full(len(j), m.zeta[i])], -1)

    j0, j1 = np.arange(meridians), np.arange(1, meridians + 1)
    quads = np.concatenate([np.stack([point(j0, i), point(j1, i), point(j1, i + 1), point(j0, i + 1)], 1)
                            for i in range(len(m.rho) - 1)])
    d1, d2 = quads[:, 2] - quads[:, 0], quads[:, 3] - quads[:, 1]
    normals = np.cross(d1, d2)
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.where(length > 0, normals / np.where(length > 0, length, 1), [0.0, 0.0, 1.0])
    strip = np.tile(np.arange(meridians) == 0, len(m.rho) - 1)
    upper = np.repeat(m.upper, meridians)
    return Mesh(quads, normals, strip), upper


def resolution(profile: Profile, meridians: int = MERIDIANS, samples: int = CURVE_SAMPLES) -> float:
    """The bound of the module docstring: how far above the plane the drawn body's lowest point may be."""
    m = meridian(profile, samples)
    return float(2 * m.rho.max() * np.sin(np.pi / (2 * meridians)) + m.arc_max / 2)


def reach(profile: Profile) -> float:
    """The farthest point of the drawn body from C (the stem included): how far it reaches in any tilt."""
    m = meridian(profile)
    far = float(np.max(np.hypot(m.rho, m.zeta)))
    if profile.stem:
        v = profile.numbers
        far = max(far, float(np.hypot(STEM_RADIUS * v["radius"], v["centre_height"] + v["radius"] * (1 + STEM_LENGTH))))
    return far


def _stem_unit() -> np.ndarray:
    """The stem's side (STEM_SIDES quads) and end cap (triangles) for axial extent 0..1, radius 1."""
    a = np.linspace(0, 2 * np.pi, STEM_SIDES + 1)
    c, s = np.cos(a), np.sin(a)
    side = np.stack([np.stack([c[:-1], s[:-1], np.zeros(STEM_SIDES)], -1), np.stack([c[1:], s[1:], np.zeros(STEM_SIDES)], -1),
                     np.stack([c[1:], s[1:], np.ones(STEM_SIDES)], -1), np.stack([c[:-1], s[:-1], np.ones(STEM_SIDES)], -1)], 1)
    centre = np.tile([0.0, 0.0, 1.0], (STEM_SIDES, 1))
    cap = np.stack([centre, side[:, 3], side[:, 2], centre], 1)
    return np.concatenate([side, cap])


_STEM = _stem_unit()


def stem_extent(profile: Profile, theta, z_centre) -> tuple:
    """(zeta_base, zeta_end) of the drawn stem at tilt ``theta`` with C at height ``z_centre`` (scalars).

    The stem (radius r = STEM_RADIUS R) leaves the sphere at zeta_base = c + sqrt(R^2 - r^2) (its
    rim there is on the sphere, so above the plane) and would end STEM_LENGTH R beyond the sphere's top;
    it is cut where its lowest line, at height z_C + zeta cos(theta) - r sin(theta), reaches the floor."""
    v = profile.numbers
    R, c = v["radius"], v["centre_height"]
    r = STEM_RADIUS * R
    base = c + np.sqrt(R * R - r * r)
    tip = c + R * (1 + STEM_LENGTH)
    cos, sin = np.cos(theta), np.sin(theta)
    if cos < 0:
        tip = min(tip, (z_centre - r * sin) / -cos)
    return float(base), float(max(base, tip))


def stem_quads(profile: Profile, theta, rotation, centre) -> np.ndarray:
    """The stem's quads in the inertial frame for one frame (cut at the floor: :func:`stem_extent`)."""
    base, end = stem_extent(profile, theta, centre[2])
    r = STEM_RADIUS * profile.numbers["radius"]
    body = _STEM * [r, r, end - base] + [0.0, 0.0, base]
    return body @ np.asarray(rotation).T + centre


def stem_normals(rotation) -> np.ndarray:
    """The stem's face normals in the inertial frame (sides radial, cap along e3)."""
    a = np.linspace(0, 2 * np.pi, STEM_SIDES + 1)
    mid = (a[:-1] + a[1:]) / 2
    side = np.stack([np.cos(mid), np.sin(mid), np.zeros(STEM_SIDES)], -1)
    cap = np.tile([0.0, 0.0, 1.0], (STEM_SIDES, 1))
    return np.concatenate([side, cap]) @ np.asarray(rotation).T


__all__ = ["CURVE_SAMPLES", "MERIDIANS", "Meridian", "Profile", "profile_for", "STEM_LENGTH", "STEM_RADIUS", "centre_height",
           "contact_radii", "mesh", "meridian", "profile_of", "reach", "resolution", "stem_extent", "stem_normals",
           "stem_quads"]
