"""The thin disk with dissipation as an explicit model term: a damping couple (issue 4, spin-down).

The conservative disk (paper Eqs. 4-46) never reaches theta = 0: on its centre-of-mass-at-rest
family the Eq. 45 motion phidot^2 = g/(k sin theta) is steady at every tilt.  A real coin
settles because energy is lost.  This module adds the loss as one explicit, documented term
of the Newton-Euler rows, so that the rest of the suite (heyoka, events, the energy) applies
unchanged and the spin-down towards theta -> 0 can be followed.

The term
--------
A *couple* (a pure torque about the centre of mass C; per m R^2, in s^-2) opposing the
rocking part of omega, the components along the line of nodes e1 and along e2:

    tau = -c sin(theta)^(-n) (omega1 e1 + omega2 e2),     omega1 = thetadot, omega2 = phidot sin(theta)

added to the right-hand side of paper Eq. 5 (the derived rows of :func:`models.rolling.derive`
become ``rows - tau``).  A couple is a free vector: it adds no force, so the momentum balance
(paper Eq. 6), the no-slip constraint (paper Eq. 7) and the elimination of the contact force
are untouched, and since the rolling contact force does no work the energy (kinetic +
potential, paper Eq. 46) obeys exactly

    dE/dt = tau . omega = -c sin(theta)^(-n) (omega1^2 + omega2^2)  <= 0.

omega3 (spin about the symmetry axis) is not damped; on the family omega3 = 0 anyway.
``c >= 0`` (s^-1) is a runtime parameter of the model; ``c = 0`` is the conservative disk.

The two laws
------------
* ``moffatt`` (n = 3).  Moffatt, Nature 404, 833 (2000): a viscous air film between the disk
  (radius a) and the table, gap h_gap = a alpha at tilt alpha, sheared as by one face turning at
  Omega relative to the other (u = Omega r z / h_gap, a plane Couette profile across the gap),
  Omega the rate at which the contact point goes round (phidot).  Its dissipation is
  Phi = int mu |du/dz|^2 dV = int_0^a mu (Omega r)^2 / h_gap 2 pi r dr = pi mu a^4 Omega^2 / (2 h_gap)
  = pi mu a^3 Omega^2 / (2 alpha) (the integral is done with sympy in tests/test_dissipation.py).
  On the steady family |omega_perp| = Omega sin(alpha) (omega_perp = omega1 e1 + omega2 e2), so
  with alpha ~ sin(alpha) at small tilt Phi = (pi mu a^3 / 2) |omega_perp|^2 / sin^3(alpha).
  Dividing by m a^2 (energies here are per m R^2, R = a) gives

      c = pi mu a / (2 m)     [s^-1],   see :func:`moffatt_coefficient`;

  air (mu = 1.8e-5 Pa s), a = 1 cm (g = 980 s^-2), m = 5 g give c = 9 pi / 500000 = 5.65e-5 s^-1,
  the default.

  The time to the singularity.  With the family's energy E = (3/2) m g a sin(alpha) (derived from
  the model, :func:`verify.studies.dissipation.family_law`) and Omega^2 sin(alpha) = 4 g / a
  (paper Eq. 45 with k = 1/4), dE/dt = -Phi gives sin^2(alpha) d(sin alpha)/dt = -4 pi mu a / (3 m),
  so

      t0 = m sin^3(alpha0) / (4 pi mu a),   see :func:`moffatt_time_to_singularity`.

  The formula usually quoted as Moffatt's, t0 = alpha0^3 m / (2 pi mu a) (with the breakdown time
  tau ~ (2a/9g)^(3/5) (2 pi mu a/m)^(1/5), i.e. alpha^3 = (2 pi mu a/m)(t0 - t)), is twice this: it is
  what half the dissipation above, Phi = pi mu a^4 Omega^2 / (4 h_gap), would give with the same E
  and Omega.  The factor is not in E(alpha) nor in Omega(alpha): both are derived from the model
  and agree with Moffatt's Eqs. 1-2 as others quote them (Omega^2 alpha = 4g/a, E = (3/2) M g a
  sin(alpha): Kilty, http://www.kilty.com/euler.htm; Bildsten, arXiv:gr-qc/0102046, with the gap
  "of width ~ a alpha"); it sits between the Couette Phi and the quoted rate law (t0 and tau as in
  Wikipedia's "Euler's disk").  Moffatt's printed Phi and any later correction were not available
  to us, so which of the two he wrote is not settled here; the couple is defined by the Couette
  Phi above and its t0 follows from it.  The coefficient is anyway a model of the film, not a
  measured number: the same Couette film over the wedge-shaped gap h = alpha (a + r cos(angle))
  dissipates (4 pi / 3) mu a^3 Omega^2 / alpha (8/3 of the above), a
  squeeze film (Reynolds) in the uniform gap (pi / 8) mu a^3 Omega^2 / alpha.  The study's runs
  set c directly (:data:`verify.studies.dissipation.STUDY_C`), so no reported number depends on
  this factor; only a reading of c in terms of mu, a, m does.
* ``contact-rate`` (n = 2).  McDonald & McDonald (arXiv:physics/0008227): a power loss
  proportional to the square of the rate at which the contact point goes round,
  P = -c Omega^2; on the steady family Omega = phidot and |omega_perp|^2 / sin^2 = phidot^2, so
  the couple with n = 2 gives exactly that.  They give no coefficient; the default
  9 pi / 50000 = 10 x the Moffatt default dissipates at the same rate as it at sin(theta) = 1/10.

The approximation
-----------------
Both published laws are stated for the steady motion only (thetadot = 0, phidot^2 =
g/(k sin theta), omega3 = 0: the family on which Eq. 45 is exact).  The couple reproduces the
stated dissipation rate exactly on that family (the Couette Phi with sin(alpha) for alpha in
the gap, a relative O(alpha^2) difference); away from it (nutation, thetadot != 0,
omega3 != 0) the form ``c sin^-n |omega_perp|^2`` is a modelling choice, not a result of either
paper: it is the simplest smooth, frame-indifferent term that is quadratic in the rocking
rates and has the published power on the family.  How the dissipation is shared between a
torque and a force at the contact, or whether omega3 is also damped, changes nothing on the
family and is not constrained by either paper.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from . import disk
from .base import Model, Parameter
from .build import damped_model
from .rolling import derive
from .symbols import omega_body, theta


@dataclass(frozen=True)
class Law:
    """A dissipation law: the exponent n of the couple and where it comes from."""

    name: str
    exponent: int
    source: str
    default_c: sp.Expr
    description: str


LAWS = {
    "moffatt": Law(
        "moffatt", 3, "Moffatt, Nature 404, 833 (2000): viscous air film, gap a*alpha",
        9 * sp.pi / 500000,
        "c = pi mu a / (2 m); default: air (mu = 1.8e-5 Pa s), a = 1 cm, m = 5 g",
    ),
    "contact-rate": Law(
        "contact-rate", 2, "McDonald & McDonald, arXiv:physics/0008227: power loss proportional to Omega^2",
        9 * sp.pi / 50000,
        "P = -c Omega^2 on the steady family; default 10 x the Moffatt default (equal loss at sin(theta) = 1/10)",
    ),
}
LAW_NAMES = tuple(LAWS)

#: The dissipation coefficient (per m R^2, in s^-1), a runtime parameter of the model.
c = sp.Symbol("c", nonnegative=True)


def law(name: str) -> Law:
    """The law called ``name``; ``ValueError`` naming it and the allowed laws otherwise."""
    if name not in LAWS:
        raise ValueError(f"unknown dissipation law {name!r}; allowed: {', '.join(LAW_NAMES)}")
    return LAWS[name]


def coefficient_parameter(name: str) -> Parameter:
    """The runtime parameter ``c`` of law ``name``: finite and >= 0 (0 is the conservative disk)."""
    lw = law(name)
    return Parameter("c", c, lw.default_c, f"dissipation coefficient of the {lw.name} couple in s^-1 ({lw.description})",
                     lower=0.0, lower_inclusive=True)


def moffatt_coefficient(mu, a, m):
    """Moffatt's c = pi mu a / (2 m) in s^-1 from viscosity mu (Pa s), radius a (m) and mass m (kg).

    Moffatt's Phi = pi mu a^3 Omega^2 / (2 alpha) in W, divided by m a^2 (energies per m R^2).
    Works for numbers and sympy expressions.
    """
    return sp.pi * sp.sympify(mu) * sp.sympify(a) / (2 * sp.sympify(m))


def moffatt_time_to_singularity(mu, a, m, alpha0):
    """t0 = m sin^3(alpha0) / (4 pi mu a) in s: the time the ``moffatt`` couple with
    c = :func:`moffatt_coefficient` (mu, a, m) takes to bring the disk down its steady family from
    tilt alpha0 to 0 (module docstring, "The time to the singularity"; not the quoted
    alpha0^3 m / (2 pi mu a), which is twice it).  Works for numbers and sympy expressions.
    """
    return sp.sympify(m) * sp.sin(sp.sympify(alpha0)) ** 3 / (4 * sp.pi * sp.sympify(mu) * sp.sympify(a))


def rocking_rate_squared() -> sp.Expr:
    """|omega_perp|^2 = omega1^2 + omega2^2 = thetadot^2 + phidot^2 sin^2(theta)."""
    w = omega_body()
    return w[0] ** 2 + w[1] ** 2


def couple(name: str) -> sp.Matrix:
    """tau = -c sin(theta)^(-n) (omega1, omega2, 0) in (e1, e2, e3), per m R^2 (module docstring)."""
    n = law(name).exponent
    w = omega_body()
    return -c * sp.sin(theta) ** (-n) * sp.Matrix([w[0], w[1], 0])


def work_rate(name: str, exponent=None) -> sp.Expr:
    """The dissipated power -tau . omega = c sin(theta)^(-n) |omega_perp|^2 >= 0.

    ``exponent`` overrides n: only for negative controls (a work integrand that does not
    match the couple in the equations of motion must fail the energy balance).
    """
    n = law(name).exponent if exponent is None else exponent
    return c * sp.sin(theta) ** (-n) * rocking_rate_squared()


def model_name(name: str) -> str:
    return f"disk+{law(name).name}"


@lru_cache(maxsize=None)
def dissipative_disk(name: str = "moffatt") -> Model:
    """The thin disk of :mod:`models.disk` with the damping couple of law ``name``.

    Parameters ``k, g, c`` (c last); the derived rows of the disk minus the couple, solved
    for (thetaddot, phiddot, psiddot).  The energy is kept as the model's first invariant
    (it is what ``solve`` reports), but it is *not* conserved: E + W is, with W the work of
    the couple (:func:`work_rate`).  Not in ``models.MODEL_NAMES`` (that registry is the
    conservative models).
    """
    lw = law(name)
    d = derive(disk.k, 2 * disk.k, disk.R2, disk.R3, "rolling")
    return damped_model(
        d, couple(name), name=model_name(name),
        title=f"thin disk rolling without slipping, damped by the {lw.name} couple (n = {lw.exponent})",
        source=f"derived rows (Eqs. 8, 17) minus the couple -c sin^-{lw.exponent}(theta) omega_perp; {lw.source}",
        parameters=disk.PARAMETERS + (coefficient_parameter(name),), domain=disk.DOMAIN, dissipation=work_rate(name))
