"""Drive a sweep: the chunks not yet in the store, on this machine or on a Dask cluster.

On one machine the chunks run one after the other, each on every core (heyoka's ensemble on
threads, batch integrators in SIMD lanes).  With ``dask`` (an address such as
``tcp://host:8786``, or ``"local"`` for a ``LocalCluster`` of one process per core) each chunk
is one Dask task: a worker rebuilds the spec from its text, runs the chunk with its own
threads and returns the rows; this process writes them into the same store as they arrive.
Either way a progress bar goes to stderr (a line per update when stderr is not a terminal).

Workers need this package importable (on a remote cluster: installed on every worker).

Before anything is computed or written, :func:`run_sweep` states the sweep's size (points,
memory, store, rough time: :func:`estimate`), refuses it with :class:`SweepTooLarge` when it
exceeds :data:`LIMITS` unless ``yes=True`` (the command line's ``--yes``), then checks every
point of the grid as a start (:func:`verify.sweep.engine.validate_points`), and only then opens
or creates the store.

The limits, and why
-------------------
* **points: 10^7.**  The shipped sweeps have 72 to 10^4 points; 10^7 is a thousand times the
  largest.  At the measured 300 to 3000 ten-second disk runs a second on two cores
  (reports/BENCHMARKS.md: 336 for random starts; near-steady starts are faster) it is one to ten
  hours and a store of about a gigabyte -- and beyond it lie typos: an extra zero on one axis's
  count is 10x, ``count = 100000000`` on two axes is 10^16 points (which took 11.9 GB in 40 s
  before the axes were made lazy and this check was added).
* **memory: 2 GiB per chunk.**  A chunk holds every sample of every lane at once (heyoka's dense
  output, ``lanes x samples x states x 8`` bytes, padded to whole batches), plus the reductions'
  copies; under Dask each worker holds one.  2 GiB leaves room beside the OS and the JIT on the
  smallest machines this runs on (CI runners have 7 GiB); the shipped sweeps need 0.5 to 150 MiB.
  A too-large chunk is fixed by a smaller ``[sweep] chunk`` or fewer ``samples``.
* **store: 2 GiB on disk**, the same bound for what is written (~8 bytes a column a row plus
  SQLite's overhead); a 10^7-point sweep recording a few quantities stays under it.
* **time: 24 hours** (estimated, roughly: from the steps a run needs, omega h ~ 0.03 at the fastest
  initial rate over t_end, and ~10^6 lane-steps a second a thread; against measured runs it is
  within a factor of 3 either way: 1.4 s for 0.56 s on near-steady disk runs, 5 s for 3 s on the
  benchmark's random ones, 6 s for 7.9 s on the ring retrograde sweeps with their reductions).
  A run of a day is a decision, not a default.

Each limit is a module constant; ``yes=True`` runs a sweep beyond them all.
"""
from __future__ import annotations

import os
import socket
import sys
import time
from dataclasses import dataclass

from ..engine.ensemble import resolve
from ..engine.lanes import simd_width
from .engine import check_readings, fastest_rate, run_chunk, validate_points
from .spec import SpecError, SweepSpec, parse
from .store import Store, columns

#: The bounds a sweep must stay within unless run with ``yes=True`` (module docstring).
LIMITS = {"points": 10_000_000, "memory_bytes": 2 * 1024 ** 3, "store_bytes": 2 * 1024 ** 3, "seconds": 24 * 3600.0}
#: Lane-steps a second on one thread, and the typical omega h of a step: for the rough time.
LANE_STEPS_PER_SECOND = 1.0e6
STEP_RADIANS = 0.03


class ClusterError(ValueError):
    """A Dask address that is malformed or does not answer; the message names it."""


class SweepTooLarge(SpecError):
    """A sweep beyond :data:`LIMITS`; ``estimate`` says by how much.  ``yes=True`` (``--yes``) runs it."""

    def __init__(self, message: str, estimate):
        super().__init__(message)
        self.estimate = estimate


@dataclass(frozen=True)
class Estimate:
    """What a sweep will cost, before it starts (rough: see the module docstring)."""

    points: int
    chunks: int
    memory_bytes: int  # per chunk in this process (each Dask worker holds one)
    store_bytes: int
    seconds: float  # rough, on ``threads`` threads
    threads: int

    def over(self) -> list:
        """The limits this sweep exceeds, in words (empty: none)."""
        out = []
        if self.points > LIMITS["points"]:
            out.append(f"{self.points:,} points (limit {LIMITS['points']:,})")
        if self.memory_bytes > LIMITS["memory_bytes"]:
            out.append(f"{_bytes(self.memory_bytes)} of memory per chunk (limit {_bytes(LIMITS['memory_bytes'])})")
        if self.store_bytes > LIMITS["store_bytes"]:
            out.append(f"a store of {_bytes(self.store_bytes)} (limit {_bytes(LIMITS['store_bytes'])})")
        if self.seconds > LIMITS["seconds"]:
            out.append(f"roughly {_duration(self.seconds)} of computing (limit {_duration(LIMITS['seconds'])})")
        return out

    def describe(self, name: str) -> str:
        return (f"{name}: {self.points:,} points in {self.chunks:,} chunks, ~{_bytes(self.memory_bytes)} of memory "
                f"per chunk, a store of ~{_bytes(self.store_bytes)}, roughly {_duration(self.seconds)} on "
                f"{self.threads} thread{'s' if self.threads != 1 else ''}")


def estimate(spec: SweepSpec, threads: int = None) -> Estimate:
    """Points, memory per chunk, store size and a rough time of ``spec``, from its text alone."""
    threads = threads or os.cpu_count() or 1
    bs = simd_width()
    lanes = -(-min(spec.chunk, spec.n_points) // bs) * bs
    n_states = 8 + (resolve(spec.model).dissipation is not None)
    # the dense output of every lane, plus ~1 copy for the reductions and the inputs
    memory = int(lanes * spec.samples * n_states * 8 * 1.5) + lanes * 1024
    store = spec.n_points * (8 * len(columns(spec)) + 40)
    steps = spec.t_end * fastest_rate(spec) / STEP_RADIANS
    seconds = spec.n_points * steps / (LANE_STEPS_PER_SECOND * threads)
    return Estimate(spec.n_points, spec.n_chunks, memory, store, seconds, threads)


def _bytes(n: float) -> str:
    for unit in ("bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"):
        if n < 1024 or unit == "EiB":
            return f"{n:.0f} {unit}" if unit == "bytes" else f"{n:.3g} {unit}"
        n /= 1024
    return f"{n:.3g} EiB"  # pragma: no cover


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    if seconds < 3 * 86400:
        return f"{seconds / 3600:.1f} h"
    if seconds < 3 * 365 * 86400:
        return f"{seconds / 86400:.0f} days"
    return f"{seconds / (365.25 * 86400):.3g} years"


@dataclass(frozen=True)
class SweepResult:
    """What a call to :func:`run_sweep` did."""

    spec: SweepSpec
    store: str
    chunks_total: int
    chunks_run: int
    chunks_skipped: int
    rows: int
    seconds: float
    where: str  # "local (N threads)" or the Dask scheduler's address
    estimate: "Estimate" = None  # what it was expected to cost


def chunk_task(spec_text: str, chunk: int, threads: int = 1, senses=None) -> tuple:
    """A chunk as a self-contained task (for Dask): (chunk, rows, seconds, worker).  ``senses``: as
    :func:`verify.sweep.engine.run_chunk`'s (a module-level function: Dask sends it by name)."""
    spec = parse(spec_text, "<spec sent to the worker>", store="unused")
    t0 = time.monotonic()
    rows = run_chunk(spec, chunk, threads=threads, senses=senses)
    return chunk, rows, time.monotonic() - t0, f"{socket.gethostname()}:{os.getpid()}"


class Progress:
    """A progress bar on stderr: chunks and trajectories done, rate, time left."""

    def __init__(self, spec: SweepSpec, done: int, todo: int, enabled: bool = True):
        self.spec, self.total, self.done, self.todo = spec, spec.n_chunks, done, todo
        self.enabled, self.t0, self.ran = enabled, time.monotonic(), 0
        self.tty = sys.stderr.isatty()
        self._show()

    def advance(self, rows: int) -> None:
        self.done += 1
        self.ran += rows
        self._show()

    def _show(self) -> None:
        if not self.enabled:
            return
        elapsed = time.monotonic() - self.t0
        rate = self.ran / elapsed if elapsed > 0 and self.ran else 0.0
        remaining = self.total - self.done
        eta = f"{remaining * (elapsed / max(1, self.done - (self.total - self.todo))):.0f} s" if rate else "?"
        width = 30
        filled = int(width * self.done / max(1, self.total))
        line = (f"{self.spec.name} [{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} chunks, "
                f"{rate:,.0f} trajectories/s, {eta} left")
        print(("\r" + line) if self.tty else line, end="" if self.tty else "\n", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.enabled and self.tty:
            print(file=sys.stderr)


def run_sweep(spec: SweepSpec, dask: str = None, threads: int = None, progress: bool = True,
              store_path=None, yes: bool = False, senses=None) -> SweepResult:
    """Run every chunk of ``spec`` that its store does not hold yet, and write each as it finishes.

    First (nothing computed, nothing written): a spec that records a sense of the orbit needs its
    reading, ``senses`` (:func:`verify.studies.orbits.senses`; :func:`verify.sweep.engine.check_readings`),
    then the size is checked against :data:`LIMITS` -- :class:`SweepTooLarge` unless ``yes`` --, then
    every point is checked as a start -- :class:`verify.sweep.spec.InvalidPoint` naming the first bad
    one --, then the store is opened (a store of another spec or format is refused) and a Dask cluster
    reached, and only then is the size stated on stderr (with ``progress``).  The errors are
    :class:`verify.sweep.spec.SpecError`, :class:`verify.sweep.store.StoreError` and :class:`ClusterError`.
    """
    check_readings(spec, senses)
    threads = threads or os.cpu_count() or 1
    t0 = time.monotonic()
    cost = estimate(spec, threads)
    over = cost.over()
    if over and not yes:
        raise SweepTooLarge(f"sweep {spec.name!r} is too large: {'; '.join(over)} ({cost.describe(spec.name)}).  "
                            "Check the axes' counts, [sweep] samples and chunk; to run it anyway pass yes=True "
                            "(command line: --yes)", cost)
    validate_points(spec)
    with Store(spec, store_path) as store:
        done = store.done_chunks()
        todo = [c for c in range(spec.n_chunks) if c not in done]
        client, cluster = _connect(dask) if dask is not None else (None, None)
        try:
            if progress:  # after every check (the store's, the cluster's): a refused sweep gets its one line only
                print(cost.describe(spec.name), file=sys.stderr, flush=True)
            bar = Progress(spec, len(done), len(todo), progress)
            try:
                if client is None:
                    where = f"local ({threads} threads)"
                    for c in todo:
                        t1 = time.monotonic()
                        rows = run_chunk(spec, c, threads=threads, senses=senses)
                        store.write_chunk(c, rows, time.monotonic() - t1, f"{socket.gethostname()}:{os.getpid()}")
                        bar.advance(len(rows))
                else:
                    where = _run_on_dask(spec, todo, client, cluster, store, bar, senses)
            finally:
                bar.close()
        finally:
            if client is not None:
                client.close()
            if cluster is not None:
                cluster.close()
        rows = store.count()
    return SweepResult(spec, str(store_path or spec.store), spec.n_chunks, len(todo), len(done), rows,
                       time.monotonic() - t0, where, cost)


def _connect(address: str) -> tuple:
    """(a Dask client, the local cluster it runs on or None) for ``--dask ADDRESS``; :class:`ClusterError` if none
    answers there."""
    try:
        from dask.distributed import Client, LocalCluster  # lazy: optional, --dask only, 0.4 s
    except ImportError:  # pragma: no cover - dask is a test dependency
        raise RuntimeError("--dask needs dask.distributed: pip install 'dask[distributed]'") from None
    if address == "local":
        cluster = LocalCluster(n_workers=os.cpu_count() or 1, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        return Client(cluster), cluster
    try:
        return Client(address, timeout="30s"), None
    except (OSError, ValueError, TimeoutError) as err:
        raise ClusterError(f"--dask {address!r}: no Dask scheduler there ({err}); allowed: 'local' or a "
                           "scheduler's address such as tcp://host:8786") from None


def _run_on_dask(spec: SweepSpec, todo: list, client, cluster, store: Store, bar: Progress, senses) -> str:
    from dask.distributed import as_completed  # lazy: optional, --dask only (imported by _connect already)

    where = client.scheduler.address if cluster is None else f"local Dask cluster ({len(cluster.workers)} workers)"
    # one thread a task: Dask runs a task on every worker thread, so the cores are already busy
    futures = [client.submit(chunk_task, spec.text, c, 1, senses, pure=False) for c in todo]
    for fut in as_completed(futures):
        chunk, rows, seconds, worker = fut.result()
        store.write_chunk(chunk, rows, seconds, worker)
        bar.advance(len(rows))
        fut.release()
    return where
