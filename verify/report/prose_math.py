"""The page's prose math: ASCII names written in the claims' and studies' texts, set as the symbols they are.

The texts of results.json are plain (``theta -> 0``, ``phidot0 = 25.7``, ``s^-1``, ``mu_req``): they are read
in terminals, REPORT.md and JSON.  On the page, where the equations are MathML, the same quantities are set
in their symbols (θ → 0, φ̇₀ = 25.7, s⁻¹, μ<sub>req</sub>) so that one quantity looks the same in a formula and
in a sentence.  :func:`typeset_prose` rewrites the text between tags only -- never inside ``<math>``,
``<code>``, ``<pre>``, ``<script>``, ``<style>`` or an attribute (anchors and ids keep their ASCII) -- and
only whole words from :data:`NAMES`, so a model name (``ring+air-drag``) or a file name is left alone.
"""
from __future__ import annotations

import re

DOT, DDOT = "\u0307", "\u0308"
_GREEK = {"theta": "θ", "phi": "φ", "psi": "ψ", "omega": "ω", "alpha": "α", "rho": "ρ", "mu": "μ", "Delta": "Δ",
          "pi": "π", "lambda": "λ", "nu": "ν", "tau": "τ", "epsilon": "ε", "eps": "ε"}
_SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
_SUP = str.maketrans("0123456789-+/()", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺ᐟ⁽⁾")
#: the names rewritten, as a regex alternation (longest first): a Greek letter, optionally dotted, optionally
#: with a digit subscript (theta0, phidot_0, omega3), and a few named subscripts
_NAME = re.compile(r"(?<![A-Za-z0-9_.&])(d?)(theta|phi|psi|omega|alpha|rho|mu|Delta|pi|lambda|nu|tau|epsilon|eps)"
                   r"(?:_?(ddot|dot))?(?:_?(\d)(?!\d)|_([a-z]+))?(?![A-Za-z0-9_]|\.[a-z]{2,5}\b)")  # not a file name (&pi; is kept by the look-behind)
_INERTIA = re.compile(r"(?<![\w./+-])I([13])(?![\w])")
_POWER = re.compile(r"(?<=[\w)\u0307\u0308])\^(\(?-?\d+(?:/\d+)?\)?)")
_ARROW = re.compile(r"\s-(?:>|&gt;)\s")
_SQRT = re.compile(r"(?<![\w.])sqrt\(")
_RELATION = {" <= ": " ≤ ", " >= ": " ≥ ", " != ": " ≠ ", " &lt;= ": " ≤ ", " &gt;= ": " ≥ "}
_SKIP = ("math", "code", "pre", "script", "style")
_TAG = re.compile(r"(<[^>]+>)")


def _name(m: re.Match) -> str:
    d, letter, dots, digit, named = m.groups()
    if letter == "pi" and (d or dots or digit or named):
        return m.group(0)
    out = d + _GREEK[letter] + {"dot": DOT, "ddot": DDOT, None: ""}[dots]
    if digit is not None:
        out += digit.translate(_SUB)
    elif named is not None:
        out += {"perp": "<sub>⊥</sub>"}.get(named, f"<sub>{named}</sub>")
    return out


def _power(m: re.Match) -> str:
    exponent = m.group(1)
    inner = exponent[1:-1] if exponent.startswith("(") and exponent.endswith(")") else exponent
    return inner.translate(_SUP)


_URL = re.compile(r"(\w+://\S+)")


def typeset_text(text: str) -> str:
    """One run of prose (no tags) with its ASCII math set in symbols; addresses (``https://...``) as they are."""
    if "://" in text:
        return "".join(part if _URL.fullmatch(part) else typeset_text(part) for part in _URL.split(text))
    text = _ARROW.sub(" → ", text)
    for ascii_, symbol in _RELATION.items():
        text = text.replace(ascii_, symbol)
    text = _SQRT.sub("√(", text)
    text = _POWER.sub(_power, text)
    text = _NAME.sub(_name, text)
    text = re.sub(r"(?<=/)d(theta|phi|psi)(?![A-Za-z0-9_])", lambda m: "d" + _GREEK[m.group(1)], text)  # dL/dtheta
    text = re.sub(r"Δ ([θφψω])", r"Δ\1", text)  # Delta theta: one quantity
    return _INERTIA.sub(lambda m: "I" + m.group(1).translate(_SUB), text)


def typeset_prose(html: str) -> str:
    """``html`` with the prose between its tags typeset (see the module docstring)."""
    out, skipping = [], []
    for piece in _TAG.split(html):
        if piece.startswith("<") and piece.endswith(">"):
            name = re.match(r"</?\s*([A-Za-z0-9]+)", piece)
            tag = name.group(1).lower() if name else ""
            if tag in _SKIP and not piece.endswith("/>"):
                if piece.startswith("</"):
                    if skipping and skipping[-1] == tag:
                        skipping.pop()
                else:
                    skipping.append(tag)
            out.append(piece)
        elif skipping or not piece.strip():
            out.append(piece)
        else:
            out.append(typeset_text(piece))
    return "".join(out)
