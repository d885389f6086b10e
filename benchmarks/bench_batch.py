"""Throughput of the batch engine against bare heyoka on identical starts, measured interleaved.

Three workloads, each timed ``ROUNDS`` times alternating with its bare baseline in this process
(the machines are shared: compare the ratios, not the seconds):

* ``sweep, benchmark starts``: the disk starts of :func:`verify.bench.sweep_throughput`'s
  ranges (theta in [1.0, 1.4], phidot in [-2, 2], psidot in [5, 15]) laid out as a sweep grid,
  10 s each, run by :func:`verify.sweep.engine.run_chunk`; bare: the model's compiled 8-dimensional
  system, ``hy.ensemble_propagate_until_batch`` to 10 s, no events, no output grid, no step cap;
* ``sweep, diameter spin``: the first chunks of verify/sweep/specs/disk-diameter-spin.toml; bare
  as above on the same starts;
* ``stability map``: :func:`verify.studies.maps.stability_map` on the disk's diameter spin;
  bare: the reduced 4-dimensional system (alive = 1), same batch size, same starts, to t_end.

Both sides run on every core with the same batch size.  Prints the trajectories per second of
each and the ratio engine / bare (the target of the engine: >= 0.8).  Not a pass/fail test.
Usage: ``python benchmarks/bench_batch.py [ROUNDS]``.
"""
from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import heyoka as hy
import numpy as np

from models import get_model
from verify.engine.compile import compile_model
from verify.engine.lanes import compile_lanes, simd_width
from verify.precision import parse_precision
from verify.studies import maps
from verify.sweep import load, parse
from verify.sweep.engine import lane_inputs, run_chunk

ROOT = Path(__file__).resolve().parent.parent
THREADS = os.cpu_count() or 1
BENCH_GRID = """
[sweep]
name = "bench-starts"
model = "disk"
t_end = 10
samples = 401
chunk = 512
store = "{store}"

[[axis]]
name = "theta"
from = 1.0
to = 1.4
count = 8

[[axis]]
name = "phidot"
from = -2
to = 2
count = 8

[[axis]]
name = "psidot"
from = 5
to = 15
count = 16

[record]
quantities = ["max_theta", "min_theta", "final_theta"]
"""


def bare_ensemble(system, pars, states, t_end: float, bs: int) -> float:
    """Seconds of a bare ensemble of batches over the columns of ``states`` (padded to whole batches)."""
    n = states.shape[1]
    padded = -(-n // bs) * bs
    cols = np.minimum(np.arange(padded), n - 1)
    states = np.ascontiguousarray(states[:, cols])
    pars = np.ascontiguousarray(pars[:, cols])
    tb = hy.taylor_adaptive_batch(system, states[:, :bs].copy(), pars=pars[:, :bs].copy())

    def gen(tc, b):
        tc.set_time(0.0)
        tc.state[:] = states[:, b * bs:(b + 1) * bs]
        tc.pars[:] = pars[:, b * bs:(b + 1) * bs]
        return tc

    start = time.perf_counter()
    hy.ensemble_propagate_until_batch(tb, t_end, padded // bs, gen, max_workers=THREADS)
    return time.perf_counter() - start


def sweep_case(spec, chunks, bs):
    model = get_model(spec.model)
    prec = parse_precision("double")
    compiled = compile_model(model, prec)
    idx = np.concatenate([np.arange(c * spec.chunk, min((c + 1) * spec.chunk, spec.n_points)) for c in chunks])
    states, model_pars, _ = lane_inputs(spec, idx)
    pars = np.stack([compiled.parameter_vector(dict(zip(model.parameter_names, model_pars[:, k])))
                     for k in range(len(idx))], axis=1)

    def engine():
        start = time.perf_counter()
        for c in chunks:
            run_chunk(spec, c, THREADS, bs)
        return time.perf_counter() - start

    return len(idx), engine, lambda: bare_ensemble(list(compiled.system), pars, states, spec.t_end, bs)


def map_case(bs):
    rates, tilts = np.linspace(14.0, 42.0, 50), np.logspace(-6, -1, 40)
    runs = maps.prepare_runs("disk", "diameter-spin", rates, tilts, 10.0, {}, maps.CAP, False, bs)
    ens = runs.ensemble
    bare = compile_lanes(ens.model, "reduced", bs, ens.cooldown, bare=True, events=())  # no events, no alive
    system = bare.template.sys
    pars = np.stack([ens.record(runs.pars, name) for name in bare.layout.names])

    def engine():
        return maps.stability_map("disk", "diameter-spin", rates=rates, tilts=tilts, batch_size=bs,
                                  threads=THREADS).wall_seconds

    return runs.n, engine, lambda: bare_ensemble(list(system), pars, runs.states[:, :runs.n], 10.0, bs)


def main(rounds=3):
    bs = simd_width()
    with tempfile.TemporaryDirectory() as tmp:
        cases = {
            "sweep, benchmark starts": sweep_case(parse(BENCH_GRID.format(store=Path(tmp) / "b.sqlite")), [0, 1], bs),
            "sweep, diameter spin": sweep_case(load(ROOT / "verify/sweep/specs/disk-diameter-spin.toml"), [0, 7, 13],
                                               bs),
            "stability map": map_case(2 * bs),
        }
        times = {k: ([], []) for k in cases}
        for name, (n, engine, bare) in cases.items():  # warm: JIT, caches
            engine(), bare()
        for _ in range(int(rounds)):
            for name, (n, engine, bare) in cases.items():
                times[name][1].append(bare())
                times[name][0].append(engine())
    print(f"{THREADS} threads, simd width {bs}, {rounds} rounds interleaved, median seconds")
    for name, (n, _, _) in cases.items():
        e, b = np.median(times[name][0]), np.median(times[name][1])
        print(f"  {name:26s} {n:6d} runs: engine {n / e:8,.0f}/s  bare {n / b:8,.0f}/s  engine/bare {b / e:.2f}x")


if __name__ == "__main__":
    main(*sys.argv[1:])
