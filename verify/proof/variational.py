"""The flow's Jacobian enclosed over a box: the variational equations in ball arithmetic.

For dy/dt = f(y) the state-transition matrix V = ∂y(t)/∂y(0) solves dV/dt = Df(y) V, V(0) = I.
The extended system (y, V) is evaluated by forward-mode differentiation: each state component
is a :class:`Dual` holding its value and its eight derivatives with respect to the start, and
the model's expressions (:class:`~verify.proof.equations.VectorField`, unchanged) run on the
duals, so ``f`` and ``Df V`` come out of one pass.  Values and derivatives may be arb balls or
arb_series, so the same extended field feeds :func:`~verify.proof.taylor.taylor_coefficients`
(Taylor coefficients of V from every start in a box) and
:func:`~verify.proof.enclosure.taylor_tube` (the Lagrange remainder's enclosure).
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, arb_mat, ctx, fmpq

from .enclosure import polynomial_range, taylor_tube
from .taylor import taylor_coefficients

DIMENSION = 8


class Dual:
    """A value and its derivatives (arb or arb_series), with the arithmetic the model reader uses."""

    __slots__ = ("d", "v")

    def __init__(self, v, d):
        self.v, self.d = v, d

    def __add__(self, o):
        if isinstance(o, Dual):
            return Dual(self.v + o.v, [a + b for a, b in zip(self.d, o.d)])
        return Dual(self.v + o, self.d)

    __radd__ = __add__

    def __neg__(self):
        return Dual(-self.v, [-a for a in self.d])

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if isinstance(o, Dual):
            return Dual(self.v * o.v, [a * o.v + self.v * b for a, b in zip(self.d, o.d)])
        return Dual(self.v * o, [a * o for a in self.d])

    __rmul__ = __mul__

    def __rtruediv__(self, o):
        inv = o / self.v
        slope = -inv / self.v
        return Dual(inv, [slope * a for a in self.d])

    def __truediv__(self, o):
        if isinstance(o, Dual):
            return self * (1 / o)
        return Dual(self.v / o, [a / o for a in self.d])

    def sqrt(self):
        s = self.v.sqrt()
        half_slope = 1 / (2 * s)
        return Dual(s, [half_slope * a for a in self.d])

    def sin(self):
        c = self.v.cos()
        return Dual(self.v.sin(), [c * a for a in self.d])

    def cos(self):
        s = -self.v.sin()
        return Dual(self.v.cos(), [s * a for a in self.d])


class VariationalField:
    """The extended right-hand side (f(y), Df(y) V) on 8 + 64 components (V row-major)."""

    def __init__(self, field):
        self.field = field

    def __call__(self, z: list) -> list:
        n = DIMENSION
        duals = [Dual(z[i], z[n + n * i:n + n * (i + 1)]) for i in range(n)]
        rates = [r if isinstance(r, Dual) else Dual(r, [arb(0)] * n) for r in self.field(duals)]  # a constant rate
        out = [r.v for r in rates]
        for r in rates:
            out.extend(r.d)
        return out


class FlowJacobian:
    """The flow's Jacobian ∂y(h)/∂y(0) enclosed for every start in a box, for any step h.

    Taylor coefficients of (y, V) from (box, I) to order m, computed once at ``prec`` bits; for a
    step h, V's Lagrange remainder from c_m over a validated tube of the extended system
    (:func:`~verify.proof.enclosure.taylor_tube`).  The Jacobian multiplies only the set's small
    parallelepiped, so its own width matters at its width times the set's: a low order and
    precision suffice (its width, ~(h/rho)^m, enters the set's growth once per step).

    Raises :class:`~verify.proof.enclosure.NoEnclosure` from :meth:`at` when no tube validates.
    """

    def __init__(self, field, box: list, *, order: int = 16, prec: int = 64):
        self.extended, self.order, self.prec = VariationalField(field), order, prec
        n = DIMENSION
        saved = ctx.prec, ctx.cap
        ctx.prec, ctx.cap = prec, max(ctx.cap, order + 2)
        try:
            start = list(box) + [arb(1 if i == j else 0) for i in range(n) for j in range(n)]
            self.coeffs = taylor_coefficients(self.extended, start, order)
            if not all(c.is_finite() for row in self.coeffs for c in row):
                raise RuntimeError("the Jacobian's Taylor coefficients are unbounded on the set's hull "
                                   "(no smaller step helps)")
        finally:
            ctx.prec, ctx.cap = saved

    def at(self, h: arb) -> arb_mat:
        """An arb_mat containing ∂y(h)/∂y(0) at every start in the box."""
        n, m = DIMENSION, self.order
        saved = ctx.prec, ctx.cap
        ctx.prec, ctx.cap = self.prec, max(ctx.cap, m + 2)
        try:
            _, top = taylor_tube(lambda box: taylor_coefficients(self.extended, box, m), self.coeffs, h,
                                 prec=self.prec)
            power = h ** m
            entries = [polynomial_range(c[:m], h) + t * power for c, t in zip(self.coeffs[n:], top[n:])]
            return arb_mat(n, n, entries)
        finally:
            ctx.prec, ctx.cap = saved


def flow_jacobian(field, box: list, h: Fraction, *, order: int = 16, prec: int = 64) -> arb_mat:
    """An arb_mat containing ∂y(h)/∂y(0) at every start in ``box`` (eight arb), step h exact."""
    saved = ctx.prec
    ctx.prec = prec
    try:
        ha = arb(fmpq(h.numerator, h.denominator))
    finally:
        ctx.prec = saved
    return FlowJacobian(field, box, order=order, prec=prec).at(ha)
