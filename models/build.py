"""Turn a derivation (or the paper's printed rows) into a :class:`models.base.Model`."""
from __future__ import annotations

from dataclasses import replace

import sympy as sp

from .base import ChaplyginSystem, Domain, Invariant, Model
from .rolling import derive
from .symbols import ACCELERATIONS, g, omega_body


def additive_scale(expr: sp.Expr) -> sp.Expr:
    """Sum of the absolute values of the terms of ``expr``: the magnitude a drift is judged by."""
    return sp.Add(*[sp.Abs(t) for t in sp.Add.make_args(sp.expand(expr))])


def invariant(name: str, expr: sp.Expr, description: str) -> Invariant:
    return Invariant(name, expr, description, additive_scale(expr))


def energy_invariant(kinetic: sp.Expr, potential: sp.Expr, unit: str) -> Invariant:
    return invariant("energy", kinetic + potential, f"kinetic + potential energy per {unit}, potential zero on the plane")


def rolling_model(
    name: str,
    title: str,
    parameters: tuple,
    I1: sp.Expr,
    I3: sp.Expr,
    r2: sp.Expr,
    r3: sp.Expr,
    domain: Domain,
    unit: str,
    contact: str = "rolling",
    extra_invariants=(),
    theta_ref=None,
    chaplygin_closed_form=None,
) -> Model:
    """A body of revolution on the plane with the derived equations (paper Eqs. 8, 73)."""
    d = derive(I1, I3, r2, r3, contact)
    w = omega_body()
    chaplygin = None
    if d.chaplygin_matrix is not None and theta_ref is not None:
        chaplygin = ChaplyginSystem(sp.ImmutableMatrix(d.chaplygin_matrix), (w[1], w[2]), theta_ref, chaplygin_closed_form)
    source = "derived: Newton-Euler about C, " + (
        "no-slip v_C = -omega x r_P (general Eqs. 8, 73)" if contact == "rolling" else "smooth plane, F = N Z"
    )
    return Model(
        name=name,
        title=title,
        equations="derived",
        source=source,
        parameters=parameters,
        accelerations=d.accelerations,
        velocity_xy=d.velocity_xy,
        invariants=(energy_invariant(d.kinetic, d.potential, unit),) + tuple(extra_invariants),
        domain=domain,
        normal_force=d.normal_force,
        vertical_acceleration=d.vertical_acceleration,
        horizontal_acceleration=d.horizontal_acceleration,
        chaplygin=chaplygin,
        units=unit,
    )


def solve_rows(rows) -> tuple:
    """Solve three equations (LHS - RHS) for (thetaddot, phiddot, psiddot)."""
    solution = sp.solve(list(rows), list(ACCELERATIONS), dict=True)
    if len(solution) != 1:
        raise RuntimeError("the rows do not determine the accelerations uniquely")
    return tuple(sp.factor_terms(sp.cancel(solution[0][q])) for q in ACCELERATIONS)


def paper_variant(derived: Model, rows, source: str, I1, I3, r2, r3, contact="rolling") -> Model:
    """The same body driven by the paper's printed rows instead of the derived ones.

    Kinematics (no-slip velocity of C), energy and invariants stay those of the body:
    where the printed equations are wrong, the invariants drift, which is the finding.
    """
    acc = solve_rows(rows)
    d = derive(I1, I3, r2, r3, contact)
    normal = sp.cancel(1 + d.vertical_acceleration.subs(dict(zip(ACCELERATIONS, acc))) / g)
    return replace(derived, equations="paper", source=source, accelerations=acc, normal_force=normal)


def damped_model(d, couple, *, name: str, title: str, source: str, parameters: tuple, domain: Domain,
                 dissipation: sp.Expr, relations: tuple = ()) -> Model:
    """A rolling body whose Newton-Euler rows ``d.rows`` also carry a dissipative couple (e1, e2, e3).

    A couple adds no force: the contact force is eliminated as before, the rows become
    ``rows - couple`` and the energy of the derivation is kept as the first invariant -- not
    conserved: E + int ``dissipation`` dt is (``dissipation`` = -couple . omega >= 0).
    """
    acc = solve_rows(d.rows - couple)
    on_shell = dict(zip(ACCELERATIONS, acc))
    normal = sp.factor_terms(sp.cancel(sp.together(1 + d.vertical_acceleration.subs(on_shell) / g)))
    energy = energy_invariant(d.kinetic, d.potential, "m R^2")
    energy = replace(energy, description=energy.description + "; not conserved: E + W is (W = work of the couple)")
    return Model(name=name, title=title, equations="derived", source=source, parameters=parameters,
                 accelerations=acc, velocity_xy=d.velocity_xy, invariants=(energy,), domain=domain,
                 normal_force=normal, vertical_acceleration=d.vertical_acceleration,
                 horizontal_acceleration=d.horizontal_acceleration, chaplygin=None, units="m R^2", dissipation=dissipation, relations=relations)
