"""The sweep engine and the stability map against a bare batch ensemble of the same starts."""
from __future__ import annotations

import dataclasses
import math
import os

import heyoka as hy
import mpmath
import numpy as np
import sympy as sp

from models import get_model
from models.symbols import STATE_NAMES

from ..engine.compile import compile_model
from ..precision import parse_precision
from .sizes import TARGETS, _g, _size
from .timing import interleaved, ratio_record

BENCH_SWEEP_TOML = """\
[sweep]
name = "bench-disk-grid"
model = "disk"
t_end = 10
samples = {samples}
chunk = {n}
store = "unused.sqlite"

[[axis]]
name = "theta"
from = 1.0
to = 1.4
count = {c}

[[axis]]
name = "phidot"
from = -2.0
to = 2.0
count = {c}

[[axis]]
name = "psidot"
from = 5.0
to = 15.0
count = {c}

[record]
quantities = ["max_theta", "min_theta", "final_theta"]
"""


def bench_sweep_spec(per_axis: int, samples: int = 101):
    """The benchmark's own sweep: theta in [1.0, 1.4] x phidot in [-2, 2] x psidot in [5, 15],
    ``per_axis`` values each, 10 s, one chunk, ``samples`` output points, three cheap reductions."""
    from ..sweep import parse

    n = per_axis ** 3
    return parse(BENCH_SWEEP_TOML.format(samples=samples, n=n, c=per_axis), "<benchmark sweep>")


def sweep_starts(spec, indices) -> np.ndarray:
    """The full 8-component starts (double) the sweep engine integrates for the points ``indices``:
    [start] values, state axes, and for ``steady = "diameter-spin"`` of the disk theta = pi/2 + tilt
    (pi/2 rounded to double first, then the tilt added in double, as the engine does) and phidot the
    rate.  Other steady motions are not needed here."""
    cols = spec.columns(np.asarray(indices, dtype=np.int64))
    n = len(indices)
    y = np.zeros((8, n))
    for k, v in spec.start.items():
        y[STATE_NAMES.index(k)] = v
    for name, values in cols.items():
        if name in STATE_NAMES:
            y[STATE_NAMES.index(name)] = values
    if spec.steady is not None:
        if (spec.model, spec.steady) != ("disk", "diameter-spin"):
            raise ValueError(f"benchmark starts for steady {spec.steady!r} of {spec.model!r} are not implemented")
        y[0] = math.pi / 2
    if "tilt" in cols:
        y[0] = y[0] + cols["tilt"]
    return y


def map_starts(rates, tilts) -> np.ndarray:
    """The stability map's starts of the disk's diameter spin, tilt-major: theta = pi/2 + tilt rounded
    once from 40 digits (as the map adds the tilt to the 36-digit steady angle), phidot = rate."""
    y = np.zeros((8, len(tilts) * len(rates)))
    with mpmath.workdps(40):
        th = [float(mpmath.pi / 2 + mpmath.mpf(float(t))) for t in tilts]
    y[0] = np.repeat(th, len(rates))
    y[4] = np.tile(np.asarray(rates, float), len(tilts))
    return y


def bare_ensemble(model_name: str, states: np.ndarray, t_end: float, batch_size: int, threads: int):
    """A bare ``ensemble_propagate_until_batch`` of ``states`` (8, n) on the model's compiled system
    (double, defaults, tolerance epsilon, no events, no step cap, no dense output), padded to whole
    batches by repeating the last start; the batch integrator is built once, outside the timing.
    Returns run() -> (final states (8, n), lanes that did not reach t_end)."""
    model = get_model(model_name)
    prec = parse_precision("double")
    compiled = compile_model(model, prec)
    defaults = {p.name: float(sp.N(p.default)) for p in model.parameters}
    pars = compiled.parameter_vector(defaults)
    n = states.shape[1]
    padded = -(-n // batch_size) * batch_size
    lanes = np.ascontiguousarray(states[:, np.minimum(np.arange(padded), n - 1)])
    tb = hy.taylor_adaptive_batch(list(compiled.system), np.ascontiguousarray(lanes[:, :batch_size]),
                                  pars=np.ascontiguousarray(np.repeat(pars[:, None], batch_size, axis=1)))

    def gen(tc, b):
        tc.set_time(0.0)
        tc.state[:] = lanes[:, b * batch_size:(b + 1) * batch_size]
        return tc

    def run():
        res = hy.ensemble_propagate_until_batch(tb, t_end, padded // batch_size, gen, max_workers=threads)
        final = np.hstack([r[0].state for r in res])[:, :n]
        stopped = sum(o[0] != hy.taylor_outcome.time_limit for r in res for o in r[0].propagate_res)
        return final, int(stopped)

    return run


def ensemble_against_bare(quick: bool, progress, repeats: int = None) -> list:
    """The sweep engine (``run_chunk``) and the stability map against a bare batch ensemble of the
    same starts, interleaved; throughput ratio = bare seconds / suite seconds (target >= 0.8)."""
    from ..studies.maps import stability_map
    from ..sweep import SPECS, load
    from ..sweep.engine import run_chunk

    repeats = repeats or _size("ensemble_rounds", quick)
    threads = os.cpu_count() or 1
    bs = hy.recommended_simd_size()
    out = []

    def sweep_case(label, spec, chunks):
        indices = [i for c in chunks for i in spec.chunk_points(c)]
        starts = sweep_starts(spec, indices)
        bare = bare_ensemble(spec.model, starts, spec.t_end, bs, threads)
        run_chunk(spec, chunks[0], threads=threads, batch_size=bs)  # warm: compile, steady motions
        progress(f"  ensembles: {label}, {len(indices)} trajectories, {repeats} rounds")

        def suite():
            return [row for c in chunks for row in run_chunk(spec, c, threads=threads, batch_size=bs)]

        times, last = interleaved({"sweep engine (run_chunk)": suite, "bare ensemble_propagate_until_batch": bare},
                                  repeats)
        rows = last["sweep engine (run_chunk)"]
        final_theta = np.array([r["final_theta"] for r in rows]) if "final_theta" in spec.record else None
        rec = {"workload": label, "trajectories": len(indices), "t_end": spec.t_end, "samples": spec.samples,
               "batch_size": bs, "threads": threads, "chunks": list(chunks), "record": list(spec.record),
               "outcomes": _counts(r["outcome"] for r in rows), "bare_lanes_stopped": last[
                   "bare ensemble_propagate_until_batch"][1],
               "ratio": ratio_record(times, "sweep engine (run_chunk)", "bare ensemble_propagate_until_batch",
                                     TARGETS["ensemble_throughput"], inverse=True)}
        if final_theta is not None:
            rec["final_theta_difference"] = _g(float(np.nanmax(np.abs(final_theta - last[
                "bare ensemble_propagate_until_batch"][0][0]))))
        out.append(rec)

    def map_case(label, spin):
        n = _size("map_per_axis", quick)
        rates = np.array(spin.axes[0].values)[:: max(1, len(spin.axes[0].values) // n)][:n]
        tilts = np.array(spin.axes[1].values)[:: max(1, len(spin.axes[1].values) // n)][:n]
        smap = stability_map("disk", "diameter-spin", rates=rates[:2], tilts=tilts[:2])  # warm
        bare = bare_ensemble("disk", map_starts(rates, tilts), smap.t_end, smap.batch_size, smap.threads)
        progress(f"  ensembles: stability map, {len(rates) * len(tilts)} trajectories, {repeats} rounds")
        times, last = interleaved({"stability_map": lambda: stability_map("disk", "diameter-spin", rates=rates, tilts=tilts),
                                   "bare ensemble_propagate_until_batch": bare}, repeats)
        smap = last["stability_map"]
        out.append({"workload": label,
                    "trajectories": smap.n_trajectories, "t_end": smap.t_end, "samples": smap.n_samples,
                    "batch_size": smap.batch_size, "threads": smap.threads, "left": int(smap.left.sum()),
                    "bare_lanes_stopped": last["bare ensemble_propagate_until_batch"][1],
                    "map_propagation_seconds": _g(smap.wall_seconds),
                    "ratio": ratio_record(times, "stability_map", "bare ensemble_propagate_until_batch",
                                          TARGETS["ensemble_throughput"], inverse=True)})

    spin = load(SPECS / "disk-diameter-spin.toml")
    if quick:  # chunks of 40 points instead of 500
        spin_chunks = dataclasses.replace(spin, chunk=40)
        chunks = [0, spin_chunks.n_chunks // 2]
    else:
        spin_chunks, chunks = spin, [0, spin.n_chunks // 3, 2 * spin.n_chunks // 3]
    cases = [("benchmark grid (disk, theta x phidot x psidot)", sweep_case, (bench_sweep_spec(_size("sweep_per_axis", quick)), [0])),
             (f"disk-diameter-spin.toml, chunks {', '.join(map(str, chunks))} (spread over the rates)", sweep_case,
              (spin_chunks, chunks)),
             ("stability map, disk diameter spin (rates x tilts of disk-diameter-spin.toml)", map_case, (spin,))]
    for label, case, args in cases:
        try:
            case(label, *args)
        except Exception as err:  # a workload that fails is reported as failed; the others still run
            progress(f"  ensembles: {label} FAILED: {type(err).__name__}: {err}")
            out.append({"workload": label, "error": f"{type(err).__name__}: {err}"})
    return out


def _counts(values) -> dict:
    out = {}
    for v in values:
        out[v] = out.get(v, 0) + 1
    return dict(sorted(out.items()))
