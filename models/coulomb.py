"""A body of revolution that rolls or slides on the plane with Coulomb friction: the sliding phase.

The rolling phase is the rolling model itself (``disk``, ``ring``: paper Eqs. 5-8, derived in
:mod:`models.rolling`).  This module derives the sliding phase, Newton-Euler about C as there
(per unit mass, lengths in units of R):

    a_C = F - g Z,          F = N Z + F_h                      (paper Eq. 6)
    I omega_dot + Omega x (I omega) = r_P x F                  (paper Eq. 5)
    F_h = -mu N u / |u|,    u = v_C + omega x r_P              (Coulomb; u horizontal)

with the height constraint z_C = -r_P . Z (the contact stays on the plane), so that
N = g + z_C'' depends on thetaddot; N is eliminated by substitution, and the three rotational
rows are linear in the accelerations and solved for them.  With no slip (u = 0) the
constraint of paper Eq. 7 replaces the force law: that is the rolling model.

The slip state
--------------
The centre of mass's horizontal velocity is no longer set by the angles and rates: the state
gains two components.  We take the contact point's slip velocity in polar form, slip speed
``s = |u| >= 0`` and slip direction ``alpha`` (inertial: u = s (cos alpha, sin alpha, 0)),
not its Cartesian components nor the CM velocity, because

* the force law is regular in it: F_h = -mu N (cos alpha, sin alpha), no u / |u|;
* the end of a sliding phase (the contact sticks, s -> 0) is a simple zero of a state
  component: Coulomb friction brings s to zero at a finite rate (ds/dt < 0 there), so
  heyoka's event on ``s`` sees a sign change and locates it to the precision's epsilon.  In
  Cartesian components |u| touches 0 and never changes sign;
* s is what the dissipated power needs: dW/dt = mu N s >= 0.

The price is the direction equation d(alpha)/dt = (e_perp . du/dt) / s, 0/0 where s = 0.
Where a sliding phase ends (s -> 0 linearly) the solution is regular and the quotient has a
finite limit; where one begins from rolling (s grows like t^2) heyoka cannot take a first step
(:mod:`verify.engine.slip_onset` starts that onset by the slow solution's power series).

Everything is written in the horizontal frame (e1, h), h = cos(theta) e2 - sin(theta) e3
= Z x e1 (paper Fig. 1), with ``beta = alpha - phi`` the slip direction measured from the line
of nodes, so no expression carries phi except through beta.  The state of a sliding phase is
the eight of the rolling models, then ``slip_speed``, ``slip_direction`` and ``work`` (the
quadrature W = int mu N s dt): E + W is conserved (dE/dt = F . u = F_h . u = -mu N s, as
N Z . u = 0).  With mu = 0 the rows are those of the smooth plane (``sliding-disk``).
"""
from __future__ import annotations

import hashlib
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import mpmath
import sympy as sp

from . import disk, get_model, ring
from .base import Parameter
from .rolling import _simplify, newton_euler
from .symbols import (
    ACCELERATIONS, STATE, g, omega_body, omega_body_dot, omega_frame, phi, phidot, theta,
    time_derivative, vertical_in_frame,
)

#: Names of the bodies that roll or slide (a rolling model plus this sliding phase): models.COULOMB_NAMES.
NAMES = ("disk+coulomb", "ring+coulomb")
#: The rolling model of each.
ROLLING = {"disk+coulomb": "disk", "ring+coulomb": "ring"}

slip_speed, slip_direction, work = sp.symbols("slip_speed slip_direction work", real=True)
mu = sp.Symbol("mu", nonnegative=True)
FRICTION = Parameter("mu", mu, sp.Integer(1), "Coulomb friction coefficient (sliding and static alike)", lower=0.0,
                     lower_inclusive=True, upper=None)

#: The state of a sliding phase: the rolling models' eight, then the slip and the work.
SLIDING_STATE_NAMES = ("theta", "phi", "psi", "thetadot", "phidot", "psidot", "x", "y",
                       "slip_speed", "slip_direction", "work")
SLIDING_STATE = STATE + (slip_speed, slip_direction, work)


@dataclass(frozen=True)
class SlidingPhase:
    """The sliding equations of one body (sympy, in :data:`SLIDING_STATE` and the rolling model's
    parameters plus ``mu``, which comes last).

    Attributes
    ----------
    rhs : tuple
        d/dt of each of :data:`SLIDING_STATE`, in that order.
    energy : sp.Expr
        Kinetic + potential energy per m R^2 (the rolling model's, with the free CM velocity).
    normal_force : sp.Expr
        N / (M g) on shell.
    slip_rate_along, slip_rate_across : sp.Expr
        e . du/dt and e_perp . du/dt (e = (cos alpha, sin alpha)); d(alpha)/dt is the second over s.
    rolling_slip_acceleration : tuple
        du/dt in the (e1, h) frame with the accelerations left symbolic and F_h given as
        ``(F1, F2)`` symbols (the response of the slip to a horizontal force; tests).
    """

    rhs: tuple
    energy: sp.Expr
    kinetic: sp.Expr
    normal_force: sp.Expr
    slip_rate_along: sp.Expr
    slip_rate_across: sp.Expr
    cm_velocity_xy: tuple
    painleve_margin: sp.Expr


def contact_kinematics(I1: sp.Expr, I3: sp.Expr, r2: sp.Expr, r3: sp.Expr) -> tuple:
    """What every sliding law starts from (paper Eqs. 5-7): omega, its rate, the frame's rate, the vertical Z,
    r_P, the inertia, the height z_C = -r_P . Z of C and its first two derivatives (z_C'' linear in thetaddot)."""
    w, wdot, Om = omega_body(), omega_body_dot(), omega_frame()
    Z = vertical_in_frame()
    r = sp.Matrix([0, r2, r3])
    height = sp.simplify(-r.dot(Z))
    zdot = time_derivative(height)
    return w, wdot, Om, Z, r, sp.diag(I1, I1, I3), height, zdot, time_derivative(zdot)


@lru_cache(maxsize=None)
def derive_sliding(I1: sp.Expr, I3: sp.Expr, r2: sp.Expr, r3: sp.Expr) -> SlidingPhase:
    """The sliding phase of a body of revolution with r_P = (0, r2(theta), r3(theta)) (paper Eqs. 5-7)."""
    w, wdot, Om, Z, r, inertia, height, zdot, zddot = contact_kinematics(I1, I3, r2, r3)

    beta = slip_direction - phi
    cb, sb = sp.cos(beta), sp.sin(beta)
    # e(alpha) in 1-2-3 components: cos(beta) e1 + sin(beta) h, h = (0, cos theta, -sin theta)
    e_slip = sp.Matrix([cb, sb * sp.cos(theta), -sb * sp.sin(theta)])
    normal = g + zddot  # N / M
    force = normal * Z - mu * normal * e_slip  # F / M
    rows, acc = newton_euler(inertia, w, wdot, Om, r, force)
    on_shell = dict(zip(ACCELERATIONS, acc))
    margin = painleve_margin(rows)

    # omega x r_P: its vertical part is -z_C' (the contact stays on the plane), its horizontal part
    # in (e1, h) is (c1, c2); the CM's horizontal velocity is u - (c1, c2).
    spin = w.cross(r)
    vertical = sp.simplify(spin.dot(Z) + zdot)
    if vertical != 0:
        raise RuntimeError("the contact point's vertical velocity is not -z_C'; r_P is not a contact of the plane")
    c1 = spin[0]
    c2 = spin[1] * sp.cos(theta) - spin[2] * sp.sin(theta)
    v1, v2 = slip_speed * cb - c1, slip_speed * sb - c2  # CM horizontal velocity along (e1, h)
    # du/dt along (e1, h): a_C,h + d/dt(c1 e1 + c2 h), with de1/dt = phidot h, dh/dt = -phidot e1
    d1 = -mu * normal * cb + time_derivative(c1) - phidot * c2
    d2 = -mu * normal * sb + time_derivative(c2) + phidot * c1
    d1, d2 = (sp.expand(d.subs(on_shell)) for d in (d1, d2))
    along = _simplify(cb * d1 + sb * d2)
    across = _simplify(-sb * d1 + cb * d2)

    xdot = v1 * sp.cos(phi) - v2 * sp.sin(phi)
    ydot = v1 * sp.sin(phi) + v2 * sp.cos(phi)
    theta_, phi_, psi_, thetadot_, phidot_, psidot_ = STATE[:6]
    normal_on_shell = _simplify(normal.subs(on_shell) / g)
    rhs = (
        thetadot_, phidot_, STATE[5], acc[0], acc[1], acc[2], xdot, ydot,
        along, across / slip_speed, mu * g * normal_on_shell * slip_speed,
    )
    kinetic = sp.Rational(1, 2) * (w.dot(inertia * w) + v1 ** 2 + v2 ** 2 + zdot ** 2)
    return SlidingPhase(rhs, kinetic + g * height, kinetic, normal_on_shell, along, across, (xdot, ydot), margin)


@lru_cache(maxsize=None)
def _body_sliding(body_name: str) -> SlidingPhase:
    """The sliding phase of a shipped or registered body file, derived once and kept on disk beside its rolling
    model (:func:`models.bodies.kept_on_disk`): sympy takes minutes on a curved profile (the egg: 2.4 min), and
    every ``--friction`` run of it would pay them again.  Keyed by the body's exact data, this module's and the
    rolling derivation's sources and sympy's version."""
    from .bodies import contact_vector, kept_on_disk  # lazy: models.bodies (0.15 s) not needed by disk+coulomb

    body, stem, key = _sliding_key(body_name)
    return kept_on_disk(stem, key, lambda: derive_sliding(*contact_vector(body)))


def _sliding_key(body_name: str) -> tuple:
    """(the body, the stem and the key its sliding phase is kept under)."""
    from .bodies import _sources_hash, fingerprint, resolve  # lazy: models.bodies (0.15 s) not needed by disk+coulomb

    body = resolve(body_name)  # as the rolling model's name resolves: never a file of that name in the working folder
    here = Path(__file__).read_bytes()
    key = hashlib.sha256(fingerprint(body).encode() + _sources_hash().encode() + here + sp.__version__.encode()).hexdigest()
    return body, f"{body.name}-sliding", key


def sliding_is_kept(name: str) -> bool:
    """False if ``body:NAME+coulomb``'s sliding phase is not kept on disk yet (its first run will spend sympy's
    time on it); True for every other Coulomb model."""
    if not name.startswith("body:"):
        return True
    from .bodies import kept_path  # lazy: models.bodies (0.15 s) not needed by disk+coulomb

    _, stem, key = _sliding_key(rolling_name(name)[len("body:"):])
    return kept_path(stem, key).exists()


def painleve_margin(rows) -> sp.Expr:
    """P = det(d rows / d accelerations) over its value at mu = 0: Painleve's margin of the sliding phase.

    N = g + z_C'' carries thetaddot, and the friction -mu N e(alpha) feeds it back into the rows, so the
    accelerations solve a linear system whose determinant is that of the frictionless body (positive)
    times P.  For a body of revolution with z_C = H(theta) only row 1 holds thetaddot, and

        P = 1 + mu sin(alpha - phi) H H' / (I1 + H'^2)          (disk: H = sin theta)

    P = 1 at mu = 0; where P reaches 0 the accelerations and N grow without bound, and for P < 0 the
    sliding equations no longer have a unique solution (Painleve's paradox: the rigid body with Coulomb
    friction jams).  It can reach 0 only if mu > min over theta of (I1 + H'^2) / |H H'|
    (:func:`critical_friction`; the thin disk's 2 sqrt(k (k + 1)))."""
    jacobian = rows.jacobian(list(ACCELERATIONS))
    det = sp.expand(jacobian.det())
    return _simplify(det / det.subs(mu, 0))


def critical_friction(name: str, params: dict | None = None, samples: int = 4096) -> float:
    """The smallest mu at which Painleve's margin can reach 0 somewhere in the body's domain (any alpha).

    min over theta of (I1 + H'^2) / |H H'|, read off :func:`painleve_margin` as 1 / max |dP/dmu| over a
    grid of ``samples`` angles in the domain and refined by golden-section search (mpmath, 30 digits);
    infinite for a body whose margin does not depend on mu.  Below it a sliding phase cannot jam."""
    rolling, sliding, parameters = body(name)
    values = {p.symbol: sp.sympify((params or {}).get(p.name, p.default)) for p in parameters if p.name != "mu"}
    slope = sp.diff(sliding.painleve_margin, mu).subs(values)  # mu sin(alpha - phi) H H' / (I1 + H'^2) / mu
    slope = sp.simplify(slope.subs(slip_direction, phi + sp.pi / 2))  # |sin(alpha - phi)| = 1
    f = sp.lambdify(theta, sp.Abs(slope), "mpmath")
    lo, hi = (sp.sympify(e).subs(values) for e in (rolling.domain.theta_min, rolling.domain.theta_max))
    with mpmath.workdps(30):
        lo, hi = mpmath.mpf(sp.N(lo, 40)), mpmath.mpf(sp.N(hi, 40))
        grid = [lo + (hi - lo) * (i + mpmath.mpf(1) / 2) / samples for i in range(samples)]
        best = max(range(samples), key=lambda i: f(grid[i]))
        a, b = grid[max(best - 1, 0)], grid[min(best + 1, samples - 1)]
        ratio = (mpmath.sqrt(5) - 1) / 2
        for _ in range(120):
            c, d = b - ratio * (b - a), a + ratio * (b - a)
            if f(c) > f(d):
                b = d
            else:
                a = c
        peak = f((a + b) / 2)
    return float("inf") if peak == 0 else float(1 / peak)


def rolling_name(name: str) -> str:
    """The rolling model of a Coulomb body: ``disk``, ``ring``, or a shipped body ``body:NAME`` of ``body:NAME+coulomb``."""
    if name in ROLLING:
        return ROLLING[name]
    if name.startswith("body:") and name.endswith("+coulomb"):
        return name[:-len("+coulomb")]
    raise ValueError(f"unknown model {name!r}; allowed: {', '.join(NAMES)}, or body:NAME+coulomb for a shipped body")


def body(name: str):
    """(rolling model, sliding phase, parameters incl. ``mu`` last) of ``disk+coulomb``, ``ring+coulomb`` or a
    shipped body file's ``body:NAME+coulomb`` (:mod:`models.bodies`: the same derivation with its contact vector)."""
    rolling = get_model(rolling_name(name))
    if name.startswith("body:"):
        return rolling, _body_sliding(rolling.name[len("body:"):]), rolling.parameters + (FRICTION,)
    if name == "disk+coulomb":
        sliding = derive_sliding(disk.k, 2 * disk.k, disk.R2, disk.R3)
    else:
        sliding = derive_sliding(ring.I1, ring.I3, ring.R2, ring.R3)
    return rolling, sliding, rolling.parameters + (FRICTION,)
