"""The drawn bodies as meshes of quadrilaterals in the body frame, and their placement.

Every mesh is an array of quads of shape (m, 4, 3) in body coordinates (b1, b2, e3; origin
at the centre of mass C; triangles repeat a vertex), a per-quad normal, and a per-quad flag
``mark`` that colours the quads showing the spin.  All vertices lie on the true surface, so
the drawn body is inside the solid and never lower than its true lowest point, the contact
point (the flat polygons between rim vertices are chords, which lie higher).

* disk: 48 sectors of the unit disk; the mark is one 7.5 degree sector at body angle 0
  (a radial line from C to the rim point b1).
* hoop (disk with k = 1/2, all mass on the rim): an annulus 1 - 0.12 < r < 1 drawn so the
  rim shows; the mark is the 22.5 degrees of rim around b1.
* ring: an annular cylinder, radii 1 - w and 1, axial extent -h .. h (the ring's contact is
  on the rim edge at -h e3, paper Eq. 47); the mark is the strip of faces around b1.
* hurricane balls and gyroscope: two unit spheres centred at -e3 and +e3, touching at C
  (paper Eq. 63); each has a marked meridian strip at body angle 0.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import RING_WALL_DEFAULT

SECTORS = 48
#: Drawn width of the hoop's band (units of R): an ideal hoop is a line.
HOOP_BAND = 0.12
SPHERE_MERIDIANS, SPHERE_PARALLELS = 16, 10


@dataclass(frozen=True)
class Mesh:
    """Quads (m, 4, 3) in the body frame, their unit normals (m, 3) and mark flags (m,)."""

    quads: np.ndarray
    normals: np.ndarray
    mark: np.ndarray

    def placed(self, rotation: np.ndarray, centre: np.ndarray) -> tuple:
        """(quads, normals) in the inertial frame for one body rotation (3, 3) and centre (3,)."""
        return self.quads @ rotation.T + centre, self.normals @ rotation.T


def _band_quads(radius: float, z0: float, z1: float) -> np.ndarray:
    a = np.linspace(0, 2 * np.pi, SECTORS + 1) - np.pi / SECTORS
    c, s = np.cos(a) * radius, np.sin(a) * radius
    pts = [(c[:-1], s[:-1], z0), (c[1:], s[1:], z0), (c[1:], s[1:], z1), (c[:-1], s[:-1], z1)]
    return np.stack([np.stack([px, py, np.full(SECTORS, pz)], -1) for px, py, pz in pts], 1)


def _band_normals(quads: np.ndarray) -> np.ndarray:
    mid = quads.mean(axis=1)
    mid[:, 2] = 0
    return mid / np.linalg.norm(mid, axis=1, keepdims=True)


def _axial_normals(n: int) -> np.ndarray:
    return np.tile([0.0, 0.0, 1.0], (n, 1))


def _sector_mark(n_rings: int, width: int = 1) -> np.ndarray:
    """Flags of the sectors within ``width`` of sector 0 (sector 0 is centred on b1)."""
    index = np.arange(SECTORS)
    near = np.minimum(index, SECTORS - index) < width
    return np.tile(near, n_rings)


def disk_mesh(hoop: bool) -> Mesh:
    """The unit disk (or, ``hoop``, the annulus of width :data:`HOOP_BAND`) in the b1-b2 plane."""
    quads = _annulus(1 - HOOP_BAND if hoop else 0.0, 1.0, 0.0)
    return Mesh(quads, _axial_normals(len(quads)), _sector_mark(1, 2 if hoop else 1))


def _annulus(r_inner: float, r_outer: float, z: float) -> np.ndarray:
    a = np.linspace(0, 2 * np.pi, SECTORS + 1) - np.pi / SECTORS
    c, s = np.cos(a), np.sin(a)
    pts = [(r_inner * c[:-1], r_inner * s[:-1]), (r_outer * c[:-1], r_outer * s[:-1]),
           (r_outer * c[1:], r_outer * s[1:]), (r_inner * c[1:], r_inner * s[1:])]
    return np.stack([np.stack([px, py, np.full(SECTORS, z)], -1) for px, py in pts], 1)


def ring_mesh(h: float, wall: float = RING_WALL_DEFAULT) -> Mesh:
    """The annular cylinder: outer band radius 1, inner band radius 1 - wall, faces at z = +-h."""
    inner = 1.0 - wall
    parts = [_band_quads(1.0, -h, h), _annulus(inner, 1.0, -h), _annulus(inner, 1.0, h)]
    normals = [_band_normals(parts[0]), _axial_normals(SECTORS), _axial_normals(SECTORS)]
    if inner > 0:
        parts.append(_band_quads(inner, -h, h))
        normals.append(_band_normals(parts[-1]))
    quads = np.concatenate(parts)
    return Mesh(quads, np.concatenate(normals), _sector_mark(len(parts), 1))


def sphere_quads(centre_z: float) -> tuple:
    """(quads, normals, mark) of the unit sphere centred at (0, 0, centre_z); the mark is the
    meridian strip centred on the b1 side."""
    lon = np.linspace(0, 2 * np.pi, SPHERE_MERIDIANS + 1) - np.pi / SPHERE_MERIDIANS
    lat = np.linspace(-np.pi / 2, np.pi / 2, SPHERE_PARALLELS + 1)
    lo0, la0 = np.meshgrid(lon[:-1], lat[:-1], indexing="ij")
    lo1, la1 = np.meshgrid(lon[1:], lat[1:], indexing="ij")

    def point(lo, la):
        return np.stack([np.cos(la) * np.cos(lo), np.cos(la) * np.sin(lo), np.sin(la) + centre_z], -1)

    quads = np.stack([point(lo0, la0), point(lo1, la0), point(lo1, la1), point(lo0, la1)], 2).reshape(-1, 4, 3)
    normals = quads.mean(axis=1) - [0.0, 0.0, centre_z]
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    meridian = np.repeat(np.arange(SPHERE_MERIDIANS), SPHERE_PARALLELS)
    return quads, normals, meridian == 0


def balls_mesh() -> Mesh:
    """Two unit spheres centred at -e3 (the lower ball) and +e3, touching at C (paper Eq. 63)."""
    lower, upper = sphere_quads(-1.0), sphere_quads(1.0)
    return Mesh(*(np.concatenate([a, b]) for a, b in zip(lower, upper)))


def mesh_for(kind: str, params: dict) -> Mesh:
    """The mesh of body ``kind`` ('disk', 'ring', 'hurricane', 'gyroscope') with its ``params``."""
    if kind == "disk":
        return disk_mesh(hoop=abs(params["k"] - 0.5) < 1e-12)
    if kind == "ring":
        return ring_mesh(params["h"], params.get("w", RING_WALL_DEFAULT))
    return balls_mesh()


def mark_point(kind: str, params: dict) -> np.ndarray:
    """The body-frame point the mark is centred on: the rim point b1 of the disk, hoop and ring
    (on the ring's contact-side edge, -h e3), the lower ball's equator point -e3 + b1."""
    if kind == "disk":
        return np.array([1.0, 0.0, 0.0])
    if kind == "ring":
        return np.array([1.0, 0.0, -params["h"]])
    return np.array([1.0, 0.0, -1.0])
