"""The conservation table (reports/conservation.md and the report's section) from the rows of
:func:`verify.studies.conservation.conservation_rows`."""
from __future__ import annotations

import json

from ..engine.invariants import NEGLIGIBLE_INITIAL


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
