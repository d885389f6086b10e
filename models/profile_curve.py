"""The ``curve`` profile kind: a smooth convex meridian given as expressions of one parameter s.

A body file gives the meridian as ``r = "..."`` (the distance from the axis) and ``z = "..."`` (the height
above the centre of mass C along e3), exact expressions of the one symbol ``s``, on ``s_min < s < s_max``,
traversed from the bottom (low z) to the top.  The contact point for the tilt theta is the point of the meridian
whose outward normal points along the plane's downward normal -Z (paper Eqs. 1, 47, 63; :mod:`models.profiles`):
with the meridian through -e2, the height -r sin(theta) + z cos(theta) is least there, so

    dr/ds sin(theta) = dz/ds cos(theta)          (the first-order condition; tan(theta) = z'(s) / r'(s))

and r_P = (0, -r(s*), z(s*)) with s* = s(theta).  This module

* **reads** r and z safely (:func:`read_expression`): Python's own parser, then a whitelist walked node by node
  into sympy (numbers read exactly, the symbol s, pi, + - * / and integer powers up to :data:`MAX_POWER`, the
  functions of :data:`FUNCTIONS`); nothing is evaluated, so no attribute, call or name outside the list can run;
* **solves** the first-order condition for s(theta) exactly with sympy (:func:`solve_contact`): for a meridian
  polynomial in sin s and cos s it is reduced modulo sin^2 + cos^2 = 1 and factored, the factors free of theta
  (the curvature, non-zero on a convex curve) dropped, and each factor linear in (sin theta, cos theta) and of
  degree <= 2 in (sin s, cos s) solved by ``sympy.solve``; for a polynomial in s, degree <= 4 (radicals).  Where
  no closed form comes out the body is **refused** in one line naming why: s is not carried implicitly (a root
  solved inside heyoka's right-hand side would need a Newton iteration per evaluation, which heyoka's Taylor
  expressions cannot hold honestly);
* **picks the branch** that is the lowest point (:func:`pick_branch`): of sympy's roots, the one that lies in
  (s_min, s_max) and whose height is at most the least of 2001 sampled heights of the whole curve, at 33 tilts of
  the domain (double; :data:`HEIGHT_SLACK` argued in :func:`pick_branch`); exactly one must;
* **checks the curve** (:func:`check_curve`), rigorously, in ball arithmetic (python-flint's arb) on a cover of
  [s_min, s_max] refined by bisection: convexity, the curvature r' z'' - z' r'' > 0 (the normal turns one way,
  so each tilt has one contact point); the centre of mass inside, r z' - z r' > 0 (C's height above the plane at
  the contact of the normal at s, times the speed |(r', z')|); the ends in the half-plane, r >= 0 there (r is
  then >= 0 between, since the normal's angle stays in [0, pi]); the normal's angle at the ends in [0, pi] (the
  meridian of a body of revolution);
* **the domain** (:func:`normal_angle`): the tilts where the contact lies on the curve are the normal's angles
  between the ends, atan2(z', r') at s_min and s_max; an end on the axis with z' = 0 is theta = 0 or pi
  (``axis_vertical``); any other end is an edge of the body (``curve_end``: the contact reaches a corner there,
  and :func:`models.profiles.check_domain` refuses a file domain that goes beyond).

Every number of the contact must be exact in binary (an integer or a fraction whose denominator is a power of
2): heyoka would round any other to double (:func:`verify.engine.compile.to_heyoka` refuses it), so such a
curve is refused here, when it is read, rather than when it is compiled.
"""
from __future__ import annotations

import ast
from dataclasses import replace
from functools import lru_cache

import flint
import numpy as np
import sympy as sp

from .symbols import theta

#: The meridian's parameter (the one symbol a curve's expressions may use).
s = sp.Symbol("s", real=True)
#: The functions a curve's expressions may call (name -> sympy function), all of which heyoka compiles.
FUNCTIONS = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "sqrt": sp.sqrt, "exp": sp.exp, "log": sp.log,
             "atan": sp.atan, "sinh": sp.sinh, "cosh": sp.cosh, "tanh": sp.tanh}
#: The largest integer power a curve may write (x**n, |n| <= MAX_POWER): a bigger one would be a typo or an attack.
MAX_POWER = 8
MAX_LENGTH = 400
MAX_DEPTH = 40
#: The sampling of :func:`pick_branch`: tilts across the domain, and points along the curve at each.
BRANCH_TILTS = 33
CURVE_SAMPLES = 2001
#: The finest piece of [s_min, s_max] the ball-arithmetic checks bisect to before they give up (relative).
FINEST = 2.0 ** -24
#: How far (in L) a root's height may lie above the least sampled height and still be the lowest point.
HEIGHT_SLACK = 1e-12


class CurveError(ValueError):
    """A curve no convex meridian is, or one whose contact has no closed form; the message names the value."""


def read_expression(text, what: str) -> sp.Expr:
    """An expression of s from a body file, read through a whitelist (no evaluation of the text)."""
    if not isinstance(text, str):
        raise CurveError(f"{what} = {text!r}: give the curve as a string of s, such as \"cos(s)/2\"")
    if not text.strip() or len(text) > MAX_LENGTH:
        raise CurveError(f"{what} = {text[:40]!r}: allowed: a non-empty expression of s of at most {MAX_LENGTH} "
                         "characters")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError:
        raise CurveError(f"{what} = {text!r}: not an expression (allowed: numbers, s, pi, + - * / **, "
                         f"{', '.join(FUNCTIONS)})") from None
    expr = _node(tree.body, text.strip(), what, 0)
    # the form kept is the one its own text reads back to (sympy distributes a sign over a sum when the text
    # is read again), so that a body written out by models.bodies.to_toml is the same Body, with the same
    # fingerprint and model name; two passes reach it for every shipped curve
    for _ in range(4):
        written = sp.sstr(expr)
        again = _node(ast.parse(written, mode="eval").body, written, what, 0)
        if again == expr:
            return expr
        expr = again
    raise CurveError(f"{what} = {text[:40]!r}: its expression has no stable written form (sympy rewrites it on every "
                     "reading); write it expanded")


def _node(node, text: str, what: str, depth: int) -> sp.Expr:
    allowed = f"numbers, s, pi, + - * /, ** with an integer |n| <= {MAX_POWER}, and {', '.join(FUNCTIONS)}"
    if depth > MAX_DEPTH:
        raise CurveError(f"{what}: nested deeper than {MAX_DEPTH} levels; allowed: {allowed}")
    if isinstance(node, ast.Constant) and type(node.value) in (int, float):
        literal = ast.get_source_segment(text, node) or ""
        mantissa, _, exponent = literal.lower().partition("e")
        if len(mantissa) > 30 or len(exponent.lstrip("+-")) > 2:
            raise CurveError(f"{what}: the number {literal!r} is too long; allowed: at most 30 digits and an "
                             "exponent of 2 digits")
        return sp.Rational(literal)
    if isinstance(node, ast.Name):
        if node.id == "s":
            return s
        if node.id == "pi":
            return sp.pi
        raise CurveError(f"{what}: the name {node.id!r}; allowed: {allowed}")
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        x = _node(node.operand, text, what, depth + 1)
        return -x if isinstance(node.op, ast.USub) else x
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub, ast.Mult, ast.Div)):
        a, b = _node(node.left, text, what, depth + 1), _node(node.right, text, what, depth + 1)
        if isinstance(node.op, ast.Div) and b == 0:
            raise CurveError(f"{what}: a division by zero")
        if isinstance(node.op, ast.Add):
            return a + b
        if isinstance(node.op, ast.Sub):
            return a - b
        return a * b if isinstance(node.op, ast.Mult) else a / b
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow):
        n = node.right
        sign = -1 if isinstance(n, ast.UnaryOp) and isinstance(n.op, ast.USub) else 1
        n = n.operand if isinstance(n, ast.UnaryOp) and isinstance(n.op, (ast.USub, ast.UAdd)) else n
        if not (isinstance(n, ast.Constant) and type(n.value) is int and n.value <= MAX_POWER):
            raise CurveError(f"{what}: the power {ast.get_source_segment(text, node)!r}; allowed: an integer exponent "
                             f"of at most {MAX_POWER} in size (sqrt for a square root)")
        return _node(node.left, text, what, depth + 1) ** (sign * n.value)
    if isinstance(node, ast.Call):
        name = node.func.id if isinstance(node.func, ast.Name) else None
        if name not in FUNCTIONS or len(node.args) != 1 or node.keywords:
            raise CurveError(f"{what}: the call {ast.get_source_segment(text, node)!r}; allowed: one argument to "
                             f"{', '.join(FUNCTIONS)}")
        return FUNCTIONS[name](_node(node.args[0], text, what, depth + 1))
    raise CurveError(f"{what}: {ast.get_source_segment(text, node)!r} is not allowed; allowed: {allowed}")


# --- exact arithmetic on balls (python-flint's arb): the rigorous checks ---------------------------------------

_ARB = {sp.sin: "sin", sp.cos: "cos", sp.tan: "tan", sp.exp: "exp", sp.log: "log", sp.atan: "atan",
        sp.sinh: "sinh", sp.cosh: "cosh", sp.tanh: "tanh"}


def ball(expr: sp.Expr, x) -> flint.arb:
    """``expr`` (of s) on the ball ``x``, in arb: an enclosure of every value on it (rationals exact, no floats)."""
    if expr is s:
        return x
    if expr.is_Rational:
        return flint.arb(int(expr.p)) / int(expr.q)
    if expr is sp.pi:
        return flint.arb.pi()
    if expr.is_Add:
        return sum((ball(a, x) for a in expr.args[1:]), ball(expr.args[0], x))
    if expr.is_Mul:
        out = ball(expr.args[0], x)
        for a in expr.args[1:]:
            out = out * ball(a, x)
        return out
    if expr.is_Pow:
        base, e = expr.args
        if e == sp.Rational(1, 2) or e == -sp.Rational(1, 2):
            root = ball(base, x).sqrt()
            return root if e > 0 else 1 / root
        if e.is_Integer:
            return ball(base, x) ** int(e)
    if type(expr) in _ARB or expr.func in _ARB:
        return getattr(ball(expr.args[0], x), _ARB[expr.func])()
    raise CurveError(f"the expression {expr} has a part ({expr.func.__name__}) the exact checks cannot evaluate")


def _positive_on(expr: sp.Expr, lo, hi, what: str) -> None:
    """Prove ``expr`` > 0 on [lo, hi] by arb on a cover refined by bisection; :class:`CurveError` where it fails."""
    a0, b0 = (flint.arb(str(sp.N(v, 40))) for v in (lo, hi))
    finest = (b0 - a0) * FINEST
    stack = [(a0, b0)]
    while stack:
        a, b = stack.pop()
        piece = flint.arb((a + b) / 2, (b - a) / 2 + (b - a) * 2.0 ** -40)  # a ball that covers [a, b]
        value = ball(expr, piece)
        if value > 0:
            continue
        mid = (a + b) / 2
        point = ball(expr, mid)
        if point <= 0 or not (b - a) > finest:
            raise CurveError(f"{what} at s = {float(mid.mid()):.6g} (value {float(point.mid()):.3g}); the curve must "
                             "keep it positive on [s_min, s_max]")
        stack += [(a, mid), (mid, b)]


def normal_angle(r: sp.Expr, z: sp.Expr, at: sp.Expr) -> sp.Expr:
    """The tilt whose contact point is the curve's point at s = ``at``: atan2(z'(at), r'(at)), exact."""
    dr, dz = (sp.nsimplify(sp.simplify(sp.diff(f, s).subs(s, at))) for f in (r, z))
    if dr == 0 and dz == 0:
        raise CurveError(f"the curve stops at s = {at} (r' = z' = 0): allowed: a regular curve, r'^2 + z'^2 > 0")
    return sp.simplify(sp.atan2(dz, dr))


def check_curve(r: sp.Expr, z: sp.Expr, s_min: sp.Expr, s_max: sp.Expr) -> tuple:
    """The rules of a convex meridian (module docstring); returns (theta_min, theta_max, below, above)."""
    if not s_min < s_max:
        raise CurveError(f"s_min = {s_min}, s_max = {s_max}: allowed: s_min < s_max")
    extra = (r.free_symbols | z.free_symbols) - {s}
    if extra:
        raise CurveError(f"the curve uses {', '.join(sorted(map(str, extra)))}; allowed: the one symbol s")
    for name, value in (("s_min", s_min), ("s_max", s_max)):
        rho = sp.nsimplify(sp.simplify(r.subs(s, value)))
        if not rho.is_real or rho < 0:
            raise CurveError(f"r({name} = {value}) = {rho}: the meridian lies at r >= 0 (the distance from the axis)")
    dr, dz = sp.diff(r, s), sp.diff(z, s)
    _positive_on(sp.expand(dr * sp.diff(dz, s) - dz * sp.diff(dr, s)), s_min, s_max,
                 "not convex: the curvature r' z'' - z' r'' is not positive")
    _positive_on(sp.expand(r * dz - z * dr), s_min, s_max,
                 "the centre of mass is not inside: r z' - z r' (C's height above the plane there) is not positive")
    lo, hi = normal_angle(r, z, s_min), normal_angle(r, z, s_max)
    if not (0 <= lo < hi <= sp.pi):
        raise CurveError(f"the curve's normal turns from {lo} to {hi}; allowed: within [0, pi], bottom to top "
                         "(the meridian of a body of revolution, from the lower pole towards the upper one)")
    ends = []
    for value, angle in ((s_min, lo), (s_max, hi)):
        on_axis = sp.simplify(r.subs(s, value)) == 0 and angle in (0, sp.pi)
        ends.append("axis_vertical" if on_axis else "curve_end")
    return lo, hi, ends[0], ends[1]


# --- the contact: the first-order condition solved exactly -------------------------------------------------------


def solve_contact(r: sp.Expr, z: sp.Expr) -> list:
    """The roots s(theta) of r'(s) sin(theta) = z'(s) cos(theta), as sympy expressions (module docstring)."""
    condition = sp.diff(r, s) * sp.sin(theta) - sp.diff(z, s) * sp.cos(theta)
    S, C, U, W = sp.symbols("S C U W")
    trig = sp.expand(sp.expand_trig(condition)).subs({sp.sin(s): S, sp.cos(s): C, sp.sin(theta): U,
                                                       sp.cos(theta): W})
    if not trig.has(s):
        try:
            basis = sp.groebner([S ** 2 + C ** 2 - 1], S, C, U, W, order="lex", domain="QQ")
            reduced = basis.reduce(sp.expand(trig))[1]
        except sp.PolynomialError:
            raise CurveError("the contact's condition is not a polynomial in sin s, cos s with rational numbers; "
                             "sympy finds no closed form s(theta): refused") from None
        roots = []
        for factor, _ in sp.factor_list(reduced)[1]:
            if not factor.has(U, W):
                continue  # the curvature (and constants): not zero on a convex curve
            degree = sp.Poly(factor, S, C).total_degree()
            if sp.Poly(factor, U, W).total_degree() != 1 or degree > 2:
                raise CurveError(f"the contact's condition has a factor of degree {degree} in sin s, cos s; sympy's "
                                 "closed form s(theta) is built for degree <= 2 here: refused")
            roots += sp.solve(factor.subs({S: sp.sin(s), C: sp.cos(s), U: sp.sin(theta), W: sp.cos(theta)}), s)
        return roots
    if sp.diff(r, s, 2).has(sp.sin, sp.cos, sp.exp, sp.log, sp.tan, sp.atan) or sp.diff(z, s, 2).has(
            sp.sin, sp.cos, sp.exp, sp.log, sp.tan, sp.atan):
        raise CurveError("the curve mixes s with functions of s; sympy finds no closed form s(theta) for its contact "
                         "(allowed: polynomials in sin s and cos s, or polynomials in s): refused")
    poly = sp.Poly(sp.expand(condition), s)
    if poly.degree() > 4:
        raise CurveError(f"the contact's condition has degree {poly.degree()} in s; closed forms exist to degree 4: "
                         "refused")
    return sp.solve(poly.as_expr(), s)


def _simplify_branch(expr: sp.Expr, lo: sp.Expr, hi: sp.Expr) -> sp.Expr:
    """atan(tan(u)) -> u where u stays in (-pi/2, pi/2) on the domain (checked in arb at its ends: u is monotone
    there when it is linear in theta, the only case rewritten)."""
    def rule(node):
        if node.func == sp.atan and node.args[0].func == sp.tan:
            u = node.args[0].args[0]
            if sp.diff(u, theta, 2) == 0 and all(abs(u.subs(theta, e)) <= sp.pi / 2 for e in (lo, hi)):
                return u
        return node
    return sp.simplify(expr.replace(lambda n: n.func == sp.atan and n.args and n.args[0].func == sp.tan, rule))


def pick_branch(r: sp.Expr, z: sp.Expr, s_min, s_max, lo, hi, roots) -> sp.Expr:
    """The root s(theta) that is the curve's lowest point at every tilt sampled in (lo, hi) (module docstring).

    In double (numpy): the heights are O(L) sums of a few dozen rounded terms, each within a few eps, so a
    root that is the lowest point lies below every sampled height up to :data:`HEIGHT_SLACK` (1e-12 L, 4500 eps,
    a factor 50 over 100 terms' worth of rounding); a wrong root (another critical point: the highest point,
    a point off the curve) lies O(L) above the lowest samples, or outside (s_min, s_max), or is not real.
    """
    a, b, t0, t1 = (float(v) for v in (s_min, s_max, lo, hi))
    tilts = t0 + (t1 - t0) * np.arange(1, BRANCH_TILTS + 1) / (BRANCH_TILTS + 1)
    curve = np.linspace(a, b, CURVE_SAMPLES)
    rz = sp.lambdify(s, [r, z], "numpy")
    rc, zc = (np.broadcast_to(np.asarray(v, dtype=float), curve.shape) for v in rz(curve))
    least = np.min(-np.outer(np.sin(tilts), rc) + np.outer(np.cos(tilts), zc), axis=1)
    good = []
    for root in roots:
        with np.errstate(all="ignore"):
            value = np.asarray(sp.lambdify(theta, root, "numpy")(tilts.astype(complex)), dtype=complex)
            value = np.broadcast_to(value, tilts.shape)
            if not np.all(np.abs(value.imag) < 1e-12):
                continue
            value = value.real
            rv, zv = (np.broadcast_to(np.asarray(v, dtype=float), tilts.shape) for v in rz(value))
            height = -rv * np.sin(tilts) + zv * np.cos(tilts)
        if np.all((a < value) & (value < b) & (height <= least + HEIGHT_SLACK)):
            good.append(root)
    if len(good) != 1:
        raise CurveError(f"sympy's roots of the contact's condition ({len(roots)}) give {len(good)} lowest points "
                         "inside (s_min, s_max) across the domain; allowed: exactly one branch")
    return _simplify_branch(good[0], lo, hi)


def dyadic_only(expr: sp.Expr, what: str) -> None:
    """Refuse a constant heyoka would round to double (not an integer nor a fraction over a power of 2)."""
    for atom in sp.preorder_traversal(expr):
        if isinstance(atom, sp.Float) or (isinstance(atom, sp.Rational) and atom.q & (atom.q - 1)):
            raise CurveError(f"{what} holds the constant {atom}, which heyoka would round to double; allowed: "
                             "integers and fractions whose denominator is a power of 2 (1/8, 3/1024)")


@lru_cache(maxsize=None)
def contact_of_curve(r: sp.Expr, z: sp.Expr, s_min: sp.Expr, s_max: sp.Expr) -> tuple:
    """(r2, r3, theta_min, theta_max, below, above) of the curve: checked, solved, the branch picked."""
    for what, e in (("profile.r", r), ("profile.z", z), ("profile.s_min", s_min), ("profile.s_max", s_max)):
        if e.free_symbols - {s}:
            raise CurveError(f"{what} uses {', '.join(sorted(map(str, e.free_symbols - {s})))}; allowed: s")
    lo, hi, below, above = check_curve(r, z, s_min, s_max)
    branch = pick_branch(r, z, s_min, s_max, lo, hi, solve_contact(r, z))
    # tan(u) -> sin(u)/cos(u): sympy writes atan's inverse through 1/tan, whose removable singularity at
    # theta = pi/2 heyoka's Taylor recurrences for tan do not survive (the ellipse curve's run met NaN there)
    r2, r3 = (e.replace(sp.tan, lambda u: sp.sin(u) / sp.cos(u)) for e in (-r.subs(s, branch), z.subs(s, branch)))
    dyadic_only(r2 + r3, "the contact point of the curve")
    return r2, r3, lo, hi, below, above


#: The contact's components as undefined functions of theta: a curve's model is derived with these (seconds),
#: then its r2(theta), r3(theta) put in (:func:`with_contact`); derived with the trigonometric polynomials
#: themselves, sympy's rational simplification of the rows runs for more than ten minutes (measured on the egg).
R2, R3 = sp.Function("curve_r2")(theta), sp.Function("curve_r3")(theta)


def with_contact(model, r2: sp.Expr, r3: sp.Expr):
    """``model`` (derived with :data:`R2`, :data:`R3`) with the curve's contact put in, derivatives first."""
    steps = [{R2.diff(theta, 2): sp.diff(r2, theta, 2), R3.diff(theta, 2): sp.diff(r3, theta, 2)},
             {R2.diff(theta): sp.diff(r2, theta), R3.diff(theta): sp.diff(r3, theta)}, {R2: r2, R3: r3}]

    def put(e):
        if e is None:
            return None
        if isinstance(e, (tuple, list)):
            return tuple(put(x) for x in e)
        for step in steps:
            e = e.xreplace(step)
        if e.has(R2.func, R3.func):
            raise RuntimeError("the curve's contact functions survived the substitution")
        return e

    chaplygin = model.chaplygin
    if chaplygin is not None:
        chaplygin = replace(chaplygin, matrix=sp.ImmutableMatrix(chaplygin.matrix.applyfunc(put)))
    return replace(model, accelerations=put(model.accelerations), velocity_xy=put(model.velocity_xy),
                   invariants=tuple(replace(i, expr=put(i.expr), scale=put(i.scale)) for i in model.invariants),
                   normal_force=put(model.normal_force), vertical_acceleration=put(model.vertical_acceleration),
                   horizontal_acceleration=put(model.horizontal_acceleration), chaplygin=chaplygin)


__all__ = ["CurveError", "R2", "R3", "with_contact", "FUNCTIONS", "MAX_POWER", "ball", "check_curve", "contact_of_curve", "dyadic_only",
           "normal_angle", "pick_branch", "read_expression", "s", "solve_contact"]
