"""Claims are data: a frozen record per checkable statement of the paper.

In the manner of scipy.special's test registry: each :class:`Claim` names its source in
the paper, quotes the paper's own words (``quote``, verbatim up to whitespace: a test finds
every quote in :data:`PAPER`), says how the check reads them where a reading is needed
(``reading``: units, a scaled form, an unstated start -- never a repair of what the quote
gets wrong), names the check that decides it and the tolerance with its reason, and, where
the paper is wrong, the expected erratum and its severity.  One parametrised test runs every
claim (tests/test_claims.py) and the report renders the same evaluations, so the two cannot
disagree.  The check computes the expected value by an independent route and compares it
with what the paper prints; the verdict comes out of that comparison.

Verdicts
--------
``confirmed``
    the independent route agrees with the quote.
``erratum``
    it does not; the evaluation carries the correction, the claim a severity:
    ``result`` (a number or conclusion is wrong), ``typo`` (the printed form is wrong but
    what the paper derives from it is right), ``rounding`` (a last printed digit).
``qualified``
    a caption's described behaviour is reproduced, but only because of an unstated or finite
    perturbation (or one unstated choice, such as a handedness), while what the caption
    implies in general -- a threshold, a sense -- is wrong or holds only for that choice; the
    evaluation states the exact threshold or the convention-free statement, and the
    perturbation or choice that produces the figure.
``not-checkable``
    nothing to decide (a definition, a diagram), or -- for a simulation -- the two
    independent measures of a qualitative statement disagree; both numbers are given.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Callable, Optional, Union

CONFIRMED, ERRATUM, QUALIFIED, NOT_CHECKABLE = "confirmed", "erratum", "qualified", "not-checkable"
VERDICTS = (CONFIRMED, ERRATUM, QUALIFIED, NOT_CHECKABLE)
RESULT, TYPO, ROUNDING = "result", "typo", "rounding"
SEVERITIES = (RESULT, TYPO, ROUNDING)  # most serious first: the report orders errata this way

#: The paper the quotes are checked against: the copy of ../shared/paper.md kept beside this module
#: (the tests check they agree), or the file named by the environment variable VERIFY_PAPER (for
#: another version of the paper: every quote it no longer contains then fails tests/test_claims.py).
PAPER_FILE = Path(os.environ.get("VERIFY_PAPER") or Path(__file__).with_name("paper.md")).resolve()


def _squash(text: str) -> str:
    return " ".join(text.split())


@lru_cache(maxsize=None)
def paper_text() -> str:
    """The paper with every run of whitespace collapsed to one space (quotes are matched in this)."""
    return _squash(PAPER_FILE.read_text(encoding="utf-8"))


def quote_fragments(quote) -> tuple:
    """A claim's quote as a tuple of verbatim fragments (one string, or several joined by the claim)."""
    return (quote,) if isinstance(quote, str) else tuple(quote)


def quote_found(quote) -> bool:
    """True when every fragment of ``quote`` stands verbatim (up to whitespace) in the paper."""
    text = paper_text()
    return all(_squash(f) and _squash(f) in text for f in quote_fragments(quote))


@dataclass(frozen=True)
class RunData:
    """What a figure shows of one run (arrays in double; the run itself may be finer)."""

    label: str
    t: tuple
    theta: tuple
    phi: tuple
    omega3: tuple
    x: tuple
    y: tuple
    energy_drift: float  # max |E(t) - E(0)| / |E(0)| over the run (InvariantTrace.max_rel_drift)
    outcome: str
    side: Optional[str] = None  # "lhs" or "rhs": the paper panel the run belongs to (None: a control, or one panel)


@dataclass(frozen=True)
class FigureData:
    name: str  # file stem, e.g. "fig-05"
    title: str
    runs: tuple  # RunData per panel column (LHS, RHS, ...)
    path_label: str = "centre of mass"


@dataclass(frozen=True)
class Evaluation:
    """The outcome of a check.

    ``expected`` is what the independent route gives, ``observed`` what the paper
    prints; ``correction`` is the corrected form for an erratum; ``qualification`` states,
    for a qualified verdict, the exact threshold and the perturbation that produces what the
    caption describes; ``measures`` names each independent measure of a simulation verdict
    with its value, so a reader sees both numbers whether they agree or not.
    """

    verdict: str
    expected: str = ""
    observed: str = ""
    detail: str = ""
    correction: Optional[str] = None
    figures: tuple = ()
    qualification: Optional[str] = None
    measures: tuple = ()  # ((name, value text), ...)


@dataclass(frozen=True)
class Claim:
    """One checkable statement of the paper.

    ``statement`` is the registry's one-line summary (for tables); ``quote`` is what the
    paper prints (one verbatim fragment or a tuple of them) and is what the check decides;
    ``reading`` says how the check reads the quote where that needs saying.  The expected
    verdict is part of the record: ``known_failure`` (with ``severity``) for an erratum,
    ``qualified`` for a qualified caption, ``undecided`` for a simulation whose two measures
    disagree, ``reason_not_checkable`` for a definition.
    """

    id: str
    source: str  # "Eq. 40", "Fig. 11 RHS", "text after Eq. 57"
    section: str  # part of the paper
    statement: str  # the registry's summary
    check: Callable[[], Evaluation] = field(compare=False)
    method: str = "algebra"  # algebra | numbers | simulation | definition
    tolerance: str = "exact (sympy identity)"
    known_failure: Optional[str] = None  # the erratum this check is expected to find
    reason_not_checkable: Optional[str] = None
    quote: Union[str, tuple] = ""
    reading: Optional[str] = None
    severity: Optional[str] = None  # for an erratum: result | typo | rounding
    qualified: Optional[str] = None  # the qualification this check is expected to find
    undecided: Optional[str] = None  # why the measures are expected to disagree

    def __post_init__(self):
        if self.known_failure is not None and self.severity not in SEVERITIES:
            raise ValueError(f"claim {self.id}: an expected erratum needs a severity from {SEVERITIES}, "
                             f"got {self.severity!r}")
        if self.known_failure is None and self.severity is not None:
            raise ValueError(f"claim {self.id}: a severity without an expected erratum")

    @property
    def expected_verdict(self) -> str:
        if self.reason_not_checkable is not None or self.undecided is not None:
            return NOT_CHECKABLE
        if self.known_failure is not None:
            return ERRATUM
        if self.qualified is not None:
            return QUALIFIED
        return CONFIRMED

    def evaluate(self) -> Evaluation:
        return _evaluate(self)


@lru_cache(maxsize=None)
def _evaluate(claim: Claim) -> Evaluation:
    if claim.reason_not_checkable is not None:
        return Evaluation(NOT_CHECKABLE, detail=claim.reason_not_checkable)
    return claim.check()


def decide(agrees: bool, expected, observed, detail="", correction=None, figures=(), measures=()) -> Evaluation:
    """Confirmed when the independent route agrees with the paper, erratum otherwise."""
    verdict = CONFIRMED if agrees else ERRATUM
    return Evaluation(verdict, str(expected), str(observed), detail, None if agrees else correction, tuple(figures),
                      measures=tuple(measures))


def qualify(expected, observed, detail, qualification: str, figures=(), measures=()) -> Evaluation:
    """The caption's behaviour is reproduced only through an unstated or finite perturbation."""
    return Evaluation(QUALIFIED, str(expected), str(observed), detail, None, tuple(figures), qualification,
                      tuple(measures))


def undecided(expected, observed, detail, figures=(), measures=()) -> Evaluation:
    """Two independent measures of a qualitative statement disagree: no verdict, both numbers shown."""
    return Evaluation(NOT_CHECKABLE, str(expected), str(observed), detail, None, tuple(figures), None,
                      tuple(measures))


def definition(id, source, section, statement, reason, quote="", reading=None) -> Claim:
    """A statement that fixes notation or sets up an approximation: nothing to decide."""
    return Claim(id, source, section, statement, check=lambda: None, method="definition",
                 tolerance="-", reason_not_checkable=reason, quote=quote, reading=reading)


def rows_identity(id, source, section, statement, printed, derived, body: str, quote="", reading=None) -> Claim:
    """A printed vector equation (LHS - RHS, 1-2-3 components) against the derived rows of ``body``."""
    def check():
        from ..mathtext import tex  # lazy: sympy stays out of verify.claims.base (figure --list imports it)
        from .vectors import same  # lazy: as above (vectors is sympy)
        import sympy as sp  # lazy: as above

        p, d = printed(), derived()
        ok = same(p, d)
        return decide(ok, f"derived Newton-Euler rows of the {body} (models/rolling.py)", f"{source} as printed, LHS - RHS",
                      "identical, row by row" if ok else f"printed - derived = {tex(sp.simplify(p - d))}")
    return Claim(id, source, section, statement, check, quote=quote, reading=reading)
