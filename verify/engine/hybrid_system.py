"""The sliding phase's heyoka system with Coulomb friction, and the functions a rolling-and-sliding run reads.

:mod:`verify.engine.hybrid` runs ``disk+coulomb`` and ``ring+coulomb``; this module compiles, once per body
and precision, what its phases and switches evaluate:

* the sliding rows of :mod:`models.coulomb` (paper Eqs. 5-8 with F_h = -mu N u/|u|, the slip speed s and
  direction alpha as state, the work W = int mu N s dt as a quadrature) and their terminal events
  (``sticks``, the domain's ends, ``contact_lost``, Painleve's margin);
* E, N and E's terms on the sliding state and on the rolling one (with the friction rolling needs), the
  launch map u = v_C + omega x r_P, the slip's rates along and across its direction, and the guards'
  quantities (Painleve's margin, v_C two ways).

Parameters: the rolling model's as ``par[i]``, then mu.
"""
from __future__ import annotations

import copy
from dataclasses import dataclass
from functools import lru_cache

import heyoka as hy
import numpy as np
import sympy as sp

from models import coulomb, get_model

from .compile import symbol_map, to_heyoka
from .validation import _domain_end as rounded_like_start_check
from ..precision import Precision

#: The sliding phase's event where Painleve's margin reaches 0 (:func:`models.coulomb.painleve_margin`).
JAM_EVENT = "painleve_margin"
#: Sliding-phase state (models.coulomb): the eight, the slip speed and direction, the work.
SLIDING_STATE_NAMES = coulomb.SLIDING_STATE_NAMES
#: Indices of the slip speed s, its direction alpha and the work W in the sliding state.
SLIP, DIRECTION, WORK = 8, 9, 10


@dataclass(frozen=True)
class SlidingSystem:
    """The compiled sliding system of one body at one precision, and the functions the run evaluates."""

    precision: Precision
    system: tuple
    events: tuple  # (name, expression, direction)
    sliding_function: object  # cfunc: 11 states -> [E, N/(Mg), E's terms...]
    rolling_function: object  # cfunc: 8 states -> [E, N/(Mg), F_x/(Mg), F_y/(Mg), E's terms...]
    launch_function: object  # cfunc: 8 states + (vx, vy) -> [s, alpha]
    rhs_function: object  # cfunc: 11 states -> their time derivatives
    slip_rates: object  # cfunc: 8 states + alpha -> [e . du/dt, e_perp . du/dt] (no s in either)
    n_pars: int
    check_function: object  # cfunc: 11 states -> [P, sliding v_C (x, y), rolling v_C (x, y)]


@lru_cache(maxsize=None)
def compiled(name: str, precision: Precision) -> SlidingSystem:
    """The sliding system of ``name`` and its functions at ``precision`` (parameters: the rolling
    model's as ``par[i]``, then mu)."""
    rolling, sliding, params = coulomb.body(name)
    variables = tuple(hy.make_vars(*SLIDING_STATE_NAMES))
    mapping = symbol_map(rolling, variables[:8])
    mapping.update({coulomb.slip_speed: variables[SLIP], coulomb.slip_direction: variables[DIRECTION],
                    coulomb.work: variables[WORK], coulomb.mu: hy.par[len(rolling.parameters)]})
    system = tuple((v, to_heyoka(rhs, mapping, compact=True)) for v, rhs in zip(variables, sliding.rhs))
    theta = variables[0]
    dom = rolling.domain
    events = (
        ("sticks", variables[SLIP], hy.event_direction.negative),
        (dom.below, theta - to_heyoka(dom.theta_min, mapping, compact=True), hy.event_direction.negative),
        (dom.above, theta - to_heyoka(dom.theta_max, mapping, compact=True), hy.event_direction.positive),
        ("contact_lost", to_heyoka(sliding.normal_force, mapping, compact=True), hy.event_direction.negative),
        (JAM_EVENT, to_heyoka(sliding.painleve_margin, mapping, compact=True), hy.event_direction.negative),
    )
    kw = precision.integrator_kwargs()
    sliding_function = hy.cfunc([to_heyoka(e, mapping) for e in (sliding.energy, sliding.normal_force,
                                                                 *energy_terms(sliding.energy))], list(variables), **kw)
    energy = rolling.energy
    force = rolling.horizontal_force
    rolling_function = hy.cfunc([to_heyoka(e, mapping) for e in (energy, rolling.normal_force, *force,
                                                                 *energy_terms(energy))], list(variables[:8]), **kw)
    vx, vy = hy.make_vars("vx", "vy")
    cm_x, cm_y = (to_heyoka(e.subs(coulomb.slip_speed, 0), mapping) for e in sliding.cm_velocity_xy)
    ux, uy = vx - cm_x, vy - cm_y  # u = v_C + omega x r_P, and omega x r_P = -(v_C at s = 0)
    launch_function = hy.cfunc([hy.sqrt(ux * ux + uy * uy), hy.atan2(uy, ux)], list(variables[:8]) + [vx, vy], **kw)
    rhs_function = hy.cfunc([rhs for _, rhs in system], list(variables), **kw)
    slip_rates = hy.cfunc([to_heyoka(e, mapping) for e in (sliding.slip_rate_along, sliding.slip_rate_across)],
                          list(variables[:8]) + [variables[DIRECTION]], **kw)
    # the guards' quantities: Painleve's margin, and v_C two ways (the sliding phase's, with its slip, and the
    # rolling model's no-slip one from models.rolling): at a stick they must agree
    check_function = hy.cfunc([to_heyoka(e, mapping) for e in (sliding.painleve_margin, *sliding.cm_velocity_xy,
                                                                 *rolling.velocity_xy)], list(variables), **kw)
    return SlidingSystem(precision, system, events, sliding_function, rolling_function, launch_function,
                         rhs_function, slip_rates, len(rolling.parameters) + 1, check_function)


def energy_terms(expr):
    """The terms of ``expr`` expanded: the sum of their absolute values is the scale its drift is judged by
    (as :func:`models.build.additive_scale`, evaluated term by term: heyoka has no Abs)."""
    return sp.Add.make_args(sp.expand(expr))


def term_scale(values, first):
    """The sum of |values[first:]|: E's term scale from a function's outputs (E's terms from ``first`` on)."""
    return sum(abs(v) for v in values[first:])


def evaluate(function, states: np.ndarray, pars: np.ndarray) -> np.ndarray:
    """``function`` (a cfunc) on one state, or on the columns of a 2-D array of states, with ``pars`` (as many
    as it reads, from the front)."""
    states = np.ascontiguousarray(states)
    pars = pars[: function.nparams]
    if states.ndim == 2:  # one column per state: the parameters once per column
        pars = np.repeat(pars[:, None], states.shape[1], axis=1)
    return function(states, pars=np.ascontiguousarray(pars))


@lru_cache(maxsize=None)
def sliding_template(name: str, precision: Precision):
    """A heyoka integrator of the sliding rows with their terminal events (state, time and parameters unset):
    :func:`new_sliding_integrator` copies it for each phase."""
    c = compiled(name, precision)
    events = [hy.t_event(ex, direction=d, fp_type=precision.fp_type) for _, ex, d in c.events]
    # compact mode at every precision: the ring's sliding rows are ~3500 operations, whose full JIT in
    # double took 490 s (measured once, cold cache); compact mode costs ~1.6x per step (HEYOKA.md)
    kw = {**precision.integrator_kwargs(), "compact_mode": True}
    return hy.taylor_adaptive(list(c.system), precision.array([0] * len(c.system)),
                              pars=precision.array([0] * c.n_pars), tol=precision.zero(), t_events=events, **kw)


def new_sliding_integrator(name: str, precision: Precision):
    """A copy of :func:`sliding_template` (compiled once, copied for each phase)."""
    return copy.copy(sliding_template(name, precision))


def launch_slip(c: SlidingSystem, y0, velocity, par_vector):
    """(s, alpha) of a start with CM velocity ``velocity``: u = v_C + omega x r_P (the launch map)."""
    return tuple(evaluate(c.launch_function, c.precision.array(list(y0) + list(velocity)), par_vector))


def slip_direction(c: SlidingSystem, y8, par_vector):
    """alpha of the slip at an onset from rolling: the direction of -F_req, the friction rolling needs."""
    values = evaluate(c.rolling_function, y8, par_vector[:-1])
    return float(np.arctan2(-float(values[3]), -float(values[2])))


def rolling_model(name: str):
    """The rolling model (``disk``, ``ring``, a body's) of a ``+coulomb`` name."""
    return get_model(coulomb.rolling_name(name))


def domain_end(end, prec: Precision):
    """A domain end (sympy: 0, pi, pi/2) as a number of the run's precision (the start check's own rounding,
    :func:`verify.engine.validation._domain_end`)."""
    return rounded_like_start_check(end, prec.zero())


def output_dtype(prec: Precision):
    """The numpy dtype of a run's outputs at ``prec`` (object for quad and MPFR numbers)."""
    return {"double": float, "long": np.longdouble}.get(prec.name, object)


def sliding_expressions(name: str) -> dict:
    """The sliding phase's right-hand sides by state name (sympy), for inspection and tests."""
    _, sliding, _ = coulomb.body(name)
    return {n: sp.sympify(e) for n, e in zip(SLIDING_STATE_NAMES, sliding.rhs)}
