"""REPORT.md from results.json: the summary, every claim with the paper's words beside its verdict and
evidence, the conservation table and the studies (rendered by their own modules), as named sections.

The claims' texts are plain text with math in ``$...$``, escaped by :func:`.markup.text`.
:func:`sections` is shared by REPORT.md and report.html
(:mod:`.page`), which shows the same sections with the claims laid out as cards.
"""
from __future__ import annotations

import json
import re
from collections import Counter
from typing import Optional

from ..claims.base import ERRATUM, VERDICTS
from ..studies.tippe.report import render_markdown as render_tippe
from .bodies import render_markdown as render_bodies
from .conservation import render_markdown as conservation_markdown
from .engines import render_markdown as render_engines
from .figures import with_alt_text
from .friction import render_markdown as render_friction
from .markup import quote, text
from .reference import render_markdown as render_reference
from .retrograde import render_markdown as render_retrograde
from .sections import render as render_studies
from .summary import SEVERITY_WORDS, render as render_summary, render_answers

def verdict_label(rec: dict) -> str:
    return rec["verdict"] + (f" ({rec['severity']})" if rec["verdict"] == ERRATUM else "")


def claim_markdown(rec: dict) -> list:
    """One claim: heading (anchored by the claim's id), the quote, the verdict and the evidence, its figures."""
    lines = [f'### <a id="{rec["id"]}"></a>{text(rec["source"])}: {verdict_label(rec)}', ""]
    lines += quote(rec["quote"]) + [""]
    if rec.get("quote_not_in_paper"):
        lines += ["**This quote is not in the paper the report was made from** (`VERIFY_PAPER`): the verdict is "
                  "about the words quoted here.", ""]
    fields = [("verdict", verdict_label(rec) + (f": {SEVERITY_WORDS[rec['severity']]}" if rec.get("severity") else "")),
              ("read as", rec.get("reading")), ("independent route", rec["expected"]), ("the paper", rec["observed"]),
              ("corrected", rec.get("correction")), ("qualification", rec.get("qualification")),
              ("measures", "; ".join(f"{m['measure']}: {m['value']}" for m in rec.get("measures", ())) or None),
              ("detail", rec["detail"]), ("method", f"{rec['method']}; tolerance: {rec['tolerance']}")]
    lines += [f"- **{name}:** {text(value)}" for name, value in fields if value]
    for fig in rec.get("figures", ()):
        lines += ["", f"![{text(fig['alt'])}](figures/{fig['file']})"]
    return lines + [""]


def benchmarks_section(latest: Optional[dict]) -> list:
    """The pointer to BENCHMARKS.md, naming the latest benchmark run (``benchmarks.json``) if any.

    Speed depends on the machine, so the numbers stay out of this byte-reproducible file; the
    report does not run the benchmarks (``make bench`` does), it names the run it points to.
    """
    lines = ["## Benchmarks", "",
             "Speed depends on the machine, so the benchmarks are not in this file: `make bench` "
             "(`python -m verify bench`) writes [BENCHMARKS.md](BENCHMARKS.md) and `benchmarks.json` -- the suite "
             "against bare heyoka on the same work, the energy error over long runs, work against precision "
             "against the reference set (heyoka at double, long, quad and MPFR; scipy's DOP853, Radau and LSODA; "
             "mpmath's odefun), heyoka's own modes and the JIT cost, with the machine they ran on. "
             "`make report` does not re-run them.", ""]
    if latest is None:
        lines += ["No benchmark run is in this folder yet.", ""]
    else:
        m = latest.get("machine", {})
        when = latest.get("date")
        src = (latest.get("sources") or {}).get("commit")
        lines += [f"Latest run{': ' + when if when else ''}, on {m.get('cpu', '?')} ({m.get('cpus', '?')} cores, SIMD batch size "
                  f"{m.get('simd_size', '?')}), heyoka {m.get('heyoka', '?')}"
                  + (f", sources at commit {src[:12]}" if src else "") + ".", ""]
    return lines


def _overview(results: dict) -> list:
    claims = results["claims"]
    counts = Counter(c["verdict"] for c in claims)
    # the tally and the two answers first: what a reader opens the report for
    lines = ["| verdict | claims |", "|---|---:|"]
    lines += [f"| {v} | {counts.get(v, 0)} |" for v in VERDICTS]
    lines += [f"| total | {len(claims)} |", ""]
    if results.get("failures"):
        lines += ["**Incomplete report:** these jobs failed, so what they compute is missing below:", ""]
        lines += [f"- `{f['job']}`: {text(f['error'])}" for f in results["failures"]]
        lines.append("")
    if results.get("summary"):
        lines += render_answers(results["summary"])
    lines += ["Every numbered equation and figure caption of the paper (`verify/claims/paper.md`, a copy of "
              "`../shared/paper.md`), each quoted and given a verdict from an independent route (sympy identities "
              "against the rows derived from the vectors, mpmath numbers, heyoka runs read by two measures each).", ""]
    if results.get("summary"):
        lines += render_summary(results["summary"])
    nc = results.get("not_covered", {})
    if nc.get("equations") or nc.get("figures"):
        lines += [f"Not yet covered by a claim: equations {nc['equations'] or 'none'}; figures {nc['figures'] or 'none'}.",
                  ""]
    return lines


def sections(results: dict, benchmarks: Optional[dict], engines: Optional[dict] = None) -> list:
    """The report as ``(anchor, title, markdown body, claims or None)`` in reading order.

    A claims section carries its claim records too, so the page can lay each out as a card;
    its Markdown body is the same claims rendered by :func:`claim_markdown`.
    """
    out = [("summary", "Summary", "\n".join(_overview(results)), None)]
    by_section = {}
    for rec in results["claims"]:
        by_section.setdefault(rec["section"], []).append(rec)
    for title, recs in by_section.items():
        body = [line for rec in recs for line in claim_markdown(rec)]
        out.append((_slug(title), title, "\n".join(body), recs))
    def guarded(title, render):
        """A study's sections; where a failed job left its data missing, a line saying so instead."""
        try:
            return render()
        except (KeyError, TypeError, IndexError, ValueError, AttributeError) as err:
            if not results.get("failures"):
                raise  # no job failed: a renderer bug, not missing data
            return [(_slug(title), title, f"Not shown: a job this section reads failed ({type(err).__name__}: "
                                          f"{text(err)}); see the list of failed jobs in the summary.", None)]

    def conservation():
        cons = conservation_markdown(results["conservation"], results["provenance"]).split("\n## Provenance")[0]
        return [("conservation", "Conservation", cons.split("\n", 1)[1].lstrip("\n"), None)]

    studies = results["studies"]
    alts = {f["file"]: f["alt"] for f in results.get("figures", ())}
    out += guarded("Conservation", conservation)
    out += guarded("Stability thresholds", lambda: _split_h2(render_studies(studies), alts))
    out += guarded("Reference trajectories", lambda: _split_h2("\n".join(
        render_reference(studies["reference"]["index"], studies["reference"]["checks"],
                         studies["reference"].get("proved")))))
    out += guarded("Retrograde turn", lambda: _split_h2("\n".join(render_retrograde(studies["retrograde"])), alts))
    if studies.get("friction") is not None:  # absent from a results.json made before the section
        out += guarded("Friction", lambda: _split_h2("\n".join(render_friction(studies["friction"],
                                                                               studies.get("dissipation")))))
    if studies.get("bodies") is not None:  # absent from a results.json made before the section
        out += guarded("Bodies of revolution", lambda: _split_h2("\n".join(
            render_bodies(studies["bodies"], studies["reference"]["index"], studies.get("body_thresholds")))))
    if studies.get("tippe_top") is not None:  # absent from a results.json made before the section
        out += guarded("Tippe top", lambda: _split_h2(render_tippe(studies["tippe_top"])))
    out += _split_h2("\n".join(render_engines(engines)))
    out += _split_h2("\n".join(benchmarks_section(benchmarks)))
    out.append(("provenance", "Provenance", "```\n" + json.dumps(results["provenance"], indent=2) + "\n```", None))
    return out


def render_markdown(results: dict, benchmarks: Optional[dict] = None, engines: Optional[dict] = None) -> str:
    """REPORT.md: every section of :func:`sections` under its ``##`` heading."""
    lines = ["# Verification report", ""]
    for anchor, title, body, _ in sections(results, benchmarks, engines):
        lines += [f'## <a id="{anchor}"></a>{title}', "", body.strip("\n"), ""]
    return "\n".join(lines)


def _split_h2(markdown: str, alts: Optional[dict] = None) -> list:
    """``## `` sections of a rendered block as (anchor, title, body, None), each figure line given
    its alt text from ``alts`` (results.json's ``figures``)."""
    markdown = with_alt_text(markdown, alts or {})
    out = []
    for chunk in re.split(r"^## ", markdown, flags=re.M)[1:]:
        title, _, body = chunk.partition("\n")
        out.append((_slug(title), title.strip(), body.strip("\n"), None))
    return out


def _slug(title: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", title.lower()).strip("-")
