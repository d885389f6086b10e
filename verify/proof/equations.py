"""The model's right-hand side in ball arithmetic: the same sympy expressions heyoka compiles.

:func:`vector_field` turns ``Model.rhs()`` (paper Eqs. 8, 73 for the disk: the derived
Newton-Euler equations) into a function that evaluates them on python-flint's ``arb`` balls
or on ``arb_series`` (truncated power series with ball coefficients), with the parameters
as exact rationals.  Every operation is Arb's, so the result encloses the exact value of the
expression for every point of the argument balls.  The sympy tree is read node by node
(after common-subexpression elimination); a node this reader does not know, or a floating-
point constant, raises: no float can enter an enclosure unnoticed.
"""
from __future__ import annotations

from fractions import Fraction

import sympy as sp
from flint import arb, arb_series, fmpq

from models.symbols import STATE


def exact(value) -> fmpq:
    """An exact rational from a decimal or rational string, an int, a Fraction or a sympy Rational."""
    q = Fraction(str(value)) if not isinstance(value, Fraction) else value
    return fmpq(q.numerator, q.denominator)


class VectorField:
    """f(y) of dy/dt = f(y) for one model and exact parameters, on arb or arb_series.

    Parameters
    ----------
    model : models.Model
        Its ``rhs()`` gives the eight time derivatives in state order.
    params : dict
        Parameter name -> exact value (string such as ``"1/4"``, int or Fraction).
    """

    def __init__(self, model, params: dict):
        self.model = model
        self.params = {p.symbol: exact(params[p.name]) for p in model.parameters}
        exprs = [d for _, d in model.rhs()]
        self.replacements, self.reduced = sp.cse(exprs)

    def __call__(self, y: list) -> list:
        """The eight derivatives at ``y`` (eight arb or eight arb_series of one length)."""
        env = dict(zip(STATE, y))
        memo = {}
        for sym, expr in self.replacements:
            env[sym] = self._eval(expr, env, memo)
        return [self._eval(e, env, memo) for e in self.reduced]

    def _eval(self, e, env, memo):
        if e in memo:
            return memo[e]
        if e.is_Symbol:
            if e in env:
                out = env[e]
            elif e in self.params:
                out = arb(self.params[e])
            else:
                raise ValueError(f"unknown symbol {e} in the right-hand side")
        elif e.is_Rational:
            out = arb(fmpq(int(e.p), int(e.q)))
        elif e.is_Add:
            out = _fold([self._eval(a, env, memo) for a in e.args], lambda a, b: a + b)
        elif e.is_Mul:
            out = _fold([self._eval(a, env, memo) for a in e.args], lambda a, b: a * b)
        elif e.is_Pow:
            base = self._eval(e.base, env, memo)
            n = e.exp
            if n.is_Integer and int(n) > 0:
                out = base
                for _ in range(int(n) - 1):
                    out = out * base
            elif n.is_Integer and int(n) < 0:
                p = base
                for _ in range(-int(n) - 1):
                    p = p * base
                out = 1 / p
            elif n == sp.Rational(1, 2):
                out = base.sqrt()
            else:
                raise ValueError(f"power {e} not supported in ball arithmetic here")
        elif isinstance(e, sp.sin):
            out = self._eval(e.args[0], env, memo).sin()
        elif isinstance(e, sp.cos):
            out = self._eval(e.args[0], env, memo).cos()
        else:
            raise ValueError(f"node {e!r} ({type(e).__name__}) is not read into ball arithmetic")
        memo[e] = out
        return out


def _fold(values: list, op):
    """Sum or product of ``values``, started from a series where there is one (so the result is one)."""
    first = next((i for i, v in enumerate(values) if isinstance(v, arb_series)), 0)
    out = values[first]
    for i, v in enumerate(values):
        if i != first:
            out = op(out, v)
    return out
