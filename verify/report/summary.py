"""The one-screen summary a reader opens first: computed into data, rendered from data.

:func:`build` reads the claim evaluations and the studies (thresholds, spin-down) and returns
a plain dict -- the two open questions answered with their numbers, the errata ordered by
severity, the qualified captions with their thresholds, the undecided ones -- which goes into
results.json; :func:`render` turns that dict, and nothing else, into Markdown.
"""
from __future__ import annotations

from models import ring

from ..claims.base import ERRATUM, NOT_CHECKABLE, QUALIFIED, SEVERITIES
from ..studies.finite_offset import RULE
from .markup import inline_quote, text

SEVERITY_WORDS = {"result": "a number or conclusion is wrong", "typo": "the printed form is wrong, what follows is right",
                  "rounding": "a last printed digit"}


def _threshold(rows, model, motion):
    for r in rows:
        if r["model"] == model and r["motion"] == motion and not r["params"]:
            return r
    raise KeyError((model, motion))


def _spindown(rows, model, family):
    return [r for r in rows if r["model"] == model and r["family"] == family]


def build(claims: list, studies: dict) -> dict:
    """The summary as data.  ``claims``: results.json's claim records; ``studies``: its studies dict."""
    verdict = {c["id"]: c["verdict"] for c in claims}
    rolling = _threshold(studies["thresholds"], "disk", "diameter-spin")
    smooth = _threshold(studies["thresholds"], "sliding-disk", "diameter-spin")
    sd = studies["spindown"]
    eq45_exact = max(abs(float(r["relative_error"])) for r in _spindown(sd, "disk", "cm-at-rest"))
    eq45_other = [(r["theta"], r["relative_error"]) for r in _spindown(sd, "disk", "zero-vertical-spin")]
    eq61 = {fam: [(r["theta"], r["relative_error"]) for r in _spindown(sd, "ring", fam)]
            for fam in ("zero-vertical-spin", "cm-at-rest")}
    ring_rows = _spindown(sd, "ring", "zero-vertical-spin") + _spindown(sd, "ring", "cm-at-rest")
    # which ring parameter set the limits are for, and the other set's limits (the rows carry both)
    eq61_set = ring_rows[-1].get("parameter_set") if ring_rows else None
    eq61_annular = {fam: [(r["theta"], r.get("relative_error_annular")) for r in _spindown(sd, "ring", fam)]
                    for fam in ("zero-vertical-spin", "cm-at-rest")}
    errata = [{"id": c["id"], "source": c["source"], "severity": c["severity"], "quote": _first(c["quote"]),
               "correction": c["correction"]} for c in claims if c["verdict"] == ERRATUM]
    errata.sort(key=lambda x: SEVERITIES.index(x["severity"]))  # stable: paper order within a severity
    qualified = [{"id": c["id"], "source": c["source"], "quote": _first(c["quote"]), "qualification": c["qualification"]}
                 for c in claims if c["verdict"] == QUALIFIED]
    undecided = [{"id": c["id"], "source": c["source"], "quote": _first(c["quote"]),
                  "measures": [f"{m['measure']}: {m['value']}" for m in c.get("measures", ())]}
                 for c in claims if c["verdict"] == NOT_CHECKABLE and c.get("undecided")]
    return {
        "olsson": {"rolling_rate": rolling["linear"], "rolling_form": f"${rolling['closed_form_tex']}$",
                   "smooth_rate": smooth["linear"], "smooth_form": f"${smooth['closed_form_tex']}$",
                   "eq41": verdict.get("eq-41"), "footnote2": verdict.get("footnote-2"),
                   "fig5": [verdict.get("fig-5-lhs"), verdict.get("fig-5-rhs")]},
        "divergence": {"eq45_cm_at_rest_max_rel_error": f"{eq45_exact:.1e}", "eq45_zero_vertical_spin": eq45_other,
                       "eq61": eq61, "eq45": verdict.get("eq-45"), "eq61_verdict": verdict.get("eq-61"),
                       "eq61_parameter_set": eq61_set, "eq61_annular": eq61_annular,
                       "eq61_parameter_values": _ring_set_values(eq61_set)},
        "errata": errata, "qualified": qualified, "undecided": undecided,
    }


def _ring_set_values(name):
    """The printed set's own numbers (decimal strings), so that the summary shows them from the data."""
    return dict(ring.PRINTED) if name == "printed" else None


def _ring_set_words(d: dict) -> str:
    """How the summary names the ring parameter set the Eq. 61 limits are for (from the data)."""
    name, values = d.get("eq61_parameter_set"), d.get("eq61_parameter_values")
    if name == "printed" and values:
        return f"for the printed ring set ({', '.join(f'{k} = {v}' for k, v in values.items())}), "
    return "for the annular ring set (the model's defaults), " if name == "annular" else ""


def _annular(d: dict, family: str) -> str:
    """' (annular set: X)' beside a printed-set limit, when the rows carry the annular value."""
    if d.get("eq61_parameter_set") != "printed":
        return ""
    rows = (d.get("eq61_annular") or {}).get(family) or []
    return f" (annular set: {rows[-1][1]})" if rows and rows[-1][1] is not None else ""


def _first(quote) -> str:
    return quote if isinstance(quote, str) else " ... ".join(quote)


S_INV = "s⁻¹"  # a unit is upright: plain text, not math (MathML sets a lone letter in italics)


def render_answers(s: dict) -> list:
    """Markdown lines of the two open questions' answers, the page's first words after the tally."""
    o, d = s["olsson"], s["divergence"]
    z45 = d["eq45_zero_vertical_spin"]
    z61 = d["eq61"]["zero-vertical-spin"]
    c61 = d["eq61"]["cm-at-rest"]
    return [
        f"**Olsson or Eq. 41?** Both, each for its own contact. Rolling without slipping (a real table) is linearly "
        f"stable while {o['rolling_form']}: rate {o['rolling_rate']} {S_INV} (Eq. 41, {o['eq41']}); a frictionless "
        f"plane, which is Olsson's zero horizontal force, needs {o['smooth_form']}: rate "
        f"{float(o['smooth_rate']):.4f} {S_INV} (footnote 2, {o['footnote2']}). The paper's own Fig. 5 runs at 1.1 and "
        f"0.9 times Eq. 41's rate are stable and unstable as Eq. 41 says "
        f"({' and '.join(str(v) for v in o['fig5'])}).",
        "",
        f"**Does $\\dot\\phi$ diverge as $\\theta \\to 0$, as Eqs. 45 and 61 say?** It diverges like "
        f"$\\theta^{{-1/2}}$ on every exact steady spin-down. Eq. 45 is exact on the family with the centre of mass at "
        f"rest (largest relative error {d['eq45_cm_at_rest_max_rel_error']}, round-off of 60-digit arithmetic) and the "
        f"leading term on the family with no vertical spin (relative error {z45[0][1]} at $\\theta$ = {z45[0][0]}, "
        f"{z45[-1][1]} at {z45[-1][0]}: like $3\\theta^2$). Eq. 61, the ring's version, is wrong ({d['eq61_verdict']}): "
        f"{_ring_set_words(d)}its relative error tends to {z61[-1][1]}{_annular(d, 'zero-vertical-spin')} on the family "
        f"with no vertical spin ($\\theta$ = {z61[-1][0]}) and {c61[-1][1]}{_annular(d, 'cm-at-rest')} with the centre "
        "of mass at rest; the factor $(1 - h)$ is spurious.",
        "",
    ]


def render(s: dict) -> list:
    """Markdown lines of the summary after the answers (no computation here): the errata, the
    qualified and the undecided captions."""
    lines = []
    if s["errata"]:
        lines += ["**Errata, most serious first** (severity: " +
                  "; ".join(f"*{k}*: {v}" for k, v in SEVERITY_WORDS.items()) + "):", "",
                  "| severity | where | the paper prints | correction |", "|---|---|---|---|"]
        lines += [f"| {e['severity']} | [{text(e['source'])}](#{e['id']}) | {inline_quote(e['quote'], table=True)} "
                  f"| {text(e['correction'], table=True)} |"
                  for e in s["errata"]]
        lines.append("")
    if s["qualified"]:
        lines += ["**Qualified captions** -- the described behaviour is reproduced only through a finite or unstated "
                  "perturbation or one unstated choice, while what the caption implies in general (a threshold, a "
                  "sense) is wrong or holds only for that choice. " + RULE, ""]
        lines += [f"- [{text(q['source'])}](#{q['id']}): {text(q['qualification'])}" for q in s["qualified"]]
        lines.append("")
    if s["undecided"]:
        lines += ["**Undecided captions** -- two independent measures disagree, so no verdict is given:", ""]
        lines += [f"- [{text(u['source'])}](#{u['id']}): " + text("; ".join(u["measures"])) for u in s["undecided"]]
        lines.append("")
    return lines
