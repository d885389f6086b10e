"""Drive a sweep: the chunks not yet in the store, on this machine or on a Dask cluster.

On one machine the chunks run one after the other, each on every core (heyoka's ensemble on
threads, batch integrators in SIMD lanes).  With ``dask`` (an address such as
``tcp://host:8786``, or ``"local"`` for a ``LocalCluster`` of one process per core) each chunk
is one Dask task: a worker rebuilds the spec from its text, runs the chunk with its own
threads and returns the rows; this process writes them into the same store as they arrive.
Either way a progress bar goes to stderr (a line per update when stderr is not a terminal).

Workers need this package importable (on a remote cluster: installed on every worker).
"""
from __future__ import annotations

import os
import socket
import sys
import time
from dataclasses import dataclass

from .engine import run_chunk
from .spec import SweepSpec, parse
from .store import Store


class ClusterError(ValueError):
    """A Dask address that is malformed or does not answer; the message names it."""


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


def chunk_task(spec_text: str, chunk: int, threads: int = 1) -> tuple:
    """A chunk as a self-contained task (for Dask): (chunk, rows, seconds, worker)."""
    spec = parse(spec_text, "<spec sent to the worker>", store="unused")
    t0 = time.monotonic()
    rows = run_chunk(spec, chunk, threads=threads)
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
              store_path=None) -> SweepResult:
    """Run every chunk of ``spec`` that its store does not hold yet, and write each as it finishes."""
    threads = threads or os.cpu_count() or 1
    t0 = time.monotonic()
    with Store(spec, store_path) as store:
        done = store.done_chunks()
        todo = [c for c in range(spec.n_chunks) if c not in done]
        bar = Progress(spec, len(done), len(todo), progress)
        try:
            if dask is None:
                where = f"local ({threads} threads)"
                for c in todo:
                    t1 = time.monotonic()
                    rows = run_chunk(spec, c, threads=threads)
                    store.write_chunk(c, rows, time.monotonic() - t1, f"{socket.gethostname()}:{os.getpid()}")
                    bar.advance(len(rows))
            else:
                where = _run_on_dask(spec, todo, dask, store, bar)
        finally:
            bar.close()
        rows = store.count()
    return SweepResult(spec, str(store_path or spec.store), spec.n_chunks, len(todo), len(done), rows,
                       time.monotonic() - t0, where)


def _run_on_dask(spec: SweepSpec, todo: list, address: str, store: Store, bar: Progress) -> str:
    try:
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError:  # pragma: no cover - dask is a test dependency
        raise RuntimeError("--dask needs dask.distributed: pip install 'dask[distributed]'") from None
    cluster = None
    if address == "local":
        cluster = LocalCluster(n_workers=os.cpu_count() or 1, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    else:
        try:
            client = Client(address, timeout="30s")
        except (OSError, ValueError, TimeoutError) as err:
            raise ClusterError(f"--dask {address!r}: no Dask scheduler there ({err}); allowed: 'local' or a "
                               "scheduler's address such as tcp://host:8786") from None
    try:
        where = client.scheduler.address if cluster is None else f"local Dask cluster ({len(cluster.workers)} workers)"
        # one thread a task: Dask runs a task on every worker thread, so the cores are already busy
        futures = [client.submit(chunk_task, spec.text, c, 1, pure=False) for c in todo]
        for fut in as_completed(futures):
            chunk, rows, seconds, worker = fut.result()
            store.write_chunk(chunk, rows, seconds, worker)
            bar.advance(len(rows))
            fut.release()
        return where
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
