"""The verification report: results in, Markdown / HTML / JSON out (no numerics here).

``python -m verify report`` evaluates every claim of the registry, runs the conservation
table, and writes atomically ``reports/REPORT.md``, ``reports/report.html``,
``reports/results.json``, the conservation table, and ``reports/timing.json`` (the only
file whose content changes from run to run).
"""
from __future__ import annotations

import base64
import html
import json
import sys
import time
from collections import Counter
from pathlib import Path

from ..claims import ERRATUM, QUALIFIED, SEVERITIES, VERDICTS, all_claims, missing
from ..claims.base import Claim, Evaluation, quote_fragments
from ..provenance import provenance, write_atomic


def evaluate_all(progress=None) -> list:
    out = []
    claims = all_claims()
    for i, claim in enumerate(claims, 1):
        t0 = time.monotonic()
        ev = claim.evaluate()
        if progress:
            progress(f"[{i:3d}/{len(claims)}] {claim.source:<28} {ev.verdict:<13} {time.monotonic() - t0:5.1f} s")
        out.append((claim, ev))
    return out


def result_record(claim: Claim, ev: Evaluation) -> dict:
    rec = {"id": claim.id, "source": claim.source, "statement": claim.statement, "quote": list(quote_fragments(claim.quote)),
           "verdict": ev.verdict, "expected": ev.expected, "observed": ev.observed, "detail": ev.detail}
    if claim.reading:
        rec["reading"] = claim.reading
    rec["method"] = claim.method
    rec["tolerance"] = claim.tolerance
    if ev.correction:
        rec["correction"] = ev.correction
    if ev.verdict == ERRATUM:
        rec["severity"] = claim.severity
    if ev.qualification:
        rec["qualification"] = ev.qualification
    if ev.measures:
        rec["measures"] = [{"measure": n, "value": v} for n, v in ev.measures]
    return rec


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


def render_html(markdown_text: str, images: dict) -> str:
    """A self-contained page: the Markdown rendered by a small converter (tables, headings, lists)."""
    body, in_table = [], False
    for raw in markdown_text.splitlines():
        line = raw.rstrip()
        if line.startswith("|"):
            cells = [html.escape(c.strip().replace("\\|", "|")) for c in line.strip("|").split(" | ")]
            if set(line.replace("|", "").strip()) <= set("-: "):
                continue
            if not in_table:
                body.append("<table>")
                body.append("<tr>" + "".join(f"<th>{c}</th>" for c in cells) + "</tr>")
                in_table = True
            else:
                body.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
            continue
        if in_table:
            body.append("</table>")
            in_table = False
        if line.startswith("![") and "](" in line:
            target = line.split("](", 1)[1].rstrip(")")
            name = target.rsplit("/", 1)[-1]
            if name in images:
                data = base64.b64encode(images[name]).decode()
                body.append(f"<p><img alt='{html.escape(name)}' src='data:image/png;base64,{data}'></p>")
            continue
        if line.startswith("#"):
            level = len(line) - len(line.lstrip("#"))
            body.append(f"<h{level}>{html.escape(line[level:].strip())}</h{level}>")
        elif line.startswith("- "):
            text = html.escape(line[2:]).replace("**", "")
            body.append(f"<li>{text}</li>")
        elif line.startswith("```"):
            body.append("<pre>" if not body or body[-1] != "<pre>" else "</pre>")
        elif line:
            body.append(f"<p>{html.escape(line)}</p>")
    if in_table:
        body.append("</table>")
    style = ("body{font-family:sans-serif;max-width:80em;margin:auto}table{border-collapse:collapse}"
             "td,th{border:1px solid #ccc;padding:2px 6px;font-size:90%;vertical-align:top}")
    return ("<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>Verification report</title>"
            f"<style>{style}</style></head><body>\n" + "\n".join(body) + "\n</body></html>\n")


def _conservation_job():
    from ..studies.conservation import conservation_rows

    t0 = time.monotonic()
    rows = conservation_rows(progress=lambda s: print(f"  conservation: {s}", file=sys.stderr, flush=True))
    return rows, round(time.monotonic() - t0, 1)


MAPS = (("disk", "diameter-spin"), ("sliding-disk", "diameter-spin"), ("disk", "straight-line"),
        ("ring", "straight-line"), ("ring", "diameter-spin"))


def _maps(say):
    """Stability maps of 100 rates x 100 tilts (10 s each) by heyoka batch + ensemble: rows, PNGs, timing."""
    import numpy as np

    from ..studies.maps import render_map, stability_map, switch_bracket
    from ..studies.thresholds import threshold

    rows, images, timing = [], {}, []
    from models.ring import parameter_set

    for model, motion in MAPS:
        say(f"  stability map {model} {motion} (10^4 trajectories)")
        params = dict(parameter_set("printed")) if model == "ring" else None  # the paper's own ring
        lin = float(threshold(model, motion, params).value)
        smap = stability_map(model, motion, rates=np.linspace(0.5 * lin, 1.5 * lin, 100), tilts=np.logspace(-6, -1, 100),
                             params=params)
        name = f"map-{model}-{motion}.png"
        images[name] = render_map(smap)
        lo, hi = switch_bracket(smap)
        rows.append({"model": model, "motion": motion, "params": params or {}, "figure": f"figures/{name}",
                     "trajectories": smap.n_trajectories,
                     "t_end": smap.t_end, "linear_threshold": f"{lin:.12g}",
                     "switch_at_tilt_1e-6": [f"{lo:.6g}", f"{hi:.6g}"]})
        timing.append({"model": model, "motion": motion, "trajectories": smap.n_trajectories,
                       "wall_seconds": round(smap.wall_seconds, 2), "batch_size": smap.batch_size})
    return rows, images, timing


def _reference_check_job(precision: str):
    from ..reference import check_set

    t0 = time.monotonic()
    return [c.to_record() for c in check_set(precision)], round(time.monotonic() - t0, 1)


def write_report(out="reports", bench: bool = True) -> None:
    from ..studies.conservation import PRECISIONS, render_markdown as conservation_markdown

    import os

    out = Path(out)
    say = lambda s: print(s, file=sys.stderr, flush=True)
    cache = Path(os.environ.get("HEYOKA_CACHE_DIR", Path.home() / ".cache" / "heyoka"))
    timing = {"heyoka_cache_at_start": "warm" if cache.exists() and any(cache.iterdir()) else "cold"}
    t0 = time.monotonic()
    # The conservation table runs in a second process (the machines have two cores) while
    # this one evaluates the claims; spawn, not fork, because heyoka's LLVM may hold threads.
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=1, mp_context=multiprocessing.get_context("spawn")) as pool:
        future = pool.submit(_conservation_job)
        quad_future = pool.submit(_reference_check_job, "quad")  # after the conservation table, in that process
        say("claims (the conservation table runs alongside):")
        results = evaluate_all(progress=lambda s: say("  " + s))
        timing["claims_seconds"] = round(time.monotonic() - t0, 1)
        t1 = time.monotonic()
        from ..studies.summary import caption_rows, precision_rows, render as render_studies, spindown_rows, threshold_rows

        studies = {"thresholds": threshold_rows(progress=lambda s: say("  " + s)), "captions": caption_rows(),
                   "spindown": spindown_rows(), "precision": precision_rows()}
        study_images = {}
        studies["maps"], map_images, timing["stability_maps"] = _maps(say)
        study_images.update(map_images)
        say("  dissipative spin-down (Moffatt, contact-rate)")
        from ..studies.dissipation import dissipation_study, render_dissipation, to_record as dissipation_record

        t2 = time.monotonic()
        laws = dissipation_study()
        studies["dissipation"] = [dissipation_record(s) for s in laws]
        study_images["dissipation.png"] = render_dissipation(laws)
        timing["dissipation_seconds"] = round(time.monotonic() - t2, 1)
        say("  retrograde turn of the ring (sweeps)")
        from ..studies.retrograde import run_study

        t3 = time.monotonic()
        retro = run_study(progress=lambda s: say("  " + s))
        for m, st in retro.items():
            study_images[f"retrograde-{m}.png"] = st.pop("figure")
            study_images[f"retrograde-{m}-roll.png"] = st.pop("figure_roll")
            # wall time belongs in timing.json: results.json must be the same bytes on every run
            timing.setdefault("retrograde_sweep_seconds", {})[m] = st.pop("seconds")
        studies["retrograde"] = retro
        timing["retrograde_seconds"] = round(time.monotonic() - t3, 1)
        say("  reference set: --check in double and long (quad runs in the second process)")
        from ..reference import check_set
        from ..reference.store import read_index

        t4 = time.monotonic()
        reference_checks = {p: [c.to_record() for c in check_set(p)] for p in ("double", "long")}
        timing["reference_check_seconds"] = {"double+long": round(time.monotonic() - t4, 1)}
        timing["studies_seconds"] = round(time.monotonic() - t1, 1)
        rows, timing["conservation_seconds"] = future.result()
        reference_checks["quad"], timing["reference_check_seconds"]["quad"] = quad_future.result()
        studies["reference"] = {"index": read_index(), "checks": reference_checks}
    from ..studies.spindown import PRECISIONS as SPINDOWN_PRECISIONS, REFERENCE as SPINDOWN_REFERENCE

    # every precision a number in the report comes from: the conservation table, the
    # variational check (double, quad) and the spin-down precision study
    prov = provenance(PRECISIONS + SPINDOWN_PRECISIONS + (SPINDOWN_REFERENCE, "long", "mp:128", "mp:256"))
    cons_md = conservation_markdown(rows, prov).split("\n## Provenance")[0]
    from ..reference.check import render_markdown as render_reference
    from ..studies.retrograde import render_markdown as render_retrograde

    extra = render_reference(studies["reference"]["index"], studies["reference"]["checks"])
    extra += render_retrograde(studies["retrograde"])
    extra += ["", "## Benchmarks", "",
              "Speed depends on the machine, so the benchmarks are not in this file (which is byte-reproducible): "
              "`python -m verify bench`, the last stage of `make report`, writes [BENCHMARKS.md](BENCHMARKS.md) and "
              "`benchmarks.json` -- work against precision against the reference set (heyoka at double, long, quad and "
              "MPFR; scipy's DOP853, Radau and LSODA; mpmath's odefun), the energy error over 10^6 steps, sweep "
              "throughput (loop, batch, ensemble, scipy) and the JIT cost with and without heyoka's disk cache, with "
              "the machine they ran on.", ""]
    from .summary import build as build_summary

    summary = build_summary(results, studies)
    md = render_markdown(results, cons_md + "\n" + render_studies(studies) + "\n".join(extra) + "\n", prov,
                         summary=summary)
    md += "\n## Provenance\n\n```\n" + json.dumps(prov, indent=2) + "\n```\n"
    from .figures import render

    images = {}
    for _, ev in results:
        for fig in ev.figures:
            images[f"{fig.name}.png"] = render(fig)
    images.update(study_images)
    for name, data in images.items():
        write_atomic(out / "figures" / name, data)
    results_json = {"summary": summary, "claims": [result_record(c, e) for c, e in results], "conservation": rows,
                    "studies": studies, "provenance": prov}
    write_atomic(out / "results.json", json.dumps(results_json, indent=2) + "\n")
    write_atomic(out / "REPORT.md", md)
    write_atomic(out / "report.html", render_html(md, images))
    write_atomic(out / "conservation.md", conservation_markdown(rows, prov))
    write_atomic(out / "conservation.json", json.dumps({"rows": rows, "provenance": prov}, indent=2) + "\n")
    timing["total_seconds"] = round(time.monotonic() - t0, 1)
    import platform

    timing["machine"] = {"platform": platform.platform(), "processor": platform.machine()}
    write_atomic(out / "timing.json", json.dumps(timing, indent=2) + "\n")
    say(f"wrote {out}/REPORT.md, report.html, results.json, conservation.md ({timing['total_seconds']} s)")
    if bench:
        from ..bench import run_benchmarks, write_benchmarks

        say("benchmarks (alone, after everything else):")
        t5 = time.monotonic()
        write_benchmarks(run_benchmarks(progress=say), out)
        timing["bench_seconds"] = round(time.monotonic() - t5, 1)
        timing["total_seconds"] = round(time.monotonic() - t0, 1)
        write_atomic(out / "timing.json", json.dumps(timing, indent=2) + "\n")
        say(f"wrote {out}/BENCHMARKS.md, benchmarks.json ({timing['bench_seconds']} s)")
