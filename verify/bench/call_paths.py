"""The same batch integrator entered along each call path of :mod:`verify.engine.call_paths`: time per step.

One thread, the disk's bare lane system (its batch width), the benchmark grid's starts, 10 s on a
101-point output grid: every batch along every path, in interleaved rounds.  The paths differ only in
how Python reaches heyoka's ``propagate_grid`` (keywords written out or a mapping; one C frame deeper
or not), so any difference in time is the machine's, not the work's: the output and the steps are
compared byte for byte.  On the machine where it was found (AVX-512, batch 8) the slowest path ran
about 1.4 times the fastest; the batch propagator times the paths and keeps the fastest.
"""
from __future__ import annotations

import copy

import numpy as np

from ..engine import batch, call_paths
from ..engine.lanes import compile_lanes, simd_width
from ..sweep.engine import ensemble_of, fastest_rate, lane_inputs
from .ensembles import bench_sweep_spec
from .sizes import _g, _size
from .timing import interleaved


def call_path_cost(quick: bool, progress) -> dict:
    """Seconds per batch step along each path (the minimum over interleaved rounds), the ratio of the
    slowest to the fastest, and whether every path gave the same bytes."""
    spec = bench_sweep_spec(_size("sweep_per_axis", quick))
    bs = simd_width()
    ens = ensemble_of(spec, bs)
    indices = np.array(list(spec.chunk_points(0)))
    states, model_pars, _ = lane_inputs(spec, indices)
    lanes = compile_lanes(ens.model, "full", bs, ens.cooldown, bare=True)
    pad = batch.pad_lanes(len(indices), bs)
    values = {**ens.model_values(model_pars[:, pad]), "theta_max": float(ens.model.domain.theta_max)}
    pars = lanes.layout.columns(len(pad), {k: v for k, v in values.items() if k in lanes.layout})
    lane_states = np.ascontiguousarray(states[:, pad])
    grid = np.ascontiguousarray(np.repeat(np.linspace(0.0, spec.t_end, spec.samples)[:, None], bs, axis=1))
    cap = 1.0 / fastest_rate(spec, ens)
    ta = copy.deepcopy(lanes.template)

    def along(path):
        def run():
            steps, outputs = 0, []
            for b in range(len(pad) // bs):
                cols = slice(b * bs, (b + 1) * bs)
                ta.set_time(0.0)
                ta.reset_cooldowns()
                ta.state[:] = lane_states[:, cols]
                ta.pars[:] = pars[:, cols]
                outputs.append(call_paths.propagate_grid(ta, grid, path, cap)[-1].tobytes())
                steps += max(int(r[3]) for r in ta.propagate_res)
            return steps, b"".join(outputs)
        return run

    runs = {f"{form}, {depth} extra C frame{'s' if depth != 1 else ''}": along((form, depth))
            for form, depth in call_paths.PATHS}
    rounds = _size("ensemble_rounds", quick)
    progress(f"  call paths: {len(runs)} paths, {len(pad) // bs} batches, {rounds} rounds")
    times, last = interleaved(runs, rounds)
    steps = {k: v[0] for k, v in last.items()}
    per_step = {k: min(times[k]) / steps[k] for k in runs}
    fastest = min(per_step.values())
    return {"batch_size": bs, "batches": len(pad) // bs, "rounds": rounds, "samples": spec.samples,
            "steps": next(iter(steps.values())),
            "same_bytes": len({v[1] for v in last.values()}) == 1 and len(set(steps.values())) == 1,
            "paths": [{"path": k, "seconds": _g(min(times[k])), "us_per_step": _g(1e6 * per_step[k]),
                       "vs_fastest": _g(per_step[k] / fastest)} for k in runs]}
