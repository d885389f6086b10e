"""The report pipeline: job keys, the cache, the job queue (failures, resuming), results.json from outcomes."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from verify.report import dependencies
from verify.report.cache import JobCache
from verify.report.figures import Image
from verify.report.jobs import Job, JobOutput, registry
from verify.report.runner import key_of, run_jobs



def job_ok(n):
    return JobOutput({"n": n, "square": n * n}, [Image(f"fig-{n}.png", bytes([n]) * 8, f"figure {n}")], {"inner": 0.1})


def job_fails(n):
    raise ArithmeticError(f"job {n} broke")


def job_counted(marker):
    """Appends to ``marker`` each time it really runs (to tell computed from cached)."""
    with open(marker, "a") as f:
        f.write("x")
    return JobOutput({"marker": marker})


def _job(name, function, *args, files=()):
    return Job(name, f"tests.test_report_pipeline:{function}", args, ("verify.report.markup",), files)


def test_queue_computes_caches_and_records_failures_without_losing_the_others(tmp_path):
    cache = JobCache(tmp_path / "cache")
    jobs = [_job("a", "job_ok", 2), _job("b", "job_fails", 3), _job("c", "job_ok", 4)]
    lines = []
    out = run_jobs(jobs, cache, workers=2, say=lines.append)
    assert [o.status for o in out.values()] == ["computed", "failed", "computed"]
    assert out["a"].data == {"n": 2, "square": 4} and out["c"].images[0].alt == "figure 4"
    assert "ArithmeticError: job 3 broke" in out["b"].error
    assert sum("FAILED" in line for line in lines) == 1 and "1 failed" in lines[-1]
    again = run_jobs(jobs, cache, workers=1, say=lines.append)
    assert [o.status for o in again.values()] == ["cached", "failed", "cached"]  # a failure is never cached
    assert again["a"].data == out["a"].data and again["c"].images == out["c"].images


def test_an_interrupted_run_resumes_and_fresh_recomputes(tmp_path):
    marker = str(tmp_path / "calls")
    cache = JobCache(tmp_path / "cache")
    jobs = [_job("counted", "job_counted", marker)]
    run_jobs(jobs, cache, workers=1, say=lambda s: None)
    run_jobs(jobs + [_job("other", "job_ok", 1)], cache, workers=1, say=lambda s: None)
    assert Path(marker).read_text() == "x"  # the finished job was not run again
    run_jobs(jobs, cache, fresh=True, workers=1, say=lambda s: None)
    assert Path(marker).read_text() == "xx"


def test_a_changed_input_file_changes_the_key_and_recomputes(tmp_path):
    data = tmp_path / "input.txt"
    data.write_text("one")
    marker = str(tmp_path / "calls")
    cache = JobCache(tmp_path / "cache")
    job = _job("counted", "job_counted", marker, files=(str(data),))
    k1 = key_of(job)
    run_jobs([job], cache, workers=1, say=lambda s: None)
    data.write_text("two")
    dependencies._file_digest.cache_clear()
    assert key_of(job) != k1
    assert run_jobs([job], cache, workers=1, say=lambda s: None)["counted"].status == "computed"
    assert Path(marker).read_text() == "xx"


def test_a_missing_image_in_the_cache_is_a_miss(tmp_path):
    cache = JobCache(tmp_path / "cache")
    job = _job("a", "job_ok", 5)
    run_jobs([job], cache, workers=1, say=lambda s: None)
    for p in (tmp_path / "cache" / "images").iterdir():
        p.unlink()
    assert run_jobs([job], cache, workers=1, say=lambda s: None)["a"].status == "computed"


def test_import_closure_follows_imports_and_stays_narrow():
    disk = dependencies.closure(["verify.claims.disk"])
    assert {"verify.claims.base", "verify.claims.vectors", "models.rolling", "verify.claims"} <= set(disk)
    assert "verify.claims.ring" not in disk and "verify.claims.simulations" not in disk
    # an import inside a function counts (the claims registry imports its modules lazily)
    assert "verify.report.markup" in dependencies.closure(["verify.report.summary"])


def test_every_key_ingredient_matters():
    job = Job("x", "claims_job", ("disk",), ("verify.claims.disk",))
    base = key_of(job)
    assert key_of(Job("x", "claims_job", ("ring",), ("verify.claims.disk",))) != base
    assert key_of(Job("y", "claims_job", ("disk",), ("verify.claims.disk",))) != base
    assert key_of(Job("x", "claims_job", ("disk",), ("verify.claims.ring",))) != base
    assert key_of(job) == base


def test_the_simd_width_the_runs_use_is_in_the_key(monkeypatch):
    """Batch runs take their width from verify.engine.lanes (VERIFY_SIMD_WIDTH overrides heyoka's
    choice) and their last bits depend on it: a result made at one width is not served at another."""
    job = Job("maps/x", "map_job", ("disk", "diameter-spin"), ("verify.studies.summary",))
    monkeypatch.setenv("VERIFY_SIMD_WIDTH", "2")
    two = key_of(job)
    monkeypatch.setenv("VERIFY_SIMD_WIDTH", "3")
    assert key_of(job) != two


def test_the_registry_covers_every_claim_module_once_with_unique_names():
    from verify.claims import SECTION_MODULES

    jobs = registry()
    names = [j.name for j in jobs]
    assert len(names) == len(set(names))
    assert [n.split("/")[1] for n in names if n.startswith("claims/")] == list(SECTION_MODULES)
    import verify.report.jobs as module

    for j in jobs:
        assert callable(getattr(module, j.function)), j.function


def test_results_json_is_assembled_from_records_in_registry_order():
    """The committed results.json: claims in the registry's order with their sections, no failures."""
    path = Path(__file__).parent.parent / "reports" / "results.json"
    if not path.exists():
        pytest.skip("no committed results.json")
    from verify.claims import all_claims

    results = json.loads(path.read_text())
    if "failures" not in results:
        pytest.skip("results.json predates the pipeline")
    assert [c["id"] for c in results["claims"]] == [c.id for c in all_claims()]
    assert results["failures"] == []
    assert all(c["section"] for c in results["claims"])


def test_render_only_without_results_is_bad_input_and_writes_nothing(tmp_path, capsys):
    from verify.cli import main

    missing = tmp_path / "new"
    assert main(["report", "--render-only", "--out", str(missing)]) == 2
    assert not missing.exists()
    assert "results.json" in capsys.readouterr().err
    (tmp_path / "results.json").write_text("{not json")
    assert main(["report", "--render-only", "--out", str(tmp_path)]) == 2
    assert "cannot be read as JSON" in capsys.readouterr().err
    assert main(["report", "--render-only", "--fresh", "--out", str(tmp_path)]) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results.json"]
