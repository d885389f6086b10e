"""``python -m verify report``: runs the claims and the studies into data, renders it, writes reports/.

Evaluates every claim of the registry, runs the conservation table and the studies (each
returns data), renders that data (:mod:`.markdown`, :mod:`.html`, :mod:`.sections`,
:mod:`.retrograde`, :mod:`.conservation`, :mod:`.summary`, :mod:`.figures`,
:mod:`.study_figures`) and is the one
writer of ``reports/REPORT.md``, ``reports/report.html``, ``reports/results.json``,
``reports/conservation.{md,json}``, ``reports/figures/`` and ``reports/timing.json`` (the only
file whose content changes from run to run).
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from ..claims import ERRATUM, all_claims
from ..claims.base import Claim, Evaluation, quote_fragments
from ..provenance import provenance, write_atomic
from .html import render_html
from .markdown import benchmarks_section, render_markdown


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


def _conservation_job():
    from ..studies.conservation import conservation_rows

    t0 = time.monotonic()
    rows = conservation_rows(progress=lambda s: print(f"  conservation: {s}", file=sys.stderr, flush=True))
    return rows, round(time.monotonic() - t0, 1)


def _reference_check_job(precision: str):
    from ..reference import check_set

    t0 = time.monotonic()
    return [c.to_record() for c in check_set(precision)], round(time.monotonic() - t0, 1)


def write_report(out="reports") -> None:
    from ..studies.conservation import PRECISIONS
    from .conservation import render_markdown as conservation_markdown

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
        from ..studies.summary import caption_rows, map_rows, precision_rows, spindown_rows, threshold_rows
        from .study_figures import render_dissipation, render_map

        studies = {"thresholds": threshold_rows(progress=lambda s: say("  " + s)), "captions": caption_rows(),
                   "spindown": spindown_rows(), "precision": precision_rows()}
        study_images = {}
        studies["maps"], maps, timing["stability_maps"] = map_rows(progress=lambda s: say("  " + s))
        for row, smap in zip(studies["maps"], maps):
            study_images[row["figure"].removeprefix("figures/")] = render_map(smap)
        say("  dissipative spin-down (Moffatt, contact-rate)")
        from ..studies.dissipation import dissipation_study, to_record as dissipation_record

        t2 = time.monotonic()
        laws = dissipation_study()
        studies["dissipation"] = [dissipation_record(s) for s in laws]
        study_images["dissipation.png"] = render_dissipation(laws)
        timing["dissipation_seconds"] = round(time.monotonic() - t2, 1)
        say("  retrograde turn of the ring (sweeps)")
        from ..studies.retrograde import run_study
        from .retrograde import figures as retrograde_figures

        t3 = time.monotonic()
        retro = run_study(progress=lambda s: say("  " + s))
        for m, st in retro.summaries.items():
            study_images.update(retrograde_figures(m, *retro.sweeps[m]))
            # wall time belongs in timing.json: results.json must be the same bytes on every run
            timing.setdefault("retrograde_sweep_seconds", {})[m] = st.pop("seconds")
        studies["retrograde"] = retro.summaries
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
    from .reference import render_markdown as render_reference
    from .retrograde import render_markdown as render_retrograde
    from .sections import render as render_studies

    extra = render_reference(studies["reference"]["index"], studies["reference"]["checks"])
    extra += render_retrograde(studies["retrograde"])
    extra += benchmarks_section(_latest_benchmarks(out))
    from .summary import build as build_summary

    summary = build_summary(results, studies)
    md = render_markdown(results, cons_md + "\n" + render_studies(studies) + "\n".join(extra) + "\n", prov,
                         summary=summary)
    md += "\n## Provenance\n\n```\n" + json.dumps(prov, indent=2) + "\n```\n"
    from .figures import render, with_alt_text

    images = {}
    for _, ev in results:
        for fig in ev.figures:
            images[f"{fig.name}.png"] = render(fig)
    images.update(study_images)  # file name -> figures.Image
    md = with_alt_text(md, images)
    for name, image in images.items():
        write_atomic(out / "figures" / name, image.data)
    results_json = {"summary": summary, "claims": [result_record(c, e) for c, e in results], "conservation": rows,
                    "studies": studies, "provenance": prov}
    write_atomic(out / "results.json", json.dumps(results_json, indent=2) + "\n")
    write_atomic(out / "REPORT.md", md)
    write_atomic(out / "report.html", render_html(md, {name: image.data for name, image in images.items()}))
    write_atomic(out / "conservation.md", conservation_markdown(rows, prov))
    write_atomic(out / "conservation.json", json.dumps({"rows": rows, "provenance": prov}, indent=2) + "\n")
    timing["total_seconds"] = round(time.monotonic() - t0, 1)
    import platform

    timing["machine"] = {"platform": platform.platform(), "processor": platform.machine()}
    write_atomic(out / "timing.json", json.dumps(timing, indent=2) + "\n")
    say(f"wrote {out}/REPORT.md, report.html, results.json, conservation.md ({timing['total_seconds']} s)")


def _latest_benchmarks(out: Path):
    """The benchmark run in ``out/benchmarks.json`` (written by ``make bench``), or None."""
    path = Path(out) / "benchmarks.json"
    if not path.exists():
        return None
    return json.loads(path.read_text())
