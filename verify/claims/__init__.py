"""The registry of the paper's claims (see :mod:`verify.claims.base`)."""
from __future__ import annotations

import importlib
import re
from functools import lru_cache

from .base import CONFIRMED, ERRATUM, NOT_CHECKABLE, QUALIFIED, SEVERITIES, VERDICTS, Claim, Evaluation

#: The claim modules, in the report's order.  Imported when the registry is asked for, not with
#: the package: a module that only needs the verdict names (``from verify.claims import ERRATUM``)
#: then does not depend on every claim module, which keeps the report's job keys narrow
#: (:mod:`verify.report.dependencies`).
SECTION_MODULES = ("disk", "simulations", "ring", "hurricane", "gyroscope")
N_EQUATIONS, N_FIGURES = 100, 20


@lru_cache(maxsize=None)
def all_claims() -> tuple:
    SECTIONS = [importlib.import_module(f"{__name__}.{m}") for m in SECTION_MODULES]
    order = [m.SECTION if hasattr(m, "SECTION") else None for m in SECTIONS]
    claims = [c for module in SECTIONS for c in module.claims()]
    claims.sort(key=lambda c: [o for o in order if o].index(c.section))  # stable: keeps order within a section
    claims = tuple(claims)
    ids = [c.id for c in claims]
    dupes = {i for i in ids if ids.count(i) > 1}
    if dupes:
        raise RuntimeError(f"duplicate claim ids: {sorted(dupes)}")
    return claims


def covered(claims=None) -> tuple:
    """(equation numbers, figure numbers) that some claim's source names."""
    eqs, figs = set(), set()
    for c in claims or all_claims():
        for a, b in re.findall(r"Eqs?\. (\d+)(?:\s*(?:-|=)\s*(\d+))?", c.source):
            lo, hi = int(a), int(b or a)
            eqs.update(range(lo, hi + 1))
        for a in re.findall(r"Figs?\. (\d+)", c.source):
            figs.add(int(a))
        for a, b in re.findall(r"Figs\. (\d+)-(\d+)", c.source):
            figs.update(range(int(a), int(b) + 1))
    return eqs, figs


def missing() -> tuple:
    eqs, figs = covered()
    return (sorted(set(range(1, N_EQUATIONS + 1)) - eqs), sorted(set(range(1, N_FIGURES + 1)) - figs))


__all__ = ["CONFIRMED", "ERRATUM", "NOT_CHECKABLE", "QUALIFIED", "SEVERITIES", "VERDICTS", "Claim", "Evaluation", "all_claims", "covered", "missing"]
