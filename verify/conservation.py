"""The conservation table: every model and equation source, in double and quad.

Until the claims report exists (issue 3) this is what ``make report`` writes:
``reports/conservation.md`` and ``reports/conservation.json``.  Each row is a 10 s run
from the model's standard state; drift is max |I(t) - I(0)| / scale (see
:class:`verify.invariants.InvariantTrace`), also in units of the precision's epsilon.
"""
from __future__ import annotations

import json
import sys
import time

from models import MODEL_NAMES, sources

from .integrate import solve
from .provenance import provenance, write_atomic
from .standard import STANDARD_STATES

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
                eps = sol.precision.eps
                rows.append({
                    "model": name, "equations": eq, "precision": prec, "t_end": T_END,
                    "outcome": sol.outcome, "steps": sol.steps,
                    "drift": {k: tr.max_rel_drift for k, tr in sol.invariants.items()},
                    "drift_in_eps": {k: round(tr.max_rel_drift / eps, 2) for k, tr in sol.invariants.items()},
                })
    return rows


def render_markdown(rows: list, prov: dict) -> str:
    lines = [
        "# Conservation of every invariant, every model",
        "",
        "Each run: 10 s from the model's standard state (`verify/standard.py`), Taylor tolerance = epsilon of the",
        "precision. Drift = max over the run of |I(t) - I(0)| / scale, scale = the largest sum of the absolute values",
        "of the terms of I along the run (for Chaplygin's integrals |c1(0)| + |c2(0)|); shown as a number and in units",
        "of the precision's epsilon (double 2.2e-16, quad 1.9e-34). Chaplygin's integrals carry the state's rounding",
        "through the inverse fundamental matrix, which grows where the body leans far over (disk: theta down to 0.24).",
        "",
        "| model | equations | precision | outcome | steps | invariant | drift | drift / eps |",
        "|---|---|---|---|---:|---|---:|---:|",
    ]
    for r in rows:
        for k, v in r["drift"].items():
            lines.append(f"| {r['model']} | {r['equations']} | {r['precision']} | {r['outcome']} | {r['steps']} "
                         f"| {k} | {v:.3e} | {r['drift_in_eps'][k]:g} |")
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
