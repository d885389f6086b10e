"""The report writer: structure of results.json, determinism, atomic writes (temporary folders only)."""
from __future__ import annotations

import json

import pytest

from verify.claims import all_claims
from verify.provenance import write_atomic
from verify.report.claim_records import claim_record
from verify.report.markdown import render_markdown
from verify.report.page import render_html

KEYS = {"id", "source", "section", "statement", "verdict", "expected", "observed", "detail"}


def _some_records():
    wanted = {"eq-40", "eq-41", "eq-1", "fig-2"}
    return [claim_record(c, c.evaluate()) for c in all_claims() if c.id in wanted]


def _results(records):
    return {"summary": None, "claims": records, "conservation": [], "not_covered": {}, "failures": [], "figures": [],
            "studies": {"thresholds": [], "captions": [], "spindown": [], "precision": [], "maps": [], "dissipation": [],
                        "retrograde": {}, "reference": {"index": {"cases": []}, "checks": {}}},
            "provenance": {"versions": {"heyoka": "x", "sympy": "y", "mpmath": "z"}, "source_sha256": "x",
                           "source_commit": {"commit": None, "modified": None}, "precisions": ["double"]}}


def test_result_records_carry_the_required_fields():
    for rec in _some_records():
        assert KEYS <= set(rec)
        if rec["verdict"] == "erratum":
            assert rec["correction"]
        json.dumps(rec)


def test_rendering_is_deterministic_and_anchors_every_claim(tmp_path, monkeypatch):
    import verify.report.markdown as md_module
    import verify.report.page as page_module

    results = _results(_some_records())
    monkeypatch.setattr(md_module, "sections", _claims_sections)
    monkeypatch.setattr(page_module, "sections", _claims_sections)
    a, b = render_markdown(results), render_markdown(results)
    assert a == b
    assert '<a id="eq-40"></a>Eq. 40: erratum (typo)' in a
    page = render_html(results, {})
    assert page.startswith("<!DOCTYPE html>") and 'id="eq-40"' in page and 'href="#eq-41"' in page
    assert page == render_html(results, {})
    write_atomic(tmp_path / "REPORT.md", a)
    assert (tmp_path / "REPORT.md").read_text() == a


def _claims_sections(results, benchmarks, engines=None):
    by = {}
    for rec in results["claims"]:
        by.setdefault(rec["section"], []).append(rec)
    from verify.report.markdown import claim_markdown

    return [(f"s{i}", title, "\n".join(line for r in recs for line in claim_markdown(r)), recs)
            for i, (title, recs) in enumerate(by.items())]


def test_atomic_write_leaves_the_old_file_on_failure(tmp_path):
    target = tmp_path / "results.json"
    write_atomic(target, "old")

    class Boom:
        def encode(self):
            raise RuntimeError("boom")

    with pytest.raises(Exception):
        write_atomic(target, Boom())
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["results.json"]


def test_provenance_names_the_sources_commit_and_every_precision():
    """The commit is the last one that changed the sources (40 hex digits in a git checkout), so
    regenerating a committed report does not change it; precisions are listed once, in ladder order."""
    import re
    import shutil

    from verify.provenance import provenance

    prov = provenance(["quad", "double", "mp:256", "quad", "mp:160"])
    assert prov["precisions"] == ["double", "quad", "mp:160", "mp:256"]
    assert set(prov["source_commit"]) == {"commit", "modified"}
    if shutil.which("git") and (__import__("pathlib").Path(__file__).parent.parent / ".git").exists():
        assert re.fullmatch(r"[0-9a-f]{40}", prov["source_commit"]["commit"])


def test_committed_results_carry_no_wall_times():
    """results.json must be the same bytes whenever the same sources run on the same versions, so
    wall times go to timing.json only. Any key naming seconds or elapsed time in the committed
    results is a leak (a retrograde-study 'seconds' once made two fresh runs differ)."""
    import pathlib

    path = pathlib.Path(__file__).parent.parent / "reports" / "results.json"
    if not path.exists():
        pytest.skip("no committed results.json")

    def keys(node):
        if isinstance(node, dict):
            for k, v in node.items():
                yield k
                yield from keys(v)
        elif isinstance(node, list):
            for v in node:
                yield from keys(v)

    leaks = sorted({k for k in keys(json.loads(path.read_text()))
                    if k == "seconds" or k.endswith("_seconds") or k in {"elapsed", "wall_time"}})
    assert not leaks, f"wall-time keys in results.json: {leaks}"
