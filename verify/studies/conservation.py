"""The conservation table: every model and equation source, in double and quad.

``make report`` writes it to ``reports/conservation.md`` and ``reports/conservation.json``
and into the report's conservation section.  Each row is a 10 s run
from the model's standard state; for every invariant it gives max |I(t) - I(0)|
(``max_abs_drift``), that over |I(0)| (``max_rel_drift``, null where I(0) is negligible) and
over the largest sum of the magnitudes of I's terms (``max_drift_vs_terms``, also in units of
the precision's epsilon): see :class:`verify.engine.invariants.InvariantTrace`.
"""
from __future__ import annotations

import json
import math
import sys
import time

from models import MODEL_NAMES, sources

from ..engine.single import solve
from ..engine.invariants import NEGLIGIBLE_INITIAL
from ..provenance import provenance, write_atomic
from ..standard import STANDARD_STATES

PRECISIONS = ("double", "quad")
T_END = "10"


def conservation_rows(progress=None) -> list:
    rows = []
    for name in MODEL_NAMES:
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


def _cell(x, fmt: str) -> str:
    return "n/a" if x is None else format(x, fmt)


def render_markdown(rows: list, prov: dict) -> str:
    lines = [
        "# Conservation of every invariant, every model",
        "",
        "Each run: 10 s from the model's standard state (`verify/standard.py`), Taylor tolerance = epsilon of the",
        "precision. ΔI = max over the run of |I(t) - I(0)|. Rel drift = ΔI / |I(0)|, n/a where |I(0)| is at most",
        f"{NEGLIGIBLE_INITIAL} eps times the term scale (indistinguishable from zero at the run's precision). Drift vs",
        "terms = ΔI / term scale, the term scale being the largest sum along the run of the absolute values of the",
        "terms of I expanded (for Chaplygin's integrals the sum |c1(0)| + |c2(0)|), which bounds the magnitudes",
        "rounded: this is the figure Brouwer's eps sqrt(N) bounds, also given in units of the precision's epsilon",
        "(double 2.2e-16, quad 1.9e-34). The relative drift is never the smaller of the two; it is larger by the ratio",
        "term scale / |I(0)| where I is a near-cancellation of its terms (the disk's energy: the expanded terms of",
        "(phidot cos theta + psidot)^2 cancel when it leans far over). Chaplygin's integrals carry the state's rounding",
        "through the inverse fundamental matrix, which grows where the body leans far over (disk: theta down to 0.24).",
        "",
        "| model | equations | precision | outcome | steps | invariant | max abs drift ΔI | max rel drift ΔI / \\|I(0)\\| "
        "| max drift vs terms ΔI / term scale | vs terms / eps |",
        "|---|---|---|---|---:|---|---:|---:|---:|---:|",
    ]
    for r in rows:
        for k, a in r["max_abs_drift"].items():
            lines.append(f"| {r['model']} | {r['equations']} | {r['precision']} | {r['outcome']} | {r['steps']} "
                         f"| {k} | {a:.3e} | {_cell(r['max_rel_drift'][k], '.3e')} "
                         f"| {_cell(r['max_drift_vs_terms'][k], '.3e')} | {_cell(r['max_drift_vs_terms_in_eps'][k], 'g')} |")
    lines += ["", "## Provenance", "", "```", json.dumps(prov, indent=2), "```", ""]
    return "\n".join(lines)


def write_report(out="reports") -> None:
    from pathlib import Path

    out = Path(out)
    start = time.monotonic()
    rows = conservation_rows(progress=lambda s: print(f"  running {s}", file=sys.stderr, flush=True))
    prov = provenance(PRECISIONS)
    write_atomic(out / "conservation.json", json.dumps({"rows": rows, "provenance": prov}, indent=2) + "\n")
    write_atomic(out / "conservation.md", render_markdown(rows, prov))
    write_atomic(out / "timing.json", json.dumps({"conservation_seconds": round(time.monotonic() - start, 1)}) + "\n")
    print(f"wrote {out}/conservation.md, {out}/conservation.json", file=sys.stderr)
