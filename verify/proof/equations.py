"""The model's right-hand side in ball arithmetic: the same sympy expressions heyoka compiles.

``VectorField`` turns ``Model.rhs()`` (paper Eqs. 8, 73 for the disk: the derived
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
    """An exact rational from a decimal or rational string, an int, a Fraction or a sympy Rational
    (a float is refused: its shortest decimal is not the number it holds, nor the one meant)."""
    if isinstance(value, float):
        raise TypeError(f"{value!r} is a float: give the exact value as a string or a Fraction")
    q = Fraction(str(value)) if not isinstance(value, Fraction) else value
    return fmpq(q.numerator, q.denominator)


class BallExpressions:
    """Expressions in given symbols, evaluated on arb or arb_series (exact parameters).

    Parameters
    ----------
    symbols : sequence of sympy.Symbol
        The arguments, in call order.
    exprs : sequence of sympy.Expr
        The outputs.
    params : dict
        sympy symbol -> exact value (fmpq, or an arb the caller vouches for).
    """

    def __init__(self, symbols, exprs, params: dict):
        self.symbols, self.params = tuple(symbols), params
        self.replacements, self.reduced = sp.cse(list(exprs))
        self._tape, self._outputs = _Tape.compile(self.symbols, self.replacements, self.reduced, params)

    def __call__(self, y: list) -> list:
        """The outputs at ``y`` (one arb or arb_series per symbol, series of one length)."""
        return self._tape.run(y, self._outputs)


class VectorField(BallExpressions):
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
        super().__init__(STATE, [d for _, d in model.rhs()],
                         {p.symbol: exact(params[p.name]) for p in model.parameters})


class _Tape:
    """The sympy tree flattened once into a straight-line program over registers (inputs first).

    Each instruction is (operation, operand registers); constants and parameters are exact arb
    registers.  Evaluating the program is then a loop over a list instead of a walk over sympy
    nodes (hashing and recursion dominated the cost before).
    """

    def __init__(self):
        self.constants = []   # (register, exact fmpq)
        self.program = []     # (kind, operands, extra)
        self.size = 0

    @classmethod
    def compile(cls, symbols, replacements, reduced, params):
        tape = cls()
        tape.size = len(symbols)
        registers = {sym: i for i, sym in enumerate(symbols)}
        for sym, expr in replacements:
            registers[sym] = tape._emit(expr, registers, params)
        outputs = [tape._emit(e, registers, params) for e in reduced]
        return tape, outputs

    def _new(self) -> int:
        self.size += 1
        return self.size - 1

    def _emit(self, e, registers, params) -> int:
        if e in registers:
            return registers[e]
        if e.is_Symbol:
            if e not in params:
                raise ValueError(f"unknown symbol {e} in the right-hand side")
            out = self._constant(params[e])
        elif e.is_Rational:
            out = self._constant(fmpq(int(e.p), int(e.q)))
        elif e.is_Add or e.is_Mul:
            operands = [self._emit(a, registers, params) for a in e.args]
            out = self._new()
            self.program.append(("add" if e.is_Add else "mul", operands, out))
        elif e.is_Pow:
            base = self._emit(e.base, registers, params)
            n = e.exp
            out = self._new()
            if n.is_Integer and int(n) != 0:
                self.program.append(("pow", [base], (out, int(n))))
            elif n == sp.Rational(1, 2):
                self.program.append(("sqrt", [base], out))
            else:
                raise ValueError(f"power {e} not supported in ball arithmetic here")
        elif isinstance(e, (sp.sin, sp.cos)):
            arg = self._emit(e.args[0], registers, params)
            out = self._new()
            self.program.append(("sin" if isinstance(e, sp.sin) else "cos", [arg], out))
        else:
            raise ValueError(f"node {e!r} ({type(e).__name__}) is not read into ball arithmetic")
        registers[e] = out
        return out

    def _constant(self, q) -> int:
        out = self._new()
        self.constants.append((out, q))
        return out

    def run(self, y: list, outputs: list) -> list:
        regs = list(y) + [None] * (self.size - len(y))
        for i, q in self.constants:
            regs[i] = arb(q)
        for kind, operands, out in self.program:
            if kind == "add":
                regs[out] = _fold([regs[i] for i in operands], lambda a, b: a + b)
            elif kind == "mul":
                regs[out] = _fold([regs[i] for i in operands], lambda a, b: a * b)
            elif kind == "pow":
                out, n = out
                base = regs[operands[0]]
                p = base
                for _ in range(abs(n) - 1):
                    p = p * base
                regs[out] = p if n > 0 else 1 / p
            elif kind == "sqrt":
                regs[out] = regs[operands[0]].sqrt()
            elif kind == "sin":
                regs[out] = regs[operands[0]].sin()
            else:
                regs[out] = regs[operands[0]].cos()
        return [regs[i] for i in outputs]


def _fold(values: list, op):
    """Sum or product of ``values``, started from a series where there is one (so the result is one)."""
    first = next((i for i, v in enumerate(values) if isinstance(v, arb_series)), 0)
    out = values[first]
    for i, v in enumerate(values):
        if i != first:
            out = op(out, v)
    return out
