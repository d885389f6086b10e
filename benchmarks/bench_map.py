"""Benchmark: a 100 x 100 stability map (10^4 runs of 10 s) by heyoka batch mode on threads.

The issue's target: "a stability map of 10^4 trajectories of 10 s for the disk in under 10 s
on 2 cores (heyoka batch plus ensemble)".  Prints the map's wall time and throughput, and,
measured in the same run as ratios of throughput (the machines are shared and noisy: compare
ratios, not seconds), the same work done

* by a plain loop of scalar heyoka integrators over a subset (same reduced equations, the
  same terminal events and freezing callbacks, the same sample grid, no step cap either);
* by batch mode without the ensemble: one batch integrator reused serially over a subset;
* by the ensemble on one thread (what the second core adds);
* by plain Python threads that each reuse one batch integrator for a contiguous share of the
  batches, written out here as a cross-check of :func:`verify.engine.batch.propagate_grid`, which
  runs the map the same way (heyoka's ensemble would deep-copy the integrator for every batch: a
  copy takes ~0.8 ms and holds the GIL, so copies do not overlap);
* with the step cap of ``verify.engine.single.max_step`` (1 / fastest rate; the map runs without:
  does the cap cost or change anything?).

The scalar and serial-batch subsets are checked against the map's own numbers.  Not a
pass/fail test.  Usage: ``python benchmarks/bench_map.py [MODEL] [MOTION] [N_RATES] [N_TILTS]``.
"""
from __future__ import annotations

import copy
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import heyoka as hy
import numpy as np

from verify.studies import maps
from verify.studies.thresholds import threshold

SUBSET_SCALAR = 200  # trajectories
SUBSET_BATCH = 2000  # trajectories


def scalar_loop(runs: maps.Runs, lanes) -> tuple:
    """max deviation and alive flag of ``lanes``, one scalar integrator each."""
    lane_system = runs.ensemble.lanes  # the map's own equations and events, parameters by name
    system = lane_system.template.sys
    events = [(name, ev.expression, ev.direction) for name, ev in zip(lane_system.events, lane_system.template.t_events)]
    alive, reason, t_stop, lower, upper = (lane_system.layout[k] for k in
                                           ("alive", "reason", "t_stop", "theta_lower", "theta_upper"))
    th, thd = lane_system.row("theta"), lane_system.row("thetadot")

    def freeze(code):
        def cb(ta, d_sgn):
            if ta.pars[alive] != 0.0:
                ta.pars[alive] = 0.0
                ta.pars[reason] = code
                ta.pars[t_stop] = ta.time
                ta.state[th] = 0.5 * (ta.pars[lower] + ta.pars[upper])
                ta.state[thd] = 0.0
            return True
        return cb

    t_events = [hy.t_event(ex, direction=d, callback=freeze(i + 1), cooldown=runs.cooldown)
                for i, (_, ex, d) in enumerate(events)]
    ta0 = hy.taylor_adaptive(list(system), runs.states[:, 0].copy(), pars=runs.pars[:, 0].copy(), t_events=t_events)
    kwargs = {} if runs.step_cap is None else {"max_delta_t": runs.step_cap}
    dev, kept = [], []
    start = time.perf_counter()
    for k in lanes:
        ta = copy.deepcopy(ta0)
        ta.time = 0.0
        ta.state[:] = runs.states[:, k]
        ta.pars[:] = runs.pars[:, k]
        out = ta.propagate_grid(runs.grid, **kwargs)
        if out[0] != hy.taylor_outcome.time_limit:
            raise RuntimeError(f"scalar run {k} stopped with {out[0]}")
        dev.append(np.max(np.abs(out[-1][:, 0] - runs.ref[k])))
        kept.append(ta.pars[alive] != 0.0)
    return time.perf_counter() - start, np.array(dev), np.array(kept)


def serial_batches(runs: maps.Runs, batches) -> tuple:
    """max deviation and alive flag of every lane of ``batches``, one batch integrator reused."""
    b = runs.batch_size
    ta = copy.deepcopy(runs.ensemble.lanes.template)
    grid = np.repeat(runs.grid, b).reshape(-1, b)
    kwargs = {} if runs.step_cap is None else {"max_delta_t": runs.step_cap}
    dev, alive = [], []
    start = time.perf_counter()
    for i in batches:
        cols = slice(i * b, (i + 1) * b)
        ta.set_time(0.0)
        ta.reset_cooldowns()
        ta.state[:] = runs.states[:, cols]
        ta.pars[:] = runs.pars[:, cols]
        out = ta.propagate_grid(grid, **kwargs)[-1]
        dev.append(np.max(np.abs(out[:, 0, :] - runs.ref[None, cols]), axis=0))
        alive.append(runs.ensemble.record(ta.pars, "alive") != 0.0)
    return time.perf_counter() - start, np.concatenate(dev), np.concatenate(alive)


def threaded_reuse(runs: maps.Runs, threads: int) -> tuple:
    """Every batch of the map, ``threads`` workers each reusing one integrator (no copy per batch)."""
    n_batches = runs.states.shape[1] // runs.batch_size
    shares = np.array_split(np.arange(n_batches), threads)
    start = time.perf_counter()
    with ThreadPoolExecutor(max_workers=threads) as pool:
        parts = list(pool.map(lambda share: serial_batches(runs, share)[1:], shares))
    wall = time.perf_counter() - start
    return wall, np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


def main(model="disk", motion="diameter-spin", n_rates=100, n_tilts=100):
    lin = float(threshold(model, motion).value)
    rates = np.linspace(0.5 * lin, 2.0 * lin, int(n_rates))
    tilts = np.logspace(-6, -1, int(n_tilts))
    maps.stability_map(model, motion, rates=rates[:4], tilts=tilts[:2])  # warm: JIT / heyoka's cache, sympy
    load = os.getloadavg()

    smap = maps.stability_map(model, motion, rates=rates, tilts=tilts)
    n = smap.n_trajectories
    rate_map = n / smap.wall_seconds
    print(f"{model} {motion}: {len(rates)} rates x {len(tilts)} tilts = {n} runs of {smap.t_end:g} s, "
          f"batch size {smap.batch_size} (2 x hy.recommended_simd_size()), {smap.threads} threads, "
          f"{os.cpu_count()} cores (load average before: {load[0]:.2f}), {smap.n_samples} samples per run, "
          f"no step cap")
    print(f"  map (batch + ensemble): {smap.wall_seconds:.2f} s wall, {rate_map:,.0f} trajectories/s, "
          f"{smap.n_steps:,} batch steps; grows {int(smap.grows.sum())}, left {int(smap.left.sum())}; "
          f"target (< 10 s): {'met' if smap.wall_seconds < 10 else 'NOT met'}")

    runs = maps.prepare_runs(model, motion, rates, tilts, smap.t_end, {}, smap.cap, False, smap.batch_size)
    flat_dev, flat_left = smap.max_deviation.ravel(), smap.left.ravel()

    stride = max(1, n // SUBSET_SCALAR)
    lanes = np.arange(0, n, stride)[:SUBSET_SCALAR]
    t_scalar, dev_s, alive_s = scalar_loop(runs, lanes)
    stayed = alive_s & ~flat_left[lanes]
    rel_s = np.abs(dev_s[stayed] - flat_dev[lanes][stayed]) / flat_dev[lanes][stayed]
    same_s = np.array_equal(~alive_s, flat_left[lanes])

    n_batches = min(SUBSET_BATCH // runs.batch_size, runs.states.shape[1] // runs.batch_size)
    batches = np.linspace(0, runs.states.shape[1] // runs.batch_size - 1, n_batches).astype(int)
    t_batch, dev_b, alive_b = serial_batches(runs, batches)
    lanes_b = np.concatenate([np.arange(i * runs.batch_size, (i + 1) * runs.batch_size) for i in batches])
    real = lanes_b < n
    dev_b = np.where(alive_b, dev_b, smap.cap)
    identical_b = np.array_equal(dev_b[real], flat_dev[lanes_b[real]]) and np.array_equal(~alive_b[real],
                                                                                          flat_left[lanes_b[real]])

    one = maps.stability_map(model, motion, rates=rates, tilts=tilts, threads=1)
    t_reuse, dev_r, alive_r = threaded_reuse(runs, smap.threads)
    dev_r = np.where(alive_r, dev_r, smap.cap)[:n]
    identical_r = np.array_equal(dev_r, flat_dev) and np.array_equal(~alive_r[:n], flat_left)
    capped = maps.stability_map(model, motion, rates=rates, tilts=tilts, step_cap=True)
    ok = ~smap.grows
    rel_cap = np.abs(capped.max_deviation - smap.max_deviation) / smap.max_deviation

    rows = [
        ("batch + ensemble, %d threads" % smap.threads, n, smap.wall_seconds, "the map"),
        ("batch + ensemble, 1 thread", n, one.wall_seconds,
         "identical bytes" if one.max_deviation.tobytes() == smap.max_deviation.tobytes() else "DIFFERENT"),
        ("batch, serial loop (no ensemble)", int(real.sum()), t_batch,
         "identical to the map" if identical_b else "DIFFERENT"),
        (f"batch, {smap.threads} threads reusing 1 integrator each", n, t_reuse,
         "identical to the map" if identical_r else "DIFFERENT"),
        ("scalar heyoka loop", len(lanes), t_scalar,
         f"same left: {same_s}; max rel diff {rel_s.max():.1e} (stayed)"),
        (f"batch + ensemble, step cap {capped.step_cap:.3g} s", n, capped.wall_seconds,
         f"{capped.n_steps:,} vs {smap.n_steps:,} steps; classification differs at "
         f"{int((capped.grows != smap.grows).sum())}; rel diff {rel_cap[ok].max():.1e} (no growth), "
         f"{rel_cap[~ok & ~smap.left].max():.1e} (growth, stayed)"),
    ]
    print(f"\n  {'route':44s} {'runs':>6s} {'wall s':>8s} {'traj/s':>9s} {'map is x faster':>16s}  check")
    for name, count, wall, note in rows:
        tps = count / wall
        print(f"  {name:44s} {count:6d} {wall:8.2f} {tps:9,.0f} {rate_map / tps:16.2f}  {note}")


if __name__ == "__main__":
    main(*sys.argv[1:])
