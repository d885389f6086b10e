"""The rolling phase of a rolling-and-sliding run (:mod:`verify.engine.hybrid`).

The rolling model (``disk``, ``ring``, a body's; paper Eqs. 5-8) is run by the engine,
:func:`verify.engine.single.solve` with ``friction=mu``, whose terminal event ``slips`` fires where the
required friction mu_req = |F_h| / N reaches mu.  Its outputs are recorded on the run with E, E's term
scale and the work so far (constant while rolling), and checked (:func:`verify.engine.hybrid_guards.check_phase`).
"""
from __future__ import annotations

import numpy as np

from . import hybrid_guards as guards
from .hybrid_run import Phase
from .hybrid_system import evaluate, rolling_model, term_scale
from .single import solve as solve_rolling
from .validation import InvalidStart


def rolling_phase(run, t0, y8):
    """A rolling phase of ``run`` from (t0, y8), its outputs recorded and checked.

    Returns
    -------
    tuple or None
        ``("slips", t, y8)`` where mu_req reached mu (the event's constraint checked), ``("cannot_roll", t0,
        y8, why)`` where rolling from (t0, y8) would need more friction than mu at once, or None where the run
        ended (t_end, or another terminal event: the run's outcome says which).  The switch is the caller's
        (:mod:`verify.engine.hybrid_switches`).
    """
    prec = run.prec
    rolling = rolling_model(run.name)
    after = [g for g in run.grid_after(t0) if g - t0 > 0]
    relative = [g - t0 for g in after]
    run.phases.append(Phase("rolling", t0, None, "running"))
    try:
        sol = solve_rolling(rolling, run.t_end - t0, y8, run.pars, precision=prec,
                            t_eval=[prec.zero()] + relative, friction=run.mu)
    except InvalidStart as err:
        run.phases.pop()
        if err.reason == "slips":
            return "cannot_roll", t0, y8, f"rolling from t = {t0} needs more friction than mu: {err}"
        # a state the run reached, not one the user gave: a failed run, not bad input
        outcome = guards.OUTSIDE_DOMAIN if err.reason == "outside_domain" else guards.SWITCH_CONSTRAINT
        raise guards.fail(run, outcome, f"the rolling phase of {run.name} from t = {float(t0):.9g} cannot "
                                        f"start: {err}", t0, y8) from None
    run.rolling_runs.append(sol)
    run.steps += int(sol.steps)
    states = [np.array(sol.y[:, j]) for j in range(sol.y.shape[1])]
    # a grid output is reported at the grid's own time: t0 + (g - t0) need not round back to g (it is g to
    # an ulp, and the state was integrated to it); the event that ends the phase is at t0 + its own time
    times = [t0] + [after[k] if k < len(relative) and tau == relative[k] else t0 + tau
                    for k, tau in enumerate(sol.t[1:])]
    values = evaluate(run.c.rolling_function, np.ascontiguousarray(sol.y), run.par_vector[:-1])
    nan = np.longdouble("nan") if prec.name == "long" else float("nan")
    run.record(times, states, values[0], term_scale(values, 4), [prec.zero()] * len(times),
               [nan] * len(times), [run.work_so_far] * len(times))
    ended = "ok" if sol.status == 0 else (sol.outcome[6:] if sol.outcome.startswith("event:") else sol.outcome)
    run.phases[-1] = Phase("rolling", t0, times[-1], ended)
    guards.check_phase(run, "rolling", times, sol.y[0], sol.y[3], ended, sol.y[:, -1])
    if ended == "slips":
        y_slip = np.ascontiguousarray(sol.y[:, -1])
        guards.check_slips(run, times[-1], y_slip)
        return "slips", times[-1], y_slip
    if ended != "ok":
        run.outcome, run.message = f"event:{ended}", sol.message
    return None
