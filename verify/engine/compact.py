"""Right-hand sides in the form heyoka's Taylor recursion computes cheaply (issue 33, item 3).

The derivation (:mod:`models.rolling`) leaves each acceleration as one quotient with an expanded
numerator: ``(k phidot^2 sin cos + phidot^2 sin cos + g cos + ...) / (k + 1)``.  heyoka decomposes
an expression into elementary terms and computes every term's Taylor coefficients on every step;
a product or quotient of two non-constant terms, a power and a sine or cosine each cost a
convolution of the order (~20 in double), a sum or a product with one parameter or number
almost nothing.  The expanded numerator repeats the same products of the rates (``phidot^2``
with ``sin cos`` twice, once with ``k``), and the common quotient divides them all.

:func:`compact` rewrites an expression as a sum
over the monomials of its *polynomial variables* (the rates, the accelerations an event function
reads: symbols that enter only polynomially, never inside a function), each monomial times one
coefficient in the other symbols (the angles' sines and cosines, the parameters), the sum divided
once by the common denominator:

    thetaddot = -(g cos + phidot^2 (k + 1) sin cos + phidot psidot (2k + 1) sin) / (k + 1)

which is paper Eq. 18 solved by hand.  A coefficient is cancelled and factored, and where a rule of
trigonometry shortens it (sin^2 = 1 - cos^2 and back) the shorter form is kept; monomial factors
common to every term are pulled out (``2 thetadot (...)``).  heyoka then shares equal
subexpressions across the system and its events (its decomposition keeps one term per distinct
expression).  On the thin disk this takes heyoka's decomposition from 54 terms to 44 (62 to 52 with
the terminal events; Eq. 18 typed by hand, 40); ``python -m verify bench`` reports them.

Terms with different denominators are compacted apart and added, never brought over a common
denominator: in the slip event (F_h/(Mg mu))^2 - (N/(Mg))^2 that would multiply N^2 by mu^2 (1e12 for
mu = 1e6) in a numerator where the force's part is 1e12 times smaller, and lose it to rounding.  (A run
with mu = 1e6 once measured four times less accurate than one without the event was noise: the event
moves heyoka's steps, and on six starts the ratio of the two errors ranges over 0.2 to 8, both forms
alike; ``tests/test_slip_event.py`` now holds each run to the conditioning bound.)  And the denominator is
not divided into each coefficient: that would make quotients of parameters such
as (2k + 1)/(k + 1), rounded once and then wrong the same way on every step -- a systematic error
under which the invariants drift like t rather than like the square root of the steps (measured: the
Chaplygin integrals of a 2 s disk run in 160-bit MPFR drifted 6.5 times more, beyond the bound of
``tests/test_conservation.py``).

It is an identity: the same rational function of the same symbols, rearranged
(``tests/test_compact.py`` checks every model's right-hand side, events and invariants against
the uncompacted expressions at random exact points).  The results of a run move by ulps (the
operations are done in another order), amplified by the flow's conditioning as any rounding is.
An expression that is not polynomial in any symbol (a square root of the rates, an absolute
value) is returned as it was; so is a form that would not be shorter, or that would bring in a
constant heyoka would round (a rational whose denominator is not a power of two).  The result
depends only on the expression (sympy's canonical ordering): the same compiled code every run.

The rewriting costs sympy seconds for a body file's model (cancel, factor and together on every
coefficient: 4.3 s for body:oblate-ellipsoid's system and events, 28 s for every model's and body's,
where heyoka compiles one in about 0.4 s), so every result is kept on disk (:func:`cache_directory`), keyed by the exact
text of the expression and its variables (``sympy.srepr``), this module's source and sympy's version,
and kept as text that is rebuilt node for node (:func:`tree_text`, :func:`from_tree_text`: a pickle
would not give back the same tree): a fresh process (a ``--body`` run, a test worker) reads it back in milliseconds
and compiles the same code as the process that wrote it.  Written atomically
(a temporary file renamed); an entry that cannot be read, or that is not an expression in the
input's symbols, is computed again and rewritten; a cache folder that cannot be written is only
skipped.
"""
from __future__ import annotations

import hashlib
import os
from functools import lru_cache
from pathlib import Path

import flint
import sympy as sp
from sympy.external.gmpy import GROUND_TYPES

from ..provenance import write_atomic


def polynomial_symbols(expr: sp.Expr, candidates) -> tuple:
    """The ``candidates`` that occur in ``expr`` only polynomially (never inside a function or a
    non-integer power), sorted by name.  These are the variables :func:`compact` collects in."""
    inside = set()
    for node in sp.preorder_traversal(expr):
        if isinstance(node, sp.Function) or (isinstance(node, sp.Pow) and not node.exp.is_Integer):
            inside |= node.free_symbols
    return tuple(sorted((s for s in candidates if s in expr.free_symbols and s not in inside), key=lambda s: s.name))


def compact(expr: sp.Expr, variables) -> sp.Expr:
    """``expr`` collected over the monomials of its polynomial ``variables`` (module docstring).

    Parameters
    ----------
    expr : sympy expression
    variables : iterable of sympy symbols
        The symbols that may be collected in (a model's state symbols and accelerations; never
        its parameters).  Only those that occur polynomially are (:func:`polynomial_symbols`).

    Returns
    -------
    sympy expression
        Identically equal to ``expr`` (the same rational function), never longer by
        :func:`sympy.count_ops`.
    """
    expr = sp.sympify(expr)
    return _compact(expr, polynomial_symbols(expr, variables))


def cache_directory() -> Path:
    """Where compact forms are kept: ``$HEYOKA_CACHE_DIR/compact`` (next to heyoka's own cache and the
    derived bodies of :func:`models.bodies.cache_directory`), else ``~/.cache/rolling-verify/compact``."""
    base = os.environ.get("HEYOKA_CACHE_DIR")
    return Path(base) / "compact" if base else Path.home() / ".cache" / "rolling-verify" / "compact"


@lru_cache(maxsize=None)
def _source_hash() -> str:
    """sha256 of this module's source, sympy's and python-flint's versions and sympy's ground types: a change
    to any makes every entry a miss."""
    h = hashlib.sha256(Path(__file__).read_bytes())
    h.update(sp.__version__.encode())
    h.update(flint.__version__.encode())
    h.update(GROUND_TYPES.encode())  # sympy's integers (python, gmpy or flint): its canonical forms may differ
    return h.hexdigest()


def cache_path(expr: sp.Expr, gens: tuple) -> Path:
    """The file that keeps the compact form of ``expr`` collected in ``gens`` (its :func:`tree_text`)."""
    key = hashlib.sha256((sp.srepr(expr) + "\n" + sp.srepr(gens) + "\n" + _source_hash()).encode()).hexdigest()
    return cache_directory() / f"{key[:32]}.tree"


def tree_text(expr: sp.Basic) -> str:
    """``expr`` as text, node for node: ``Type(arg, ...)`` in the order of the node's own ``args``, leaves
    (symbols with their assumptions, numbers) by ``sympy.srepr``.  Not ``srepr`` itself, which reorders a
    product's factors and splits its coefficient (-2 k as ``Mul(Integer(-1), Integer(2), k)``)."""
    if not expr.args:
        return sp.srepr(expr)
    return f"{type(expr).__name__}({', '.join(tree_text(a) for a in expr.args)})"


def from_tree_text(text: str) -> sp.Basic:
    """The expression :func:`tree_text` wrote, rebuilt with sympy's evaluation off.

    Not pickle, nor ``sympify``: both rebuild the tree *evaluated*, and sympy's constructors do not
    keep every form they return -- ``-(a + b)`` (a product of -1 and a sum, which :func:`sympy.factor`
    returns) comes back as ``-a - b``, two more operations for heyoka and another rounding, so a
    process reading the cache would compile other code than the one that wrote it.  The text is
    trusted as the cache folder is (it is evaluated); :func:`_compact` checks what it gives.
    """
    namespace = dict(vars(sp))
    namespace["__builtins__"] = {}
    with sp.evaluate(False):
        return eval(text, namespace)  # our own text: see the docstring


@lru_cache(maxsize=4096)
def _compact(expr: sp.Expr, gens: tuple) -> sp.Expr:
    """The compact form, from memory, else from the disk cache, else computed (:func:`compacted`) and written.

    An entry is its text's sha256 on the first line, then the text.  It is taken only if the digest matches
    (a damaged digit would still parse, as another expression in the same symbols) and it is an expression in
    the input's symbols whose text it gives back (the same tree); a computed form is kept only if its text
    gives back an equal tree (``==`` on sympy trees compares node for node), else it is returned and computed
    again by the next process.  Written by :func:`verify.provenance.write_atomic`.
    """
    path = cache_path(expr, gens)
    try:
        digest, text = path.read_text(encoding="utf-8").split("\n", 1)
        kept = from_tree_text(text) if digest == hashlib.sha256(text.encode()).hexdigest() else None
    except Exception:  # any unreadable entry is only a miss: missing, truncated or garbage (eval raises
        kept = None  # SyntaxError, NameError, TypeError, ... depending on the damage)
    if isinstance(kept, sp.Expr) and kept.free_symbols <= expr.free_symbols and tree_text(kept) == text:
        return kept
    result = compacted(expr, gens)
    text = tree_text(result)
    try:
        if from_tree_text(text) != result:
            return result
        write_atomic(path, hashlib.sha256(text.encode()).hexdigest() + "\n" + text)
    except OSError:
        pass
    return result


def forget() -> None:
    """Empty the in-memory cache (the disk cache stays): the next :func:`compact` reads the disk as a fresh
    process would."""
    _compact.cache_clear()


#: Larger expressions (by :func:`sympy.count_ops`) are left as they are: the rewriting's cost grows fast with
#: the size (sympy's own factorisation of the egg's ~3900-operation invariants did not finish in 10 minutes;
#: with FLINT's, the egg's slip event, 1543 operations, takes 21 s).  Every expression compiled compact stays
#: below but that one: disk 89, ring 146, hurricane 212, ring+air-drag 414, the ellipsoids 959.
MAX_OPS = 1500


def compacted(expr: sp.Expr, gens: tuple) -> sp.Expr:
    """The compact form of ``expr`` collected in ``gens`` computed afresh (no cache): :func:`compact`'s work."""
    if sp.count_ops(expr) > MAX_OPS:
        return expr
    plain, atoms = _atomized(expr)
    if not gens:
        candidate = _coefficient(plain, atoms)
    else:
        groups = {}  # the terms by their own denominator: never brought over a common one (see below)
        for term in sp.Add.make_args(plain):
            groups.setdefault(sp.fraction(sp.together(term))[1], []).append(term)
        parts = [_collected(sp.Add(*groups[d]), gens, atoms) for d in sorted(groups, key=sp.default_sort_key)]
        candidate = None if any(p is None for p in parts) else sp.Add(*parts)
    if candidate is None:
        return expr
    candidate = candidate.xreplace({a: f for a, f in atoms.items()})
    if not _exact_constants(candidate) or sp.count_ops(candidate) > sp.count_ops(expr):
        return expr
    return candidate


def _atomized(expr: sp.Expr) -> tuple:
    """(``expr`` with every function application and root replaced by a plain symbol, {symbol: what it stands for}).

    The rational arithmetic (cancel, factor) is then done on polynomials in plain symbols, which is
    what makes it fast (sympy's polynomial routines on sin(theta), sqrt(...) as generators recompute
    their structure at every step).  ``q^(p/n)`` (p/n not an integer) becomes ``R^p`` with R standing
    for ``q^(1/n)``.  The symbols are numbered in sympy's canonical order of what they stand for, so
    the same expression gives the same symbols.
    """
    roots = {}
    for node in sp.preorder_traversal(expr):
        if isinstance(node, sp.Pow) and node.exp.is_Rational and not node.exp.is_Integer:
            roots.setdefault(node.base ** sp.Rational(1, node.exp.q), None)
    functions = [f for f in expr.atoms(sp.Function)]
    standing = sorted(set(functions) | set(roots), key=sp.default_sort_key)
    atoms = {sp.Symbol(f"compact_atom_{i}"): f for i, f in enumerate(standing)}
    back = {f: a for a, f in atoms.items()}

    def replace(node):
        if node in back:
            return back[node]
        if isinstance(node, sp.Pow) and node.exp.is_Rational and not node.exp.is_Integer:
            root = node.base ** sp.Rational(1, node.exp.q)
            if root in back:
                return back[root] ** node.exp.p
        if node.args:
            return node.func(*[replace(a) for a in node.args])
        return node

    return replace(expr), atoms


def _collected(expr: sp.Expr, gens: tuple, atoms: dict):
    """sum over monomials m of gens: (coefficient of m / denominator) m, or None if not polynomial."""
    numerator, denominator = sp.fraction(sp.together(expr))
    gens = tuple(v for v in gens if not denominator.has(v))  # a slip speed that divides: a coefficient's
    if not gens:
        return _coefficient(expr, atoms)
    try:
        poly = sp.Poly(sp.expand(numerator), *gens)
    except sp.PolynomialError:
        return None
    if any(c.has(*gens) for c in poly.coeffs()):
        return None
    terms = []
    for powers, coefficient in poly.terms():
        monomial = sp.Mul(*[v ** n for v, n in zip(gens, powers)])
        terms.append(_coefficient(coefficient, atoms) * monomial)
    # The common denominator divides the sum once, not each coefficient: a quotient of parameters such
    # as (2k + 1)/(k + 1) would be rounded once and then bias every step the same way (a systematic error
    # that makes the invariants drift like t, where the roundings of a state-dependent quotient average
    # out like sqrt(steps): tests/test_conservation.py's MPFR drift bound caught it).
    return sp.factor_terms(sp.Add(*terms)) / _coefficient(denominator, atoms)


def _coefficient(expr: sp.Expr, atoms: dict) -> sp.Expr:
    """A coefficient (no polynomial variable) cancelled and factored, in its shortest trigonometric form.

    ``expr`` is atomized (:func:`_atomized`, ``atoms`` says what each symbol stands for).  Tried: as
    it is; with sin(a)^2 -> 1 - cos(a)^2; with cos(a)^2 -> 1 - sin(a)^2 (each angle a with both);
    the shortest by count_ops wins, the first on a tie (deterministic).
    """
    forms = [_factored(expr)]
    present = expr.free_symbols
    by_value = {f: a for a, f in atoms.items() if a in present}
    for f in sorted(by_value, key=sp.default_sort_key):
        if not isinstance(f, sp.sin) or sp.cos(f.args[0]) not in by_value:
            continue
        s, c = by_value[f], by_value[sp.cos(f.args[0])]
        forms.append(_factored(_reduced(expr, s, c)))
        forms.append(_factored(_reduced(expr, c, s)))
    return min(forms, key=sp.count_ops)


def _reduced(expr: sp.Expr, a: sp.Symbol, b: sp.Symbol) -> sp.Expr:
    """``expr`` with every a^2 replaced by 1 - b^2 (a, b: the sine and cosine of one angle, or the reverse)."""
    numerator, denominator = sp.fraction(sp.together(expr))

    def reduce(p):
        return sp.expand(sp.expand(p).subs(a ** 2, 1 - b ** 2))

    return reduce(numerator) / reduce(denominator)


def _factored(expr: sp.Expr) -> sp.Expr:
    """``expr`` cancelled, its numerator and denominator factored over the rationals (:func:`_factor`)."""
    try:
        numerator, denominator = sp.fraction(sp.cancel(expr))
        return _factor(numerator) / _factor(denominator)
    except sp.PolynomialError:  # an algebraic extension sympy cannot factor over: leave it
        return expr


def _factor(p: sp.Expr) -> sp.Expr:
    """The polynomial ``p`` (in plain symbols) factored over the rationals: by FLINT's multivariate
    factorisation (python-flint's ``fmpq_mpoly.factor``), which gives the same factors as
    :func:`sympy.factor` in a small part of its time (the ring's coefficients: 0.3 s against 2.2 s;
    sympy's Wang-Hensel lifting on the egg's ran past minutes).  A factor's sign and the order of the
    factors are FLINT's (positive leading term in lexicographic order of the symbols' names); the
    product is rebuilt by sympy, which orders it canonically.  A polynomial with other than rational
    coefficients (an algebraic number, a symbol's root left as a number) goes to :func:`sympy.factor`.
    """
    gens = tuple(sorted(p.free_symbols, key=lambda s: s.name))
    if not gens:
        return sp.factor(p)
    poly = sp.Poly(p, *gens)
    if poly.domain not in (sp.ZZ, sp.QQ):
        return sp.factor(p)
    ctx = flint.fmpq_mpoly_ctx.get(tuple(f"x{i}" for i in range(len(gens))), "lex")  # by position: any name
    content, factors = ctx.from_dict({m: flint.fmpq(int(c.p), int(c.q)) for m, c in poly.terms()}).factor()
    product = [sp.Rational(int(content.p), int(content.q))]
    for factor, power in factors:  # FLINT's integers (fmpz) made Python's: sympy takes an fmpz exponent for a
        # float (x**2.0) unless its own ground types are FLINT's
        terms = [sp.Rational(int(c.p), int(c.q)) * sp.Mul(*[v ** int(n) for v, n in zip(gens, m)])
                 for m, c in sorted(factor.to_dict().items())]
        product.append(sp.Add(*terms) ** int(power))
    return sp.Mul(*product)


def _exact_constants(expr: sp.Expr) -> bool:
    """False if ``expr`` holds a float or a rational whose denominator is not a power of two
    (:func:`verify.engine.compile.to_heyoka` refuses those: heyoka would round them to double)."""
    for atom in expr.atoms(sp.Number):
        if isinstance(atom, sp.Float):
            return False
        if isinstance(atom, sp.Rational) and not atom.is_Integer and atom.q & (atom.q - 1):
            return False
    return True
