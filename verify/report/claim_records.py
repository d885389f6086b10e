"""A claim and its evaluation as a results.json record: everything the report shows of it, as data."""
from __future__ import annotations

from ..claims.base import ERRATUM, NOT_CHECKABLE, Claim, Evaluation, quote_found, quote_fragments


def claim_record(claim: Claim, ev: Evaluation, images=()) -> dict:
    """The record of one claim; ``images`` are the drawn ``ev.figures`` (same order), each an
    :class:`~.figures.Image`, named in the record with their title and alt text."""
    rec = {"id": claim.id, "source": claim.source, "section": claim.section, "statement": claim.statement,
           "quote": list(quote_fragments(claim.quote)), "verdict": ev.verdict, "expected": ev.expected,
           "observed": ev.observed, "detail": ev.detail}
    if not quote_found(claim.quote):  # only with another paper (VERIFY_PAPER): the quote is not in it
        rec["quote_not_in_paper"] = True
    if claim.reading:
        rec["reading"] = claim.reading
    rec["method"] = claim.method
    rec["tolerance"] = claim.tolerance
    if ev.correction:
        rec["correction"] = ev.correction
    if ev.verdict == ERRATUM:
        rec["severity"] = claim.severity
    if ev.qualification:
        rec["qualification"] = ev.qualification
    if ev.measures:
        rec["measures"] = [{"measure": n, "value": v} for n, v in ev.measures]
    if ev.verdict == NOT_CHECKABLE and claim.undecided is not None:
        rec["undecided"] = True
    if images:
        rec["figures"] = [{"file": img.filename, "title": fig.title, "alt": img.alt}
                          for fig, img in zip(ev.figures, images)]
    return rec
