"""What a body file costs (issue 32's performance): its sympy derivation cold and cached, and its runs
against the built-in model with the same equations.

* **Derivation.** A fresh process with an empty ``HEYOKA_CACHE_DIR`` loads each body and derives its
  model (``models.bodies.load`` + ``model_of``: the contact vector, paper Eqs. 5-8 and 73, the invariants);
  a second fresh process with the cache the first left does the same. Wall seconds of each, per body.
* **Runs.** ``solve`` of ``body:disk`` against ``solve`` of ``disk`` (paper Eq. 18 with I1 = k, I3 = 2k:
  the same equations, a sympy identity in tests/test_bodies.py) and of ``body:hurricane`` against
  ``hurricane`` (the same expressions term for term), the same start, in interleaved rounds in one
  process: the ratio of the best times (target <= 1.1: "as fast as the built-in model").
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from ..standard import STANDARD_STATES
from .timing import interleaved, ratio_record

#: the bodies whose derivation is timed: one of each new kind of contact (torus rim, ellipse, sphere)
DERIVED = ("rounded-coin", "prolate-ellipsoid", "tippe-top")

_DERIVE_SCRIPT = r"""
import json, sys, time
from models.bodies import load, model_of
out = {}
for name in json.loads(sys.argv[1]):
    t0 = time.perf_counter()
    model_of(load(name))
    out[name] = time.perf_counter() - t0
print(json.dumps(out))
"""

#: (body run, built-in run) with the same equations; both start from the built-in model's standard
#: state (verify.standard), with its default parameters (the disk's k = 1/4 is the body's I1 = 1/4, I3 = 1/2)
PAIRS = (("body:disk", "disk"), ("body:hurricane", "hurricane"))


def derivation_cost(quick: bool, progress) -> dict:
    """Wall seconds of deriving each body of :data:`DERIVED` in a fresh process: with an empty cache,
    then with the cache that run left (the second pays for reading it, not for sympy)."""
    bodies = DERIVED[:1] if quick else DERIVED
    root = Path(__file__).resolve().parent.parent.parent
    runs = {}
    with tempfile.TemporaryDirectory(prefix="body-cache-") as cache:
        env = dict(os.environ, HEYOKA_CACHE_DIR=cache, PYTHONPATH=str(root))
        for label in ("empty cache", "warm cache"):
            progress(f"  body derivation: fresh process, {label}")
            res = subprocess.run([sys.executable, "-c", _DERIVE_SCRIPT, json.dumps(bodies)], env=env, cwd=root,
                                 capture_output=True, text=True, check=True)
            runs[label] = json.loads(res.stdout.strip().splitlines()[-1])
    return {"bodies": list(bodies), "seconds": runs}


def body_runs(quick: bool, progress) -> list:
    """``solve`` of a body file against the built-in model with the same equations (10 s runs,
    interleaved rounds): one :func:`ratio_record` per pair, target <= 1.1."""
    from verify.engine.single import solve  # lazy: heyoka (0.45 s) only when the benchmark runs

    rounds = 3 if quick else 7
    records = []
    for body, builtin in PAIRS:
        progress(f"  body runs: {body} against {builtin}")
        state = STANDARD_STATES[builtin]
        runs = {body: lambda b=body, s=state: solve(b, "10", s), builtin: lambda m=builtin, s=state: solve(m, "10", s)}
        ends = {name: run().t[-1] for name, run in runs.items()}  # compiles and fills the integrator pool
        if any(end != 10 for end in ends.values()):
            raise RuntimeError(f"the body benchmark's runs must reach t = 10 s; they end at {ends}")
        times, _ = interleaved(runs, rounds)
        records.append(ratio_record(times, body, builtin, target=("<=", 1.1)))
    return records


def body_cost(quick: bool, progress) -> dict:
    """The body files' section of the benchmark: derivation cost and run speed."""
    return {"derivation": derivation_cost(quick, progress), "runs": body_runs(quick, progress)}
