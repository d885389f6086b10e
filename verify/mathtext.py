"""Typeset math for the report's texts (claims, threshold closed forms): sympy expressions as inline LaTeX, ``$...$``.

The report turns every ``$...$`` of a claim's text into MathML (markdown-it's dollarmath
plugin, then latex2mathml), so a text says ``$\\dot{\\psi}_0^{2}$`` where ``str(expr)`` would
say ``psidot_0**2``.  The symbols keep the paper's notation: a name ending in ``dot`` or
``ddot`` is a time derivative (``thetadot`` -> theta with a dot), a trailing digit or
``_0`` a subscript (``omega3``, ``I1``, ``theta0``, ``psidot_0``), ``p_phi`` a momentum
with a Greek subscript.

Two limits of the renderer shape what is printed: inline math must not contain ``|`` (a
table cell would split on it), so an absolute value is ``\\lvert x \\rvert``; and a vector is
printed as the paper prints it, a tuple ``(a, b, c)`` of its 1-2-3 components, whether sympy
holds it as a row or a column.
"""
from __future__ import annotations

import re

import sympy as sp
from sympy.printing.latex import LatexPrinter

_GREEK = {
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa", "lambda", "mu",
    "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi", "omega",
    "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi", "Omega",
}
#: Names that are not read by the rule of :func:`symbol_latex`.
_SPECIAL = {
    "th": r"\theta",  # the small angle of a series in theta
    "J1": r"\tilde{I}_1",  # I1 + 4, the moment the paper writes I1 in Eqs. 87-93 (tilde dropped there)
    "L_perp": r"L_\perp",  # the horizontal component of L (Eqs. 19, 51)
}
_NAME = re.compile(r"^(?P<base>[A-Za-z]+?)(?P<dots>ddot|dot)?(?:_?(?P<sub>\d+)|_(?P<word>[A-Za-z]+))?$")


def _letter(name: str) -> str:
    return "\\" + name if name in _GREEK else name


def symbol_latex(name: str) -> str:
    """LaTeX for one of the claims' symbol names: ``psidot_0`` -> ``\\dot{\\psi}_0``."""
    if name in _SPECIAL:
        return _SPECIAL[name]
    match = _NAME.match(name)
    if match is None or (match["base"] not in _GREEK and len(match["base"]) > 1):
        return sp.latex(sp.Symbol(name))
    body = _letter(match["base"])
    if match["dots"]:
        body = f"\\{match['dots']}{{{body}}}"
    if match["sub"]:
        body += f"_{{{match['sub']}}}" if len(match["sub"]) > 1 else f"_{match['sub']}"
    elif match["word"]:
        body += f"_{{{_letter(match['word'])}}}"
    return body


class _Printer(LatexPrinter):
    """sympy's LaTeX printer with the two changes the report's renderer needs (see the module)."""

    def _print_Abs(self, expr, exp=None):
        text = r"\lvert %s \rvert" % self._print(expr.args[0])
        return f"{text}^{{{exp}}}" if exp is not None else text

    def _print_MatrixBase(self, expr):
        if 1 in expr.shape:
            return r"\left(%s\right)" % ", ".join(self._print(x) for x in expr)
        return super()._print_MatrixBase(expr)

    _print_ImmutableMatrix = _print_ImmutableDenseMatrix = _print_Matrix = _print_MutableDenseMatrix = _print_MatrixBase


def latex(expr) -> str:
    """LaTeX of a sympy expression (or number) in the paper's notation, without the dollars."""
    expr = sp.sympify(expr)
    names = {s: symbol_latex(s.name) for s in expr.free_symbols if isinstance(s, sp.Symbol)}
    return _Printer({"symbol_names": names, "fold_func_brackets": True}).doprint(expr)


def tex(expr) -> str:
    """Inline math, ``$<latex>$``, for a sympy expression: what a claim's text embeds."""
    return f"${latex(expr)}$"


def equation(lhs, rhs) -> str:
    """Inline math for ``lhs = rhs`` of two sympy expressions, neither side simplified."""
    return f"${latex(lhs)} = {latex(rhs)}$"
