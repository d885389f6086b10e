"""Runs the report's jobs on every core, from the cache where their key is unchanged.

:func:`run_jobs` keys every job (:mod:`.dependencies`), takes what the cache holds for that
key, and computes the rest on a process pool (spawn: heyoka's LLVM may hold threads) of one
worker per core, longest first by each job's last wall time, so the queue, not a fixed split,
keeps both cores busy to the end.  Each finished job is cached at once (an interrupted run
resumes); a job that raises is recorded as failed, with its error, and the others go on.  One
progress line per job, with its time, and a total.
"""
from __future__ import annotations

import inspect
import json
import multiprocessing
import os
import time
import traceback
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import dataclass, field
from typing import Any, Optional

from .cache import JobCache
from .dependencies import job_key
from . import jobs as jobs_module
from .jobs import Job, run


@dataclass
class Outcome:
    """What became of one job: ``status`` is ``computed``, ``cached`` or ``failed`` (then ``error``)."""

    job: Job
    status: str
    data: Any = None
    images: list = field(default_factory=list)
    timing: dict = field(default_factory=dict)
    seconds: float = 0.0  # wall time of the job's computation (for a cached one, when it was computed)
    error: Optional[str] = None


def key_of(job: Job) -> str:
    # the job function's own source counts, not the rest of jobs.py nor its imports (each job
    # names the modules it uses)
    return job_key(job.name, job.modules, list(job.args), job.files, inspect.getsource(jobs_module.function_of(job)))


def _work(job: Job):
    """Run ``job`` (in a worker); its output with JSON-normalised data, or the error as text."""
    t0 = time.monotonic()
    try:
        out = run(job)
        data = json.loads(json.dumps(out.data))  # what the cache will give back, exactly
        return data, out.images, out.timing, time.monotonic() - t0, None
    except Exception as err:  # noqa: BLE001 -- a job's failure is data for the report
        where = traceback.extract_tb(err.__traceback__)[-1]
        text = f"{type(err).__name__}: {err} ({os.path.basename(where.filename)}:{where.lineno})"
        return None, [], {}, time.monotonic() - t0, text


def run_jobs(jobs, cache: JobCache = None, fresh: bool = False, workers: Optional[int] = None, say=print,
             hints: Optional[dict] = None) -> dict:
    """Every job's :class:`Outcome`, by job name (in the order of ``jobs``).

    ``fresh`` ignores the cache (and refills it); ``workers`` defaults to the cores this
    process may use; ``workers=1`` runs in this process (no pool).  ``hints``: job name ->
    seconds, for ordering jobs the cache has never timed (e.g. the committed timing.json's).
    """
    cache = cache or JobCache()
    t0 = time.monotonic()
    outcomes, todo = {}, []
    for job in jobs:
        key = key_of(job)
        entry = None if fresh else cache.get(job.name, key)
        if entry is None:
            todo.append((job, key))
        else:
            outcomes[job.name] = Outcome(job, "cached", entry["data"], entry["images"], entry["timing"], entry["seconds"])
    width = max((len(j.name) for j in jobs), default=10)
    n, done = len(jobs), len(outcomes)
    if outcomes:
        say(f"{len(outcomes)} of {n} jobs unchanged since their last run: from the cache")

    def finish(job, key, result):
        nonlocal done
        data, images, timing, seconds, error = result
        if error is None:
            cache.put(job.name, key, data, images, timing, seconds)
            outcomes[job.name] = Outcome(job, "computed", data, images, timing, seconds)
        else:
            outcomes[job.name] = Outcome(job, "failed", seconds=seconds, error=error)
        done += 1
        say(f"[{done:3d}/{n}] {job.name:<{width}} {seconds:6.1f} s" + (f"  FAILED: {error}" if error else ""))

    # longest first (unknown jobs count as long): the last jobs to start are the short ones
    hints = hints or {}
    todo.sort(key=lambda jk: -(cache.last_seconds(jk[0].name) or hints.get(jk[0].name) or float("inf")))
    workers = workers or len(os.sched_getaffinity(0))
    if workers == 1 or len(todo) <= 1:
        for job, key in todo:
            finish(job, key, _work(job))
    elif todo:
        with ProcessPoolExecutor(max_workers=min(workers, len(todo)),
                                 mp_context=multiprocessing.get_context("spawn")) as pool:
            pending = {pool.submit(_work, job): (job, key) for job, key in todo}
            try:
                while pending:
                    finished, _ = wait(pending, return_when=FIRST_COMPLETED)
                    for fut in finished:
                        job, key = pending.pop(fut)
                        try:
                            result = fut.result()
                        except Exception as err:  # noqa: BLE001 -- a worker died (e.g. out of memory)
                            result = (None, [], {}, 0.0, f"{type(err).__name__}: {err}")
                        finish(job, key, result)
            except BaseException:
                for fut in pending:
                    fut.cancel()
                raise
    computed = [o for o in outcomes.values() if o.status == "computed"]
    failed = [o for o in outcomes.values() if o.status == "failed"]
    say(f"{n} jobs: {len(computed)} computed (their wall times sum to {sum(o.seconds for o in computed):.1f} s), "
        f"{n - len(computed) - len(failed)} from the cache, {len(failed)} failed; "
        f"{time.monotonic() - t0:.1f} s on {workers} worker(s)")
    return {job.name: outcomes[job.name] for job in jobs}
