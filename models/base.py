"""What a model is: named state, parameters with ranges, equations and invariants as sympy.

A model is data plus expressions, in the manner of heyoka's own ``model`` module: the
right-hand side, the energy, the other invariants and the normal force are sympy
expressions in the state symbols of :mod:`models.symbols` and the parameter symbols
below.  :mod:`verify.engine.compile` turns them into heyoka expressions with the parameters as
runtime ``par[i]``, so a sweep over parameters needs no recompilation.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Callable, Optional

import sympy as sp

from .symbols import ACCELERATIONS, STATE, STATE_NAMES, g


@dataclass(frozen=True)
class Parameter:
    """A physical parameter with its exact default and its allowed range.

    ``default`` is an exact sympy number (e.g. ``Rational(1, 4)``) so that every
    precision gets the correctly rounded value, not a double.
    """

    name: str
    symbol: sp.Symbol
    default: sp.Expr
    description: str
    lower: Optional[float] = None
    upper: Optional[float] = None
    lower_inclusive: bool = False
    upper_inclusive: bool = True

    def allowed(self) -> str:
        """The allowed range, in words, for error messages."""
        lo = "(-inf" if self.lower is None else ("[" if self.lower_inclusive else "(") + f"{self.lower:g}"
        hi = "+inf)" if self.upper is None else f"{self.upper:g}" + ("]" if self.upper_inclusive else ")")
        return f"{lo}, {hi}"

    def check(self, value, shown=None) -> None:
        """Raise ``ValueError`` naming the value if it is not finite or out of range."""
        v = float(value)
        value = value if shown is None else shown
        if not math.isfinite(v):
            raise ValueError(f"parameter {self.name}={value} is not a finite number")
        bad_lo = self.lower is not None and (v < self.lower or (v == self.lower and not self.lower_inclusive))
        bad_hi = self.upper is not None and (v > self.upper or (v == self.upper and not self.upper_inclusive))
        if bad_lo or bad_hi:
            raise ValueError(
                f"parameter {self.name}={value} is out of its physical range {self.allowed()} ({self.description})"
            )


@dataclass(frozen=True)
class Invariant:
    """A conserved quantity as a closed-form expression of state and parameters.

    ``scale`` is the magnitude the drift is measured against (for the energy, kinetic
    plus the absolute potential), so that a relative drift is meaningful even where the
    invariant itself is near zero.
    """

    name: str
    expr: sp.Expr
    description: str
    scale: Optional[sp.Expr] = None


@dataclass(frozen=True)
class ChaplyginSystem:
    """The linear ODE d(w)/d(theta) = A(theta) w for w = (omega2, omega3).

    The rows of the rolling equations without thetaddot make the body-frame rates
    omega2, omega3 obey a linear ODE in theta.  Transporting w back to ``theta_ref``
    with its fundamental matrix gives two first integrals (Chaplygin's), named
    ``chaplygin_1`` (omega2 at theta_ref) and ``chaplygin_2`` (omega3 at theta_ref).
    ``closed_form``, where one exists, evaluates the same two numbers another way
    (for the thin disk: Legendre functions through mpmath's hypergeometric function).
    """

    matrix: sp.Matrix  # 2x2 in theta and parameters
    rates: tuple  # (omega2, omega3) as expressions of the state
    theta_ref: sp.Expr
    closed_form: Optional[Callable] = None  # (theta, w2, w3, params as mpf) -> (c1, c2)


@dataclass(frozen=True)
class Domain:
    """The open interval of theta where the model holds, with the names of its ends."""

    theta_min: sp.Expr
    theta_max: sp.Expr
    below: str  # event name when theta falls to theta_min
    above: str  # event name when theta rises to theta_max

    def contains(self, theta) -> bool:
        return float(self.theta_min) < float(theta) < float(self.theta_max)


@dataclass(frozen=True)
class Model:
    """A body, one source of its equations, and everything the suite measures on it."""

    name: str
    title: str
    equations: str  # "derived" or "paper"
    source: str  # where the equations come from (paper equation numbers)
    parameters: tuple
    accelerations: tuple  # (thetaddot, phiddot, psiddot) expressions
    velocity_xy: tuple  # (xdot, ydot) of the centre of mass
    invariants: tuple  # of Invariant; energy first
    domain: Domain
    normal_force: Optional[sp.Expr] = None  # N / (M g); contact holds while positive
    # a_C . Z with thetaddot, phiddot, psiddot left as symbols: normal_force is 1 + this / g on shell
    # (paper Eq. 6); the terminal event reads N through it and the right-hand side's own expressions
    vertical_acceleration: Optional[sp.Expr] = None
    # (a_C . X, a_C . Y) with the accelerations left as symbols: the horizontal contact force is
    # M times this (paper Eq. 6, gravity is vertical).  None without rolling contact: a smooth
    # plane has no friction, a fixed pivot's force is not friction, the effective Lagrangian no contact
    horizontal_acceleration: Optional[tuple] = None
    chaplygin: Optional[ChaplyginSystem] = None
    constraints: tuple = field(default_factory=tuple)  # (name, expr == 0 at start, description)
    units: str = ""
    relations: tuple = field(default_factory=tuple)  # (text, predicate(params dict of floats))
    dissipation: Optional[sp.Expr] = None  # power lost (>= 0) by a dissipative term: E + int dissipation dt is conserved

    @property
    def horizontal_force(self) -> Optional[tuple]:
        """(F . X, F . Y) / (M g): the horizontal contact force on shell, or None (paper Eq. 6).

        ``horizontal_acceleration`` / g with this model's own accelerations substituted (a paper
        variant's printed rows give its own force, as they give its ``normal_force``).
        """
        if self.horizontal_acceleration is None:
            return None
        on_shell = dict(zip(ACCELERATIONS, self.accelerations))
        return tuple(a.subs(on_shell) / g for a in self.horizontal_acceleration)

    @property
    def friction_required(self) -> Optional[sp.Expr]:
        """mu_req = |F_h| / N: the smallest friction coefficient that lets the body roll, or None.

        Meaningful where N > 0 only (where N <= 0 the contact is lost, whatever the friction).
        """
        force = self.horizontal_force
        if force is None or self.normal_force is None:
            return None
        return sp.sqrt(force[0] ** 2 + force[1] ** 2) / self.normal_force

    @property
    def parameter_names(self) -> tuple:
        return tuple(p.name for p in self.parameters)

    @property
    def parameter_symbols(self) -> tuple:
        return tuple(p.symbol for p in self.parameters)

    @property
    def energy(self) -> sp.Expr:
        return self.invariants[0].expr

    def check_relations(self, values: dict) -> None:
        """Raise ``ValueError`` if the parameters together violate a physical relation."""
        for text, holds in self.relations:
            if not holds({k: float(v) for k, v in values.items()}):
                shown = ", ".join(f"{k}={v}" for k, v in values.items() if k != "g")
                raise ValueError(f"parameters {shown} violate {text}")

    def parameter(self, name: str) -> Parameter:
        for p in self.parameters:
            if p.name == name:
                return p
        raise KeyError(name)

    def rhs(self) -> list:
        """(state symbol, time derivative) pairs, in the order of ``STATE_NAMES``."""
        theta, phi, psi, thetadot, phidot, psidot, x, y = STATE
        ddot = self.accelerations
        return [
            (theta, thetadot), (phi, phidot), (psi, psidot),
            (thetadot, ddot[0]), (phidot, ddot[1]), (psidot, ddot[2]),
            (x, self.velocity_xy[0]), (y, self.velocity_xy[1]),
        ]

    def invariant_names(self) -> tuple:
        names = tuple(i.name for i in self.invariants)
        if self.chaplygin is not None:
            names += ("chaplygin_1", "chaplygin_2")
        return names

    def with_invariants(self, invariants) -> "Model":
        """A copy with other invariants (used by negative controls and paper sources)."""
        return replace(self, invariants=tuple(invariants))


STATE_INDEX = {n: i for i, n in enumerate(STATE_NAMES)}
