"""Parameter sweeps from a TOML file, stored in SQLite a chunk at a time, resumable, on threads or Dask.

* :mod:`.spec` -- the TOML layout and its validation;
* :mod:`.engine` -- one chunk: heyoka batch integrators over an ensemble of threads, reductions;
* :mod:`.store` -- the SQLite store (a chunk per transaction: kill-safe, resumable, no duplicates);
* :mod:`.runner` -- the chunks still missing, locally or on a Dask cluster, with a progress bar;
* :mod:`.plot` -- maps from the store.

``python -m verify sweep SPEC.toml [--dask ADDRESS|local] [--plot] [--yes]``.

A sweep is refused before anything is written when it is too large (:class:`SweepTooLarge`,
overridden by ``run_sweep(..., yes=True)``) or when a point of its grid is not a valid start
(:class:`InvalidPoint`); both are :class:`SpecError`.
"""
from __future__ import annotations

from pathlib import Path

from .runner import LIMITS, ClusterError, Estimate, SweepResult, SweepTooLarge, estimate, run_sweep
from .spec import InvalidPoint, SpecError, SweepSpec, load, parse
from .store import Store, StoreError

SPECS = Path(__file__).resolve().parent / "specs"

__all__ = ["ClusterError", "Estimate", "InvalidPoint", "LIMITS", "SPECS", "SpecError", "Store", "StoreError", "SweepResult",
           "SweepSpec", "SweepTooLarge", "estimate", "load", "parse", "run_sweep"]
