"""Bit-identity of the batch engine's results across code changes: dump, then compare.

``python benchmarks/batch_identity.py dump FILE`` writes the sweep rows and stability-map arrays of
small grids (disk, ring with a dissipative term and [stop], runs that leave by events, widths 4 and
8) to FILE; ``... compare FILE`` recomputes them and names every value whose bytes differ.  Run
``dump`` on the old code and ``compare`` on the new one, on the same machine and versions.
"""
from __future__ import annotations

import pickle
import sys
import tempfile
from pathlib import Path

import numpy as np

from verify.studies import maps
from verify.studies.orbits import senses
from verify.sweep import parse
from verify.sweep.engine import run_chunk

DISK = """
[sweep]
name = "identity-disk"
model = "disk"
t_end = 3
samples = 301
chunk = 64
store = "{store}"

[start]
phidot = 1.0
psidot = 4.0

[[axis]]
name = "theta"
from = 0.3
to = 1.5
count = 6

[[axis]]
name = "thetadot"
from = -2
to = 2
count = 5

[record]
quantities = ["max_theta", "min_theta", "final_theta", "final_phi", "final_x", "final_psidot", "max_theta_deviation"]
"""

FALLS = """
[sweep]
name = "identity-falls"
model = "disk"
t_end = 2
samples = 201
chunk = 25
store = "{store}"

[start]
phidot = 0.0
psidot = 0.5

[[axis]]
name = "theta"
from = 0.2
to = 1.5
count = 5

[[axis]]
name = "thetadot"
from = -12
to = 12
count = 5

[record]
quantities = ["max_theta", "min_theta", "final_theta", "final_thetadot", "final_y"]
"""

STEADY = """
[sweep]
name = "identity-steady"
model = "disk"
t_end = 4
samples = 201
chunk = 40
store = "{store}"

[start]
steady = "diameter-spin"

[[axis]]
name = "phidot"
from = 14
to = 42
count = 10

[[axis]]
name = "tilt"
from = 1e-6
to = 1e-1
count = 4
scale = "log"

[record]
quantities = ["max_theta_deviation", "growth", "max_theta", "min_theta"]
"""

RING = """
[sweep]
name = "identity-ring"
model = "ring+air-drag"
t_end = 12
samples = 4801
chunk = 8
store = "{store}"

[geometry]
kind = "annulus"

[start]
theta = 1.2
phidot = 40

[[axis]]
name = "c"
from = 0.05
to = 0.5
count = 2
scale = "log"

[[axis]]
name = "h"
from = 0.01
to = 0.4344
count = 2

[[axis]]
name = "w"
from = 0.1366
to = 1.0
count = 2

[record]
quantities = ["orbit_start", "orbit_end", "orbit_last", "t_orbit_start", "t_orbit_end",
              "orbit_reversal", "t_orbit_reversal", "spin_start", "spin_end", "retrograde_turn",
              "retrograde_by_last_read", "retrograde_end", "t_retrograde", "windows",
              "windows_undecided", "strobe_last", "mean_last", "points_per_nutation",
              "node_turn_start", "node_turn_end", "node_retrograde_turn", "path_start", "path_end",
              "path_reversal", "roll_start", "roll_end", "roll_reversal", "t_roll_reversal",
              "min_theta"]

[stop]
theta_below = 0.6
"""


def results() -> dict:
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in (("disk", DISK), ("falls", FALLS), ("steady", STEADY), ("ring", RING)):
            spec = parse(text.format(store=Path(tmp) / f"{name}.sqlite"))
            for bs in (4, 8):
                out[f"sweep {name} bs={bs}"] = [run_chunk(spec, c, 2, bs, senses=senses) for c in range(spec.n_chunks)]
    lin = 28.0
    for model, motion, kwargs in (("disk", "diameter-spin", {}), ("disk", "diameter-spin", {"step_cap": True}),
                                  ("sliding-disk", "diameter-spin", {}), ("disk", "straight-line", {}),
                                  ("disk", "diameter-spin", {"params": {"k": "0.5"}, "cap": 0.05})):
        for bs in (4, 8):
            m = maps.stability_map(model, motion, rates=np.linspace(0.5 * lin, 1.6 * lin, 7),
                                   tilts=[1e-6, 1e-3, 3e-2], t_end=5.0, batch_size=bs, **kwargs)
            out[f"map {model} {motion} {kwargs} bs={bs}"] = {
                k: getattr(m, k) for k in ("max_deviation", "left", "reason", "t_left", "theta_steady", "n_steps",
                                           "n_samples", "step_cap")}
    return out


def _flat(value, path=""):
    if isinstance(value, dict):
        for k in value:
            yield from _flat(value[k], f"{path}/{k}")
    elif isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            yield from _flat(v, f"{path}[{i}]")
    elif isinstance(value, np.ndarray):
        yield path, (value.dtype.str, value.shape, value.tobytes())
    elif isinstance(value, float):
        yield path, np.float64(value).tobytes()
    else:
        yield path, repr(value)


def main(argv):
    mode, file = argv
    if mode == "dump":
        Path(file).write_bytes(pickle.dumps(dict(_flat(results()))))
        return 0
    old = pickle.loads(Path(file).read_bytes())
    new = dict(_flat(results()))
    bad = [k for k in old.keys() | new.keys() if old.get(k) != new.get(k)]
    for k in sorted(bad)[:40]:
        print("DIFFERENT", k, old.get(k), new.get(k))
    print(f"{len(old)} values compared: {len(bad)} differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
