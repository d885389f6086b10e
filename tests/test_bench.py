"""The benchmark's logic (no timing is asserted anywhere: the numbers are reported, not tested)."""
from __future__ import annotations

import json

import pytest

from verify.bench import Attempt, render_markdown, run_benchmarks, same_accuracy_speedup, write_benchmarks


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


@pytest.mark.slow
def test_quick_benchmark_runs_and_writes_its_files(tmp_path):
    """The whole benchmark at quick sizes (about a minute), written to a temporary folder."""
    results = run_benchmarks(quick=True)
    write_benchmarks(results, tmp_path)
    data = json.loads((tmp_path / "benchmarks.json").read_text())
    methods = {a["method"] for a in data["work_precision"]["attempts"]}
    assert {"heyoka double", "heyoka long", "heyoka quad", "scipy DOP853", "scipy LSODA", "scipy Radau"} <= methods
    assert any(a["method"] == "mpmath odefun" for a in data["work_precision"]["short"])
    eps_run = next(a for a in data["work_precision"]["attempts"] if a["setting"] == "tol eps" and a["method"] == "heyoka double")
    loose = next(a for a in data["work_precision"]["attempts"] if a["setting"] == "rtol=atol 1e-06")
    assert eps_run["error"] < loose["error"]  # accuracy, not time
    for system in data["sweep"]["systems"].values():
        assert system["max_difference_to_loop"]["ensemble"] == 0.0  # same integrator, same bits
    by_tol = data["sweep"]["tolerances"]
    assert [t["tol"] for t in by_tol] == ["eps", "1e-12", "1e-09", "1e-06"]
    assert by_tol[0]["max_difference_to_eps"] == 0.0 < by_tol[-1]["max_difference_to_eps"]
    assert by_tol[-1]["order"] < by_tol[0]["order"]
    assert (tmp_path / "BENCHMARKS.md").read_text().startswith("# Benchmarks")
    assert (tmp_path / "figures" / "bench-work-precision.png").read_bytes()[:4] == b"\x89PNG"
    assert "Machine:" in render_markdown(data)
