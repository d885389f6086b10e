"""One validation path for the start of a run, whichever way it arrives.

``solve`` (and through it the reference cases, the studies and the command line) and the sweeps
(their fixed values, their axis values, every point of their grid) check a start by the
functions of this module, so the same start is accepted or refused everywhere, with the same
words:

* :func:`parameters` -- known names, finite numbers, each in its physical range
  (``models.base.Parameter.check``), the relations between them (``Model.check_relations``);
* :func:`state` -- a mapping of state names, or a full-length sequence in the model's state
  order (``theta, phi, psi, thetadot, phidot, psidot, x, y``), each a finite number;
* :func:`start_problems` -- the start as a whole, column by column: finite, theta inside the
  model's domain (the open interval whose ends are its terminal events), the model's
  constraints (the effective Lagrangian's psidot = phidot), and a positive normal force
  N/(Mg) > 0 where the model has a contact (N <= 0: the body would leave the plane at t = 0, so
  a run would stop there at ``contact_lost`` with no dynamics in it); with a friction coefficient
  mu, a required friction mu_req < mu (else the body slips at t = 0 and no rolling run exists).

Every refusal is an :class:`InvalidStart` (a ``ValueError``) whose message names the value and
what is allowed, and whose ``reason`` is one of :data:`REASONS`.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from functools import lru_cache

import heyoka as hy
import mpmath
import numpy as np
import sympy as sp

from models import get_model
from models.base import Model
from models.symbols import STATE, STATE_NAMES

from ..precision import Precision
from .compile import compile_model, symbol_map, to_heyoka
from .invariants import friction_required

#: Why a start is refused (``InvalidStart.reason``).
REASONS = ("unknown_name", "not_a_number", "non_finite", "parameter_range", "parameter_relation", "shape",
           "outside_domain", "constraint", "normal_force", "slips")

STATE_ORDER = ", ".join(STATE_NAMES)


class InvalidStart(ValueError):
    """A start (state or parameters) that the model cannot be integrated from.

    ``reason`` is one of :data:`REASONS`; the message names the value and what is allowed.
    """

    def __init__(self, message: str, reason: str):
        super().__init__(message)
        self.reason = reason

    def __reduce__(self):  # picklable with its reason: a worker process's refusal reaches the caller as itself
        return type(self), (str(self), self.reason)


# --- parameters ------------------------------------------------------------------------------------

def parameters(model: Model, values, precision: Precision) -> dict:
    """Every parameter of the model at ``precision``: defaults overridden by ``values`` (a mapping)."""
    if values is None:
        values = {}
    if not isinstance(values, Mapping):
        raise InvalidStart(f"params={values!r} is a {type(values).__name__}; allowed: a mapping of parameter names "
                           f"({', '.join(model.parameter_names)}) to numbers or decimal strings", "shape")
    values = dict(values)
    unknown = sorted(set(values) - set(model.parameter_names), key=str)
    if unknown:
        raise InvalidStart(f"unknown parameter {unknown[0]!r} for model {model.name!r}; allowed: "
                           f"{', '.join(model.parameter_names)}", "unknown_name")
    out = {}
    for p in model.parameters:
        raw = values.get(p.name, p.default)
        try:
            val = _default(precision, raw) if p.name not in values else precision.number(raw)
        except (ValueError, TypeError) as err:
            reason = "non_finite" if "finite" in str(err) else "not_a_number"
            raise InvalidStart(f"parameter {p.name}={raw!r}: {err}", reason) from None
        try:
            p.check(val, shown=raw)
        except ValueError as err:
            raise InvalidStart(str(err), "parameter_range") from None
        out[p.name] = val
    try:
        model.check_relations(out)
    except ValueError as err:
        raise InvalidStart(str(err), "parameter_relation") from None
    return out


@lru_cache(maxsize=None)
def _default(precision: Precision, value):
    """A parameter's default (an exact sympy number) at ``precision``, rounded once per precision."""
    return precision.number(value)


def check_parameter_value(model: Model, name: str, value, shown=None) -> None:
    """One parameter value against its range alone (a sweep's fixed value or an axis end)."""
    try:
        model.parameter(name).check(value, shown=shown)
    except ValueError as err:
        raise InvalidStart(str(err), "parameter_range") from None


# --- the state -------------------------------------------------------------------------------------

def state(model: Model, values, precision: Precision) -> np.ndarray:
    """The eight-component initial state at ``precision`` (not yet checked against the domain).

    ``values`` is a mapping of state names (unset components are 0) or a sequence (list, tuple,
    1-D array) of exactly eight values in the order ``theta, phi, psi, thetadot, phidot, psidot,
    x, y``.
    """
    if values is None:
        values = {}
    if isinstance(values, Mapping):
        values = dict(values)
        unknown = sorted(set(values) - set(STATE_NAMES), key=str)
        if unknown:
            raise InvalidStart(f"unknown state variable {unknown[0]!r}; allowed: {STATE_ORDER}", "unknown_name")
    else:
        values = _sequence(values)
    out = []
    zero = None
    for name in STATE_NAMES:
        if name not in values:  # unset: 0, read once
            zero = precision.zero() if zero is None else zero
            out.append(zero)
            continue
        raw = values[name]
        try:
            out.append(precision.number(raw))
        except (ValueError, TypeError) as err:
            reason = "non_finite" if "finite" in str(err) else "not_a_number"
            raise InvalidStart(f"state {name}={raw!r}: {err}", reason) from None
    return precision.array(out)


def _sequence(values) -> dict:
    allowed = (f"allowed: a mapping of state names to values, or a sequence of {len(STATE_NAMES)} values in the "
               f"order {STATE_ORDER}")
    if isinstance(values, (str, bytes)):
        raise InvalidStart(f"state={values!r} is a string; {allowed}", "shape")
    if isinstance(values, np.ndarray):
        if values.ndim != 1:
            raise InvalidStart(f"state is an array of shape {values.shape}; {allowed}", "shape")
        items = list(values)
    else:
        try:
            items = list(values)
        except TypeError:
            raise InvalidStart(f"state={values!r} of type {type(values).__name__}; {allowed}", "shape") from None
    if len(items) != len(STATE_NAMES):
        raise InvalidStart(f"state has {len(items)} values ({_short(items)}); {allowed}", "shape")
    return dict(zip(STATE_NAMES, items))


def _short(items) -> str:
    text = ", ".join(repr(v) for v in items[:4])
    return text + (", ..." if len(items) > 4 else "")


# --- the start as a whole --------------------------------------------------------------------------

def start_problems(model: Model, states, normal=None, shown=None):
    """The problems of each start, column by column: a list of (column, reason, message).

    ``states`` is an (8, n) array (any of the precisions' dtypes); ``normal`` the normal force
    N/(Mg) at each column (None where the model has no contact); ``shown`` optional per-column
    mappings of the values as the user wrote them (for the messages).  Empty list: every start is
    valid.  Each column reports its first problem only, in the order finite, domain, constraint,
    normal force.
    """
    states = np.asarray(states)
    as_float = np.array([[float(v) for v in row] for row in states]) if states.dtype == object else \
        states.astype(float)
    dom = model.domain
    lo, hi = domain_ends(dom)
    problems, seen = [], set()

    def add(cols, reason, message):
        for j in cols:
            j = int(j)
            if j not in seen:
                seen.add(j)
                problems.append((j, reason, message(j)))

    def shown_value(j, i):
        if shown is not None and shown[j] is not None and STATE_NAMES[i] in shown[j]:
            return shown[j][STATE_NAMES[i]]
        return _text(states[i, j])

    bad = ~np.isfinite(as_float)
    add(np.flatnonzero(bad.any(axis=0)), "non_finite",
        lambda j: f"state {STATE_NAMES[int(np.flatnonzero(bad[:, j])[0])]}="
                  f"{shown_value(j, int(np.flatnonzero(bad[:, j])[0]))} is not a finite number")
    outside = ~_inside_domain(dom, states[0], as_float[0])
    add(np.flatnonzero(outside), "outside_domain",
        lambda j: f"state theta={shown_value(j, 0)} is outside the domain of {model.name!r}: {lo:.17g} < theta < "
                  f"{hi:.17g} (at the lower end: {dom.below}; at the upper end: {dom.above})")
    for name, expr, text in model.constraints:
        values = _constraint_values(expr, states, as_float)
        add(np.flatnonzero(values != 0), "constraint",
            lambda j: f"state violates the constraint {name} = 0 ({text}); it is {float(values[j]):g}")
    if normal is not None:
        for j, reason, message in _normal_force_problems(model, normal):
            add([j], reason, lambda _, message=message: message)
    problems.sort()
    return problems


def _normal_force_problems(model: Model, normal) -> list:
    """(column, "normal_force", message) of each start whose normal force N/(Mg) is not a finite N > 0."""
    nf = np.array([float(v) for v in np.asarray(normal).ravel()])
    with np.errstate(invalid="ignore"):
        low = ~((nf > 0) & np.isfinite(nf))
    return [(int(j), "normal_force",
             (f"the initial state of {model.name!r} has normal force N/(Mg) = {nf[j]:.6g} <= 0: the body "
              "would leave the plane; allowed: states with N > 0") if math.isfinite(nf[j]) else
             (f"the initial state of {model.name!r} has normal force N/(Mg) = {nf[j]}: its rates overflow "
              "the precision; allowed: states with a finite N > 0")) for j in np.flatnonzero(low)]


@lru_cache(maxsize=None)
def domain_ends(dom) -> tuple:
    """(theta_min, theta_max) of a model's domain as doubles (sympy's evaluation, once per domain)."""
    return float(dom.theta_min), float(dom.theta_max)


def _domain_end(end, like):
    """A domain end (sympy: 0, pi, ...) rounded to the type of ``like``, a value of the start."""
    if isinstance(like, hy.real):
        return hy.real(str(sp.N(end, int(like.prec * 0.302) + 10)), like.prec)
    if isinstance(like, hy.real128):
        return hy.real128(str(sp.N(end, 45)))
    if isinstance(like, np.longdouble):
        return np.longdouble(str(sp.N(end, 30)))
    return float(end)


def _inside_domain(dom, thetas, as_float) -> np.ndarray:
    """theta_min < theta < theta_max for each start, compared at the start's own precision (in double a
    quad theta of 1e-400 would be 0, and one between float(pi) and pi would sit on the end)."""
    if thetas.dtype == np.float64:
        lo, hi = domain_ends(dom)
        with np.errstate(invalid="ignore"):
            return (lo < as_float) & (as_float < hi)
    out = np.zeros(len(thetas), bool)
    for j, th in enumerate(thetas):
        if math.isnan(float(th)):
            continue
        out[j] = bool(_domain_end(dom.theta_min, th) < th < _domain_end(dom.theta_max, th))
    return out


def _text(value) -> str:
    try:
        return repr(float(value)) if isinstance(value, (float, np.floating)) else str(value)
    except (TypeError, ValueError):
        return str(value)


def _constraint_values(expr, states, as_float) -> np.ndarray:
    """The constraint expression at each column: exactly (mpmath) for MPFR/quad, in the dtype otherwise."""
    if states.dtype in (np.float64, np.longdouble):
        f = _lambdified(expr)
        out = np.asarray(f(*states), dtype=states.dtype)
        return np.broadcast_to(out, (states.shape[1],))
    out = []
    for j in range(states.shape[1]):
        col = [states[i, j] for i in range(len(STATE))]
        bits = max(getattr(v, "prec", 113) for v in col) + 16
        with mpmath.workprec(bits):
            out.append(expr.subs({s: mpmath.mpf(str(v)) for s, v in zip(STATE, col)}))
    return np.array([0.0 if v == 0 else float(v) if float(v) != 0 else math.copysign(1e-300, float(v))
                     for v in out])


@lru_cache(maxsize=None)
def _lambdified(expr):
    return sp.lambdify(list(STATE), expr, modules="numpy")


def first_problem(model: Model, states, normal=None, shown=None):
    """The first (column, reason, message) of :func:`start_problems`, or None."""
    problems = start_problems(model, states, normal, shown)
    return problems[0] if problems else None


# --- one start at a run's precision (solve) --------------------------------------------------------

def _invariant_rows(compiled, y: np.ndarray, pars: dict) -> np.ndarray:
    n = y.shape[1]
    p = np.ascontiguousarray(np.repeat(compiled.parameter_vector(pars, for_function=True)[:, None], n, axis=1))
    return compiled.invariant_function(np.ascontiguousarray(y), pars=p)


def normal_force(compiled, y: np.ndarray, pars: dict):
    """N/(Mg) at each column of ``y`` from the compiled model's own cfunc (None: no contact)."""
    if not compiled.has_normal_force:
        return None
    return _invariant_rows(compiled, y, pars)[compiled.n_invariants]


def _overflowing_invariant(model: Model, rows: np.ndarray):
    """The first invariant (energy, ...) that is not finite at the start, as (name, value), or None.

    ``rows``: the compiled invariant function at the start (one column).  Finite state values can
    still overflow the precision in the invariants (psidot = 1e200 in double: I3 psidot^2 / 2 = inf);
    heyoka would then fail at its first step.
    """
    for inv, row in zip(model.invariants, rows):
        v = row[0]
        with np.errstate(invalid="ignore"):  # inf - inf
            finite = v - v == 0  # at the precision's own range (float(v) would overflow quad's)
        if not finite:
            return inv.name, row[0]
    return None


def validate(model: Model, state_values, params, precision: Precision, compiled=None, friction=None):
    """(initial state, parameters) at ``precision``, or :class:`InvalidStart` naming the first problem.

    The single entry point of ``solve``: parameters, state, then the start as a whole
    (:func:`start_problems`) with the normal force from the compiled model at ``precision``, and
    with ``friction`` (checked by :func:`friction`) the friction the start needs.
    """
    pars = parameters(model, params, precision)
    y0 = state(model, state_values, precision)
    shown = [dict(state_values)] if isinstance(state_values, Mapping) else None
    problem = first_problem(model, y0[:, None], None, shown)
    if problem is None:
        if compiled is None:
            compiled = compile_model(model, precision)
        rows = _invariant_rows(compiled, y0[:, None].copy(), pars)  # the invariants, then N/(Mg)
        overflow = _overflowing_invariant(model, rows)
        if overflow is not None:
            raise InvalidStart(f"the initial state of {model.name!r} has {overflow[0]} = {overflow[1]}: its values "
                               f"overflow {precision.name}; allowed: states whose invariants are finite (smaller "
                               "rates, or mp:BITS)", "non_finite")
        if model.normal_force is not None and compiled.has_normal_force:  # the rest was checked above
            low = _normal_force_problems(model, rows[compiled.n_invariants])
            problem = low[0] if low else None
    if problem is None and friction is not None:
        problem = _slip_problem(model, y0, pars, friction, precision)
    if problem is not None:
        raise InvalidStart(problem[2], problem[1])
    return y0, pars


def friction(model: Model, value, events: bool, precision: Precision):
    """A friction coefficient at ``precision`` (finite, > 0) for a model that rolls, or None for None."""
    if value is None:
        return None
    if model.friction_required is None:
        raise ValueError(f"friction={value!r}: model {model.name!r} has no rolling contact, so no friction to run "
                         "out of; allowed: friction with a model that rolls (python -m verify models)")
    if not events:
        raise ValueError(f"friction={value!r} with events=False: the slip is a terminal event; allowed: "
                         "events=True, or no friction")
    return positive_number("friction", value, precision)


def _slip_problem(model: Model, y0, pars: dict, friction, precision: Precision):
    """('slips', message) as a problem if the start needs mu_req >= ``friction``, else None."""
    need = friction_required(compile_model(model, precision), y0[:, None].copy(), pars)[0]
    if need < friction:
        return None
    return (0, "slips", f"the start of {model.name!r} needs the friction coefficient mu_req = |F_h|/N = "
            f"{float(need):.9g} >= friction = {friction}: it slips at t = 0 and cannot roll; allowed: "
            "friction > the start's mu_req, or a start that needs less")


# --- run settings ----------------------------------------------------------------------------------

def positive_number(name: str, value, precision: Precision):
    """``value`` at ``precision``, refused (``ValueError`` naming ``name``) unless finite and > 0."""
    try:
        v = precision.number(value)
    except (ValueError, TypeError) as err:
        raise ValueError(f"{name}={value!r}: {err}") from None
    if not float(v) > 0:
        raise ValueError(f"{name}={value} must be a positive finite number")
    return v


def tolerance(value, precision: Precision):
    """The Taylor tolerance at ``precision``: None is its epsilon (heyoka's 0); else eps <= tol < 1.

    Below epsilon nothing is gained (every step rounds at eps) while heyoka's order,
    ~ -ln(tol)/2 + 1, and with it the compile time grow: tol = 1e-300 in double asks for
    order ~346, which compiles for a quarter of an hour.
    """
    if value is None:
        return precision.zero()
    try:
        exact = mpmath.mpf(str(value).strip()) if isinstance(value, str) else mpmath.mpf(value)
    except (ValueError, TypeError):
        exact = None
    eps = precision.eps
    allowed = (f"allowed: {eps:.3g} <= tol < 1 (the {precision.name} epsilon 2^{1 - precision.bits} and up; "
               "for a smaller tolerance choose more bits: quad, or mp:BITS)")
    if exact is not None and mpmath.isfinite(exact) and 0 < exact < eps:
        raise ValueError(f"tol={value!r} is below the {precision.name} epsilon: {allowed}")
    v = positive_number("tol", value, precision)
    if not float(v) < 1:
        raise ValueError(f"tol={value!r} is not below 1; {allowed}")
    return v


def flag(name: str, value) -> bool:
    """A run's switch (``events``, ``high_accuracy``): True or False, nothing else."""
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name}={value!r}: allowed: True or False")
    return bool(value)


# --- many starts in double (sweeps) ----------------------------------------------------------------

@lru_cache(maxsize=None)
def normal_force_function(model_name: str):
    """A double-precision cfunc of N/(Mg) over columns (state rows, then the model's parameters), or None."""
    model = get_model(model_name)
    if model.normal_force is None:
        return None
    variables = list(hy.make_vars(*STATE_NAMES))
    return hy.cfunc([to_heyoka(model.normal_force, symbol_map(model, variables))], variables)


def normal_force_columns(model_name: str, states: np.ndarray, pars: np.ndarray):
    """N/(Mg) at each column of ``states`` (8, n) with per-column parameters ``pars`` (n_pars, n), in double."""
    f = normal_force_function(model_name)
    if f is None:
        return None
    states = np.ascontiguousarray(states[:8], dtype=float)
    p = np.ascontiguousarray(pars[: f.nparams], dtype=float)
    if f.nparams == 0:
        return f(states)[0]
    return f(states, pars=p)[0]
