"""What each terminal event of the disk costs a run (bare heyoka, ratios in one process).

One ``taylor_adaptive`` per set of terminal events -- none, the domain's ends (theta = 0 and
theta = pi, both ``lies_flat``), ``contact_lost`` (N = 0), all three -- on the disk's compiled
equations from its standard start, tolerance epsilon; each reset and run to t_end interleaved
with the others, REPEATS times; medians and ratios to the run without events are printed.

Usage: PYTHONPATH=. python benchmarks/event_costs.py [REPEATS]
"""
from __future__ import annotations

import statistics
import sys
import time

import heyoka as hy

from models import get_model
from verify.engine.problem import problem
from verify.standard import STANDARD_STATES


def main(repeats: int) -> None:
    p = problem(get_model("disk"), STANDARD_STATES["disk"])
    c = p.compiled
    names = [name for name, _, _ in c.events]
    fresh = c.t_events()
    sets = {"none": [], "domain ends": [e for n, e in zip(names, fresh) if n != "contact_lost"],
            "contact_lost": [e for n, e in zip(names, c.t_events()) if n == "contact_lost"], "all": c.t_events()}
    tas = {k: hy.taylor_adaptive(list(c.system), p.y0, pars=p.par_vector, t_events=ev) for k, ev in sets.items()}
    for t_end in (10.0, 100.0):
        times = {k: [] for k in tas}
        for _ in range(repeats + 1):
            for k, ta in tas.items():
                ta.time = 0.0
                ta.state[:] = p.y0
                if ta.with_events:
                    ta.reset_cooldowns()
                t0 = time.perf_counter()
                ta.propagate_until(t_end)
                times[k].append(time.perf_counter() - t0)
        med = {k: statistics.median(v[1:]) for k, v in times.items()}
        print(f"t_end={t_end:g} [{repeats} repeats, medians]: " + "  ".join(
            f"{k} {med[k] * 1e3:.2f} ms ({med[k] / med['none']:.3f}x)" for k in tas), flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 20)
