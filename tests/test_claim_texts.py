"""The claims' texts as the report prints them: typeset math, never a sympy repr.

The report turns each ``$...$`` of a claim's text into MathML (dollarmath, then latex2mathml)
and puts several texts in table cells, so every text field of every evaluation is checked
for (1) leftovers of ``str(expr)`` -- the review's ``Matrix([[thetadot, ...`` and
``psidot_0**2`` -- and (2) math the renderer cannot take: a ``|`` (a table splits on it), a
space at either end, an unbalanced dollar, LaTeX outside the dollars, or LaTeX that
latex2mathml does not know (it passes an unknown command through as text, ``<mi>\\foo</mi>``,
rather than failing, so the converted MathML is searched for a backslash).  Each check has a
negative control showing it catches what it is for.  The paper's quotes are verbatim LaTeX of
the paper and are not a text the checks decide.
"""
from __future__ import annotations

import re

import pytest
import sympy as sp
from latex2mathml.converter import convert

from verify.claims import ERRATUM, all_claims
from verify.mathtext import equation, latex, symbol_latex, tex

#: What ``str`` / ``repr`` of a sympy object leaves in a text, each with the object that shows it.
x, y = sp.symbols("x psidot_0")
SYMPY_REPRS = {
    r"Matrix\(": sp.Matrix([[x, y]]),
    r"\*\*": y**2,
    r"\w\*\w|\)\*|\*\(": 2 * x * sp.sin(x),
    r"sqrt\(": sp.sqrt(x + 1),
    r"Rational\(": sp.srepr(sp.Rational(1, 3)),
    r"Symbol\(": sp.srepr(x),
    r"Integer\(": sp.srepr(sp.Integer(3)),
    r"Derivative\(": sp.Derivative(sp.Function("f")(x), x),
    r"\w+dot_\d": y,  # a sympy symbol's own name (the texts write the typeset dot)
    r"\[\[": sp.ImmutableMatrix([[x]]).tolist(),
    r"\bzoo\b|\boo\b": sp.oo,
    r"\bEq\(": sp.Eq(x, y),
}
TEXT_FIELDS = ("expected", "observed", "detail", "correction", "qualification")
MATH = re.compile(r"\$([^$]*)\$")


@pytest.fixture(scope="module")
def texts():
    """(claim id, field, text) for every text the report prints of every claim, evaluated once."""
    out = []
    for claim in all_claims():
        ev = claim.evaluate()
        for f in TEXT_FIELDS:
            if getattr(ev, f):
                out.append((claim.id, f, getattr(ev, f)))
        for name, value in ev.measures:
            out.append((claim.id, "measures", f"{name}: {value}"))
        for f in ("reading", "statement"):
            if getattr(claim, f):
                out.append((claim.id, f, getattr(claim, f)))
    return out


def sympy_reprs(text: str) -> list:
    """The patterns of :data:`SYMPY_REPRS` found in ``text``."""
    return [p for p in SYMPY_REPRS if re.search(p, text)]


def math_problems(text: str) -> list:
    """What the report's renderer could not take in ``text`` (empty when nothing)."""
    problems = []
    if text.count("$") % 2:
        problems.append("unbalanced $")
    outside = MATH.sub("", text)
    if "\\" in outside:
        problems.append(f"LaTeX outside math: {outside!r}")
    for m in MATH.findall(text):
        if not m or m != m.strip():
            problems.append(f"empty or space at an end: ${m}$")
        if "|" in m:
            problems.append(f"pipe: ${m}$")
        if m.count("{") != m.count("}"):
            problems.append(f"unbalanced braces: ${m}$")
        try:
            mathml = convert(m)
        except Exception as exc:  # latex2mathml raises its own exception classes
            problems.append(f"latex2mathml: {type(exc).__name__} on ${m}$")
            continue
        if "\\" in mathml:
            problems.append(f"unknown command left as text: ${m}$")
    return problems


# --- the checkers catch what they are for -----------------------------------------------

@pytest.mark.parametrize("pattern", list(SYMPY_REPRS))
def test_sympy_repr_checker_catches(pattern):
    obj = SYMPY_REPRS[pattern]
    shown = obj if isinstance(obj, str) else str(obj)
    assert pattern in sympy_reprs(f"the derived row is {shown} here"), shown


@pytest.mark.parametrize("bad", [
    r"$\lvert x \rvert$ but $a | b$",  # pipe
    r"$ x$", r"$x $",  # a space at an end
    r"one $x$ and $y",  # unbalanced dollar
    r"\dot{\phi} outside",  # LaTeX outside the dollars
    r"$\frac{1{2}$",  # unbalanced braces
    r"$x^$",  # latex2mathml raises
    r"$\notacommand x$",  # passed through as text by latex2mathml
])
def test_math_checker_catches(bad):
    assert math_problems(bad)


def test_checkers_pass_typeset_math():
    psi0 = sp.Symbol("psidot_0")
    text = f"threshold {equation(psi0**2, sp.Symbol('g') / 2)}; {tex(sp.Abs(sp.Symbol('thetadot')))}"
    assert not sympy_reprs(text) and not math_problems(text), text


# --- the module ------------------------------------------------------------------------

@pytest.mark.parametrize("name, want", [
    ("thetadot", r"\dot{\theta}"), ("psidot_0", r"\dot{\psi}_0"), ("phidot", r"\dot{\phi}"),
    ("thetaddot", r"\ddot{\theta}"), ("omega3", r"\omega_3"), ("I1", "I_1"), ("theta0", r"\theta_0"),
    ("phidot0", r"\dot{\phi}_0"), ("p_phi", r"p_{\phi}"), ("alphaddot", r"\ddot{\alpha}"), ("pdot", r"\dot{p}"),
    ("I_12", "I_{12}"), ("L_perp", r"L_\perp"), ("g", "g"), ("rho", r"\rho"),
])
def test_symbol_names(name, want):
    assert symbol_latex(name) == want


def test_vectors_are_tuples_and_abs_has_no_pipe():
    th = sp.Symbol("theta")
    assert latex(sp.Matrix([1, th, 0])) == latex(sp.Matrix([[1, th, 0]])) == r"\left(1, \theta, 0\right)"
    assert "|" not in latex(sp.Abs(th) ** 2)


# --- every claim's texts ----------------------------------------------------------------

def test_no_sympy_repr_in_any_text(texts):
    found = [(i, f, sympy_reprs(t), t) for i, f, t in texts if sympy_reprs(t)]
    assert not found, "\n".join(map(str, found))


def test_every_math_span_renders(texts):
    found = [(i, f, math_problems(t)) for i, f, t in texts if math_problems(t)]
    assert not found, "\n".join(map(str, found))


def test_checked_texts_carry_math(texts):
    """Not vacuous: the texts hold many math spans, and the equations the review saw are typeset."""
    spans = sum(len(MATH.findall(t)) for _, _, t in texts)
    assert spans > 300, spans
    by_id = {(i, f): t for i, f, t in texts}
    assert by_id[("eq-14", "expected")].startswith(r"$\Omega = \left(\dot{\theta}, ")
    assert r"\dot{\psi}_0^{2}" in by_id[("eq-31", "expected")]


#: Errata whose correction is words, each with why no equation belongs in it.
WORDED_CORRECTIONS = {}


def test_erratum_corrections_are_typeset(texts):
    errata = {c.id for c in all_claims() if c.evaluate().verdict == ERRATUM}
    assert errata, "no errata: the check below would be vacuous"
    corrections = {i: t for i, f, t in texts if f == "correction"}
    assert errata <= set(corrections)
    plain = sorted(i for i in errata if not MATH.search(corrections[i]) and i not in WORDED_CORRECTIONS)
    assert not plain, plain
