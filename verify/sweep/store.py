"""The sweep's store: an SQLite file, one row per trajectory, written a whole chunk at a time.

Tables
------
``meta``   (key, value): the spec's text and sha256, the column list, the format.
``runs``   one row per trajectory: ``idx`` (the point's index, primary key), ``chunk``, the
           inputs ``in_<axis>``, ``outcome``, ``t_stop``, ``energy_drift_vs_terms`` and the recorded
           quantities.
``chunks`` one row per finished chunk: ``chunk`` (primary key), ``n`` rows, ``seconds``, ``worker``.

A chunk's rows and its ``chunks`` row are written in one transaction, so a process killed at
any moment leaves either the whole chunk or none of it (SQLite's journal rolls an unfinished
transaction back when the file is next opened).  ``idx`` is the primary key and a chunk that
is already in ``chunks`` is never written again, so running the same sweep twice neither
repeats work nor duplicates rows.  A store made by a different spec is refused.
"""
from __future__ import annotations

import json
import sqlite3
from pathlib import Path

from .spec import ALWAYS, SweepSpec

#: Format 2: a stopped run's ``final_*`` is the state at its stop (format 1 held the last sample before
#: it); a store of another format is refused rather than resumed with rows of two meanings.
FORMAT = "rolling-verify sweep store, format 2"


class StoreError(ValueError):
    """A store that does not belong to the spec, or is not a sweep store."""


def columns(spec: SweepSpec) -> list:
    """(name, SQL type) of the runs table, in order."""
    cols = [("idx", "INTEGER PRIMARY KEY"), ("chunk", "INTEGER NOT NULL")]
    cols += [(f"in_{a.name}", "REAL") for a in spec.axes]
    cols += [("outcome", "TEXT NOT NULL")] + [(q, "REAL") for q in ALWAYS] + [(q, "REAL") for q in spec.record]
    return cols


class Store:
    """An open store for ``spec`` (created if missing)."""

    def __init__(self, spec: SweepSpec, path=None):
        self.spec = spec
        self.path = Path(path if path is not None else spec.store)
        self.cols = columns(spec)
        self.db = None
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self.db = sqlite3.connect(self.path, timeout=60)
            self.db.execute("PRAGMA journal_mode=WAL")
            self.db.execute("PRAGMA synchronous=FULL")
            self._init()
        except (OSError, sqlite3.Error) as err:
            if self.db is not None:
                self.db.close()
            raise StoreError(f"cannot open the sweep store {str(self.path)!r}: {err} "
                             "(give a writable path with --store, or [sweep] store in the spec)") from None
        except StoreError:
            self.db.close()
            raise

    def _init(self) -> None:
        tables = {r[0] for r in self.db.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
        if not tables:
            with self.db:
                self.db.execute("CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
                self.db.execute("CREATE TABLE runs (" + ", ".join(f'"{n}" {t}' for n, t in self.cols) + ")")
                self.db.execute("CREATE TABLE chunks (chunk INTEGER PRIMARY KEY, n INTEGER NOT NULL, "
                                "seconds REAL, worker TEXT)")
                self.db.executemany("INSERT INTO meta VALUES (?, ?)", [
                    ("format", FORMAT), ("spec_sha256", self.spec.sha256), ("spec", self.spec.text),
                    ("columns", json.dumps([n for n, _ in self.cols])), ("n_points", str(self.spec.n_points)),
                    ("n_chunks", str(self.spec.n_chunks))])
            return
        if not {"meta", "runs", "chunks"} <= tables:
            raise StoreError(f"{self.path} is not a sweep store (tables {sorted(tables)})")
        meta = dict(self.db.execute("SELECT key, value FROM meta"))
        if meta.get("format") != FORMAT:
            raise StoreError(f"{self.path} has format {meta.get('format')!r}; this version writes {FORMAT!r}: "
                             "delete it (or give another --store) and run the sweep again")
        if meta.get("spec_sha256") != self.spec.sha256:
            raise StoreError(f"{self.path} was made by a different spec (sha256 {meta.get('spec_sha256', '?')[:12]}..., "
                             f"this one {self.spec.sha256[:12]}...): delete it or give another --store")

    def done_chunks(self) -> set:
        return {r[0] for r in self.db.execute("SELECT chunk FROM chunks")}

    def write_chunk(self, chunk: int, rows: list, seconds: float = None, worker: str = "") -> bool:
        """Write a chunk's rows and mark it done, in one transaction; False if it was already there."""
        expected = list(self.spec.chunk_points(chunk))
        if sorted(r["idx"] for r in rows) != expected:
            raise ValueError(f"chunk {chunk}: rows for points {sorted(r['idx'] for r in rows)[:3]}..., "
                             f"expected {expected[:3]}... ({len(expected)} points)")
        names = [n for n, _ in self.cols]
        with self.db:
            if self.db.execute("SELECT 1 FROM chunks WHERE chunk = ?", (chunk,)).fetchone():
                return False
            self.db.executemany(
                f"INSERT INTO runs ({', '.join(chr(34) + n + chr(34) for n in names)}) "
                f"VALUES ({', '.join('?' for _ in names)})",
                [[chunk if n == "chunk" else r.get(n) for n in names] for r in rows])
            self.db.execute("INSERT INTO chunks VALUES (?, ?, ?, ?)", (chunk, len(rows), seconds, worker))
        return True

    def rows(self) -> list:
        """Every stored row as a dict, in point order (NaN-valued quantities come back as None)."""
        names = [n for n, _ in self.cols]
        cur = self.db.execute(f"SELECT {', '.join(chr(34) + n + chr(34) for n in names)} FROM runs ORDER BY idx")
        return [dict(zip(names, r)) for r in cur]

    def count(self) -> int:
        return self.db.execute("SELECT COUNT(*) FROM runs").fetchone()[0]

    def close(self) -> None:
        self.db.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
