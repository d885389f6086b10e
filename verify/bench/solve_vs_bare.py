"""``verify.solve`` against bare heyoka ``propagate_until`` on the same compiled equations (BENCHMARKS.md's first table)."""
from __future__ import annotations

import heyoka as hy
import numpy as np

from models import get_model
from models.symbols import STATE_NAMES

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


def hand_written_disk(y0, k: float, g: float):
    """A bare run of paper Eq. 18 solved by hand (the issue's outside baseline): the eight states,
    ``k`` and ``g`` typed in as numbers, no events; built once, reset before each run.

    thetaddot = -phidot^2 sin cos - (g cos + (1 + 2k) phidot psidot sin) / (1 + k),
    phiddot = 2 psidot thetadot / sin, psiddot = 2 thetadot ((1 + k)/(1 + 2k) phidot sin - psidot cos / sin),
    and the no-slip velocity of C (paper Eq. 7).  Returns (run(t_end) -> steps, decomposition terms).
    """
    th, ph, _, thd, phd, psd, x, y = variables = hy.make_vars(*STATE_NAMES)
    s, c, sf, cf = hy.sin(th), hy.cos(th), hy.sin(ph), hy.cos(ph)
    rhs = [thd, phd, psd, -(phd * phd * s * c) - (g * c + (1 + 2 * k) * phd * psd * s) / (1 + k),
           2.0 * psd * thd / s, 2.0 * thd * ((1 + k) / (1 + 2 * k) * phd * s - psd * c / s),
           thd * sf * s - psd * cf - phd * cf * c, -(psd * sf + phd * c * sf + thd * cf * s)]
    ta = hy.taylor_adaptive(list(zip(variables, rhs)), y0)

    def run(t_end):
        ta.time = 0.0
        ta.state[:] = y0
        return int(ta.propagate_until(float(t_end))[3])

    return run, decomposition_terms(ta)


def decomposition_terms(ta) -> int:
    """The elementary terms of an integrator's Taylor decomposition (the state's own entries and the
    right-hand sides' outputs not counted; the event functions' terms counted)."""
    return len(ta.decomposition) - 2 * len(ta.state)


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
    terms = {"system": decomposition_terms(hy.taylor_adaptive(list(compiled.system), y0, pars=parr, **kw)),
             "system_and_events": decomposition_terms(hy.taylor_adaptive(list(compiled.system), y0, pars=parr,
                                                                         t_events=compiled.t_events(), **kw))}
    hand = None
    if model_name == "disk" and prec.name == "double":  # the outside baseline: Eq. 18 typed by hand
        hand, terms["hand_written_eq18"] = hand_written_disk(y0, float(first.params["k"]), float(first.params["g"]))
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
        if hand is not None:
            runs[HAND] = lambda: hand(T)
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
                "decomposition_terms": terms, "n_output_points": int(len(sol.t)), "seconds": {k: [_g(v) for v in vs] for k, vs in times.items()},
                "ratios": [ratio_record(times, "bare propagate_until + events", "bare propagate_until"),
                           ratio_record(times, "solve", "bare propagate_until"),
                           ratio_record(times, "solve", "bare propagate_until + events",
                                        TARGETS["solve_quad" if prec.name == "quad" else "solve"]),
                           ratio_record(times, "solve", REDUCED)]}
        if hand is not None:
            case["steps_hand_written"] = last[HAND]
            case["ratios"].append(ratio_record(times, "solve", HAND, TARGETS["solve_hand_1s" if float(t_end) <= 1
                                                                              else "solve_hand"]))
        if invariants:
            case["ratios"] += [ratio_record(times, "solve, invariants read", "bare propagate_until"),
                               ratio_record(times, "solve, invariants read", "bare propagate_until + events",
                                            TARGETS["solve_invariants"])]
        rows.append(case)
    return rows


#: The name of the hand-written baseline in the timings.
HAND = "bare hand-written Eq. 18, no events"


def _read_invariants(sol):
    """Every invariant's values (read, so a lazy evaluation is paid inside the timing)."""
    return {name: np.asarray(trace.values) for name, trace in sol.invariants.items()}
