"""The reference set: agreeing digits, the committed files, the double check and its negative controls.

The committed set (reports/reference/, written only by ``python -m verify reference --make``)
is read, never written, here; anything written goes to a temporary folder.
"""
from __future__ import annotations

import copy
import json
import math
import re
from pathlib import Path

import mpmath
import pytest

from models import MODEL_NAMES
from verify.cli import main
from verify.engine.single import solve
from verify.precision import parse_precision
from verify.reference import DIRECTORY, check_case, check_set, load_set
from verify.reference.cases import cases
from verify.reference.agreement import agree
from verify.reference.store import read_index

ROOT = Path(__file__).resolve().parent.parent


# --- agreeing digits (synthetic values) ---------------------------------------------------------

def test_stored_digits_are_the_agreeing_ones():
    with mpmath.workprec(300):
        high = mpmath.mpf("1.23456789012345678901234567890123456789")
        low = high + mpmath.mpf("3e-25")
        c = agree(low, high, 128, 256)
    # 25 digits: rounding moves the value by 3.2e-25, the runs differ by 3e-25, together 6.2e-25, within
    # one unit (1e-24) of the 25th digit; at 26 digits the same sum would exceed the unit 1e-25
    assert c.digits == 25 and c.text == "1.234567890123456789012346"
    with mpmath.workprec(300):
        assert abs(mpmath.mpf(c.text) - high) + abs(low - high) <= mpmath.mpf(c.abs_error) == mpmath.mpf("1e-24")
        assert abs(mpmath.mpf(mpmath.nstr(high, 26)) - high) + abs(low - high) > mpmath.mpf("1e-25")


def test_agreement_caps_at_the_lower_precision_and_handles_zero_and_carry():
    with mpmath.workprec(300):
        same = mpmath.mpf(1) / 3
        assert agree(same, same, 128, 256).digits == math.floor(128 * math.log10(2))  # 38
        assert agree(mpmath.mpf(0), mpmath.mpf(0), 128, 256).digits is None
        tiny = agree(mpmath.mpf("1e-30"), mpmath.mpf("-1e-30"), 128, 256)  # sign not even certain
        assert tiny.digits == 0 and mpmath.mpf(tiny.abs_error) >= mpmath.mpf("2e-30")
        carry = agree(mpmath.mpf("9.9996"), mpmath.mpf("9.99996"), 128, 256)
        assert mpmath.mpf(carry.text) == 10 and abs(mpmath.mpf(carry.text) - mpmath.mpf("9.99996")) + \
            mpmath.mpf("0.00036") <= mpmath.mpf(carry.abs_error)


# --- the committed set ------------------------------------------------------------------------

@pytest.fixture(scope="module")
def records():
    return load_set(DIRECTORY)  # also checks every file against the index's sha256


def test_the_set_covers_every_model_both_kinds_and_1_to_100_seconds(records):
    assert len(records) >= 16
    models = {r["model"]["name"] for r in records}
    assert models >= set(MODEL_NAMES), set(MODEL_NAMES) - models
    assert any(r["model"]["name"] == "disk" and r["model"]["parameters"]["k"]["exact"] == "1/2" for r in records)  # hoop
    assert {r["kind"] for r in records} == {"quiet", "wild"}
    durations = {float(r["t_end"]) for r in records}
    assert min(durations) == 1 and max(durations) == 100
    assert sum("paper Fig." in r["source"] for r in records) >= 8
    assert [r["name"] for r in records] == [c.name for c in cases()]  # the set is the case list, in order


def test_at_least_30_agreeing_digits_at_the_final_time_up_to_10_seconds(records):
    """Every component of every case of at most 10 s, except those whose exact value is 0 (thetadot of
    a steady motion, x and y of a model whose centre of mass stays put): those are agreed as 0
    to within abs_error, which must then be below 1e-30."""
    from verify.reference.store import final_summary

    for r in records:
        if float(r["t_end"]) > 10:
            continue
        s = final_summary(r)
        assert s["min_digits_final"] >= 30, f"{r['name']}: {s['min_digits_final']} agreeing digits at t_end"
        assert all(float(e) < 1e-30 for e in s["zero_within_final"].values()), (r["name"], s["zero_within_final"])


def test_every_stored_value_is_within_its_bound_of_a_third_precision(records):
    """Independent of the agreement: disk-standard-1 at 192 bits (neither of the two runs)
    must lie within abs_error of every stored value (its own error, ~1e-55, is negligible)."""
    r = next(r for r in records if r["name"] == "disk-standard-1")
    sol = solve("disk", r["t_end"], r["initial_state"], precision="mp:192", t_eval=r["grid"])
    p = parse_precision("mp:192")
    with mpmath.workprec(320):
        for i, n in enumerate(r["state"]):
            for j, (text, bound) in enumerate(zip(r["state"][n]["value"], r["state"][n]["abs_error"])):
                assert abs(p.to_mpf(sol.y[i, j]) - mpmath.mpf(text)) <= mpmath.mpf(bound), (n, r["grid"][j])


def test_every_case_is_within_its_bound_in_double():
    """The issue's test: ``reference --check`` in double passes on every case."""
    checks = check_set("double")
    bad = [(c.case, c.ratio, c.where, c.message) for c in checks if not c.ok]
    assert not bad, bad
    assert all(0 < c.ratio for c in checks)  # each run genuinely differs from the reference


# --- negative controls: the check can fail ------------------------------------------------------

def test_a_slightly_wrong_parameter_fails_the_check(records):
    r = next(r for r in records if r["name"] == "ring-standard-10")
    assert check_case(r, "double").ok
    wrong = check_case(r, "double", params={"g": "980.0001"})  # 1e-7 relative: a mistyped digit
    assert not wrong.ok and wrong.ratio > 10


def _corrupted(record: dict, relative: str) -> dict:
    r = copy.deepcopy(record)
    col = r["state"]["theta"]
    with mpmath.workdps(50):
        col["value"][-1] = mpmath.nstr(mpmath.mpf(col["value"][-1]) * (1 + mpmath.mpf(relative)), 40)
    return r


def test_a_corrupted_reference_value_fails_the_check(records):
    """One final value off by 1e-6 fails in double; off by 1e-20 it passes in double (whose bound there is
    2e-8: eps sqrt(N) R* Y) and fails in quad, whose bound is 1e-16 times smaller."""
    r = next(r for r in records if r["name"] == "disk-standard-1")
    assert not check_case(_corrupted(r, "1e-6"), "double").ok
    slightly = _corrupted(r, "1e-20")
    assert check_case(slightly, "double").ok and not check_case(slightly, "quad").ok


def test_a_reference_for_other_equations_is_refused_as_stale(records):
    r = copy.deepcopy(records[0])
    r["model"]["equations_sha256"] = "0" * 64
    result = check_case(r, "double")
    assert not result.ok and "stale" in result.message


def test_a_file_changed_after_it_was_made_is_refused(tmp_path):
    for f in (f for f in DIRECTORY.iterdir() if f.is_file()):
        (tmp_path / f.name).write_bytes(f.read_bytes())
    target = tmp_path / "disk-standard-1.json"
    target.write_text(target.read_text().replace('"kind": "wild"', '"kind": "quiet"', 1))
    with pytest.raises(ValueError, match="sha256"):
        load_set(tmp_path, ["disk-standard-1"])


# --- the README and the command line ------------------------------------------------------------

def test_the_readme_recipe_reads_a_case_without_this_package(monkeypatch):
    text = (DIRECTORY / "README.md").read_text()
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    assert "import verify" not in code and "from verify" not in code and "models" not in code.split("case =")[0]
    monkeypatch.chdir(ROOT)
    scope = {}
    exec(compile(code, "README.md", "exec"), scope)  # noqa: S102 -- our own documentation
    assert len(scope["theta"]) == len(scope["t"]) and scope["bound"][-1] > 0


def test_index_summarises_the_files():
    index = read_index(DIRECTORY)
    assert index["precisions"] == {"low": "mp:128", "high": "mp:256"}
    for e in index["cases"]:
        record = json.loads((DIRECTORY / e["file"]).read_text())
        assert record["precisions"]["low"] == "mp:128" and record["precisions"]["high"] == "mp:256"


def test_reference_check_command_line(capsys):
    assert main(["reference", "--check", "--case", "ring-fig10-lhs", "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out[0]["case"] == "ring-fig10-lhs" and out[0]["ok"] and set(out[0]) >= {"ratio", "where", "error", "bound"}


@pytest.mark.parametrize("argv,message", [
    (["reference", "--check", "--precision", "float"], "allowed: double, long, quad"),
    (["reference", "--check", "--case", "nope"], "unknown reference case 'nope'"),
    (["reference", "--make", "--jobs", "0"], "--jobs 0 must be at least 1"),
    (["reference", "--make", "--precision", "quad"], "--precision is for --check"),
])
def test_reference_bad_input(capsys, argv, message):
    assert main(argv) == 2
    assert message in capsys.readouterr().err


def test_make_writes_a_small_set_atomically(tmp_path):
    """--make for one short case into a temporary folder (low precisions, to stay quick)."""
    from verify.reference import make_set

    make_set(["ring-fig10-lhs"], jobs=1, directory=tmp_path, low="mp:64", high="mp:96")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["README.md", "index.json", "ring-fig10-lhs.json"]
    record = load_set(tmp_path)[0]
    assert record["precisions"]["low"] == "mp:64"
    assert check_case(record, "double").ok


def test_the_reference_agrees_with_an_integrator_that_is_not_heyoka():
    """Independent route: mpmath's odefun (its own Taylor series, on the sympy-lambdified derived
    equations, in Python) from the start of disk-standard-1 to its first grid time, 1/32 s, at 20
    digits. odefun's local tolerance is 10^-20 and the run takes ~10 steps of a flow whose transition
    matrix is ~1 there, so the two agree to ~1e-20 relative (measured 1.1e-21); 1e-18 leaves the
    margin for the rounding of the start and the parameters at 20 digits. A reference corrupted at
    1e-15 in theta (a wrong 16th digit) fails the same comparison."""
    from verify.bench import ReferenceProblem, odefun_attempts

    problem = ReferenceProblem("disk-standard-1")
    attempt = odefun_attempts(problem, (20,), index=1)[0]
    assert attempt.t_end == "0.03125"
    assert attempt.error < 1e-18, attempt.error
    corrupted = ReferenceProblem("disk-standard-1")
    with mpmath.workdps(50):
        col = corrupted.record["state"]["theta"]["value"]
        col[1] = mpmath.nstr(mpmath.mpf(col[1]) * (1 + mpmath.mpf("1e-15")), 40)
    assert odefun_attempts(corrupted, (20,), index=1)[0].error > 1e-18
