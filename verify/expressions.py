"""Numbers a person can type: ``pi/2``, ``pi/2 - 0.05``, ``sqrt(980/1.25)``, read exactly.

A value given on the command line (``--state theta=pi/2``) or in a named start is either a plain
decimal (``1.2``, ``-3e-4``), kept as its text so that each precision rounds it once, or a simple
expression.  An expression is read by Python's own parser (:mod:`ast`: syntax only, nothing is
run) and built node by node into an exact sympy number from a whitelist: decimal literals (taken
from their text, ``0.1`` is 1/10), ``pi`` and ``e``, ``+ - * / **``, unary minus, and the functions
``sqrt, sin, cos, tan, asin, acos, atan, exp, log``.  Nothing else is accepted, and ``eval`` is
never called.  The exact value is then rounded once at the run's precision
(:meth:`verify.precision.Precision.number` reads sympy numbers to every digit), so ``pi/2`` in quad
is the quad number nearest pi/2, not the double.

Bad input raises :class:`ExpressionError` (a ValueError) naming the text and what is allowed.
"""
from __future__ import annotations

import ast
import re

#: What an expression may contain, for the error messages.
ALLOWED = ("a decimal number (1.2, -3e-4) or an expression of numbers, pi and e with + - * / ** and "
           "sqrt, sin, cos, tan, asin, acos, atan, exp, log (e.g. pi/2 - 0.05, sqrt(980/1.25))")
_DECIMAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_FUNCTIONS = ("sqrt", "sin", "cos", "tan", "asin", "acos", "atan", "exp", "log")
MAX_LENGTH = 200  # characters: a start value, not a program
MAX_EXPONENT = 1024  # |b| in a ** b, and a decimal literal's power of ten at most MAX_LITERAL_EXPONENT
MAX_LITERAL_EXPONENT = 10_000
MAX_DIGITS = 10_000  # digits of an exact power a ** b: beyond, sympy would build integers for minutes


class ExpressionError(ValueError):
    """A value that is neither a decimal number nor an allowed expression."""


def is_decimal(text: str) -> bool:
    """True for a plain decimal number such as 1.2, -3e-4 or .5."""
    return bool(_DECIMAL.fullmatch(text.strip())) and text.isascii()


def read_value(text: str, what: str = "value"):
    """``text`` itself if it is a plain decimal, else the exact sympy number it denotes.

    Parameters
    ----------
    text : str
        What the person typed.
    what : str
        How the error message names the value (``--state theta``).

    Raises
    ------
    ExpressionError
        If ``text`` is not a decimal number or an allowed expression, or its value is not a
        finite real number (``sqrt(-1)``, ``1/0``, ``log(0)``).
    """
    s = str(text).strip()
    if is_decimal(s):
        return s
    return exact_value(s, what)


def exact_value(text: str, what: str = "value"):
    """The exact sympy number of an allowed expression (see the module's docstring)."""
    s = str(text).strip()
    if not s or len(s) > MAX_LENGTH or not s.isascii() or not s.isprintable():
        shown = s if len(s) <= 60 else s[:57] + "..."
        raise ExpressionError(f"{what} {shown!r}: allowed {ALLOWED}")
    try:
        tree = ast.parse(s, mode="eval")
    except SyntaxError:
        raise ExpressionError(f"{what} {s!r} is not a number or expression; allowed {ALLOWED}") from None
    import sympy as sp  # lazy: sympy (0.23 s) after the syntax check: bad input is refused first

    try:
        value = _build(tree.body, s, sp)
    except ExpressionError as err:
        raise ExpressionError(f"{what} {s!r}: {err}; allowed {ALLOWED}") from None
    except (ValueError, ZeroDivisionError, OverflowError, TypeError):
        raise ExpressionError(f"{what} {s!r} has no finite real value; allowed {ALLOWED}") from None
    try:
        numeric = sp.N(value, 30)
    except (OverflowError, ValueError, ZeroDivisionError):  # exp(exp(exp(exp(10)))): beyond any float
        raise ExpressionError(f"{what} {s!r} is too large to evaluate; allowed {ALLOWED}") from None
    if value.has(sp.zoo, sp.oo, -sp.oo, sp.nan) or not numeric.is_real or not numeric.is_finite:
        raise ExpressionError(f"{what} {s!r} = {sp.sstr(numeric)} is not a finite real number; allowed {ALLOWED}")
    return value


def _build(node, source: str, sp):
    """The sympy number of one whitelisted node (raises ExpressionError on anything else)."""
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            raise ExpressionError(f"{node.value!r} is not a number")
        literal = ast.get_source_segment(source, node) or repr(node.value)
        literal = literal.replace("_", "")
        power = re.search(r"[eE]([+-]?\d+)$", literal)
        if power and abs(int(power.group(1))) > MAX_LITERAL_EXPONENT:
            raise ExpressionError(f"the literal {literal} is out of range (powers of ten up to {MAX_LITERAL_EXPONENT})")
        return sp.Rational(literal)
    if isinstance(node, ast.Name):
        if node.id == "pi":
            return sp.pi
        if node.id == "e":
            return sp.E
        raise ExpressionError(f"unknown name {node.id!r}")
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        inner = _build(node.operand, source, sp)
        return -inner if isinstance(node.op, ast.USub) else inner
    if isinstance(node, ast.BinOp):
        a, b = _build(node.left, source, sp), _build(node.right, source, sp)
        if isinstance(node.op, ast.Add):
            return a + b
        if isinstance(node.op, ast.Sub):
            return a - b
        if isinstance(node.op, ast.Mult):
            return a * b
        if isinstance(node.op, ast.Div):
            if b == 0:
                raise ZeroDivisionError
            return a / b
        if isinstance(node.op, ast.Pow):
            if abs(sp.N(b, 15)) > MAX_EXPONENT:
                raise ExpressionError(f"an exponent of {sp.N(b, 6)} (allowed at most {MAX_EXPONENT} in size)")
            if a != 0 and abs(sp.N(b, 15)) * abs(sp.N(sp.log(abs(a), 10), 15)) > MAX_DIGITS:
                raise ExpressionError(f"a power of about 10^{sp.N(b * sp.log(abs(a), 10), 6)} (allowed results of at "
                                      f"most {MAX_DIGITS} digits)")
            return a ** b
        raise ExpressionError(f"the operator {type(node.op).__name__} is not allowed")
    if isinstance(node, ast.Call):
        name = node.func.id if isinstance(node.func, ast.Name) else None
        if name not in _FUNCTIONS or node.keywords or len(node.args) != 1:
            shown = name or ast.get_source_segment(source, node.func)
            raise ExpressionError(f"{shown}(...) is not allowed (functions of one argument: {', '.join(_FUNCTIONS)})")
        arg = _build(node.args[0], source, sp)
        return {"sqrt": sp.sqrt, "sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "asin": sp.asin, "acos": sp.acos,
                "atan": sp.atan, "exp": sp.exp, "log": sp.log}[name](arg)
    raise ExpressionError(f"{ast.get_source_segment(source, node) or type(node).__name__!r} is not allowed")
