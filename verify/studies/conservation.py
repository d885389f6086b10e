"""The conservation table's data: every model and equation source, in double and quad.

:func:`conservation_rows` returns the rows; ``make report`` renders them
(:mod:`verify.report.conservation`) into ``reports/conservation.md``, ``reports/conservation.json``
and the report's conservation section.  Each row is a 10 s run
from the model's standard state; for every invariant it gives max |I(t) - I(0)|
(``max_abs_drift``), that over |I(0)| (``max_rel_drift``, null where I(0) is negligible) and
over the largest sum of the magnitudes of I's terms (``max_drift_vs_terms``, also in units of
the precision's epsilon): see :class:`verify.engine.invariants.InvariantTrace`.
"""
from __future__ import annotations

import math

from models import MODEL_NAMES, sources

from ..engine.single import solve
from ..standard import STANDARD_STATES

PRECISIONS = ("double", "quad")
T_END = "10"


def conservation_models() -> tuple:
    """The models of the table, in its order."""
    return tuple(MODEL_NAMES)


def conservation_rows(progress=None, models=None) -> list:
    """The table's rows for ``models`` (default: all, :func:`conservation_models`)."""
    rows = []
    for name in models or conservation_models():
        for eq in sources(name):
            # The printed sources are the same equations (tests/test_derivation.py): quad once, on the derived ones.
            for prec in PRECISIONS if eq == "derived" else PRECISIONS[:1]:
                if progress:
                    progress(f"{name} ({eq}) in {prec}")
                sol = solve(name, T_END, STANDARD_STATES[name], equations=eq, precision=prec, n_eval=201)
                inv = sol.invariants
                rows.append({
                    "model": name, "equations": eq, "precision": prec, "t_end": T_END,
                    "outcome": sol.outcome, "steps": sol.steps,
                    "max_abs_drift": {k: tr.max_abs_drift for k, tr in inv.items()},
                    "max_rel_drift": {k: _finite(tr.max_rel_drift) for k, tr in inv.items()},
                    "max_drift_vs_terms": {k: _finite(tr.max_drift_vs_terms) for k, tr in inv.items()},
                    "max_drift_vs_terms_in_eps": {k: _finite(round(tr.max_drift_vs_terms_in_eps, 2))
                                                  for k, tr in inv.items()},
                })
    return rows


def _finite(x: float):
    """NaN (an undefined ratio) as None: null in JSON, n/a in the table."""
    return None if math.isnan(x) else x
