"""The benchmark's logic and layout (no timing is asserted anywhere: the numbers are reported, not tested)."""
from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from verify.bench import (Attempt, TARGETS, bare_ensemble, bench_sweep_spec, interleaved, map_starts, ratio_record,
                          render_markdown, run_benchmarks, same_accuracy_speedup, solve_against_bare, sweep_starts,
                          write_benchmarks)
from verify.bench.markdown import _md_ensembles, _md_solve


def _a(method, setting, seconds, error):
    return Attempt(method, setting, seconds, error, 100, "1")


def test_same_accuracy_compares_the_slow_methods_best_with_the_fastest_run_at_least_as_accurate():
    attempts = [_a("heyoka double", "tol 1e-6", 0.001, 1e-7), _a("heyoka double", "tol 1e-9", 0.002, 1e-10),
                _a("heyoka double", "tol eps", 0.004, 1e-14), _a("scipy DOP853", "rtol=atol 1e-10", 0.5, 3e-9),
                _a("scipy DOP853", "rtol=atol 1e-13", 1.0, 2e-11)]
    sa = same_accuracy_speedup(attempts)
    assert sa["slow"]["setting"] == "rtol=atol 1e-13"
    assert sa["fast"]["setting"] == "tol eps"  # the only heyoka run at least as accurate as 2e-11
    assert sa["speedup"] == pytest.approx(250) and sa["accuracy_ratio_tightest"] == pytest.approx(2000)
    # negative control: if DOP853 were more accurate than every heyoka run, the tightest heyoka run is used
    worse = [a for a in attempts if a.method == "scipy DOP853"] + [_a("heyoka double", "tol 1e-6", 0.001, 1e-7)]
    assert same_accuracy_speedup(worse)["fast"]["setting"] == "tol 1e-6"


def test_interleaved_runs_every_variant_once_a_round_and_rotates_the_order():
    calls = []
    runs = {name: (lambda name=name: calls.append(name) or name) for name in ("a", "b", "c")}
    times, last = interleaved(runs, 4)
    assert calls == ["a", "b", "c", "b", "c", "a", "c", "a", "b", "a", "b", "c"]
    assert {k: len(v) for k, v in times.items()} == {"a": 4, "b": 4, "c": 4} and last == {"a": "a", "b": "b", "c": "c"}


def test_ratio_record_is_the_ratio_of_the_minima_with_the_per_round_spread():
    times = {"suite": [3.0, 2.0, 4.0], "bare": [1.0, 1.6, 2.0]}
    rec = ratio_record(times, "suite", "bare", ("<=", 1.25))
    assert rec["ratio"] == 2.0 and rec["median_round_ratio"] == 2.0 and rec["round_ratio_range"] == [1.25, 3.0]
    assert rec["target"] == "<= 1.25" and rec["met"] is False
    thru = ratio_record(times, "suite", "bare", (">=", 0.5), inverse=True)  # trajectories per second relative to bare
    assert thru["ratio"] == 0.5 and thru["met"] is True and thru["kind"] == "throughput"
    assert "met" not in ratio_record(times, "suite", "bare")  # no target, no verdict


def test_the_benchmark_grid_and_the_diameter_spin_starts_are_the_suites_starts():
    spec = bench_sweep_spec(2)
    y = sweep_starts(spec, range(spec.n_points))
    assert y.shape == (8, 8) and set(y[0]) == {1.0, 1.4} and set(y[4]) == {-2.0, 2.0} and set(y[5]) == {5.0, 15.0}
    assert not y[[1, 2, 3, 6, 7]].any()
    # the map: tilt-major, theta = pi/2 + tilt rounded once, phidot = the rate
    starts = map_starts([14.0, 42.0], [1e-6, 0.1])
    assert starts[4].tolist() == [14.0, 42.0, 14.0, 42.0]
    assert starts[0, 2] == starts[0, 3] == pytest.approx(math.pi / 2 + 0.1, abs=1e-15) and starts[0, 0] > math.pi / 2


def test_bare_ensemble_pads_to_whole_batches_and_reports_every_start():
    spec = bench_sweep_spec(2)
    y = sweep_starts(spec, range(5))  # 5 starts: not a whole number of batches
    final, stopped = bare_ensemble("disk", y, 0.05, 4, 1)()
    assert final.shape == (8, 5) and stopped == 0 and np.isfinite(final).all()
    assert not np.array_equal(final, y)  # it moved


def test_solve_against_bare_names_every_ratio_with_its_baseline_and_target():
    cases = solve_against_bare("disk", ("0.05",), "double", repeats=1)
    (case,) = cases
    assert case["outcome_solve"] == "ok" and case["outcome_bare"].endswith("time_limit")
    assert case["final_state_difference"] < 1e-12  # the same trajectory, not just the same time
    pairs = {(r["measured"], r["baseline"]): r for r in case["ratios"]}
    assert pairs[("solve", "bare propagate_until + events")]["target"] == "<= {:g}".format(TARGETS["solve"][1])
    assert pairs[("solve, invariants read", "bare propagate_until + events")]["target"] == "<= 1.5"
    assert "target" not in pairs[("solve", "bare propagate_until")]
    text = "\n".join(_md_solve({"solve_vs_bare": cases}))
    rows = [ln for ln in text.splitlines() if ln.startswith("| solve")]
    assert len(rows) == 6 and sum("bare propagate_until" in ln for ln in rows) == 5
    assert sum("<= 1.25: " in ln for ln in rows) == 1 and sum("<= 1.5: " in ln for ln in rows) == 1
    # the outside baseline (Eq. 18 by hand, no events) at t_end <= 1 s, and the decomposition sizes
    hand = pairs[("solve", "bare hand-written Eq. 18, no events")]
    assert hand["target"] == "<= 2" and sum("<= 2: " in ln for ln in rows) == 1
    terms = case["decomposition_terms"]
    assert terms["hand_written_eq18"] < terms["system"] < terms["system_and_events"]
    assert "Decomposition terms: system " in text
    # the angle-reducing baseline: steps comparable with solve's, its per-step ratio and the overhead named
    assert case["steps_bare_events_reduced"] > 0 and case["per_step_ratio_vs_bare_events_reduced"] > 0
    assert "per-step ratio against it" in text and "per-call overhead" in text


def test_a_workload_that_failed_is_shown_as_failed_not_left_out():
    text = "\n".join(_md_ensembles({"ensembles_vs_bare": [{"workload": "stability map", "error": "ImportError: x"}]}))
    (row,) = [ln for ln in text.splitlines() if ln.startswith("| stability map")]
    assert "failed: ImportError: x" in row and "met" not in row


def _skeleton(markdown: str) -> list:
    """The layout of BENCHMARKS.md with every number taken out."""
    lines = [re.sub(r"-?\d[\d,.]*(e[+-]?\d+)?", "#", ln) for ln in markdown.splitlines()]
    return [re.sub(r"NOT met|undecided \(interval spans it\)|met", "VERDICT", ln) for ln in lines]


def _scaled(obj, factor):
    if isinstance(obj, bool):
        return obj
    if isinstance(obj, float):
        return obj * factor
    if isinstance(obj, dict):
        return {k: _scaled(v, factor) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_scaled(v, factor) for v in obj]
    return obj


@pytest.mark.slow
def test_quick_benchmark_runs_and_writes_its_files(tmp_path):
    """The whole benchmark at quick sizes (about a minute), written to a temporary folder."""
    results = run_benchmarks(quick=True)
    write_benchmarks(results, tmp_path)
    data = json.loads((tmp_path / "benchmarks.json").read_text())
    assert [c.get("error") for c in data["ensembles_vs_bare"]] == [None] * 3  # every workload ran
    assert data["call_paths"]["same_bytes"]  # every path integrates the same bits
    assert [c["precision"] for c in data["solve_vs_bare"]] == ["double", "double", "quad"]
    assert data["energy"]["starts"] == len(data["energy"]["exponent_per_start"]["suite"])
    methods = {a["method"] for a in data["work_precision"]["attempts"]}
    assert {"heyoka double", "heyoka long", "heyoka quad", "scipy DOP853", "scipy LSODA", "scipy Radau"} <= methods
    eps_run = next(a for a in data["work_precision"]["attempts"] if a["setting"] == "tol eps" and a["method"] == "heyoka double")
    loose = next(a for a in data["work_precision"]["attempts"] if a["setting"] == "rtol=atol 1e-06")
    assert eps_run["error"] < loose["error"]  # accuracy, not time
    for system in data["sweep"]["systems"].values():
        assert system["max_difference_to_loop"]["ensemble"] == 0.0  # same integrator, same bits
    by_tol = data["sweep"]["tolerances"]
    assert [t["tol"] for t in by_tol] == ["eps", "1e-12", "1e-09", "1e-06"]
    assert by_tol[0]["max_difference_to_eps"] == 0.0 < by_tol[-1]["max_difference_to_eps"]
    md = (tmp_path / "BENCHMARKS.md").read_text()
    assert md.startswith("# Benchmarks")
    assert [ln for ln in md.splitlines() if ln.startswith("## ")] == [
        "## Targets", "## solve against bare heyoka", "## The sweep engine and the stability map against a bare ensemble",
        "## Call paths", "## Long-run energy error", "## heyoka's own modes on the benchmark grid", "## Work against precision",
        "## Compile cost", "## Body files", "## The command line"]
    # the layout does not depend on the numbers
    assert _skeleton(render_markdown(_scaled(data, 1.37))) == _skeleton(md)
    assert (tmp_path / "figures" / "bench-work-precision.png").read_bytes()[:4] == b"\x89PNG"


def test_the_compile_cost_script_runs_in_a_fresh_process():
    """The script is a string run by ``python -c``: nothing else checks that its names are defined
    (a refactoring once dropped its imports and only the full benchmark found out)."""
    import json
    import subprocess
    import sys
    from pathlib import Path

    from verify.bench.compile_cost import _COMPILE_SCRIPT

    root = Path(__file__).resolve().parents[1]
    res = subprocess.run([sys.executable, "-c", _COMPILE_SCRIPT, json.dumps([])], cwd=root,
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr[-2000:]


def test_the_body_derivation_script_runs_in_a_fresh_process_and_leaves_its_cache(tmp_path):
    """The body files' derivation script (a string run by ``python -c``: nothing else checks its names) runs
    twice in fresh processes, and the first leaves the derivation in the given cache folder for the second
    (what the benchmark's 'warm cache' column times; times are the benchmark's, not a test's)."""
    import json
    import os
    import subprocess
    import sys
    from pathlib import Path

    from verify.bench.bodies import _DERIVE_SCRIPT

    root = Path(__file__).resolve().parents[1]
    env = dict(os.environ, HEYOKA_CACHE_DIR=str(tmp_path), PYTHONPATH=str(root))
    for _ in range(2):
        res = subprocess.run([sys.executable, "-c", _DERIVE_SCRIPT, json.dumps(["tippe-top"])], cwd=root, env=env,
                             capture_output=True, text=True, timeout=300)
        assert res.returncode == 0, res.stderr[-2000:]
        assert json.loads(res.stdout.strip().splitlines()[-1])["tippe-top"] > 0
    assert any((tmp_path / "bodies").iterdir())  # the derivation was cached in the given folder


def test_the_report_names_the_latest_benchmark_run_and_does_not_run_one():
    import inspect

    from verify.report.markdown import benchmarks_section
    from verify.report.write import write_report

    assert "bench" not in inspect.signature(write_report).parameters
    assert "No benchmark run" in "\n".join(benchmarks_section(None))
    run = {"date": "2026-11-24 16:00 UTC", "sources": {"commit": "0123456789abcdef", "modified": False},
           "machine": {"cpu": "AMD EPYC", "cpus": 2, "simd_size": 4, "heyoka": "7.13.2"}}
    text = "\n".join(benchmarks_section(run))
    assert "2026-11-24 16:00 UTC" in text and "0123456789ab" in text and "AMD EPYC" in text
    assert "No benchmark run" not in text


def test_ensemble_rows_name_the_same_guard_yardstick_and_each_guards_cost():
    """The batch rows compare with the bare ensemble that has the suite's events and step cap (target), show
    the ratio to the plain bare ensemble beside it, and list what each guard costs."""
    times = {"suite": [1.0, 1.1], "bare, same events and step cap": [0.95, 1.0], "bare, no events, no step cap": [0.7, 0.72],
             "bare, same events and step cap, output grid": [1.25, 1.3]}
    case = {"workload": "w", "trajectories": 100, "samples": 11, "batch_size": 4, "threads": 2, "step_cap": 0.03,
            "bare_lanes_stopped": {"bare, same events and step cap": 0}, "outcomes": {"ok": 100},
            "ratio": ratio_record(times, "suite", "bare, same events and step cap", TARGETS["ensemble_throughput"],
                                  inverse=True),
            "ratio_no_guards": ratio_record(times, "suite", "bare, no events, no step cap", inverse=True),
            "ratio_same_output": ratio_record(times, "suite", "bare, same events and step cap, output grid",
                                              inverse=True),
            "guards": [{"variant": "bare + step cap only", "throughput_vs_plain": 0.8}]}
    assert TARGETS["ensemble_throughput"] == (">=", 0.9)
    text = "\n".join(_md_ensembles({"ensembles_vs_bare": [case]}))
    (row,) = [ln for ln in text.splitlines() if ln.startswith("| w | 100")]
    assert ">= 0.9: met" in row and "| 0.7 | 1.25 |" in row  # 0.95/1.0 met; 0.7/1.0 and 1.25/1.0 beside it
    assert "| w | bare + step cap only | 0.8 |" in text
