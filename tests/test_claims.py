"""One parametrised test over every claim of the registry (verify/claims).

The expectation is part of the record: a claim with a known-failure note must come out
as an erratum (with its correction), one marked not checkable must say why, every other
one must be confirmed.  The report renders the same evaluations.
"""
from __future__ import annotations

import pytest

from verify.claims import CONFIRMED, ERRATUM, NOT_CHECKABLE, all_claims, missing

CLAIMS = all_claims()


@pytest.mark.parametrize("claim", CLAIMS, ids=[c.id for c in CLAIMS])
def test_claim(claim):
    ev = claim.evaluate()
    if claim.reason_not_checkable is not None:
        assert ev.verdict == NOT_CHECKABLE and ev.detail
    elif claim.known_failure is not None:
        assert ev.verdict == ERRATUM, f"{claim.source}: expected the erratum '{claim.known_failure}', got {ev}"
        assert ev.correction, "an erratum must show its correction"
    else:
        assert ev.verdict == CONFIRMED, f"{claim.source}: {ev.expected} vs {ev.observed} ({ev.detail})"


def test_claim_ids_are_unique():
    ids = [c.id for c in CLAIMS]
    assert len(ids) == len(set(ids))


def test_every_equation_and_caption_has_a_claim():
    eqs, figs = missing()
    assert not eqs and not figs, f"missing equations {eqs}, figures {figs}"


def test_a_misprinted_equation_is_caught():
    """Negative control: the Eq. 12 check run on a copy with the gravity term's sign flipped."""
    from verify.claims import disk
    from verify.claims.vectors import E1, c

    from models.symbols import g

    good = disk._vector_identity("x", "Eq. 12", "", disk._eq12).evaluate()
    bad = disk._vector_identity("y", "Eq. 12", "", lambda: disk._eq12() - 2 * E1 * c * g).evaluate()
    assert good.verdict == CONFIRMED and bad.verdict == ERRATUM


def test_a_misprinted_number_is_caught():
    """Negative control: the Fig. 6 check with psidot misprinted by one unit in the last digit."""
    from verify.claims import disk

    assert disk._fig6_check("cm-at-rest", ("-626.104", "626.073"))().verdict == CONFIRMED
    assert disk._fig6_check("cm-at-rest", ("-626.104", "626.074"))().verdict == ERRATUM
