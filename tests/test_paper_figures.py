"""``python -m verify figure``: the list of the paper's figures, one figure made again, bad input.

The verdicts this command prints must be the report's: the list reads them from
reports/results.json, and a figure's are computed by the same ``Claim.evaluate`` and compared
with that file (verify/paper_figures.py).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from verify import paper_figures as pf
from verify.cli import main
from verify.figure_starts import figures_with_runs

ROOT = Path(__file__).resolve().parents[1]
PNG = b"\x89PNG\r\n\x1a\n"


def _stored() -> dict:
    return pf.read_results(pf.RESULTS_FILE)


needs_results = pytest.mark.skipif(not pf.RESULTS_FILE.exists(), reason="no reports/results.json (make report)")


def _cli(*argv, cwd=ROOT):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "verify", *argv], capture_output=True, text=True, cwd=cwd, env=env,
                          timeout=600)


# --- the list -----------------------------------------------------------------------------------

@needs_results
def test_list_is_complete_and_its_verdicts_are_results_json_s():
    listing = pf.figure_list()
    assert [f.number for f in listing.figures] == list(range(1, 21))
    assert all(f.title for f in listing.figures)
    assert {f.number for f in listing.figures if f.has_simulation} == set(figures_with_runs())
    listed = {c.id: c.verdict for f in listing.figures for c in f.claims}
    stored = {i: r["verdict"] for i, r in _stored().items() if pf.figure_of(r["source"]) is not None}
    assert listed == stored
    assert all(f.claims for f in listing.figures)  # every figure has a claim
    assert {f.number for f in listing.figures if not f.has_simulation} >= {1, 7, 13, 14}


def test_list_without_results_says_how_to_get_them(tmp_path):
    listing = pf.figure_list(tmp_path / "results.json")
    assert len(listing.figures) == 20 and not any(f.claims for f in listing.figures)
    assert "make report" in listing.note and listing.results_file is None
    assert "make report" in pf.list_text(listing).splitlines()[-1]


@needs_results
def test_figure_list_on_the_command_line(capsys):
    listed = _cli("figure", "--list")
    assert listed.returncode == 0 and listed.stderr == ""
    assert listed.stdout == pf.list_text(pf.figure_list()) + "\n"
    assert main(["figure", "--list"]) == 0  # in process, the same text
    assert capsys.readouterr().out == listed.stdout
    doc = json.loads(_cli("figure", "--list", "--format", "json").stdout)
    assert [f["number"] for f in doc["figures"]] == list(range(1, 21))
    assert doc["figures"][4]["starts"] == ["fig5-lhs", "fig5-rhs"]


def test_figure_list_imports_nothing_heavy():
    """figure --list must answer in well under a second: no sympy, heyoka, numpy, matplotlib, claim module."""
    res = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "verify", "figure", "--list"], capture_output=True, text=True,
        cwd=ROOT, env=dict(os.environ, PYTHONPATH=str(ROOT)), timeout=120)
    assert res.returncode == 0
    imported = {line.split("|")[-1].strip() for line in res.stderr.splitlines() if line.startswith("import time:")}
    heavy = {m for m in imported if m.split(".")[0] in ("sympy", "heyoka", "numpy", "matplotlib", "mpmath")
             or m.startswith(("verify.claims.simulations", "verify.report"))
             or m in ("verify.claims.disk", "verify.claims.ring", "verify.claims.hurricane", "verify.claims.gyroscope")}
    assert heavy == set()


# --- one figure ---------------------------------------------------------------------------------

def _check_made(fig: pf.PaperFigure, stored: dict):
    assert fig.mismatches == ()
    for rec in fig.records:
        assert rec["verdict"] == stored[rec["id"]]["verdict"], rec["id"]
        assert rec["quote"] == stored[rec["id"]]["quote"]
    for img in fig.images:
        assert img.data.startswith(PNG) and img.alt
        drawn = ROOT / "reports" / "figures" / img.filename
        if fig.side is None and drawn.exists():  # the report's own figure, byte for byte
            assert img.data == drawn.read_bytes(), img.filename


@needs_results
def test_fig2_is_made_as_the_report_makes_it():
    fig = pf.make_figure(2)
    _check_made(fig, _stored())
    assert [r["id"] for r in fig.records] == ["fig-2"]
    assert [img.filename for img in fig.images] == ["fig-02.png"]
    assert fig.images[0].alt == next(f["alt"] for f in _stored()["fig-2"]["figures"])  # the report's figure


@needs_results
def test_fig5_lhs_on_the_command_line(tmp_path, capsys):
    code = main(["figure", "5", "--side", "lhs", "--out", str(tmp_path)])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert sorted(os.listdir(tmp_path)) == ["fig-05-lhs.png"]
    assert (tmp_path / "fig-05-lhs.png").read_bytes().startswith(PNG)
    assert "Fig. 5 LHS [fig-5-lhs]: CONFIRMED" in out and "fig-5-rhs" not in out
    assert out.rstrip().splitlines()[-1].startswith("next: python -m verify animate --figure 5 --side lhs")
    assert "trajectory --start fig5-lhs" in out
    fig = pf.make_figure(5, "lhs")
    _check_made(fig, _stored())
    assert "(LHS): for 1 run" in fig.images[0].alt  # the LHS panel's run only: the psidot0 = 0 control is not drawn


@needs_results
def test_a_stale_results_json_fails_loudly(tmp_path, capsys, monkeypatch):
    stale = json.loads(pf.RESULTS_FILE.read_text())
    for rec in stale["claims"]:
        if rec["id"] == "fig-2":
            rec["verdict"] = "erratum"
    path = tmp_path / "results.json"
    path.write_text(json.dumps(stale))
    monkeypatch.setattr(pf, "RESULTS_FILE", path)
    code = main(["figure", "2", "--out", str(tmp_path)])
    out, err = capsys.readouterr()
    assert code == 1
    assert "(results.json: erratum)" in out
    assert err.count("\n") == 1 and "fig-2 computed confirmed, results.json erratum" in err


@pytest.mark.slow
@needs_results
def test_every_figure_is_made_with_the_report_s_verdicts():
    stored = _stored()
    for n in range(1, 21):
        fig = pf.make_figure(n)
        _check_made(fig, stored)
        assert {r["id"] for r in fig.records} == {i for i, r in stored.items() if pf.figure_of(r["source"]) == n}
        assert bool(fig.images) == (n in figures_with_runs()), n
        if n not in figures_with_runs():
            assert "no run to draw" in fig.note
        for side in ("lhs", "rhs"):
            if side in pf.figure_list().figures[n - 1].sides and n in figures_with_runs():
                _check_made(pf.make_figure(n, side), stored)


@pytest.mark.slow  # ~21 s: every figure's runs
@needs_results
def test_every_figure_claim_gives_the_report_s_verdict():
    """After the claim code took its starts from verify/figure_starts.py, every fig-* verdict is results.json's."""
    from verify.claims import all_claims

    stored = _stored()
    got = {c.id: c.evaluate().verdict for c in all_claims() if pf.figure_of(c.source) is not None}
    assert got == {i: r["verdict"] for i, r in stored.items() if pf.figure_of(r["source"]) is not None}


# --- bad input ----------------------------------------------------------------------------------

BAD = [
    (["figure"], "give a figure number"),
    (["figure", "0"], "figure '0': allowed an integer 1 to 20"),
    (["figure", "21"], "figure '21'"),
    (["figure", "five"], "figure 'five'"),
    (["figure", "5.0"], "figure '5.0'"),
    (["figure", "-3"], "-3"),
    (["figure", "5", "--side", "top"], "--side top: allowed lhs, rhs, both"),
    (["figure", "2", "--side", "lhs"], "Fig. 2 has no LHS panel; allowed: both"),
    (["figure", "7", "--side", "rhs"], "Fig. 7 has no RHS panel"),
    (["figure", "5", "--out", "missing-folder"], "--out missing-folder: no such folder"),
    (["figure", "5", "--out", "a-file"], "--out a-file: a file, not a folder"),
    (["figure", "5", "--format", "xml"], "xml"),
    (["figure", "--list", "5"], "--list takes no figure number"),
    (["figure", "--list", "--side", "lhs"], "--list takes no figure number"),
    (["figure", "5", "6"], "unrecognized arguments"),
]


@pytest.mark.parametrize("argv,said", BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_input_is_one_line_exit_2_and_writes_nothing(argv, said, tmp_path, monkeypatch, capsys):
    (tmp_path / "a-file").write_text("")
    monkeypatch.chdir(tmp_path)
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 2, (out, err)
    assert out == "" and err.count("\n") == 1 and err.startswith("error: ") and said in err, err
    assert sorted(os.listdir(tmp_path)) == ["a-file"]
