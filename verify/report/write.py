"""``python -m verify report``: compute every job into results.json, then render the report from that file.

:func:`compute` runs the registry (:mod:`.jobs`) through the cached job queue (:mod:`.runner`) and
is the one writer of ``reports/results.json``, ``reports/figures/`` and ``reports/timing.json``
(the only file whose content changes from run to run).  :func:`render` reads results.json and
figures/ and nothing else, and is the one writer of ``reports/REPORT.md``, ``reports/report.html``
and ``reports/conservation.{md,json}``.  :func:`write_report` does both.
"""
from __future__ import annotations

import json
import os
import platform
import sys
import time
from pathlib import Path

from ..provenance import write_atomic

def compute(out="reports", fresh: bool = False, workers=None, say=None) -> dict:
    """Run every job (from the cache where unchanged), write results.json, figures/ and timing.json.

    Returns the results dict.  Raises :class:`ReportIncomplete` after writing, when a job failed.
    """
    from .cache import JobCache  # lazy: 0.8 s, not in 'report' input checks
    from .jobs import registry  # lazy: 0.8 s, not in 'report' input checks
    from .results import assemble  # lazy: 0.8 s, not in 'report' input checks
    from .runner import run_jobs  # lazy: 0.8 s, not in 'report' input checks

    out = Path(out)
    say = say or (lambda s: print(s, file=sys.stderr, flush=True))
    t0 = time.monotonic()
    heyoka_cache = Path(os.environ.get("HEYOKA_CACHE_DIR", Path.home() / ".cache" / "heyoka"))
    timing = {"heyoka_cache_at_start": "warm" if heyoka_cache.exists() and any(heyoka_cache.iterdir()) else "cold"}
    outcomes = run_jobs(registry(), JobCache(), fresh=fresh, workers=workers, say=say, hints=_last_job_seconds(out))
    results = assemble(outcomes)
    images = {img.filename: img.data for o in outcomes.values() for img in o.images}
    for name, data in images.items():
        path = out / "figures" / name
        if not path.exists() or path.read_bytes() != data:
            write_atomic(path, data)
    for name in _previous_figures(out) - set(images):
        if not results["failures"]:  # kept while a job failed: it may be that job's
            (out / "figures" / name).unlink(missing_ok=True)  # a figure no job draws any more
    write_atomic(out / "results.json", json.dumps(results, indent=2) + "\n")
    timing["jobs"] = {name: {"status": o.status, "wall_seconds": round(o.seconds, 2), **({"detail": o.timing} if o.timing else {})}
                      for name, o in outcomes.items()}
    timing["total_seconds"] = round(time.monotonic() - t0, 1)
    timing["machine"] = {"platform": platform.platform(), "processor": platform.machine(), "cpus": os.cpu_count()}
    write_atomic(out / "timing.json", json.dumps(timing, indent=2) + "\n")
    return results


def _previous_figures(out: Path) -> set:
    """The figures the report last written to ``out`` named (others there, e.g. make bench's, are not ours)."""
    try:
        return {f["file"] for f in json.loads((out / "results.json").read_text()).get("figures", ())}
    except (OSError, ValueError, AttributeError, TypeError, KeyError):
        return set()


def _last_job_seconds(out: Path) -> dict:
    """Job name -> wall seconds of the last report written to ``out`` (timing.json), for ordering a
    queue the cache cannot order (a fresh clone); {} when there is none."""
    try:
        jobs = json.loads((out / "timing.json").read_text()).get("jobs", {})
    except (OSError, ValueError):
        return {}
    return {name: j["wall_seconds"] for name, j in jobs.items()
            if isinstance(j, dict) and j.get("wall_seconds") and j.get("status") != "failed"}


class MissingResults(ValueError):
    """No readable results.json to render from (the message names the file)."""


def read_results(out) -> dict:
    """``out/results.json``, or :class:`MissingResults` naming it."""
    path = Path(out) / "results.json"
    try:
        return json.loads(path.read_text())
    except FileNotFoundError:
        raise MissingResults(f"no {path}: run 'python -m verify report' without --render-only first") from None
    except (OSError, ValueError) as err:
        raise MissingResults(f"{path} cannot be read as JSON ({err}); rerun 'python -m verify report'") from None


def render(out="reports", say=None) -> None:
    """REPORT.md, report.html and conservation.{md,json} from ``out/results.json`` and ``out/figures/``.

    All four are rendered before any is written, so a results.json the renderers cannot read
    leaves the old files as they were."""
    from .conservation import render_markdown as conservation_markdown  # lazy: 0.8 s, not in 'report' input checks
    from .markdown import render_markdown  # lazy: 0.8 s, not in 'report' input checks
    from .page import render_html  # lazy: 0.8 s, not in 'report' input checks

    out = Path(out)
    say = say or (lambda s: print(s, file=sys.stderr, flush=True))
    results = read_results(out)
    images = {}
    for f in results.get("figures", ()):
        try:
            images[f["file"]] = (out / "figures" / f["file"]).read_bytes()
        except FileNotFoundError:
            say(f"  figure {f['file']} named in results.json is missing from {out / 'figures'}")
    benchmarks = latest_benchmarks(out)
    engines = latest_engines(out)
    if engines is not None and (out / "figures" / "engines.png").exists():
        images["engines.png"] = (out / "figures" / "engines.png").read_bytes()
    files = {"REPORT.md": render_markdown(results, benchmarks, engines),
             "report.html": render_html(results, images, benchmarks, engines),
             "conservation.md": conservation_markdown(results["conservation"], results["provenance"]),
             "conservation.json": json.dumps({"rows": results["conservation"], "provenance": results["provenance"]},
                                             indent=2) + "\n"}
    for name, text in files.items():
        write_atomic(out / name, text)


class ReportIncomplete(RuntimeError):
    """Some jobs failed; the report was written without what they compute."""


def write_report(out="reports", fresh: bool = False, render_only: bool = False, workers=None) -> None:
    say = lambda s: print(s, file=sys.stderr, flush=True)
    t0 = time.monotonic()
    failures = []
    if not render_only:
        failures = compute(out, fresh=fresh, workers=workers, say=say)["failures"]
    t1 = time.monotonic()
    render(out, say=say)
    say(f"wrote {out}/REPORT.md, report.html, results.json, conservation.md "
        f"(render {time.monotonic() - t1:.1f} s; total {time.monotonic() - t0:.1f} s)")
    if failures:
        raise ReportIncomplete(f"{len(failures)} job(s) failed: " + ", ".join(f["job"] for f in failures)
                               + "; the report says so and lacks what they compute")


def latest_engines(out):
    """The engines' board in ``out/engines.json`` (written by ``make engines``), or None."""
    path = Path(out) / "engines.json"
    if not path.exists():
        return None
    return json.loads(path.read_text())


def latest_benchmarks(out):
    """The benchmark run in ``out/benchmarks.json`` (written by ``make bench``), or None."""
    path = Path(out) / "benchmarks.json"
    if not path.exists():
        return None
    return json.loads(path.read_text())
