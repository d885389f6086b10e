"""Score two of the suite's own double runs against the reference case disk-standard-1.

A stand-in for a comparison with another engine that runs anywhere: the suite's double
integrator at a loose tolerance (1e-6) and at the precision's epsilon, written as form (a)
(Euler) and as form (b) (rotation matrix, centre of mass, angular velocity), each scored by
``verify.score``.  Run: ``python examples/score_suite_runs.py``.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from models.symbols import STATE_NAMES  # noqa: E402
from verify import score, solve  # noqa: E402
from verify.reference.store import DIRECTORY  # noqa: E402
from verify.frames import QUATERNION, euler_to_b  # noqa: E402

CASE = "disk-standard-1"


def main() -> None:
    record = json.loads((DIRECTORY / f"{CASE}.json").read_text())
    params = {k: float(v["decimal"]) for k, v in record["model"]["parameters"].items()}
    print("| run | steps | form | min digits (where) | median digits of the weakest | energy drift | contact height | contact velocity |")
    print("|---|---:|---|---|---:|---:|---:|---:|")
    for label, tol in (("double, tol = 1e-6", 1e-6), ("double, tol = eps", None)):
        sol = solve("disk", record["t_end"], record["initial_state"], precision="double", tol=tol, t_eval=record["grid"])
        euler = {"t": np.asarray(sol.t, float), **{n: np.asarray(sol.y[i], float) for i, n in enumerate(STATE_NAMES)}}
        b = euler_to_b("disk", {n: euler[n] for n in STATE_NAMES}, params)
        matrix = {"t": euler["t"], **{k: v for k, v in b.items() if k not in QUATERNION}}
        for form, run in (("euler", euler), ("matrix", matrix)):
            s = score(run, CASE)
            weakest = s.components[s.worst.split()[0]]
            height = "-" if s.contact_height is None else f"{s.contact_height:.1e}"
            velocity = "-" if s.contact_velocity is None else f"{s.contact_velocity:.1e}"
            print(f"| {label} | {sol.steps} | {form} | {s.min_digits:.2f} ({s.worst}) | {weakest.median_digits:.2f} | "
                  f"{s.energy_rel_drift:.1e} | {height} | {velocity} |")
        print(f"<!-- {label}: {s.verdict} -->")


if __name__ == "__main__":
    main()
