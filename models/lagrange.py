"""Euler-Lagrange equations for the holonomic models (gyroscope, effective Lagrangian)."""
from __future__ import annotations

import sympy as sp

from .symbols import time_derivative


def euler_lagrange(L: sp.Expr, coordinates) -> tuple:
    """Accelerations and energy of a Lagrangian.

    Parameters
    ----------
    L : sympy expression in the state symbols
    coordinates : sequence of (q, qdot, qddot) symbol triples

    Returns
    -------
    (dict qddot -> expression, energy expression, dict q -> generalised momentum)
    """
    rows, momenta = [], {}
    for q, qd, _ in coordinates:
        p = sp.diff(L, qd)
        momenta[q] = sp.factor_terms(sp.cancel(p))
        rows.append(sp.expand(time_derivative(p) - sp.diff(L, q)))
    unknowns = [qdd for _, _, qdd in coordinates]
    solution = sp.solve(rows, unknowns, dict=True)
    if len(solution) != 1:
        raise RuntimeError("the Lagrangian is degenerate: no unique accelerations")
    acc = {q: sp.factor_terms(sp.cancel(solution[0][q])) for q in unknowns}
    energy = sp.expand(sum(qd * sp.diff(L, qd) for _, qd, _ in coordinates) - L)
    return acc, energy, momenta
