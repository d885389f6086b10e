"""Claims are data: a frozen record per checkable statement of the paper.

In the manner of scipy.special's test registry: each :class:`Claim` names its source in
the paper, the statement as printed, the check that decides it, the tolerance with its
reason, and, where the paper is wrong, a known-failure note.  One parametrised test runs
every claim (tests/test_claims.py) and the report renders the same evaluations, so the
two cannot disagree.  The check computes the expected value by an independent route and
compares it with what the paper prints; the verdict comes out of that comparison.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Callable, Optional

CONFIRMED, ERRATUM, NOT_CHECKABLE = "confirmed", "erratum", "not-checkable"


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
    energy_drift: float
    outcome: str


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
    prints; ``correction`` is the corrected form for an erratum.
    """

    verdict: str
    expected: str = ""
    observed: str = ""
    detail: str = ""
    correction: Optional[str] = None
    figures: tuple = ()


@dataclass(frozen=True)
class Claim:
    id: str
    source: str  # "Eq. 40", "Fig. 11 RHS", "text after Eq. 57"
    section: str  # part of the paper
    statement: str  # as printed
    check: Callable[[], Evaluation] = field(compare=False)
    method: str = "algebra"  # algebra | numbers | simulation | definition
    tolerance: str = "exact (sympy identity)"
    known_failure: Optional[str] = None  # the erratum this check is expected to find
    reason_not_checkable: Optional[str] = None

    def evaluate(self) -> Evaluation:
        return _evaluate(self)


@lru_cache(maxsize=None)
def _evaluate(claim: Claim) -> Evaluation:
    if claim.reason_not_checkable is not None:
        return Evaluation(NOT_CHECKABLE, detail=claim.reason_not_checkable)
    return claim.check()


def decide(agrees: bool, expected, observed, detail="", correction=None, figures=()) -> Evaluation:
    """Confirmed when the independent route agrees with the paper, erratum otherwise."""
    verdict = CONFIRMED if agrees else ERRATUM
    return Evaluation(verdict, str(expected), str(observed), detail, None if agrees else correction, tuple(figures))


def definition(id, source, section, statement, reason) -> Claim:
    """A statement that fixes notation or sets up an approximation: nothing to decide."""
    return Claim(id, source, section, statement, check=lambda: None, method="definition",
                 tolerance="-", reason_not_checkable=reason)


def rows_identity(id, source, section, statement, printed, derived, body: str) -> Claim:
    """A printed vector equation (LHS - RHS, 1-2-3 components) against the derived rows of ``body``."""
    def check():
        from .vectors import same, show
        import sympy as sp

        p, d = printed(), derived()
        ok = same(p, d)
        return decide(ok, f"derived Newton-Euler rows of the {body} (models/rolling.py)", f"{source} as printed, LHS - RHS",
                      "identical, row by row" if ok else f"printed - derived = {show(sp.simplify(p - d).T)}")
    return Claim(id, source, section, statement, check)
