"""Every benchmark in one run (:func:`run_benchmarks`) and the one writer of its files (:func:`write_benchmarks`)."""
from __future__ import annotations

import datetime
import json
import os
import platform
import time
from pathlib import Path

import heyoka as hy

from ..provenance import cpu_model, source_commit, write_atomic
from .commands import command_speed
from .bodies import body_cost
from .call_paths import call_path_cost
from .compile_cost import compile_cost
from .energy import energy_growth
from .ensembles import ensemble_against_bare
from .figures import render_energy, render_work_precision
from .markdown import render_markdown
from .modes import sweep_throughput
from .sizes import TARGETS, _size
from .solve_vs_bare import solve_against_bare
from .work_precision import same_accuracy_speedup, work_precision


def machine() -> dict:
    info = {"platform": platform.platform(), "processor": platform.machine(), "cpus": os.cpu_count(),
            "python": platform.python_version(), "heyoka": hy.__version__,
            "simd_size": hy.recommended_simd_size(), "cpu": cpu_model()}
    return info


def run_benchmarks(quick: bool = False, progress=None) -> dict:
    t0 = time.monotonic()

    def say(text):
        if progress:
            progress(f"{text} [{time.monotonic() - t0:.0f} s]")

    results = {"machine": machine(), "quick": quick,
               "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
               "sources": source_commit(), "targets": {k: f"{op} {v:g}" for k, (op, v) in TARGETS.items()},
               "load_average_start": [round(v, 2) for v in os.getloadavg()]}
    results["solve_vs_bare"] = (solve_against_bare("disk", _size("solve_t_ends", quick), "double",
                                                   _size("solve_rounds", quick), progress=say)
                                + solve_against_bare("disk", (_size("quad_t_end", quick),), "quad",
                                                     _size("quad_rounds", quick), invariants=False, progress=say))
    results["ensembles_vs_bare"] = ensemble_against_bare(quick, say)
    results["call_paths"] = call_path_cost(quick, say)
    results["energy"] = energy_growth(quick, say)
    results["sweep"] = sweep_throughput(quick, say)
    wp = work_precision(quick, say)
    results["work_precision"] = {**{k: v for k, v in wp.items() if k not in ("attempts", "short", "long")},
                                 "attempts": [a.to_record() for a in wp["attempts"]],
                                 "short": [a.to_record() for a in wp["short"]],
                                 "long": [a.to_record() for a in wp["long"]],
                                 "same_accuracy": same_accuracy_speedup(wp["attempts"]),
                                 "same_accuracy_long": same_accuracy_speedup(wp["long"]) if wp["long"] else {}}
    results["compile"] = compile_cost(quick, say)
    results["bodies"] = body_cost(quick, say)
    results["commands"] = command_speed(quick, say)
    results["load_average_end"] = [round(v, 2) for v in os.getloadavg()]
    results["wall_seconds"] = round(time.monotonic() - t0, 1)
    return results


def write_benchmarks(results: dict, out: Path) -> None:
    out = Path(out)
    # everything is rendered before the first file is replaced: a rendering error leaves the old set whole
    files = {Path("figures") / "bench-work-precision.png": render_work_precision(results),
             Path("figures") / "bench-energy.png": render_energy(results),
             Path("benchmarks.json"): json.dumps(results, indent=2) + "\n",
             Path("BENCHMARKS.md"): render_markdown(results)}
    for name, data in files.items():
        write_atomic(out / name, data)
