"""Benchmark: the cost of ``verify.solve`` against bare heyoka, for any model and t_end.

The same measurement as the "solve against bare heyoka" section of ``python -m verify bench``
(:func:`verify.bench.solve_against_bare`), for one model and the t_end values given: solve
with default settings from the model's standard state, against a bare ``taylor_adaptive``
(built once, reset before each run) on the same compiled equations, without events and with
the events solve compiles, in interleaved rounds.  Prints ratios measured in one run (the
machines are shared and noisy: compare ratios, not seconds).  scipy's DOP853 against heyoka is
in the benchmark's "work against precision" section.

Usage: ``python benchmarks/bench_trajectory.py [MODEL] [T_END ...] [--quad] [--rounds N]``.
"""
from __future__ import annotations

import argparse

from verify.bench import solve_against_bare


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("model", nargs="?", default="disk")
    ap.add_argument("t_end", nargs="*", default=["1", "10"])
    ap.add_argument("--quad", action="store_true", help="in quad precision instead of double")
    ap.add_argument("--rounds", type=int, default=5, help="interleaved rounds (default 5)")
    args = ap.parse_args(argv)
    cases = solve_against_bare(args.model, tuple(args.t_end), "quad" if args.quad else "double", args.rounds,
                               invariants=not args.quad)
    for case in cases:
        print(f"{case['model']} {case['precision']}, t_end {case['t_end']} s, {case['rounds']} interleaved rounds; "
              f"steps solve {case['steps_solve']}, bare {case['steps_bare']}; final states differ by "
              f"{case['final_state_difference']:.1e}")
        for rec in case["ratios"]:
            lo, hi = rec["round_ratio_range"]
            target = f"  target {rec['target']}: {'met' if rec['met'] else 'NOT met'}" if "met" in rec else ""
            print(f"  {rec['measured']:>30s} {rec['seconds'] * 1e3:10.3f} ms / {rec['baseline']:<30s} "
                  f"{rec['baseline_seconds'] * 1e3:10.3f} ms = {rec['ratio']:8.3g} (rounds {lo:.3g} - {hi:.3g}){target}")


if __name__ == "__main__":
    main()
