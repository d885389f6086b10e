"""JIT compile cost: fresh processes with an empty heyoka disk cache, then with the cache they left."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

_COMPILE_SCRIPT = r"""
import json, resource, sys, time
t0 = time.perf_counter()
import heyoka as hy
t_import = time.perf_counter() - t0
from models import get_model
from models.common import PAPER_G
from verify.engine.compile import compile_model
from verify.precision import parse_precision
t0 = time.perf_counter()
model = get_model("disk")
t_derive = time.perf_counter() - t0
out = {"import": t_import, "derive": t_derive}
for label, precision, compact in json.loads(sys.argv[1]):
    prec = parse_precision(precision)
    c = compile_model(model, prec)
    kw = prec.integrator_kwargs(); kw["compact_mode"] = compact
    t0 = time.perf_counter()
    hy.taylor_adaptive(list(c.system), [1.2, 0, 0, 0, 1, 10, 0, 0] if precision == "double" else
                       prec.array(["1.2", 0, 0, 0, 1, 10, 0, 0]), pars=c.parameter_vector({"k": prec.number("0.25"), "g": prec.number(PAPER_G)}), **kw)
    first = time.perf_counter() - t0
    t0 = time.perf_counter()
    hy.taylor_adaptive(list(c.system), [1.2, 0, 0, 0, 1, 10, 0, 0] if precision == "double" else
                       prec.array(["1.2", 0, 0, 0, 1, 10, 0, 0]), pars=c.parameter_vector({"k": prec.number("0.25"), "g": prec.number(PAPER_G)}), **kw)
    out[label] = {"first": first, "again_in_process": time.perf_counter() - t0}
out["max_rss_mib"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps(out))
"""
COMPILE_CASES = (("double default", "double", False), ("double compact", "double", True),
                 ("quad compact", "quad", True), ("mp:128 compact", "mp:128", True))


def compile_cost(quick: bool, progress) -> dict:
    cases = COMPILE_CASES[:2] if quick else COMPILE_CASES
    root = Path(__file__).resolve().parent.parent.parent
    with tempfile.TemporaryDirectory(prefix="heyoka-cache-") as cache:
        env = dict(os.environ, HEYOKA_CACHE_DIR=cache, PYTHONPATH=str(root))
        runs = {}
        for label in ("empty disk cache", "warm disk cache"):
            progress(f"  compile cost: fresh process, {label}")
            res = subprocess.run([sys.executable, "-c", _COMPILE_SCRIPT, json.dumps(cases)], env=env, cwd=root,
                                 capture_output=True, text=True, check=True)
            runs[label] = json.loads(res.stdout.strip().splitlines()[-1])
    return {"cases": [c[0] for c in cases], "runs": runs}
