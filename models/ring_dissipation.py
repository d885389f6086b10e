"""The thick ring with dissipation, for the retrograde turn (paper text after Fig. 12; issue 6).

Spinning rings, unlike disks, reverse the sense of their orbit before they stop (Jalali,
Sarebangholi & Alam, Phys. Rev. E 92, 032913, 2015): at first the centre of mass orbits in
the sense of the spin about the vertical, at the end in the opposite sense.  Two
explanations compete, and each is added here as one explicit term of the Newton-Euler rows
(the same way as :mod:`models.dissipative` adds the disk's couple):

* ``air-drag`` -- Jalali et al.: the ring's *hollow geometry tunes the rotational air drag*.
  A quadratic drag couple on the rocking part of omega (the components along e1 and e2),

      tau = -c A(w) |omega_perp| omega_perp,    A(w) = 1 - (1 - w)^5,

  (|omega_perp| smoothed at 1/1024 rad/s, see :data:`SMOOTHING`),

  where A is the pressure-drag torque of a flat annulus (outer radius R, wall w, in units of
  R) rocking about a diameter relative to a full disk: a local pressure ~ (omega y)^2 on the
  area element gives a torque ~ int |y|^3 dA, which scales as the fifth power of the radius,
  so the hole removes (1 - w)^5 of it.  Spin about the symmetry axis (skin friction only) and
  the translation are not damped.  Jalali et al.'s own force laws were not available to us:
  this is the simplest term with their stated property (the hole sets the rotational drag).
* ``rolling-friction`` -- Borisov, Kilin & Karavaev (arXiv:1611.02957; Phys. Usp. 60, 931,
  2017): *viscous rolling friction*, a couple opposing the horizontal part of omega (rolling
  about horizontal axes) and not the spin about the vertical Z (pivoting),

      tau = -c (omega - (omega . Z) Z),

  the same for a ring and a disk: only the inertia and the rim offset h differ.  Their
  published coefficient form was not available to us either; this is the standard linear
  viscous law with their stated property (no pivoting friction).

Parameters and geometry
-----------------------
Both models keep the ring's parameters I1, I3, h, g of :mod:`models.ring` (runtime
parameters, so a sweep over shapes needs no recompilation), add ``c >= 0`` (``c = 0`` is the
conservative ring, checked in the tests) and, for ``air-drag``, the wall ``w``.  For a ring of
the paper's kind -- an annular cylinder of outer radius R, inner radius R(1 - w) and
half-thickness h (text after Eq. 62; all in units of R) -- :func:`annulus_inertia` gives

    I3 = (1 + (1 - w)^2) / 2,    I1 = (3 (1 + (1 - w)^2) + (2 h)^2) / 12;

``w = 1`` is a solid disk (no hole), ``h -> 0`` a flat one; the paper's ring is h = 0.4344,
w = 0.5/3.66 = 0.1366.  (I1 and I3 stay parameters rather than expressions of h and w
because 1/12 and 1/3 are not binary fractions: heyoka would round them to double.)

Energy
------
A couple adds no force, so the contact force is eliminated as before and does no work:
dE/dt = tau . omega <= 0.  The model's ``dissipation`` = -tau . omega is integrated alongside
so that E + W is the conserved quantity a run is checked against.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from . import ring
from .base import Model, Parameter
from .build import damped_model
from .common import AXIAL_BOUND
from .rolling import derive
from .symbols import omega_body, theta

h = ring.h
w = sp.Symbol("w", positive=True)
c = sp.Symbol("c", nonnegative=True)


def annulus_inertia(h_value, w_value) -> tuple:
    """(I1, I3) per m R^2 of an annular cylinder: half-thickness h, wall w (units of R)."""
    outer_inner = 1 + (1 - w_value) ** 2
    return (3 * outer_inner + (2 * h_value) ** 2) / 12, outer_inner / 2


@dataclass(frozen=True)
class RingLaw:
    name: str
    source: str
    description: str
    default_c: sp.Expr


LAWS = {
    "air-drag": RingLaw("air-drag", "Jalali, Sarebangholi & Alam, Phys. Rev. E 92, 032913 (2015)",
                        "tau = -c A(w) |omega_perp| omega_perp, A(w) = 1 - (1 - w)^5 (quadratic rotational air drag)",
                        sp.Rational(1, 1000)),
    "rolling-friction": RingLaw("rolling-friction", "Borisov, Kilin & Karavaev, arXiv:1611.02957; Phys. Usp. 60, 931 (2017)",
                                "tau = -c (omega - (omega . Z) Z) (viscous rolling friction, no pivoting friction)",
                                sp.Rational(1, 10)),
}
LAW_NAMES = tuple(LAWS)


def law(name: str) -> RingLaw:
    if name not in LAWS:
        raise ValueError(f"unknown ring dissipation {name!r}; allowed: {', '.join(LAW_NAMES)}")
    return LAWS[name]


def hole_factor(w_value):
    """A(w) = 1 - (1 - w)^5: the rocking drag of the annulus relative to the full disk."""
    return 1 - (1 - w_value) ** 5


#: |omega_perp| is taken as sqrt(omega_perp^2 + SMOOTHING^2): the quadratic law |x| x is not analytic
#: at x = 0 (a start rolling straight upright has omega_perp = 0 exactly), and Taylor's method needs
#: analytic right-hand sides.  1/1024 rad/s changes the couple by less than 1e-6 of itself once
#: |omega_perp| > 1 rad/s.
SMOOTHING = sp.Rational(1, 1024)


def couple(name: str) -> sp.Matrix:
    """The dissipative couple in (e1, e2, e3) components, per m R^2 (module docstring)."""
    law(name)
    om = omega_body()
    if name == "air-drag":
        perp = sp.Matrix([om[0], om[1], 0])
        return -c * hole_factor(w) * sp.sqrt(om[0] ** 2 + om[1] ** 2 + SMOOTHING ** 2) * perp
    vertical = sp.Matrix([0, sp.sin(theta), sp.cos(theta)])
    return -c * (om - om.dot(vertical) * vertical)


def power(name: str) -> sp.Expr:
    """The dissipated power -tau . omega (>= 0)."""
    return sp.expand(-couple(name).dot(omega_body()))


WALL = Parameter("w", w, sp.Rational(1, 2) / sp.Rational(366, 100),
                 "wall of the ring in units of R (inner radius R(1 - w)); 1 is a solid disk", lower=0.0, upper=1.0)


@lru_cache(maxsize=None)
def dissipative_ring(name: str = "air-drag") -> Model:
    """The ring of :mod:`models.ring` with the couple of law ``name``; parameters I1, I3, h, g, (w,) c."""
    lw = law(name)
    d = derive(ring.I1, ring.I3, ring.R2, ring.R3, "rolling")
    coefficient = Parameter("c", c, lw.default_c, f"coefficient of the {lw.name} couple ({lw.description})",
                            lower=0.0, lower_inclusive=True)
    return damped_model(
        d, couple(name), name=f"ring+{lw.name}", title=f"thick ring or coin rolling on one rim, with {lw.name}",
        source=f"derived rows (Eqs. 8, 47-50) minus the couple {lw.description}; {lw.source}",
        parameters=ring.PARAMETERS + ((WALL,) if name == "air-drag" else ()) + (coefficient,), domain=ring.DOMAIN,
        dissipation=power(name), relations=(AXIAL_BOUND,))


def model_names() -> tuple:
    return tuple(f"ring+{n}" for n in LAW_NAMES)
