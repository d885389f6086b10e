"""Convex bodies of revolution from their meridian profile: the contact point for each tilt.

A body of revolution about e3 with its centre of mass C on the axis is given by its meridian
profile, a convex curve (rho, zeta) in the half-plane rho >= 0 (rho the distance from the axis,
zeta the height along e3 above C), lengths in the body's unit L.  On a horizontal plane, with the
vertical Z = sin(theta) e2 + cos(theta) e3 in the 1-2-3 frame (paper Fig. 1; theta the tilt of e3
from the vertical), the contact point P is the body's lowest point, the support point of the
profile in the direction -Z: on the meridian through -e2 it minimises

    height(rho, zeta) = -rho sin(theta) + zeta cos(theta)

so r_P = (0, r2, r3) = (0, -rho*, zeta*) (paper Eqs. 1, 47, 63: the disk r_P = -e2, the ring
-e2 - h e3, the hurricane balls' lower sphere -sin(theta) e2 - (1 + cos(theta)) e3).  Each kind
below is that minimisation done exactly (sympy), with the tilts where the minimiser is unique and
moves smoothly (the kind's domain: a corner of the profile, where the minimiser jumps from one
smooth piece to another, is an end of it):

* ``point-rim`` (the thin disk or hoop): a point at (radius, 0): r_P = (0, -radius, 0), theta in (0, pi);
* ``two-rims`` (the paper's ring): points at (radius, +-half_thickness): below theta = pi/2 the lower rim,
  r_P = (0, -radius, -half_thickness); at pi/2 the contact jumps to the other rim (``rim_switch``);
* ``sphere``: a circle of radius ``radius`` centred at zeta = centre_height: r_P = (0, -radius sin(theta),
  centre_height - radius cos(theta)), theta in (0, pi) (the hurricane balls' lower ball: radius 1,
  centre_height -1, up to pi/2 where the other ball touches: a narrower domain in the file);
* ``torus-rim`` (a coin with rounded rims): circles of radius tube_radius centred at
  (radius - tube_radius, +-(half_thickness - tube_radius)): below pi/2 the lower one,
  r2 = -(radius - tube_radius) - tube_radius sin(theta), r3 = -(half_thickness - tube_radius) - tube_radius
  cos(theta); with tube_radius = half_thickness the two circles are one and the contact passes
  theta = pi/2 smoothly (domain (0, pi)); with tube_radius < half_thickness the flat band between them
  touches at pi/2 (a jump: ``rim_switch``); tube_radius -> 0 is ``two-rims``;
* ``ellipse`` (an ellipsoid of revolution): semi-axes a (equatorial) and c (polar), centred at
  zeta = centre_height: r2 = -a^2 sin(theta)/D, r3 = centre_height - c^2 cos(theta)/D,
  D = sqrt(a^2 sin^2(theta) + c^2 cos^2(theta)), theta in (0, pi);
* ``curve`` (any smooth convex meridian): r(s), z(s) as exact expressions of s on (s_min, s_max), bottom to top;
  the contact's s(theta) solved by sympy from r'(s) sin(theta) = z'(s) cos(theta), the branch that is the
  lowest point picked, convexity and C inside proved in ball arithmetic, the domain the normal's angles at
  the ends (:mod:`models.profile_curve`; a curve sympy cannot solve in closed form is refused).

Each formula is checked in the tests against the minimisation itself (the first-order condition
d height/ds = 0 on the profile and a numerical minimum over the profile's points).
"""
from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .profile_curve import CurveError, contact_of_curve
from .symbols import theta

KINDS = ("point-rim", "two-rims", "sphere", "torus-rim", "ellipse", "curve")
#: The numbers each kind reads (exact), beyond the inertia.
FIELDS = {
    "point-rim": ("radius",),
    "two-rims": ("radius", "half_thickness"),
    "sphere": ("radius", "centre_height"),
    "torus-rim": ("radius", "half_thickness", "tube_radius"),
    "ellipse": ("a", "c", "centre_height"),
    "curve": ("r", "z", "s_min", "s_max"),
}
#: The fields that are expressions of s (read by :func:`models.profile_curve.read_expression`), not numbers.
EXPRESSIONS = {"curve": ("r", "z")}


class InvalidBody(ValueError):
    """A body no convex body of revolution is, or one this module cannot follow; the message names the value."""


@dataclass(frozen=True)
class Contact:
    """The contact vector r_P = (0, r2, r3) of a profile and the tilts where it holds.

    ``theta_min``, ``theta_max`` (exact) bound the open domain; ``below`` and ``above`` name what happens
    there (the terminal events of a run: 'lies_flat', 'rim_switch', 'axis_vertical', ...).
    """

    r2: sp.Expr
    r3: sp.Expr
    theta_min: sp.Expr
    theta_max: sp.Expr
    below: str
    above: str


def contact(kind: str, values: dict) -> Contact:
    """The contact of profile ``kind`` with exact ``values`` (sympy Rationals), checked; :class:`InvalidBody` otherwise."""
    if kind not in KINDS:
        raise InvalidBody(f"profile kind {kind!r}; allowed: {', '.join(KINDS)}")
    missing = [f for f in FIELDS[kind] if f not in values]
    if missing:
        raise InvalidBody(f"profile kind {kind!r} needs {', '.join(missing)}")
    extra = sorted(set(values) - set(FIELDS[kind]))
    if extra:
        raise InvalidBody(f"profile kind {kind!r} takes {', '.join(FIELDS[kind])}; not {', '.join(extra)}")
    v = values
    half = sp.pi / 2
    if kind == "curve":
        try:
            r2, r3, lo, hi, below, above = contact_of_curve(v["r"], v["z"], v["s_min"], v["s_max"])
        except CurveError as err:
            raise InvalidBody(str(err)) from None
        return Contact(r2, r3, lo, hi, below, above)
    r2, r3 = vector(kind, v)
    if kind == "point-rim":
        _positive(v, "radius")
        return Contact(r2, r3, sp.Integer(0), sp.pi, "lies_flat", "lies_flat")
    if kind == "two-rims":
        _positive(v, "radius")
        _positive(v, "half_thickness", zero=True)
        return Contact(r2, r3, sp.Integer(0), half, "lies_flat", "rim_switch")
    if kind == "sphere":
        _positive(v, "radius")
        if not abs(v["centre_height"]) <= v["radius"]:
            raise InvalidBody(f"centre_height = {v['centre_height']}: the centre of mass would lie outside the sphere of "
                              f"radius {v['radius']}; allowed: |centre_height| <= radius")
        return Contact(r2, r3, sp.Integer(0), sp.pi, "axis_vertical", "axis_vertical")
    if kind == "torus-rim":
        _positive(v, "radius")
        _positive(v, "half_thickness")
        _positive(v, "tube_radius")
        rho, h, R = v["tube_radius"], v["half_thickness"], v["radius"]
        if not rho <= h or not rho <= R:
            raise InvalidBody(f"tube_radius = {rho}: the rounding must fit the rim; allowed: 0 < tube_radius <= "
                              f"half_thickness ({h}) and <= radius ({R})")
        smooth = rho == h
        return Contact(r2, r3, sp.Integer(0), sp.pi if smooth else half, "lies_flat",
                       "lies_flat" if smooth else "rim_switch")
    _positive(v, "a")
    _positive(v, "c")
    if not abs(v["centre_height"]) < v["c"]:
        raise InvalidBody(f"centre_height = {v['centre_height']}: the centre of mass would lie outside the ellipsoid "
                          f"(polar semi-axis c = {v['c']}); allowed: |centre_height| < c")
    return Contact(r2, r3, sp.Integer(0), sp.pi, "axis_vertical", "axis_vertical")


def vector(kind: str, v: dict) -> tuple:
    """(r2, r3) of profile ``kind`` with values or symbols ``v`` (no checks: :func:`contact` checks)."""
    if kind == "point-rim":
        return -v["radius"], sp.Integer(0)
    if kind == "two-rims":
        return -v["radius"], -v["half_thickness"]
    if kind == "sphere":
        return -v["radius"] * sp.sin(theta), v["centre_height"] - v["radius"] * sp.cos(theta)
    if kind == "torus-rim":
        rho, h, R = v["tube_radius"], v["half_thickness"], v["radius"]
        return -(R - rho) - rho * sp.sin(theta), -(h - rho) - rho * sp.cos(theta)
    if kind == "curve":  # checked and solved once per curve (cached): the checks cannot fail here after contact()
        return contact_of_curve(v["r"], v["z"], v["s_min"], v["s_max"])[:2]
    d = sp.sqrt(v["a"] ** 2 * sp.sin(theta) ** 2 + v["c"] ** 2 * sp.cos(theta) ** 2)
    return -v["a"] ** 2 * sp.sin(theta) / d, v["centre_height"] - v["c"] ** 2 * sp.cos(theta) / d


#: What must hold between a kind's numbers (beyond each one's sign), as text and a predicate on their values:
#: checked again at every run, where --param may change them.
RELATIONS = {
    "sphere": (("|centre_height| <= radius (the centre of mass inside the sphere)",
                lambda p: abs(p["centre_height"]) <= p["radius"]),),
    "torus-rim": (("tube_radius <= half_thickness and tube_radius <= radius (the rounding fits the rim)",
                   lambda p: p["tube_radius"] <= p["half_thickness"] and p["tube_radius"] <= p["radius"]),),
    "ellipse": (("|centre_height| < c (the centre of mass inside the ellipsoid)",
                 lambda p: abs(p["centre_height"]) < p["c"]),),
}


def _positive(values: dict, name: str, zero: bool = False) -> None:
    x = values[name]
    if not (x >= 0 if zero else x > 0):
        raise InvalidBody(f"{name} = {x}: allowed: {'>= 0' if zero else '> 0'} (a length in the body's unit)")


def check_inertia(I1, I3) -> None:
    """Moments of inertia a mass distribution can have: I1, I3 > 0 and I3 <= 2 I1 (2 I1 - I3 = 2 sum m z^2)."""
    for name, x in (("I1", I1), ("I3", I3)):
        if not x > 0:
            raise InvalidBody(f"{name} = {x}: a moment of inertia about C is positive")
    if not I3 <= 2 * I1:
        raise InvalidBody(f"I3 = {I3} > 2 I1 = {2 * I1}: no body of revolution has it (2 I1 - I3 = 2 sum m z^2 >= 0, "
                          "0 only for a flat one)")


def check_domain(c: Contact, theta_min, theta_max) -> tuple:
    """The file's domain, which must lie inside the profile's (a wider one would let the contact reach a corner)."""
    lo = c.theta_min if theta_min is None else theta_min
    hi = c.theta_max if theta_max is None else theta_max
    if not (c.theta_min <= lo < hi <= c.theta_max):
        raise InvalidBody(f"domain ({lo}, {hi}): allowed: inside ({c.theta_min}, {c.theta_max}), where the contact point "
                          f"moves smoothly on one piece of the profile (beyond: {c.below} / {c.above})")
    return lo, hi


__all__ = ["Contact", "EXPRESSIONS", "FIELDS", "InvalidBody", "KINDS", "RELATIONS", "check_domain", "check_inertia", "contact", "vector"]
