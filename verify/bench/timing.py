"""Timing on a shared machine: the best of repeated calls, interleaved rounds, and the ratio of two timings."""
from __future__ import annotations

import math
import time

import numpy as np

from .sizes import _g


def _timed(f, repeats: int):
    """(best wall time of ``repeats`` calls, the last result)."""
    best, out = math.inf, None
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


def interleaved(runs: dict, repeats: int) -> tuple:
    """Wall seconds of every callable in ``runs`` over ``repeats`` rounds, and the last results.

    In every round each callable runs once, the order rotated by one place from round to round,
    so a slow spell of the shared machine falls on all of them alike and none always runs first
    (warm caches) or last.  Returns ({name: [seconds per round]}, {name: last result}).
    """
    names = list(runs)
    times = {n: [] for n in names}
    results = {}
    for r in range(max(1, repeats)):
        k = r % len(names)
        for name in names[k:] + names[:k]:
            t0 = time.perf_counter()
            results[name] = runs[name]()
            times[name].append(time.perf_counter() - t0)
    return times, results


def ratio_record(times: dict, measured: str, baseline: str, target=None, inverse: bool = False) -> dict:
    """One ratio of two interleaved timings: min(measured) / min(baseline), and the median and range
    of the per-round ratios (measured and baseline ran in the same round).  ``inverse`` gives the
    ratio of throughputs instead (min(baseline) / min(measured): trajectories per second of the
    measured route over the baseline's).  ``target`` is (operator, bound), operator "<=" or ">="."""
    a, b = np.array(times[measured]), np.array(times[baseline])
    per_round = b / a if inverse else a / b
    value = float(b.min() / a.min() if inverse else a.min() / b.min())
    rec = {"measured": measured, "baseline": baseline, "seconds": _g(a.min()), "baseline_seconds": _g(b.min()),
           "ratio": _g(value), "median_round_ratio": _g(float(np.median(per_round))),
           "round_ratio_range": [_g(float(per_round.min())), _g(float(per_round.max()))], "rounds": len(a),
           "kind": "throughput" if inverse else "time"}
    if target is not None:
        op, bound = target
        rec["target"] = f"{op} {bound:g}"
        rec["met"] = bool(value <= bound if op == "<=" else value >= bound)
    return rec
