"""The sweep engine and the stability map against bare batch ensembles of the same starts: the yardstick with
the suite's events and step cap, the plain ensemble without them, and what each guard costs."""
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

from ..engine.batch import pad_lanes
from ..engine.compile import compile_model
from ..engine.lanes import compile_lanes
from ..precision import parse_precision
from ..studies.maps import prepare_runs, stability_map
from ..sweep import SPECS, load, parse
from ..sweep.engine import ensemble_of, fastest_rate, lane_inputs, run_chunk
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


def bare_lanes(ens, form_kwargs: dict, states, values: dict, end, threads: int, max_delta_t=None, events=None):
    """heyoka's own ensemble on the lane system of ``ens`` made bare (:func:`verify.engine.lanes.compile_lanes`
    with ``bare``: no ``alive`` factor, the events' callback freezes nothing), only the ``events`` named
    (None: all), no Python per lane.  ``end``: t_end (``ensemble_propagate_until_batch``) or an output grid
    (``ensemble_propagate_grid_batch``).  Returns run() -> lanes that did not reach the end."""
    lanes = compile_lanes(ens.model, ens.form, ens.batch_size, ens.cooldown, bare=True, events=events, **form_kwargs)
    tb, bs = lanes.template, ens.batch_size
    n = states.shape[1]
    pad = pad_lanes(n, bs)
    lane_states = np.ascontiguousarray(states[:, pad])
    # heyoka sizes a bare system's parameters by the highest it reads: only those are laid out (by name)
    pars = lanes.layout.columns(len(pad), {k: (v[pad] if np.ndim(v) else v) for k, v in values.items()
                                           if k in lanes.layout})
    options = {} if max_delta_t is None else {"max_delta_t": max_delta_t}

    def gen(tc, b):
        tc.set_time(0.0)
        if tc.with_events:
            tc.reset_cooldowns()
        tc.state[:] = lane_states[:, b * bs:(b + 1) * bs]
        tc.pars[:] = pars[:, b * bs:(b + 1) * bs]
        return tc

    def run():
        if np.ndim(end):
            res = hy.ensemble_propagate_grid_batch(tb, np.asarray(end, float), len(pad) // bs, gen,
                                                   max_workers=threads, **options)
        else:
            res = hy.ensemble_propagate_until_batch(tb, float(end), len(pad) // bs, gen, max_workers=threads,
                                                    **options)
        return int(sum(o[0] != hy.taylor_outcome.time_limit for r in res for o in r[0].propagate_res))

    return run


#: The suite's route and its yardstick in every workload's record.
SUITE, SAME, PLAIN = "suite", "bare, same events and step cap", "bare, no events, no step cap"
#: The yardstick with the suite's dense output on its grid too (heyoka's ``ensemble_propagate_grid_batch``).
SAME_OUTPUT = "bare, same events and step cap, output grid"


def guard_variants(ens, form_kwargs, states, values, t_end, grid, threads, cap) -> dict:
    """Bare ensembles that add the suite's guards one at a time (name -> run()): the yardstick with every
    event and the step cap (:data:`SAME`), the plain ensemble without them (:data:`PLAIN`), each event alone,
    the step cap alone, and the yardstick with the dense output on the suite's grid."""
    variants = {SAME: bare_lanes(ens, form_kwargs, states, values, t_end, threads, cap),
                PLAIN: bare_lanes(ens, form_kwargs, states, values, t_end, threads, None, events=())}
    if cap is not None:
        variants["bare + step cap only"] = bare_lanes(ens, form_kwargs, states, values, t_end, threads, cap, events=())
    for name in dict.fromkeys(ens.lanes.events):  # the domain's two ends share a name: one guard
        variants[f"bare + event {name} only"] = bare_lanes(ens, form_kwargs, states, values, t_end, threads, None,
                                                          events=(name,))
    variants[SAME_OUTPUT] = bare_lanes(ens, form_kwargs, states, values, grid,
                                                                        threads, cap)
    return variants


def guard_costs(times: dict) -> list:
    """Each guard's throughput relative to the plain bare ensemble (medians of the rounds; < 1: it costs)."""
    plain = float(np.median(times[PLAIN]))
    return [{"variant": k, "throughput_vs_plain": _g(plain / float(np.median(v)))} for k, v in times.items()
            if k not in (PLAIN,)]


def ensemble_against_bare(quick: bool, progress, repeats: int = None) -> list:
    """The sweep engine (``run_chunk``) and the stability map against bare batch ensembles of the same starts,
    interleaved.  The yardstick (target >= 0.9 of its throughput) has the suite's events and step cap: the
    guards are correctness; beside it, the ratio to a plain ensemble without them and the cost of each guard."""
    repeats = repeats or _size("ensemble_rounds", quick)
    threads = os.cpu_count() or 1
    bs = hy.recommended_simd_size()
    out = []

    def record(label, times, last, n, extra):
        rec = {"workload": label, "trajectories": n, **extra,
               "bare_lanes_stopped": {k: v for k, v in last.items() if k != SUITE},
               "ratio": ratio_record(times, SUITE, SAME, TARGETS["ensemble_throughput"], inverse=True),
               "ratio_no_guards": ratio_record(times, SUITE, PLAIN, inverse=True),
               "ratio_same_output": ratio_record(times, SUITE, SAME_OUTPUT, inverse=True),
               "guards": guard_costs({k: v for k, v in times.items() if k != SUITE})}
        out.append(rec)

    def sweep_case(label, spec, chunks):
        indices = np.array([i for c in chunks for i in spec.chunk_points(c)])
        ens = ensemble_of(spec, bs)
        states, model_pars, _ = lane_inputs(spec, indices)
        values = {**ens.model_values(model_pars), "theta_max": float(ens.model.domain.theta_max)}
        form = {"stop": spec.theta_stop is not None, "friction": spec.slips}
        if spec.theta_stop is not None:
            values = {**ens.model_values(model_pars), "theta_stop": spec.theta_stop}
        grid = np.linspace(0.0, spec.t_end, spec.samples)
        cap = 1.0 / fastest_rate(spec, ens)
        runs = {SUITE: lambda: [row for c in chunks for row in run_chunk(spec, c, threads=threads, batch_size=bs)],
                **guard_variants(ens, form, states, values, spec.t_end, grid, threads, cap)}
        for run in runs.values():
            run()  # warm: compile, steady motions
        progress(f"  ensembles: {label}, {len(indices)} trajectories, {len(runs)} routes, {repeats} rounds")
        times, last = interleaved(runs, repeats)
        rows = last.pop(SUITE)
        record(label, times, last, len(indices), {
            "t_end": spec.t_end, "samples": spec.samples, "batch_size": bs, "threads": threads, "chunks": list(chunks),
            "record": list(spec.record), "step_cap": _g(cap), "outcomes": _counts(r["outcome"] for r in rows)})

    def map_case(label, spin):
        n = _size("map_per_axis", quick)
        rates = np.array(spin.axes[0].values)[:: max(1, len(spin.axes[0].values) // n)][:n]
        tilts = np.array(spin.axes[1].values)[:: max(1, len(spin.axes[1].values) // n)][:n]
        smap = stability_map("disk", "diameter-spin", rates=rates[:2], tilts=tilts[:2])  # warm
        runs_in = prepare_runs("disk", "diameter-spin", rates, tilts, smap.t_end, {}, smap.cap, False, smap.batch_size)
        ens, k = runs_in.ensemble, runs_in.n
        names = (*ens.model.parameter_names, "theta_lower", "theta_upper")
        values = {name: ens.record(runs_in.pars, name)[:k] for name in names}
        states = runs_in.states[:, :k]
        runs = {SUITE: lambda: stability_map("disk", "diameter-spin", rates=rates, tilts=tilts),
                **guard_variants(ens, {}, states, values, smap.t_end, runs_in.grid, smap.threads, None)}
        for run in list(runs.values())[1:]:
            run()
        progress(f"  ensembles: stability map, {k} trajectories, {len(runs)} routes, {repeats} rounds")
        times, last = interleaved(runs, repeats)
        smap = last.pop(SUITE)
        record(label, times, last, smap.n_trajectories, {
            "t_end": smap.t_end, "samples": smap.n_samples, "batch_size": smap.batch_size, "threads": smap.threads,
            "step_cap": None, "left": int(smap.left.sum()), "map_propagation_seconds": _g(smap.wall_seconds)})

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
