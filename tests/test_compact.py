"""The compact forms heyoka receives (verify.engine.compact) are identities, and shorter.

Identity, checked exactly: every expression compiled compact for a model (its eight right-hand sides,
the domain's bounds, the terminal events' functions, the dissipated power, the Chaplygin matrix)
and its compact form are evaluated at random exact points -- rational rates and parameters, and
sin/cos of each angle from a rational t by sin = 2t/(1+t^2), cos = (1-t^2)/(1+t^2), so sin^2 + cos^2 = 1
holds exactly and the trigonometric rewriting is exercised -- and the difference must be exactly 0
(sympy's rational arithmetic; with a square root of a non-square rational, the difference is
denested with radsimp and must expand to 0).  This is a route independent of the compaction:
substitution and arithmetic on numbers, no cancelling or factoring of expressions.  Negative
control: the same check flags a rewriting with a wrong trigonometric rule (sin^2 -> 1 + cos^2).
"""
from __future__ import annotations

import hashlib
import os
import pickle
import random
import subprocess
import sys
from pathlib import Path

import heyoka as hy
import pytest
import sympy as sp

from models import ALL_NAMES, get_model, sources
from models.bodies import shipped
from models.symbols import ACCELERATIONS, STATE, STATE_NAMES
from verify.engine import compact as compact_module
from verify.engine.compact import compact, compacted, polynomial_symbols
from verify.engine.compile import FRICTION, contact_event_function, slip_event_function

VARIABLES = STATE + ACCELERATIONS
SIGNED = set(VARIABLES)  # drawn of either sign (the parameters stay in their positive ranges)
POINTS = 3  # random exact points per expression: a non-identity that is a rational function vanishes on a
#           # hypersurface, so a single random point already exposes it with probability 1


def _expressions(model) -> list:
    """What a Taylor integrator computes on every step, and so what is compacted (``to_heyoka(...,
    compact=True)``): the right-hand sides, the domain's bounds, the terminal events' functions (contact,
    slip), the dissipated power and the Chaplygin transport matrix.  Functions read on output samples
    (invariants, forces) reach heyoka as the derivation left them."""
    out = [rhs for _, rhs in model.rhs()]
    out += [model.domain.theta_min, model.domain.theta_max]
    for e in (contact_event_function(model), slip_event_function(model), model.dissipation):
        if e is not None:
            out.append(e)
    if model.chaplygin is not None:
        out += list(model.chaplygin.matrix)
    return out


def _point(expr, rng: random.Random) -> dict:
    """Exact values for every symbol and for sin/cos of every angle of ``expr``: the angles anywhere on the
    circle (t of either sign), the state's and accelerations' values of either sign (a rewriting that
    holds only for positive values, such as sqrt(s^2) -> s, is caught), the parameters positive."""
    values = {}
    for f in sorted(expr.atoms(sp.sin, sp.cos), key=sp.default_sort_key):
        a = f.args[0]
        if sp.sin(a) in values:
            continue
        t = rng.choice((-1, 1)) * sp.Rational(rng.randint(1, 97), rng.randint(1, 97))
        values[sp.sin(a)] = 2 * t / (1 + t ** 2)
        values[sp.cos(a)] = (1 - t ** 2) / (1 + t ** 2)
    for s in sorted(expr.free_symbols, key=lambda s: s.name):
        sign = rng.choice((-1, 1)) if s in SIGNED else 1
        values[s] = sign * sp.Rational(rng.randint(1, 199), rng.randint(1, 53))
    return values


def _at(expr, values: dict):
    trig = {k: v for k, v in values.items() if not isinstance(k, sp.Symbol)}
    return expr.xreplace(trig).xreplace({k: v for k, v in values.items() if isinstance(k, sp.Symbol)})


def differs(original, rewritten, seed: int) -> bool:
    """True if ``original`` and ``rewritten`` differ at one of POINTS random exact points."""
    rng = random.Random(seed)
    both = original + rewritten  # every atom of either expression gets a value
    for _ in range(POINTS):
        values = _point(both, rng)
        a, b = _at(original, values), _at(rewritten, values)
        if a.has(sp.zoo, sp.nan) or b.has(sp.zoo, sp.nan):
            continue  # a pole of the random point: draw another
        d = sp.expand(sp.radsimp(sp.together(a - b)))
        if d != 0:
            return True
    return False


def _models():
    names = [(n, e) for n in ALL_NAMES for e in sources(n)]
    return names + [("body:" + b, "derived") for b in shipped()]


@pytest.mark.parametrize("name,equations", _models())
def test_compact_forms_are_identities(name, equations):
    model = get_model(name, equations)
    for i, expr in enumerate(_expressions(model)):
        expr = sp.sympify(expr)
        new = compact(expr, VARIABLES)
        assert not differs(expr, new, seed=i), f"{name} ({equations}) expression {i}: {expr} != {new}"


def test_coulomb_and_smooth_systems_are_identities():
    from models import coulomb, smooth_friction

    _, sliding, _ = coulomb.body("disk+coulomb")
    exprs = list(sliding.rhs) + [sliding.normal_force, sliding.painleve_margin]
    _, smooth, _ = smooth_friction.body("disk")
    exprs += list(smooth.rhs) + [smooth.normal_force, smooth.painleve_margin]
    extra = (coulomb.slip_speed, coulomb.slip_direction, coulomb.work, smooth_friction.slip_e1,
             smooth_friction.slip_h, smooth_friction.work)
    for i, expr in enumerate(exprs):
        new = compact(sp.sympify(expr), VARIABLES + extra)
        assert not differs(sp.sympify(expr), new, seed=i), f"expression {i}: {expr} != {new}"


def test_a_wrong_rewriting_is_flagged():
    """Negative control: sin^2 -> 1 + cos^2 (the wrong sign) in the disk's psi'' and in its compact form."""
    model = get_model("disk")
    psiddot = sp.sympify(model.accelerations[2])
    theta = STATE[0]
    assert sp.sin(theta) ** 2 in psiddot.atoms(sp.Pow)  # the control changes something
    wrong = sp.expand(psiddot).subs(sp.sin(theta) ** 2, 1 + sp.cos(theta) ** 2)
    assert differs(psiddot, wrong, seed=0)
    assert not differs(psiddot, sp.expand(psiddot).subs(sp.sin(theta) ** 2, 1 - sp.cos(theta) ** 2), seed=0)


def test_a_rewriting_true_only_for_positive_values_is_flagged():
    """Negative control of the signs drawn: sqrt(thetadot^2) -> thetadot holds for thetadot > 0 only."""
    thetadot = STATE[3]
    assert differs(sp.sqrt(thetadot ** 2) + STATE[4], thetadot + STATE[4], seed=0)


#: What a fresh process prints: the sha256 of the compact forms (tree_text) of the disk's and the ring's
#: compacted expressions, computed afresh (no cache), and whether any holds a float.
FRESH = """
import hashlib, sympy as sp
from models import get_model
from models.symbols import ACCELERATIONS, STATE
from verify.engine.compact import compacted, polynomial_symbols, tree_text
from tests.test_compact import _expressions
texts, floats = [], False
for name in ("disk", "ring"):
    for e in _expressions(get_model(name)):
        e = sp.sympify(e)
        form = compacted(e, polynomial_symbols(e, STATE + ACCELERATIONS))
        floats |= bool(form.atoms(sp.Float))
        texts.append(tree_text(form))
print(hashlib.sha256("\\n".join(texts).encode()).hexdigest(), floats)
"""


def test_the_forms_do_not_depend_on_the_process():
    """The same forms (the compiled code's cache key) in fresh processes with other hash seeds and with
    sympy's integers its own pure-Python ones rather than FLINT's (SYMPY_GROUND_TYPES=python): a form built
    from FLINT's integers once carried float exponents (x**2.0) there, and was then refused, silently."""
    root = Path(__file__).resolve().parent.parent
    seen = set()
    for env in ({"PYTHONHASHSEED": "1"}, {"PYTHONHASHSEED": "2", "SYMPY_GROUND_TYPES": "python"}):
        out = subprocess.run([sys.executable, "-c", FRESH], cwd=root, env={**os.environ, **env}, capture_output=True,
                             text=True, timeout=300)
        assert out.returncode == 0, out.stderr[-2000:]
        digest, floats = out.stdout.split()
        assert floats == "False", env
        seen.add(digest)
    assert len(seen) == 1, seen


def test_compact_is_deterministic_and_leaves_other_forms():
    """The same expression gives the same form (the compiled code's cache key); an expression with no
    polynomial variable and nothing to shorten comes back as it was, and FRICTION stays a coefficient."""
    model = get_model("disk")
    rhs = sp.sympify(model.accelerations[0])
    gens = polynomial_symbols(rhs, VARIABLES)
    assert sp.srepr(compacted(rhs, gens)) == sp.srepr(compacted(rhs, gens))
    assert compact(STATE[3], VARIABLES) == STATE[3]
    slip = slip_event_function(model)
    assert FRICTION in compact(slip, VARIABLES).free_symbols


@pytest.mark.parametrize("name", ALL_NAMES)
def test_the_decomposition_is_never_longer(name):
    """What the rewriting is for, measured by another route than its own criterion (sympy's count_ops, which
    compacted() keeps from growing by construction): heyoka's Taylor decomposition of each model's system,
    whose every term costs its Taylor coefficients on every step.  The compact form's is never longer, and
    strictly shorter for the paper's three bodies (measured: disk 54 -> 44, ring 110 -> 85, hurricane
    116 -> 80; sliding-disk 30 = 30)."""
    from verify.engine.compile import symbol_map

    model = get_model(name)
    variables = tuple(hy.make_vars(*STATE_NAMES))
    mapping = symbol_map(model, variables)
    exprs = [rhs for _, rhs in model.rhs()]
    sizes = []
    for convert in (lambda e: hy.from_sympy(sp.sympify(e), mapping),
                    lambda e: hy.from_sympy(compact(sp.sympify(e), VARIABLES), mapping)):
        system = [(v, convert(e)) for v, e in zip(variables, exprs)]
        ta = hy.taylor_adaptive(system, [0.5] * 8, pars=[0.3] * len(model.parameters), compact_mode=True)
        sizes.append(len(ta.decomposition) - 2 * len(variables))
    assert sizes[1] <= sizes[0], sizes
    if name in ("disk", "ring", "hurricane"):
        assert sizes[1] < sizes[0], sizes


def entry(text: str) -> str:
    """A cache entry as compact writes it: the text's sha256, then the text."""
    return hashlib.sha256(text.encode()).hexdigest() + "\n" + text


def test_compact_forms_are_kept_on_disk_and_a_damaged_entry_is_computed_again(tmp_path, monkeypatch):
    """A compact form is written under $HEYOKA_CACHE_DIR/compact and read back by a later process (the
    memory cache cleared stands for one); garbage, a truncated entry, or an expression in symbols the
    input does not have, is computed again and rewritten -- also a damaged digit that still parses as an
    expression in the same symbols, which only the entry's sha256 tells apart, and an entry without its digest.
    Control that the reading is real: a valid entry planted under the key is what compact returns."""
    monkeypatch.setenv("HEYOKA_CACHE_DIR", str(tmp_path))
    rhs = sp.sympify(get_model("disk").accelerations[0])
    gens = polynomial_symbols(rhs, VARIABLES)
    path = compact_module.cache_path(rhs, gens)
    assert path.parent == tmp_path / "compact"
    form = compacted(rhs, gens)
    fresh = compact_module.tree_text(form)
    try:
        compact_module.forget()
        assert compact_module.tree_text(compact(rhs, VARIABLES)) == fresh
        assert path.read_text() == entry(fresh) and not list(path.parent.glob("*.tmp"))  # whole, no temporary left
        altered = fresh.replace("Integer(2)", "Integer(3)", 1)  # a damaged digit: still an expression, same symbols
        assert altered != fresh
        for damage in ("not an expression", fresh[:40], entry(fresh)[:80], entry(fresh).split("\n")[0] + "\n" + altered,
                       entry(compact_module.tree_text(sp.Symbol("stranger") * rhs)), fresh):
            path.write_text(damage)
            compact_module.forget()
            assert compact_module.tree_text(compact(rhs, VARIABLES)) == fresh
            assert path.read_text() == entry(fresh)  # rewritten
        path.write_text(entry(compact_module.tree_text(sp.expand(rhs))))  # whole, in the input's symbols: read
        compact_module.forget()
        assert compact(rhs, VARIABLES) == sp.expand(rhs) != form
    finally:
        compact_module.forget()  # leave no form read from this temporary folder behind


def test_a_form_read_back_is_the_tree_that_was_written(tmp_path, monkeypatch):
    """A process that reads the cache compiles the same code as the one that wrote it: every compact form
    of the disk's expressions comes back node for node (equal trees, ``==`` compares node for node).
    Negative control: a pickle round trip, which rebuilds sympy trees evaluated, changes one of them
    (-(a + b) becomes -a - b), so the comparison sees a form that is not kept."""
    monkeypatch.setenv("HEYOKA_CACHE_DIR", str(tmp_path))
    exprs = [sp.sympify(e) for e in _expressions(get_model("disk"))]
    try:
        compact_module.forget()
        written = [compact(e, VARIABLES) for e in exprs]
        assert len(list((tmp_path / "compact").glob("*.tree"))) == len(set(exprs))
        compact_module.forget()
        assert [compact(e, VARIABLES) for e in exprs] == written
        assert [pickle.loads(pickle.dumps(w)) for w in written] != written
    finally:
        compact_module.forget()
