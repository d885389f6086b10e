"""The issue-4 results as data for the report: thresholds (linear and nonlinear) and spin-down."""
from __future__ import annotations

import mpmath

from .spindown import FAMILIES, spindown
from .thresholds import bracket, threshold

THRESHOLD_CASES = (("disk", "diameter-spin"), ("disk", "straight-line"), ("sliding-disk", "diameter-spin"),
                   ("ring", "straight-line"), ("ring", "diameter-spin"), ("hurricane", "precession"))
HOOP = {"k": "0.5"}
TILT = "1e-6"
THETAS = ("1e-1", "1e-2", "1e-4", "1e-6", "1e-8")


def threshold_rows(progress=None) -> list:
    rows = []
    cases = [(m, mo, {}) for m, mo in THRESHOLD_CASES] + [("disk", "diameter-spin", HOOP), ("disk", "straight-line", HOOP)]
    for model, motion, params in cases:
        if progress:
            progress(f"threshold {model} {motion} {params or ''}")
        t = threshold(model, motion, params)
        b = bracket(model, motion, TILT, params, iterations=16) if t.value is not None else None
        rows.append({
            "model": model, "motion": motion, "params": params,
            "rate": t.name, "linear": None if t.value is None else mpmath.nstr(t.value, 15),
            "closed_form": t.closed_form, "method": t.method,
            "bracket_at_tilt_1e-6": None if b is None else [mpmath.nstr(b[0], 8), mpmath.nstr(b[1], 8)],
        })
    return rows


def spindown_rows() -> list:
    rows = []
    for model in ("disk", "ring"):
        for family in FAMILIES:
            for th in THETAS:
                s = spindown(model, th, family)
                rows.append({"model": model, "family": family, "theta": th, "phidot": mpmath.nstr(s.phidot, 15),
                             "psidot": mpmath.nstr(s.psidot, 15), "energy": mpmath.nstr(s.energy, 15),
                             "paper": s.paper_source, "relative_error": mpmath.nstr(s.relative_error, 6)})
    return rows


def render(thresholds: list, spins: list) -> str:
    lines = [
        "## Stability thresholds (issue 4, first part)",
        "",
        "Linear: the reduced Jacobian about the steady motion has characteristic polynomial lambda^2 (lambda^2 + w2);",
        "oscillatory while w2 > 0. Nonlinear: bisection on the rate with theta perturbed by 1e-6, growth = leaving the",
        "domain or moving more than 1000 x the tilt within 10 s. Both diameter-spin thresholds are right, each for its own",
        "contact: g/(k+1) rolling (the paper's Eq. 41), g/k on a frictionless plane (Olsson's assumption of zero",
        "horizontal force is exactly the smooth-plane model).",
        "",
        "| model | motion | params | rate | linear threshold | closed form | nonlinear bracket (tilt 1e-6) |",
        "|---|---|---|---|---:|---|---|",
    ]
    for r in thresholds:
        br = "-" if r["bracket_at_tilt_1e-6"] is None else f"[{r['bracket_at_tilt_1e-6'][0]}, {r['bracket_at_tilt_1e-6'][1]}]"
        lines.append(f"| {r['model']} | {r['motion']} | {r['params'] or 'defaults'} | {r['rate']} | "
                     f"{r['linear'] or 'none (stable)'} | {r['closed_form'] or '-'} | {br} |")
    lines += [
        "",
        "## Steady spin-down states (issue 4, second part, begun)",
        "",
        "Exact (50 digits) steady motions with thetadot = 0 on the family with the centre of mass at rest and on the",
        "family with no vertical spin; relative error of the paper's Eq. 45 (disk) or Eq. 61 (ring) against them.",
        "",
        "| model | family | theta | phidot | psidot | energy | paper | relative error |",
        "|---|---|---:|---:|---:|---:|---|---:|",
    ]
    for r in spins:
        lines.append(f"| {r['model']} | {r['family']} | {r['theta']} | {r['phidot']} | {r['psidot']} | {r['energy']} "
                     f"| {r['paper']} | {r['relative_error']} |")
    return "\n".join(lines) + "\n"
