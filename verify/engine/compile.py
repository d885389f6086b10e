"""From a model's sympy expressions to heyoka: the system, its events and its cfuncs.

Parameters become runtime ``par[i]`` (``par[i]`` is ``model.parameters[i]``), so one compiled
integrator serves a whole sweep; the values for them are laid out by name
(:meth:`CompiledModel.parameter_vector`), never by the order of a caller's mapping.  Compiled
objects are cached per (model, precision); heyoka itself caches the machine code in memory and
on disk.

The terminal events guard every run, so what they cost is paid on every step: heyoka adds each
event's function to the Taylor decomposition of the system and computes its Taylor
coefficients with the state's.  The loss of contact is therefore detected on
N/(Mg) = 1 + a_C . Z / g (:func:`contact_event`) written with the right-hand side's own
expressions for the accelerations, which the decomposition shares: 6 more terms for the disk,
where the simplified N/(Mg) of :attr:`models.base.Model.normal_force` (which shares nothing
with the right-hand side) added 20.

heyoka's step size is not blind to the events: it takes the largest magnitude over the state
*and the event functions* (of the values and of the last two Taylor coefficients).  So an
event's function keeps the scale of what it replaces -- N/(Mg) itself, not g N/(Mg) -- and a
run's steps stay those of the simplified N wherever the state, not N, sets that maximum (the
usual case: N/(Mg) is of order 1 and its coefficients are those of the accelerations over g).
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from functools import lru_cache

import heyoka as hy
import sympy as sp

from models.base import Model
from models.symbols import ACCELERATIONS, STATE, STATE_NAMES, g, theta

from ..precision import Precision
from .compact import compact as compact_form


def to_heyoka(expr: sp.Expr, mapping: dict, *, compact: bool = False):
    """Convert a sympy expression, refusing constants heyoka would round to double.

    ``compact=True`` for what a Taylor integrator computes on every step (a right-hand side, an event's
    function): the expression is first rewritten by :func:`verify.engine.compact.compact` (an identity:
    collected over the monomials of the symbols ``mapping`` sends to heyoka variables or expressions of
    them, the state and the accelerations, never the parameters), which shortens heyoka's Taylor
    decomposition.  A function read on output samples (a cfunc: invariants, forces) is converted as the
    derivation left it: rewriting it would save little, and costs sympy seconds on a cold cache.
    """
    expr = sp.sympify(expr)
    for atom in sp.preorder_traversal(expr):
        if isinstance(atom, sp.Rational) and not atom.is_Integer and atom.q & (atom.q - 1):
            raise ValueError(f"the constant {atom} would be rounded to double; keep it as a parameter")
        if isinstance(atom, sp.Float):
            raise ValueError(f"the float constant {atom} would be rounded to double; use exact numbers")
    return hy.from_sympy(compact_form(expr, _state_like(mapping)) if compact else expr, mapping)


def _state_like(mapping: dict) -> tuple:
    """The symbols of ``mapping`` whose heyoka value holds a variable (the state, expressions of it);
    not the parameters (``par[i]``) and numbers, which stay inside the coefficients."""
    return tuple(s for s, v in mapping.items() if isinstance(s, sp.Symbol) and hy.get_variables(v))


@dataclass(frozen=True)
class CompiledModel:
    """A model's heyoka system at one precision."""

    model: Model
    precision: Precision
    variables: tuple  # heyoka variables in STATE_NAMES order
    system: tuple  # (variable, rhs) pairs
    events: tuple  # (name, heyoka expression, heyoka direction)
    invariant_function: object  # cfunc: state -> [closed-form invariants..., normal force?, omega2?, omega3?]
    has_normal_force: bool
    n_pars_system: int  # heyoka wants exactly as many parameter values as the highest par[i] used
    n_pars_function: int
    friction: bool = False  # the terminal event ``slips`` reads a friction coefficient from par[len(parameters)]

    def parameter_vector(self, values: Mapping, for_function: bool = False, every: bool = False):
        """The ``par[i]`` values of the system (or of ``invariant_function``) from a name -> value mapping.

        ``par[i]`` is ``model.parameters[i]`` whatever the order of ``values``; heyoka wants exactly
        as many values as the highest ``par[i]`` used, so the vector is cut there.  Every name of
        the mapping must be a parameter of the model, and every parameter the vector holds must be
        given; the values are read at the compiled precision.  ``every``: all of the model's
        parameters, for a system extended with more ``par[i]`` after them.
        """
        if self.friction and not (every or for_function):
            raise ValueError("a system with the slip event reads every parameter and then the friction "
                             "coefficient: lay it out with every=True and append the coefficient")
        names = self.model.parameter_names
        unknown = [n for n in values if n not in names]
        if unknown:
            raise KeyError(f"{unknown[0]!r} is not a parameter of {self.model.name!r} ({', '.join(names)})")
        n = len(names) if every else self.n_pars_function if for_function else self.n_pars_system
        missing = [name for name in names[:n] if name not in values]
        if missing:
            raise KeyError(f"no value for the parameter {missing[0]!r} of {self.model.name!r}")
        return self.precision.array([values[name] for name in names[:n]])

    @property
    def n_invariants(self) -> int:
        return len(self.model.invariants)

    def t_events(self):
        """Fresh terminal heyoka events for a new integrator."""
        return [hy.t_event(ex, direction=d, fp_type=self.precision.fp_type) for _, ex, d in self.events]


def symbol_map(model: Model, variables) -> dict:
    """State symbols to ``variables``; the parameter ``model.parameters[i]`` to ``par[i]``."""
    mapping = dict(zip(STATE, variables))
    mapping.update({p.symbol: hy.par[i] for i, p in enumerate(model.parameters)})
    return mapping


def contact_event_function(model: Model):
    """N/(Mg) as the terminal event ``contact_lost`` reads it (a sympy expression), or None.

    1 + a_C . Z / g (paper Eq. 6: M a_C = F - M g Z, N = F . Z) with the accelerations left as the
    symbols ``ACCELERATIONS``: on shell it is ``model.normal_force``, the same function at the
    same scale (see the module docstring for why the scale matters).  A model without
    ``vertical_acceleration`` falls back to its ``normal_force`` itself.
    """
    if model.normal_force is None:
        return None
    if model.vertical_acceleration is None:
        return model.normal_force
    return 1 + model.vertical_acceleration / g


def contact_event(model: Model, mapping: dict, accelerations):
    """The heyoka function of the terminal event ``contact_lost`` (direction negative), or None.

    :func:`contact_event_function` with ``mapping`` for the state and parameter symbols and
    ``accelerations`` -- the heyoka expressions of thetaddot, phiddot, psiddot the system
    integrates -- for the accelerations: heyoka's decomposition then computes those once, for
    the system and the event alike.  Pass the very expressions of the system's right-hand side
    (or of a factor of it, e.g. before a batch system multiplies it by a lane's ``alive``).
    """
    f = contact_event_function(model)
    if f is None:
        return None
    return to_heyoka(f, {**mapping, **dict(zip(ACCELERATIONS, accelerations))}, compact=True)


#: The friction coefficient of the terminal event ``slips``; compiled as ``par[len(model.parameters)]``.
FRICTION = sp.Symbol("friction", positive=True)


def slip_event_function(model: Model):
    """(F_h/(Mg friction))^2 - (N/(Mg))^2 as the terminal event ``slips`` reads it, or None.

    Positive exactly where the rolling motion needs more than ``friction`` (mu_req = |F_h|/N >
    friction with N > 0, paper Eq. 6: F = M (a_C + g Z)); the accelerations are left as the symbols
    ``ACCELERATIONS``, as in :func:`contact_event_function`, so that the event shares the right-hand
    side's Taylor decomposition.  Squares, not mu_req itself: mu_req's square root and quotient are
    not smooth where F_h or N vanish, and would steer heyoka's steps (see the module docstring).  The
    horizontal force is divided by the coefficient, not the normal force multiplied by it, so that
    the function keeps the scale of (N/(Mg))^2 ~ 1 while the motion rolls well within its friction,
    whatever the coefficient (friction^2 N^2 would be 1e12 for friction = 1e6 and take over the
    step-size rule).  None without rolling contact.
    """
    normal = contact_event_function(model)
    if model.horizontal_acceleration is None or normal is None:
        return None
    fx, fy = (a / g for a in model.horizontal_acceleration)
    return (fx ** 2 + fy ** 2) / FRICTION ** 2 - normal ** 2


@lru_cache(maxsize=None)
def compile_with_friction(model: Model, precision: Precision) -> CompiledModel:
    """:func:`compile_model` with one more terminal event, ``slips`` (direction positive).

    The run stops where the friction the rolling motion needs reaches the coefficient in
    ``par[len(model.parameters)]`` (:func:`slip_event_function`); a sweep over it needs no
    recompilation.  Raises ``ValueError`` for a model without rolling contact.
    """
    f = slip_event_function(model)
    if f is None:
        raise ValueError(f"model {model.name!r} has no rolling contact, so no friction to run out of; allowed: "
                         "friction with a model that rolls (python -m verify models)")
    base = compile_model(model, precision)
    mapping = symbol_map(model, base.variables)
    mapping[FRICTION] = hy.par[len(model.parameters)]
    mapping.update(zip(ACCELERATIONS, [rhs for _, rhs in base.system[3:6]]))
    slips = ("slips", to_heyoka(f, mapping, compact=True), hy.event_direction.positive)
    return replace(base, events=base.events + (slips,), n_pars_system=len(model.parameters) + 1, friction=True)


@lru_cache(maxsize=None)
def compile_model(model: Model, precision: Precision) -> CompiledModel:
    variables = tuple(hy.make_vars(*STATE_NAMES))
    mapping = symbol_map(model, variables)
    system = tuple((mapping[v], to_heyoka(rhs, mapping, compact=True)) for v, rhs in model.rhs())
    th = mapping[theta]
    dom = model.domain
    events = [
        (dom.below, th - to_heyoka(dom.theta_min, mapping, compact=True), hy.event_direction.negative),
        (dom.above, th - to_heyoka(dom.theta_max, mapping, compact=True), hy.event_direction.positive),
    ]
    outputs = [to_heyoka(inv.expr, mapping) for inv in model.invariants]
    if model.normal_force is not None:
        events.append(("contact_lost", contact_event(model, mapping, [rhs for _, rhs in system[3:6]]),
                       hy.event_direction.negative))
        outputs.append(to_heyoka(model.normal_force, mapping))
    if model.chaplygin is not None:
        outputs += [to_heyoka(r, mapping) for r in model.chaplygin.rates]
    cf = hy.cfunc(outputs, list(variables), **precision.integrator_kwargs())
    system_exprs = [rhs for _, rhs in model.rhs()] + [model.domain.theta_min, model.domain.theta_max]
    function_exprs = [i.expr for i in model.invariants] + list(model.chaplygin.rates if model.chaplygin else [])
    if model.normal_force is not None:
        system_exprs.append(contact_event_function(model))
        function_exprs.append(model.normal_force)
    return CompiledModel(model, precision, variables, system, tuple(events), cf, model.normal_force is not None,
                         _n_pars(model, system_exprs), _n_pars(model, function_exprs))


def _n_pars(model: Model, exprs) -> int:
    used = [i for i, p in enumerate(model.parameters) if any(sp.sympify(e).has(p.symbol) for e in exprs)]
    return max(used) + 1 if used else 0


@dataclass(frozen=True)
class FrictionFunction:
    """A cfunc of the state: [N/(Mg), mu_req] with mu_req = |F_h| / N (paper Eq. 6), at one precision.

    Both are written on the right-hand side's own expressions for the accelerations (as
    :func:`contact_event` is), so heyoka's decomposition computes them once for N and F_h alike.
    ``n_pars``: how many of the model's parameters, in order, the cfunc reads.
    """

    function: object
    n_pars: int


@lru_cache(maxsize=None)
def friction_function(model: Model, precision: Precision, batch_size: int = None):
    """The :class:`FrictionFunction` of a rolling model, or None without rolling contact.

    Compiled apart from :func:`compile_model` and only when asked for: a run that never reads
    its required friction pays nothing for it.  ``batch_size``: heyoka's (None: its default);
    1 gives the scalar build that :class:`verify.engine.batch.ScalarTwin` pairs with the default.
    """
    normal = contact_event_function(model)
    if model.horizontal_acceleration is None or normal is None:
        return None
    variables = tuple(hy.make_vars(*STATE_NAMES))
    mapping = symbol_map(model, variables)
    accelerations = [to_heyoka(a, mapping) for a in model.accelerations]
    mapping.update(zip(ACCELERATIONS, accelerations))
    n = to_heyoka(normal, mapping)
    fx, fy = (to_heyoka(a / g, mapping) for a in model.horizontal_acceleration)
    mu = hy.sqrt(fx * fx + fy * fy) / n
    size = {} if batch_size is None else {"batch_size": batch_size}
    cf = hy.cfunc([n, mu], list(variables), **precision.integrator_kwargs(), **size)
    exprs = [normal, *model.horizontal_acceleration, *model.accelerations]
    return FrictionFunction(cf, _n_pars(model, exprs))
