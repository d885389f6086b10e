"""The proved enclosures of the reference set (reports/reference/proved/, ``reference --prove``).

They hold every stored agreed value's claim (no contradiction at any proved time), the summary
is the one their writer makes, a run at a working precision comes within its own bound of the
balls while a run of a perturbed problem does not, and the writer resumes and stops on its budget.
"""
from __future__ import annotations

import json
import shutil
import subprocess
import sys
from decimal import Decimal, localcontext
from fractions import Fraction
from pathlib import Path

import pytest
from flint import arb, ctx

from verify.reference import DIRECTORY, check_case, load_set
from verify.reference.proved import (
    ball,
    claims,
    decimal_ball,
    load_proofs,
    proof_path,
    proved_directory,
    prove_case,
    read_proof,
    settings_of,
    summary,
)
from verify.reference.store import read_case

SHORT = [r["name"] for r in load_set() if Fraction(r["t_end"]) <= 10 and "friction" not in r]  # Coulomb: agreed only
PROOF_FILES = sorted(proved_directory().glob("*bit.json"))


def test_every_case_of_at_most_ten_seconds_has_a_proof():
    """Each case of <= 10 s has a 128-bit enclosure on file (how far it reached is the summary's)."""
    proofs = load_proofs()
    missing = [n for n in SHORT if not any(p["settings"]["prec"] == 128 for p in proofs.get(n, []))]
    assert not missing, f"no 128-bit proof for {missing}: run 'python -m verify reference --prove'"


@pytest.mark.parametrize("path", PROOF_FILES, ids=[p.name for p in PROOF_FILES])
def test_no_stored_value_lies_outside_its_proved_ball(path):
    """The MPFR runs and the enclosure agree: at every proved time and component the stored value's
    claim |value - exact| <= abs_error meets the proved ball (never disjoint)."""
    proof = read_proof(path)
    record = read_case(DIRECTORY / f"{proof['case']}.json")
    verdict = claims(record, proof)
    assert verdict["contradicted"] == 0, verdict["contradictions"]
    assert verdict["proved"] + verdict["consistent"] == 8 * len(proof["times"])


def test_a_ball_moved_off_the_stored_value_is_a_contradiction():
    """Negative control of the claims count: a proved ball shifted by 1e-20 in theta no longer meets
    the stored value's interval."""
    proof = read_proof(proof_path(DIRECTORY, "disk-standard-1", 128))
    record = read_case(DIRECTORY / "disk-standard-1.json")
    moved = json.loads(json.dumps(proof))
    mids = moved["state"]["theta"]["mid"]
    with localcontext() as exact:
        exact.prec = 200
        mids[-1] = str(Decimal(mids[-1]) + Decimal("1e-20"))
    assert claims(record, moved)["contradicted"] == 1


def test_the_summary_on_file_is_its_writers():
    """proved/index.json is what the writer makes from the proof files now (nobody edited it)."""
    index = json.loads((proved_directory() / "index.json").read_text())
    proofs = load_proofs()
    fresh = [summary(read_case(DIRECTORY / f"{n}.json"), p)
             for n, items in proofs.items() for p in sorted(items, key=lambda p: p["settings"]["prec"])]
    assert index["proofs"] == fresh


@pytest.mark.parametrize("value", ["1.2", "-3.5e-40", "0", "12345.678901234567890123456789", "1e30"])
@pytest.mark.parametrize("radius", ["0", "1e-75", "3e-33", "0.5"])
def test_a_decimal_ball_contains_the_ball_it_writes(value, radius):
    """The stored decimal interval [mid - rad, mid + rad] contains the Arb ball, whatever the scales."""
    saved = ctx.prec
    ctx.prec = 320
    try:
        b = arb(value) / 3 + arb(0, arb(radius).upper())
        mid, rad = decimal_ball(b, 256)
        assert (arb(mid) + arb(0, arb(rad).upper())).contains(b)
    finally:
        ctx.prec = saved
    # the same ball written while the context is at python-flint's default 53 bits: no wider
    assert decimal_ball(b, 256) == (mid, rad)


def test_a_run_comes_within_its_bound_of_the_proof_and_a_perturbed_one_does_not():
    """reference --check's second measure: double-precision runs of disk-standard-1 land within
    their own error bound of every proved ball; with g changed in the 7th digit they do not."""
    record = read_case(DIRECTORY / "disk-standard-1.json")
    proofs = load_proofs()["disk-standard-1"]
    good = check_case(record, "double", proofs=proofs)
    assert good.ok and good.proof_ratio is not None and good.proof_ratio <= 1, good
    wrong = check_case(record, "double", params={"g": "980.0001"}, proofs=proofs)
    assert wrong.proof_ratio > 1, wrong


def test_an_mpfr_run_lands_within_its_bound_of_the_proofs_and_a_perturbed_one_does_not():
    """The MPFR runs and the enclosures agree: an MPFR-128 run of disk-standard-1 comes within its own
    bound (~1e-32) of every 128- and 256-bit proved ball; with g changed by 1e-25 relative, a change no
    run at 53 or 113 bits could see, it does not."""
    record = read_case(DIRECTORY / "disk-standard-1.json")
    proofs = load_proofs()["disk-standard-1"]
    assert {p["settings"]["prec"] for p in proofs} >= {128, 256}
    good = check_case(record, "mp:128", proofs=proofs)
    assert good.ok and good.proof_ratio <= 1, good
    wrong = check_case(record, "mp:128", params={"g": "980.0000000000000000000001"}, proofs=proofs)
    assert wrong.proof_ratio > 1, wrong


def _copy_set(source: Path, target: Path) -> None:
    target.mkdir(parents=True, exist_ok=True)
    for name in ("index.json", "disk-standard-1.json"):
        shutil.copy(source / name, target / name)


@pytest.fixture()
def small_set(tmp_path):
    """A copy of the reference set's index and disk-standard-1 in a temporary folder."""
    _copy_set(DIRECTORY, tmp_path)
    return tmp_path


def test_the_writer_resumes_and_stops_on_its_budget(small_set):
    """A proof to 1/32 s, resumed to 1/16 s, has the times of a run straight to 1/16 s and balls that meet
    it (both hold the exact solution); a budget already spent
    stops after the first grid time with the reason written; every written ball holds the stored value."""
    record = read_case(small_set / "disk-standard-1.json")
    settings = settings_of(128)
    first = prove_case(record, directory=small_set, until="0.03125", settings=settings)
    assert first["times"] == ["0", "0.03125"] and not first["complete"]
    resumed = prove_case(record, directory=small_set, until="0.0625", settings=settings)
    assert resumed["times"] == ["0", "0.03125", "0.0625"] and resumed["resumed_at"] == ["0.03125"]
    _copy_set(DIRECTORY, small_set / "straight")
    straight = prove_case(record, directory=small_set / "straight", until="0.0625", settings=settings)
    for n in ("theta", "psidot", "x"):  # the resumed balls and the straight run's hold the same solution
        assert ball(resumed, n, -1).overlaps(ball(straight, n, -1)), n
    stopped = prove_case(record, directory=small_set, until="0.125", settings=settings, budget=-1)
    assert stopped["times"][-1] == "0.09375" and "budget" in stopped["stopped"]
    assert read_proof(proof_path(small_set, "disk-standard-1", 128)) == stopped
    assert claims(record, stopped)["contradicted"] == 0


@pytest.mark.parametrize("args, says", [
    (["--precision", "double"], "mp:BITS"),
    (["--until", "abc"], "not a number"),
    (["--until", "-1"], "positive"),
    (["--budget", "-5"], "--budget"),
    (["--until", "1e-9", "--case", "disk-standard-1"], "first grid time"),
    (["--format", "json"], "--format is for --check and --export"),
    (["--jobs", "4"], "--jobs is for --make"),
])
def test_bad_prove_arguments_are_refused(small_set, args, says):
    """One line naming the value and what is allowed, exit 2, nothing written."""
    out = subprocess.run([sys.executable, "-m", "verify", "reference", "--prove", "--dir", str(small_set), *args],
                         capture_output=True, text=True, cwd=Path(__file__).parents[1])
    assert out.returncode == 2, out.stderr
    assert says in out.stderr and "Traceback" not in out.stderr
    assert not (small_set / "proved").exists()
