"""``verify.solve`` against bare heyoka ``propagate_until`` on the same compiled equations (BENCHMARKS.md's first table)."""
from __future__ import annotations

import heyoka as hy
import numpy as np

from models import get_model

from ..engine.compile import compile_model
from ..engine.single import solve
from ..standard import STANDARD_STATES
from .sizes import TARGETS, _g
from .timing import interleaved, ratio_record


#: The bare baseline with the events solve compiles and heyoka's own reduction of phi and psi.
REDUCED = "bare propagate_until + events + angle reduction"


def _bare_single(compiled, y0, parr, kw, events: bool, reduce_angles: bool = False):
    """A bare integrator built once (construction outside every timing) and a run that resets it
    and propagates it to t_end: (outcome, steps, final state).  ``reduce_angles``: heyoka's own
    ``angle_reducer`` step callback keeps phi and psi in [0, 2 pi) after every step, so that the error
    control (relative to the largest state component) does not loosen as they grow (solve keeps them
    small by its segments)."""
    ta = hy.taylor_adaptive(list(compiled.system), y0, pars=parr,
                            t_events=compiled.t_events() if events else [], **kw)
    zero = ta.time
    angles = [v for v, _ in compiled.system if str(v) in ("phi", "psi")]
    options = {"callback": hy.callback.angle_reducer(angles)} if reduce_angles else {}

    def run(t_end):
        ta.time = zero
        ta.state[:] = y0
        if events:
            ta.reset_cooldowns()
        res = ta.propagate_until(t_end, **options)
        return res[0], int(res[3]), np.array(ta.state)

    return run


def solve_against_bare(model_name: str = "disk", t_ends=("1", "10", "100"), precision: str = "double",
                       repeats: int = 7, invariants: bool = True, progress=None) -> list:
    """``verify.solve`` (default settings) against bare heyoka on the same compiled equations.

    For each t_end, from the model's standard state (:data:`verify.standard.STANDARD_STATES`),
    interleaved rounds of: ``solve(...)``; ``solve(...)`` with every invariant's values read
    (default output grid); bare ``taylor_adaptive.propagate_until`` on
    ``compile_model(model, precision).system`` without events, and with the terminal events
    solve compiles (``compile_model(...).t_events()``: the domain's ends, loss of contact).  The
    bare integrators are built once and reset before each run (solve builds its own inside its
    timing); same start, same parameters, tolerance epsilon for both, no step cap for the bare
    runs (solve's cap of one radian of the fastest rate does not bind on the standard states:
    compare the steps).  The start and parameters are read back from a first ``solve`` run.
    """
    state = STANDARD_STATES[model_name]
    first = solve(model_name, t_ends[0], state, precision=precision)  # JIT and sympy caches warm
    prec, model = first.precision, get_model(model_name)
    compiled = compile_model(model, prec)
    y0 = np.array(first.y[:, 0])
    parr = compiled.parameter_vector(first.params)
    kw = prec.integrator_kwargs()
    bare, bare_events = _bare_single(compiled, y0, parr, kw, False), _bare_single(compiled, y0, parr, kw, True)
    bare_reduced = _bare_single(compiled, y0, parr, kw, True, reduce_angles=True)
    rows = []
    for t_end in t_ends:
        if progress:
            progress(f"  solve against bare heyoka: {model_name}, {precision}, t_end {t_end} s, {repeats} rounds")
        T = prec.number(t_end)
        runs = {"solve": lambda: solve(model_name, t_end, state, precision=precision),
                "bare propagate_until": lambda: bare(T),
                "bare propagate_until + events": lambda: bare_events(T),
                REDUCED: lambda: bare_reduced(T)}
        if invariants:
            runs["solve, invariants read"] = lambda: _read_invariants(solve(model_name, t_end, state, precision=precision))
        times, last = interleaved(runs, repeats)
        sol = last["solve"]
        outcome_bare, steps_bare, final_bare = last["bare propagate_until"]
        outcome_events, steps_events = last["bare propagate_until + events"][:2]
        steps_reduced = last[REDUCED][1]
        # solve keeps phi, psi, x, y small between segments, so heyoka's error control does not
        # loosen as the angles grow and solve takes more steps than bare: the wall ratio mixes that
        # accuracy with overhead, the per-step ratio (minimum seconds per Taylor step) isolates the overhead
        per_step = (min(times["solve"]) / int(sol.steps)) / (min(times["bare propagate_until + events"]) / steps_events)
        # against bare with the same events whose angles heyoka keeps small after every step (solve does
        # it per segment): comparable steps; the seconds solve spends beyond its steps at that rate are
        # its per-call overhead (validation, the segments' Python, the guards on the output)
        per_step_reduced = (min(times["solve"]) / int(sol.steps)) / (min(times[REDUCED]) / steps_reduced)
        overhead = min(times["solve"]) - int(sol.steps) * min(times[REDUCED]) / steps_reduced
        case = {"model": model_name, "precision": prec.name, "t_end": t_end, "state": dict(state), "rounds": repeats,
                "steps_solve": int(sol.steps), "steps_bare": steps_bare, "steps_bare_events": int(steps_events),
                "per_step_ratio_vs_bare_events": _g(per_step), "steps_bare_events_reduced": int(steps_reduced),
                "per_step_ratio_vs_bare_events_reduced": _g(per_step_reduced),
                "per_call_overhead_seconds": _g(overhead), "outcome_solve": sol.outcome,
                "outcome_bare": str(outcome_bare), "outcome_bare_events": str(outcome_events),
                "final_state_difference": _g(float(np.max(np.abs(np.array(sol.y[:, -1], dtype=float)
                                                               - np.array(final_bare, dtype=float))))),
                "n_output_points": int(len(sol.t)), "seconds": {k: [_g(v) for v in vs] for k, vs in times.items()},
                "ratios": [ratio_record(times, "bare propagate_until + events", "bare propagate_until"),
                           ratio_record(times, "solve", "bare propagate_until"),
                           ratio_record(times, "solve", "bare propagate_until + events",
                                        TARGETS["solve_quad" if prec.name == "quad" else "solve"]),
                           ratio_record(times, "solve", REDUCED)]}
        if invariants:
            case["ratios"] += [ratio_record(times, "solve, invariants read", "bare propagate_until"),
                               ratio_record(times, "solve, invariants read", "bare propagate_until + events",
                                            TARGETS["solve_invariants"])]
        rows.append(case)
    return rows


def _read_invariants(sol):
    """Every invariant's values (read, so a lazy evaluation is paid inside the timing)."""
    return {name: np.asarray(trace.values) for name, trace in sol.invariants.items()}
