"""heyoka integrators built once per compiled system and reused.

Building a ``taylor_adaptive`` costs 6-10 ms even when heyoka finds the machine code in its
cache (the expression system is decomposed and the JIT state rebuilt), which dominated short
runs.  An integrator is instead built once per key -- (compiled system, precision, tolerance,
events wanted, high_accuracy, and what else the caller's system holds) -- as a *template* that
is never integrated, and a run borrows one:

* an idle integrator of that key, left by an earlier run, if there is one;
* else a copy of the template (``copy.copy`` of a ``taylor_adaptive`` is a deep C++ copy in
  heyoka.py: state, parameters, events and compiled code are the copy's own; ~0.6 ms against
  6-10 ms for a build).

Before it is handed out its time, state and parameters are set and its terminal events'
cooldowns reset (``reset_cooldowns``), so it carries nothing of an earlier run: a borrowed
integrator gives the same bits as a freshly built one (tests/test_integrator_pool.py compares
the bytes, for runs ending at t_end and at terminal events, with and without high accuracy).
Borrowing is thread-safe; two threads never share an integrator.
"""
from __future__ import annotations

import copy
import threading
from contextlib import contextmanager

import heyoka as hy

from models.symbols import theta

from .compile import symbol_map, to_heyoka

#: Idle integrators kept per key (more are copied when more threads run at once, then dropped).
IDLE_PER_KEY = 4

_lock = threading.Lock()
_templates: dict = {}
_idle: dict = {}


def _template(key, build):
    with _lock:
        found = _templates.get(key)
    if found is not None:
        return found
    made = build()
    with _lock:
        return _templates.setdefault(key, made)


@contextmanager
def borrowed(key, build, time, state, pars):
    """A ``taylor_adaptive`` of ``key`` at ``time``, ``state``, ``pars``, for the block.

    ``build()`` makes the template the first time ``key`` is seen (its state and parameters
    do not matter, only its shape); ``key`` must identify everything ``build`` bakes into the
    integrator (system, precision, tolerance, events, high_accuracy, compact mode).
    """
    with _lock:
        idle = _idle.setdefault(key, [])
        ta = idle.pop() if idle else None
    if ta is None:
        ta = copy.copy(_template(key, build))
    ta.time = time
    ta.state[:] = state
    if len(pars):
        ta.pars[:] = pars
    if ta.with_events:
        ta.reset_cooldowns()
    try:
        yield ta
    finally:
        with _lock:
            idle = _idle.setdefault(key, [])
            if len(idle) < IDLE_PER_KEY:
                idle.append(ta)


def for_model(compiled, tol, *, events: bool, high_accuracy: bool):
    """(key, build) of the integrator of a compiled model's eight equations (:mod:`.single`)."""
    prec = compiled.precision
    key = ("model", compiled.model, prec, prec.to_text(tol), bool(events), bool(high_accuracy), compiled.friction)

    def build():
        n_state = len(compiled.system)
        return hy.taylor_adaptive(
            list(compiled.system), prec.array([0] * n_state), pars=prec.array([0] * compiled.n_pars_system),
            tol=tol, t_events=compiled.t_events() if events else [], high_accuracy=high_accuracy,
            **prec.integrator_kwargs(),
        )

    return key, build


def for_extended(compiled, extra_states: tuple, theta_stop: bool):
    """(key, build) of a compiled model's eight equations with more states and a theta_stop event.

    ``extra_states``: (name, sympy right-hand side in the model's state and parameter symbols)
    pairs, appended after the eight states; ``theta_stop``: a terminal event where theta falls
    through ``par[len(model.parameters)]`` (the parameter after the model's own).  Tolerance
    epsilon, the model's terminal events first (:mod:`.single`, ``propagate_in_turns``).
    """
    prec, model = compiled.precision, compiled.model
    key = ("extended", model, prec, tuple((name, str(rhs)) for name, rhs in extra_states), bool(theta_stop))

    def build():
        mapping = symbol_map(model, compiled.variables)
        system = list(compiled.system) + [(hy.make_vars(name), to_heyoka(rhs, mapping, compact=True)) for name, rhs in extra_states]
        events = compiled.t_events()
        if theta_stop:
            stop = mapping[theta] - hy.par[len(model.parameters)]
            events.append(hy.t_event(stop, direction=hy.event_direction.negative, fp_type=prec.fp_type))
        n_pars = len(model.parameters) + (1 if theta_stop else 0)
        return hy.taylor_adaptive(system, prec.array([0] * len(system)), pars=prec.array([0] * n_pars),
                                  tol=prec.zero(), t_events=events, **prec.integrator_kwargs())

    return key, build


def clear() -> None:
    """Forget every template and idle integrator (tests; memory)."""
    with _lock:
        _templates.clear()
        _idle.clear()
