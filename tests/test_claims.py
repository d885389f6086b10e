"""One parametrised test over every claim of the registry (verify/claims).

The expectation is part of the record (``Claim.expected_verdict``): a claim with a
known-failure note must come out as an erratum with its correction and severity, a
qualified caption with its exact threshold and perturbation, a claim whose measures are
expected to disagree as not checkable with both numbers, a definition as not checkable with
its reason, every other one as confirmed.  Any verdict that changes fails.  Every quote must
stand verbatim in the paper.  The report renders the same evaluations.
"""
from __future__ import annotations

import hashlib
import pathlib

import pytest

from verify.claims import CONFIRMED, ERRATUM, NOT_CHECKABLE, QUALIFIED, SEVERITIES, all_claims, missing
from verify.claims.base import PAPER_FILE, paper_text, quote_found, quote_fragments

CLAIMS = all_claims()


@pytest.mark.parametrize("claim", CLAIMS, ids=[c.id for c in CLAIMS])
def test_claim(claim):
    ev = claim.evaluate()
    assert ev.verdict == claim.expected_verdict, (
        f"{claim.source}: expected {claim.expected_verdict}, got {ev.verdict}: {ev.expected} vs {ev.observed} ({ev.detail})")
    if ev.verdict == ERRATUM:
        assert ev.correction, "an erratum must show its correction"
        assert claim.severity in SEVERITIES
    if ev.verdict == QUALIFIED:
        assert ev.qualification and any(ch.isdigit() for ch in ev.qualification), \
            "a qualified verdict must state the exact threshold and the perturbation, with numbers"
    if ev.verdict == NOT_CHECKABLE:
        assert ev.detail
        if claim.undecided is not None:
            assert len(ev.measures) >= 2, "an undecided simulation shows both measures"
    if claim.method == "simulation" and ev.verdict != NOT_CHECKABLE:
        assert len(ev.measures) >= 2, "a simulation verdict rests on two independent measures"


@pytest.mark.parametrize("claim", CLAIMS, ids=[c.id for c in CLAIMS])
def test_quote_is_verbatim(claim):
    """The claim quotes the paper's own words, found verbatim (up to whitespace) in the paper."""
    fragments = quote_fragments(claim.quote)
    assert fragments and all(f.strip() for f in fragments), f"{claim.id}: no quote"
    missing_ = [f for f in fragments if not quote_found(f)]
    assert not missing_, f"{claim.id}: not in the paper verbatim: {missing_}"


def test_quote_check_can_fail():
    """Negative control: a repaired quotation (Eq. 40 with phidot_0 for the printed psidot_0) is not found."""
    printed = r"(k+1)\ddot{\alpha} = -\left((k+1)\dot{\psi}_0^2 - g\right)\alpha"
    assert quote_found(printed)
    assert not quote_found(printed.replace(r"\dot{\psi}_0", r"\dot{\phi}_0"))


def test_packaged_paper_is_the_shared_paper():
    """The claims read a copy of the paper; where the shared original is present it must be the same bytes."""
    shared = pathlib.Path(__file__).resolve().parents[1].parent / "shared" / "paper.md"
    if not shared.exists():
        pytest.skip("../shared/paper.md is not beside this clone")
    assert hashlib.sha256(shared.read_bytes()).digest() == hashlib.sha256(PAPER_FILE.read_bytes()).digest()
    assert "Hurricane Balls" in paper_text()


def test_every_erratum_has_a_severity_and_every_severity_an_erratum():
    for c in CLAIMS:
        assert (c.known_failure is None) == (c.severity is None), c.id


def test_claim_ids_are_unique():
    ids = [c.id for c in CLAIMS]
    assert len(ids) == len(set(ids))


def test_every_equation_and_caption_has_a_claim():
    eqs, figs = missing()
    assert not eqs and not figs, f"missing equations {eqs}, figures {figs}"


def test_a_misprinted_equation_is_caught():
    """Negative control: the Eq. 12 check run on a copy with the gravity term's sign flipped."""
    from verify.claims import disk_equations as disk
    from verify.claims.vectors import E1, c

    from models.symbols import g

    good = disk._vector_identity("x", "Eq. 12", "", disk._eq12).evaluate()
    bad = disk._vector_identity("y", "Eq. 12", "", lambda: disk._eq12() - 2 * E1 * c * g).evaluate()
    assert good.verdict == CONFIRMED and bad.verdict == ERRATUM


def test_a_misprinted_number_is_caught():
    """Negative control: the Fig. 6 check with psidot misprinted by one unit in the last digit."""
    from verify.claims import disk_spindown as disk

    assert disk._fig6_check("cm-at-rest", ("-626.104", "626.073"))().verdict == CONFIRMED
    assert disk._fig6_check("cm-at-rest", ("-626.104", "626.074"))().verdict == ERRATUM


def test_citation_check_counts_printed_components():
    """Negative control for the Fig. 19 citation check: it reads the paper, so a 3-vector equation
    (Eq. 18, Eq. 81) counts 3 and the scalar Eq. 82 counts 1."""
    from verify.claims.simulations.hurricane import _printed_components

    assert (_printed_components(18), _printed_components(81), _printed_components(82)) == (3, 3, 1)
