"""Benchmarks: the suite against bare heyoka, long-run energy error, accuracy for the time spent, JIT cost.

``python -m verify bench`` (``make bench``; the report does not re-run it) measures, in
one run, and writes ``reports/BENCHMARKS.md``, ``reports/benchmarks.json`` and two figures.
The machines are shared and noisy, so speed is reported as *ratios measured in the same run*
against bare heyoka doing the same work on the same compiled equations
(``compile_model(model, precision).system``), same starts, same tolerance, in interleaved
rounds (:func:`interleaved`: every variant once a round, the order rotated from round to
round), seconds taken as the minimum over the rounds and the ratio as the ratio of the minima,
with the median and range of the per-round ratios beside it.  Nothing here passes or fails: the
targets (:data:`TARGETS`) are printed beside the ratios.

* **solve against bare heyoka** (:func:`solve_against_bare`).  ``verify.solve`` with default
  settings from the disk's standard state, t_end 1, 10 and 100 s in double and 10 s in quad,
  against ``taylor_adaptive.propagate_until`` built once and reset, without events and with the
  events solve compiles; and solve with every invariant read.
* **The sweep engine and the stability map against a bare ensemble**
  (:func:`ensemble_against_bare`).  ``verify.sweep.engine.run_chunk`` on the benchmark grid
  (:func:`bench_sweep_spec`) and on chunks of ``disk-diameter-spin.toml``, and
  ``verify.studies.maps.stability_map`` on that spec's rates and tilts, against
  ``ensemble_propagate_until_batch`` of the same starts: trajectories per second, relative.
* **Long-run energy error** (:func:`energy_growth`).  32 starts, ~2.4e5 Taylor steps each (fewer
  steps than the former 8 starts x 1e6, for the same time: the spread over the starts is what
  decides), by solve, solve in high-accuracy mode and plain heyoka; the exponent of t^a with a
  bootstrap interval and the per-start exponents' median and quartiles.
* **heyoka's own modes** on the benchmark grid (loop, batch lanes, ensembles; full and reduced
  system; looser tolerances): what the engines can build on.
* **Work against precision.**  The final state of a reference case (agreeing digits, see
  :mod:`verify.reference`) by heyoka at double (several tolerances), long, quad and MPFR, by
  scipy's ``solve_ivp`` (DOP853, Radau, LSODA; right-hand side and Jacobian compiled by heyoka's
  ``cfunc``, so only the integrator differs), and by mpmath's ``odefun`` on a short run.
* **Compile cost.**  Fresh processes with an empty heyoka disk cache, then again with the cache
  it left, for the disk at double (default and compact mode), quad and MPFR.
"""
from __future__ import annotations

from .compile_cost import COMPILE_CASES, compile_cost
from .energy import ENERGY_LABELS, energy_growth, energy_starts
from .ensembles import BENCH_SWEEP_TOML, bare_ensemble, bench_sweep_spec, ensemble_against_bare, map_starts, sweep_starts
from .figures import render_energy, render_work_precision
from .markdown import render_markdown
from .modes import REDUCED, sweep_throughput
from .sizes import SIZES, TARGETS
from .solve_vs_bare import solve_against_bare
from .suite import machine, run_benchmarks, write_benchmarks
from .timing import interleaved, ratio_record
from .work_precision import (LONG_CASE, ODEFUN_GRID_INDEX, WORK_CASE, Attempt, ReferenceProblem, heyoka_attempt,
                             odefun_attempts, same_accuracy_speedup, scipy_attempts, work_precision)

__all__ = ["BENCH_SWEEP_TOML", "COMPILE_CASES", "ENERGY_LABELS", "LONG_CASE", "ODEFUN_GRID_INDEX", "REDUCED", "SIZES",
           "TARGETS", "WORK_CASE", "Attempt", "ReferenceProblem", "bare_ensemble", "bench_sweep_spec", "compile_cost",
           "energy_growth", "energy_starts", "ensemble_against_bare", "heyoka_attempt", "interleaved", "machine",
           "map_starts", "odefun_attempts", "ratio_record", "render_energy", "render_markdown", "render_work_precision",
           "run_benchmarks", "same_accuracy_speedup", "scipy_attempts", "solve_against_bare", "sweep_starts",
           "sweep_throughput", "work_precision", "write_benchmarks"]
