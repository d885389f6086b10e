"""What ``solve`` costs against bare heyoka on the same compiled equations (ratios, one process).

Bare: one ``taylor_adaptive`` on ``compile_model(disk).system`` from the disk's standard start,
tolerance epsilon, built once (with and without the model's terminal events) and reset (time,
state) before each ``propagate_until(t_end)``.  ``solve``: default settings (101 output points,
events on), once without reading ``Trajectory.invariants`` and once reading them.  Every case
is run interleaved with the others, REPEATS times; medians are printed with their ratios.

Usage: python scripts/solve_overhead.py [REPEATS]
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


def _bare(prec, events: bool):
    model = get_model("disk")
    y0, pars = validation.validate(model, STANDARD_STATES["disk"], None, prec)
    compiled = compile_model(model, prec)
    par_vector = prec.array([pars[p.name] for p in model.parameters])[: compiled.n_pars_system]
    ta = hy.taylor_adaptive(list(compiled.system), y0, pars=par_vector,
                            t_events=compiled.t_events() if events else [], **prec.integrator_kwargs())

    def run(t_end):
        ta.time = prec.zero()
        ta.state[:] = y0
        ta.propagate_until(prec.number(t_end))
    return run


def _solve(prec, read_invariants: bool):
    def run(t_end):
        sol = solve("disk", t_end, STANDARD_STATES["disk"], precision=prec.name)
        if read_invariants:
            sol.invariants["energy"].max_rel_drift
    return run


def main(repeats: int) -> None:
    cases = [("double", 1), ("double", 10), ("double", 100), ("quad", 10)]
    for name, t_end in cases:
        prec = parse_precision(name)
        runs = {"bare": _bare(prec, False), "bare+events": _bare(prec, True),
                "solve": _solve(prec, False), "solve+invariants": _solve(prec, True)}
        n = max(1, repeats // 5) if name == "quad" else repeats
        times = {k: [] for k in runs}
        for f in runs.values():  # warm-up: compile, caches
            f(t_end)
        for _ in range(n):
            for k, f in runs.items():
                t0 = time.perf_counter()
                f(t_end)
                times[k].append(time.perf_counter() - t0)
        med = {k: statistics.median(v) for k, v in times.items()}
        b, be = med["bare"], med["bare+events"]
        print(f"{name:6s} t_end={t_end:<4d} bare {b * 1e3:9.3f} ms  bare+events {be * 1e3:9.3f} ms ({be / b:.2f}x)  "
              f"solve {med['solve'] * 1e3:9.3f} ms ({med['solve'] / b:.2f}x bare, {med['solve'] / be:.2f}x bare+events)  "
              f"solve+invariants {med['solve+invariants'] * 1e3:9.3f} ms ({med['solve+invariants'] / b:.2f}x bare, "
              f"{med['solve+invariants'] / be:.2f}x bare+events)  [{n} repeats]", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 20)
