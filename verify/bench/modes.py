"""heyoka's own modes on the benchmark grid: a loop, batch lanes and ensembles, full and reduced system, looser tolerances."""
from __future__ import annotations

import os

import heyoka as hy
import numpy as np
import sympy as sp

from models import get_model

from ..engine.compile import compile_model
from ..precision import parse_precision
from .ensembles import bench_sweep_spec, sweep_starts
from .sizes import _size
from .timing import _timed

REDUCED = (0, 3, 4, 5)  # theta, thetadot, phidot, psidot: their right-hand sides use no other state


def sweep_throughput(quick: bool, progress) -> dict:
    """Trajectories per second of heyoka's own modes on the benchmark grid (:func:`bench_sweep_spec`):
    the full 8-dimensional system and the reduced one (the compiled system's equations of theta,
    thetadot, phidot, psidot, which use no other state: all a stability sweep needs), by a loop of one
    reused integrator, batch lanes and ensembles on threads; then the best mode at looser tolerances."""
    spec = bench_sweep_spec(_size("sweep_per_axis", quick))
    n, T = spec.n_points, float(spec.t_end)
    model = get_model("disk")
    prec = parse_precision("double")
    compiled = compile_model(model, prec)
    pars = compiled.parameter_vector({p.name: float(sp.N(p.default)) for p in model.parameters})
    ys = sweep_starts(spec, range(n))
    reduced = [compiled.system[i] for i in REDUCED]
    out = {"trajectories": n, "t_end": T, "threads": os.cpu_count() or 1, "systems": {}}
    for label, system, states in (("full 8-dim", list(compiled.system), ys), ("reduced 4-dim", reduced, ys[list(REDUCED)])):
        progress(f"  heyoka's modes: {n} trajectories of {T:g} s, {label}")
        out["systems"][label] = _throughput(system, np.ascontiguousarray(pars), np.ascontiguousarray(states), T)
    progress("  heyoka's modes: the reduced system at looser tolerances")
    out["tolerances"] = _throughput_by_tolerance(reduced, np.ascontiguousarray(pars),
                                                 np.ascontiguousarray(ys[list(REDUCED)]), T)
    return out


def _batch_integrator(system, pars, ys, bs: int, **kwargs):
    """A batch integrator of ``bs`` lanes for ``system``, every lane with the parameters ``pars``."""
    return hy.taylor_adaptive_batch(system, np.ascontiguousarray(ys[:, :bs]),
                                    pars=np.ascontiguousarray(np.repeat(pars[:, None], bs, axis=1)), **kwargs)


def _ensemble_of_batches(tb, ys, T: float) -> tuple:
    """(seconds, final states) of every whole batch of the columns of ``ys`` to time T, batches on threads."""
    bs = tb.batch_size
    m = ys.shape[1] // bs

    def gen(tc, b):
        tc.set_time(0.0)
        tc.state[:] = ys[:, b * bs:(b + 1) * bs]
        return tc

    seconds, res = _timed(lambda: hy.ensemble_propagate_until_batch(tb, T, m, gen), 1)
    return seconds, np.hstack([r[0].state for r in res])


def _throughput_by_tolerance(system, pars, ys, T: float, tolerances=(None, 1e-12, 1e-9, 1e-6)) -> list:
    """The best mode (batch lanes in an ensemble) at looser tolerances: what the issue's 3,000/s would
    cost in accuracy. Each row's error is the largest final-state difference to the run at eps."""
    bs = hy.recommended_simd_size()
    rows, at_eps = [], None
    for tol in tolerances:
        tb = _batch_integrator(system, pars, ys, bs, **({} if tol is None else {"tol": tol}))
        seconds, final = _ensemble_of_batches(tb, ys, T)
        at_eps = final if at_eps is None else at_eps
        rows.append({"tol": "eps" if tol is None else f"{tol:g}", "order": int(tb.order), "lanes": bs,
                     "per_second": float(f"{final.shape[1] / seconds:.4g}"),
                     "max_difference_to_eps": float(f"{np.max(np.abs(final - at_eps)):.2e}")})
    return rows


def _throughput(system, pars, ys, T: float) -> dict:
    n = ys.shape[1]
    results, agree, finals = {}, {}, {}
    ta = hy.taylor_adaptive(system, ys[:, 0], pars=pars)

    def loop():
        out = np.empty_like(ys)
        for i in range(n):
            ta.time = 0.0
            ta.state[:] = ys[:, i]
            ta.propagate_until(T)
            out[:, i] = ta.state
        return out

    results["loop"], ref = _timed(loop, 1)

    def gen_scalar(tc, i):
        tc.time = 0.0
        tc.state[:] = ys[:, i]
        return tc

    results["ensemble"], ens = _timed(lambda: hy.ensemble_propagate_until(ta, T, n, gen_scalar), 1)
    finals["ensemble"] = np.array([r[0].state for r in ens]).T
    for bs in sorted({hy.recommended_simd_size(), 2 * hy.recommended_simd_size()}):
        m = n // bs
        tb = _batch_integrator(system, pars, ys, bs)

        def batch_loop():
            out = np.empty_like(ys[:, : m * bs])
            for b in range(m):
                tb.set_time(0.0)
                tb.state[:] = ys[:, b * bs:(b + 1) * bs]
                tb.propagate_until(T)
                out[:, b * bs:(b + 1) * bs] = tb.state
            return out

        results[f"batch{bs}"], finals[f"batch{bs}"] = _timed(batch_loop, 1)
        results[f"ensemble_batch{bs}"], finals[f"ensemble_batch{bs}"] = _ensemble_of_batches(tb, ys, T)
    for name, fin in finals.items():
        agree[name] = float(np.max(np.abs(fin - ref[:, : fin.shape[1]])))
    per_second = {}
    for name, sec in results.items():
        bs = int(name.rsplit("batch", 1)[1]) if "batch" in name else 1
        per_second[name] = (n // bs) * bs / sec
    return {"seconds": {k2: float(f"{v:.4g}") for k2, v in results.items()},
            "per_second": {k2: float(f"{v:.4g}") for k2, v in per_second.items()},
            "ratio_to_loop": {k2: float(f"{v / per_second['loop']:.3g}") for k2, v in per_second.items()},
            "max_difference_to_loop": {k2: float(f"{v:.2e}") for k2, v in agree.items()}}
