"""Inline LaTeX (``$\\dot{\\phi}_0 = \\sqrt{g/R}$``) as plain Unicode for a terminal (``φ̇₀ = √(g/R)``).

The paper's captions and the suite's texts write math as ``$...$`` (the report typesets it as MathML);
a terminal shows the raw TeX.  :func:`plain` rewrites the math of a text into Unicode: Greek letters,
dots over letters (combining U+0307, U+0308), sub- and superscript digits, ``\\sqrt{x}`` as ``√(x)``,
``\\frac{a}{b}`` as ``(a)/(b)``, bold vectors as plain letters, and the usual relations.  What it does not
know it leaves as it is, without the dollars.  Standard library only: the listings stay instant.
"""
from __future__ import annotations

import re

_GREEK = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "varepsilon": "ε", "zeta": "ζ",
          "eta": "η", "theta": "θ", "vartheta": "ϑ", "iota": "ι", "kappa": "κ", "lambda": "λ", "mu": "μ", "nu": "ν",
          "xi": "ξ", "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ", "upsilon": "υ", "phi": "φ", "varphi": "φ",
          "chi": "χ", "psi": "ψ", "omega": "ω", "Gamma": "Γ", "Delta": "Δ", "Theta": "Θ", "Lambda": "Λ", "Xi": "Ξ",
          "Pi": "Π", "Sigma": "Σ", "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω"}
_SYMBOLS = {"approx": "≈", "leq": "≤", "le": "≤", "geq": "≥", "ge": "≥", "neq": "≠", "ne": "≠", "times": "×",
            "cdot": "·", "pm": "±", "mp": "∓", "infty": "∞", "leftarrow": "←", "rightarrow": "→", "to": "→",
            "lvert": "|", "rvert": "|", "vert": "|", "partial": "∂", "nabla": "∇", "sim": "~", "propto": "∝",
            "ll": "≪", "gg": "≫", "equiv": "≡", "int": "∫", "sum": "Σ", "quad": " ", "qquad": "  ", ",": " ",
            ";": " ", "!": "", "left": "", "right": "", "sin": "sin", "cos": "cos", "tan": "tan", "cot": "cot",
            "exp": "exp", "log": "log", "ln": "ln", "arccos": "arccos", "arcsin": "arcsin", "arctan": "arctan"}
_SUB = str.maketrans("0123456789+-=()aeoxhklmnpst", "₀₁₂₃₄₅₆₇₈₉₊₋₌₍₎ₐₑₒₓₕₖₗₘₙₚₛₜ")
_SUP = str.maketrans("0123456789+-=()n", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁼⁽⁾ⁿ")
_GROUP = r"\{((?:[^{}]|\{[^{}]*\})*)\}"  # one brace group, one level of nesting inside
_MATH = re.compile(r"\$([^$]+)\$")


def _script(text: str, table: dict, mark: str) -> str:
    """Sub- or superscript characters where every character has one, else ``_x`` / ``^(xy)``."""
    if text and all(ord(c) in table for c in text):
        return text.translate(table)
    return f"{mark}{text}" if len(text) == 1 else f"{mark}({text})"


def _math(tex: str) -> str:
    s = re.sub(r"\\(dd?ot|sqrt|mathbf|hat|tilde|bar)\s*(\\[A-Za-z]+|[A-Za-z0-9])", r"\\\1{\2}", tex)  # \dot\phi
    for _ in range(3):  # nested groups: \sqrt{\dot{\phi}}
        s = re.sub(r"\\(?:mathbf|boldsymbol|mathrm|text|textrm|operatorname|mathit|vec)" + _GROUP, r"\1", s)
        s = re.sub(r"\\frac" + _GROUP + _GROUP, r"(\1)/(\2)", s)
        s = re.sub(r"\\sqrt" + _GROUP, r"√(\1)", s)
        s = re.sub(r"\\ddot" + _GROUP, lambda m: m.group(1) + "\u0308", s)
        s = re.sub(r"\\dot" + _GROUP, lambda m: m.group(1) + "\u0307", s)
        s = re.sub(r"\\(?:hat|tilde|bar)" + _GROUP, r"\1", s)
        s = re.sub(r"\\([A-Za-z]+)", lambda m: _GREEK.get(m.group(1), _SYMBOLS.get(m.group(1), m.group(0))), s)
    s = re.sub(r"\\([,;!])", lambda m: _SYMBOLS[m.group(1)], s)
    s = re.sub(r"_" + _GROUP, lambda m: _script(m.group(1), _SUB, "_"), s)
    s = re.sub(r"\^" + _GROUP, lambda m: _script(m.group(1), _SUP, "^"), s)
    s = re.sub(r"_([0-9A-Za-z])", lambda m: _script(m.group(1), _SUB, "_"), s)
    s = re.sub(r"\^([0-9n])", lambda m: _script(m.group(1), _SUP, "^"), s)
    s = s.replace("{", "").replace("}", "")
    return re.sub(r"\s+", " ", s).strip()


def plain(text: str) -> str:
    """``text`` with every ``$...$`` rewritten in Unicode (see the module docstring)."""
    out = _MATH.sub(lambda m: _math(m.group(1)), str(text))
    return re.sub(r"\\(?:mathbf|boldsymbol)" + _GROUP, r"\1", out)  # the paper's bold vectors outside math too
