"""What ``solve`` costs against bare heyoka on the same compiled equations (ratios, one process).

Bare: one ``taylor_adaptive`` on ``compile_model(disk).system`` from the disk's standard start,
tolerance epsilon, built once (with and without the model's terminal events) and reset (time,
state) before each ``propagate_until(t_end)``.  Bare heyoka lets phi and psi grow without bound,
which loosens its error control (HEYOKA.md) and saves steps: ``solve`` keeps them reduced and
takes ~20 % more steps at t_end = 100 for Brouwer's law.  The same work in bare heyoka is the
run with heyoka's own ``callback.angle_reducer`` on phi and psi ("bare+events+angles"), printed
beside it with the steps each took.  ``solve``: default settings (101 output points,
events on), once without reading ``Trajectory.invariants`` and once reading them.  Every case
is run interleaved with the others, REPEATS times; medians are printed with their ratios.

Usage: PYTHONPATH=. python scripts/solve_overhead.py [REPEATS]   (from the tree to measure; the
first line printed names the ``verify`` package that was imported)
"""
from __future__ import annotations

import statistics
import sys
import time

import heyoka as hy

from models import get_model
from verify.engine.compile import compile_model
from verify.engine.single import solve
from verify.engine import validation
from verify.precision import parse_precision
from verify.standard import STANDARD_STATES


def _bare(prec, events: bool, angles: bool = False):
    model = get_model("disk")
    y0, pars = validation.validate(model, STANDARD_STATES["disk"], None, prec)
    compiled = compile_model(model, prec)
    par_vector = prec.array([pars[p.name] for p in model.parameters])[: compiled.n_pars_system]
    ta = hy.taylor_adaptive(list(compiled.system), y0, pars=par_vector,
                            t_events=compiled.t_events() if events else [], **prec.integrator_kwargs())
    kwargs = {"callback": hy.callback.angle_reducer(list(compiled.variables[1:3]))} if angles else {}

    def run(t_end):
        ta.time = prec.zero()
        ta.state[:] = y0
        if events:
            ta.reset_cooldowns()
        return int(ta.propagate_until(prec.number(t_end), **kwargs)[3])
    return run


def _solve(prec, read_invariants: bool):
    def run(t_end):
        sol = solve("disk", t_end, STANDARD_STATES["disk"], precision=prec.name)
        if read_invariants:
            sol.invariants["energy"].max_rel_drift
        return sol.steps
    return run


def main(repeats: int) -> None:
    import verify
    print(f"verify from {verify.__file__}", flush=True)
    cases = [("double", 1), ("double", 10), ("double", 100), ("quad", 10)]
    for name, t_end in cases:
        prec = parse_precision(name)
        runs = {"bare": _bare(prec, False), "bare+events": _bare(prec, True),
                "bare+events+angles": _bare(prec, True, angles=True),
                "solve": _solve(prec, False), "solve+invariants": _solve(prec, True)}
        n = max(1, repeats // 5) if name == "quad" else repeats
        times = {k: [] for k in runs}
        steps = {k: f(t_end) for k, f in runs.items()}  # also the warm-up: compile, caches
        for _ in range(n):
            for k, f in runs.items():
                t0 = time.perf_counter()
                f(t_end)
                times[k].append(time.perf_counter() - t0)
        med = {k: statistics.median(v) for k, v in times.items()}
        b, be, ba = med["bare"], med["bare+events"], med["bare+events+angles"]
        print(f"{name} t_end={t_end} [{n} repeats, medians]", flush=True)
        for k in runs:
            print(f"    {k:20s} {med[k] * 1e3:10.3f} ms {steps[k]:7d} steps   {med[k] / b:7.2f}x bare  "
                  f"{med[k] / be:7.2f}x bare+events  {med[k] / ba:7.2f}x bare+events+angles", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 20)
