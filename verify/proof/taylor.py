"""Taylor coefficients of the flow in ball arithmetic, and one validated Taylor step.

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

from flint import arb, arb_series, ctx

from .enclosure import NoEnclosure, polynomial_range, taylor_tube


def taylor_coefficients(field, start: list, order: int) -> list:
    """Coefficients c[i][k] ⊇ y_i^(k)(0)/k!, k = 0..order, of the solutions from ``start`` (balls).

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
    coeffs = [[c] for c in start]
    for length in range(2, order + 2):
        rates = field([arb_series(c, prec=length - 1) for c in coeffs])
        coeffs = [[c] + [r / (k + 1) for k, r in enumerate(_padded(rate, length - 1))]
                  for c, rate in zip(start, rates)]
    return coeffs


def _padded(s, length: int) -> list:
    """The first ``length`` coefficients of s (exact zeros where the series stored fewer terms; a
    rate that does not depend on the state comes back as one arb, a constant)."""
    c = [s] if isinstance(s, arb) else s.coeffs()
    return c[:length] + [arb(0)] * (length - len(c))


class TaylorExpansion:
    """The Taylor coefficients c_0..c_n of the solutions from a set of starts, and steps from them.

    Parameters
    ----------
    field : callable
        The right-hand side on balls and series.
    start : list of arb
        The starting balls (points for Lohner's centre, the whole set for the direct method).
    order : int
        n: the polynomial has degree n - 1, the Lagrange remainder is of order n.
    tube_prec : int
        Working precision of the tube and the remainder's coefficient (:mod:`.enclosure`).
    """

    def __init__(self, field, start: list, order: int, *, tube_prec: int = 64):
        self.field, self.order, self.tube_prec = field, order, tube_prec
        self.coeffs = taylor_coefficients(field, start, order)
        if not all(c.is_finite() for row in self.coeffs for c in row):
            raise RuntimeError("the Taylor coefficients are unbounded at the step's start (no smaller step helps)")

    def suggested_step(self, allowed: float, inflation: float = 1.0) -> float:
        """The step at which the start's own c_n, times ``inflation``, would make a remainder of
        ``allowed`` (a predictor: the tube's c_n is larger than the start's, by a factor the
        integrator learns from the last step, :meth:`inflation`)."""
        top = max(float(abs(c[self.order]).upper()) for c in self.coeffs) * inflation
        return math.inf if top == 0 else (allowed / top) ** (1.0 / self.order)

    def inflation(self, h: float, bound: float) -> float:
        """How much larger the tube's remainder ``bound`` at step h was than the start's c_n h^n."""
        top = max(float(abs(c[self.order]).upper()) for c in self.coeffs)
        return 1.0 if top == 0 or h == 0 else max(1.0, bound / (top * h ** self.order))

    def advance(self, h: arb, allowed: float):
        """(balls holding every solution from the start at time h, the remainder's bound).

        Steps 1-4 of :mod:`.integrator`; raises :class:`NoEnclosure` when no tube validates or the
        remainder's bound exceeds ``allowed``.
        """
        n = self.order

        def expand(box):
            return taylor_coefficients(self.field, box, n)

        _, tube_top = taylor_tube(expand, self.coeffs, h, prec=self.tube_prec)
        power = h ** n
        bound = max(float(abs(t).upper()) for t in tube_top) * float(power.upper())
        if not math.isfinite(bound) or bound > allowed:
            raise NoEnclosure(f"remainder {bound:.2e} over {float(h.mid()):.3g}")
        return [polynomial_range(c[:n], h) + t * power for c, t in zip(self.coeffs, tube_top)], bound
