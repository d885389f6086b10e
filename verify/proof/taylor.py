"""Taylor coefficients of the flow in ball arithmetic, by Picard iteration on truncated series.

For dy/dt = f(y), y(0) = y0, the iteration y <- y0 + integral_0^t f(y) on power series
truncated after t^n fixes one more coefficient per pass: after n + 1 passes the coefficients
of t^0 .. t^n are exactly those of the solution (a truncated series' coefficients up to t^n
depend only on the operands' coefficients up to t^n).  Evaluated by Arb on ``arb_series``
whose constant terms are balls, every coefficient is a ball that contains the exact Taylor
coefficient y^(k)(0) / k! of the solution from every point of the starting balls: automatic
differentiation of the model's expressions, rigorous by inclusion.
"""
from __future__ import annotations

import math
from fractions import Fraction

from flint import arb, arb_series, ctx, fmpq

from .enclosure import NoEnclosure, a_priori_box


def taylor_coefficients(field, start: list, order: int) -> list:
    """Coefficients c[i][k] ⊇ y_i^(k)(0)/k!, k = 0..order, of the solutions from ``start`` (eight arb).

    Parameters
    ----------
    field : VectorField
        The right-hand side on series.
    start : list of arb
        The starting balls.
    order : int
        The highest power kept.
    """
    if ctx.cap < order + 1:
        raise ValueError(f"python-flint's series cap {ctx.cap} would truncate order {order}: set ctx.cap")
    series = [arb_series([c], prec=1) for c in start]
    for length in range(2, order + 2):
        rates = field([arb_series(s.coeffs(), prec=length - 1) for s in series])
        series = [arb_series([c] + [_coeff(r, k) / (k + 1) for k in range(length - 1)], prec=length)
                  for c, r in zip(start, rates)]
    return [[_coeff(s, k) for k in range(order + 1)] for s in series]


def _coeff(s, k):
    """The coefficient of t^k (an exact 0 where the series stored fewer terms)."""
    c = s.coeffs()
    from flint import arb

    return c[k] if k < len(c) else arb(0)


def validated_step(field, y, h: Fraction, order: int, allowed: float):
    """One validated Taylor step of exact size h from the balls y: (balls containing every solution
    from y at h, the Lagrange remainder's bound), or :class:`NoEnclosure` when the box does not
    validate or the bound exceeds ``allowed`` (steps 1-4 of :mod:`.integrator`)."""
    ha = arb(fmpq(h.numerator, h.denominator))
    coeffs = taylor_coefficients(field, y, order - 1)
    box = a_priori_box(field, y, ha)
    rem = [c[order] for c in taylor_coefficients(field, box, order)]
    bound = max(float(abs(r).upper()) for r in rem) * float(h) ** order
    if not math.isfinite(bound) or bound > allowed:
        raise NoEnclosure(f"remainder {bound:.2e} over {float(h):.3g}")
    new = []
    for c, r in zip(coeffs, rem):
        acc = r
        for k in range(order - 1, -1, -1):
            acc = acc * ha + c[k]
        new.append(acc)
    return new, bound
