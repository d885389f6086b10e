"""High-accuracy reference trajectories with agreeing digits (``reports/reference/``).

* :mod:`.cases` -- which runs (every model, quiet and wild, 1 to 100 s, the paper's figures);
* :mod:`.make` -- two MPFR runs per case, the equations' fingerprint, the conditioning;
* :mod:`.agreement` -- the digits two precisions agree on (agreement, not proof);
* :mod:`.store` -- the JSON format, the index and the README;
* :mod:`.check` -- re-integrate at double, long or quad and compare within the argued bound;
* :mod:`.proved` -- proved enclosures of the cases (``reference --prove``), beside the agreed digits.

``python -m verify reference --make`` writes the set; ``--prove`` encloses it; ``--check``
verifies an integrator (this suite's, at a working precision) against both.
"""
from __future__ import annotations

import multiprocessing
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

from ..precision import parse_precision
from .cases import ReferenceCase, case, cases
from .check import CHECK_PRECISIONS, CaseCheck, check_case, render_checks
from .make import HIGH, LOW, run_case
from .proved import load_proofs
from .store import DIRECTORY, case_record, load_set, read_case, write_case, write_set


def make_set(names=None, jobs: int = 2, directory: Path = DIRECTORY, low: str = LOW, high: str = HIGH,
             progress=None) -> list:
    """Compute the named cases (default: all) at ``low`` and ``high`` bits and write them.

    The runs go to ``jobs`` processes, longest first; nothing is written until every run of
    the request has finished.  With ``names`` only those files are replaced (the index and
    README are refreshed from the files on disk); without, the whole set is rewritten.
    Returns the records.
    """
    chosen = [case(n) for n in names] if names else list(cases())
    lo, hi = parse_precision(low), parse_precision(high)
    if not (lo.is_mpfr and hi.is_mpfr and lo.bits < hi.bits):
        raise ValueError(f"precisions {low!r}, {high!r}: need two MPFR precisions, the second higher")
    say = progress or (lambda s: None)
    tasks = [(c.name, p) for c in sorted(chosen, key=_cost, reverse=True) for p in (hi.name, lo.name)]
    runs, t0 = {}, time.monotonic()
    with ProcessPoolExecutor(max_workers=max(1, int(jobs)), mp_context=multiprocessing.get_context("spawn")) as pool:
        futures = {pool.submit(run_case, n, p): (n, p) for n, p in tasks}
        for fut in as_completed(futures):
            n, p = futures[fut]
            runs[(n, p)] = fut.result()
            say(f"  {n} at {p}: {runs[(n, p)].steps} steps ({time.monotonic() - t0:.0f} s)")
    records = [case_record(c, runs[(c.name, lo.name)], runs[(c.name, hi.name)], lo.bits, hi.bits) for c in chosen]
    if names:
        for r in records:
            write_case(r, directory)
    else:
        write_set(records, directory)
    return records


def _cost(c: ReferenceCase) -> float:
    """Rough relative cost, to start the longest runs first: duration times the fastest initial rate."""
    rates = [abs(float(c.state.get(n, "0"))) for n in ("thetadot", "phidot", "psidot")]
    return float(c.t_end) * max(rates + [30.0])


def check_set(precision: str = "double", names=None, directory: Path = DIRECTORY, progress=None) -> list:
    """:func:`check_case` for every case of the stored set (or those named)."""
    bits = precision[3:] if precision.startswith("mp:") else ""
    if precision not in CHECK_PRECISIONS and not (bits.isdigit() and 64 <= int(bits) <= 512):
        raise ValueError(f"--precision {precision!r}; allowed: {', '.join(CHECK_PRECISIONS)} or mp:BITS "
                         "(64 <= BITS <= 512: an MPFR run measured against the agreed digits and the proved balls)")
    proofs = load_proofs(directory)
    out = []
    for record in load_set(directory, names):
        out.append(check_case(record, precision, proofs=proofs.get(record["name"])))
        if progress:
            progress(f"  {record['name']} {precision}: ratio {out[-1].ratio:.2e}")
    return out


__all__ = ["CHECK_PRECISIONS", "CaseCheck", "DIRECTORY", "ReferenceCase", "case", "cases", "check_case", "check_set",
           "load_set", "make_set", "read_case", "render_checks"]
