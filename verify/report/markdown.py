"""REPORT.md's body from the claim evaluations: the verdict counts, errata, qualified captions, every claim
and the regenerated figures, with the sections rendered elsewhere spliced in (no numerics here)."""
from __future__ import annotations

from collections import Counter
from typing import Optional

from ..claims import ERRATUM, QUALIFIED, SEVERITIES, VERDICTS, missing
from ..claims.base import Claim, quote_fragments


def benchmarks_section(latest: Optional[dict]) -> list:
    """The pointer to BENCHMARKS.md, naming the latest benchmark run (``benchmarks.json``) if any.

    Speed depends on the machine, so the numbers stay out of this byte-reproducible file; the
    report does not run the benchmarks (``make bench`` does), it names the run it points to.
    """
    lines = ["", "## Benchmarks", "",
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
        when = latest.get("date", "an unrecorded date")
        src = (latest.get("sources") or {}).get("commit")
        lines += [f"Latest run: {when}, on {m.get('cpu', '?')} ({m.get('cpus', '?')} cores, SIMD batch size "
                  f"{m.get('simd_size', '?')}), heyoka {m.get('heyoka', '?')}"
                  + (f", sources at commit {src[:12]}" if src else "") + ".", ""]
    return lines


def _quote_text(claim: Claim) -> str:
    return " ... ".join(quote_fragments(claim.quote))


def _md_escape(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def render_markdown(results: list, conservation_md: str, prov: dict, figure_dir: str = "figures",
                    summary: dict = None) -> str:
    from .summary import render as render_summary

    counts = Counter(ev.verdict for _, ev in results)
    eqs, figs = missing()
    lines = [
        "# Verification report",
        "",
        "Every numbered equation and figure caption of `../shared/paper.md`, each quoted and given a verdict from an",
        "independent route (sympy identities against the rows derived from the vectors, mpmath numbers, heyoka runs",
        "read by two measures each).",
        "",
    ]
    if summary is not None:
        lines += render_summary(summary)
    lines += ["| verdict | claims |", "|---|---:|"]
    lines += [f"| {v} | {counts.get(v, 0)} |" for v in VERDICTS]
    lines += [f"| total | {len(results)} |", ""]
    if eqs or figs:
        lines += [f"Not yet covered by a claim: equations {eqs or 'none'}; figures {figs or 'none'}.", ""]
    lines += ["## Errata, by severity", ""]
    for severity in SEVERITIES:
        for claim, ev in results:
            if ev.verdict == ERRATUM and claim.severity == severity:
                lines += [f"### {claim.source} ({severity})", "",
                          f"- **the paper:** {_quote_text(claim)}",
                          *([f"- **read as:** {claim.reading}"] if claim.reading else []),
                          f"- **as printed:** {ev.observed}",
                          f"- **corrected:** {ev.correction}",
                          f"- **evidence:** {ev.expected}. {ev.detail}", ""]
    lines += ["## Qualified captions", ""]
    for claim, ev in results:
        if ev.verdict == QUALIFIED:
            lines += [f"### {claim.source}", "", f"- **the paper:** {_quote_text(claim)}",
                      *([f"- **read as:** {claim.reading}"] if claim.reading else []),
                      f"- **qualification:** {ev.qualification}",
                      f"- **evidence:** {ev.expected}. {ev.detail}", ""]
    section = None
    for claim, ev in results:
        if claim.section != section:
            section = claim.section
            lines += [f"## {section}", "", "| source | the paper | verdict | independent route | paper | detail |",
                      "|---|---|---|---|---|---|"]
        verdict = ev.verdict + (f" ({claim.severity})" if ev.verdict == ERRATUM else "")
        detail = ev.detail + ("" if not ev.measures else " Measures: " + "; ".join(f"{n}: {v}" for n, v in ev.measures))
        lines.append(f"| {claim.source} | {_md_escape(_quote_text(claim))} | {verdict} | {_md_escape(ev.expected)} "
                     f"| {_md_escape(ev.observed)} | {_md_escape(detail)} |")
    lines += ["", "## Regenerated figures", ""]
    for claim, ev in results:
        for fig in ev.figures:
            lines += [f"### {fig.title} ({ev.verdict})", "", f"![{fig.title}]({figure_dir}/{fig.name}.png)", ""]
    lines += ["", conservation_md.replace("# Conservation", "## Conservation", 1), ""]
    return "\n".join(lines)
