"""Standard initial states: one ordinary motion per model, used by the conservation table,
the drift tests and the benchmarks.  Each stays inside its model's domain for 10 s.

Values are exact decimal strings (read at the run's precision); where a rate is a square
root it is given to 40 digits.
"""
from __future__ import annotations

import mpmath

from models.common import PAPER_G

with mpmath.workdps(40):  # local: importing this module must not change mpmath's global precision
    _SQRT_25G = mpmath.nstr(mpmath.sqrt(25 * PAPER_G), 40)  # steady precession near theta = 1.20 (Fig. 16)

STANDARD_STATES = {
    "disk": {"theta": "1.2", "phidot": "1", "psidot": "10"},
    "ring": {"theta": "1.0", "phidot": "-3", "psidot": "20"},
    "hurricane": {"theta": "1.21", "phidot": _SQRT_25G, "psidot": _SQRT_25G},
    "sliding-disk": {"theta": "1.2", "phidot": "5", "psidot": "10"},
    "gyroscope": {"theta": "0.5", "phidot": "2", "psidot": "50"},
    "effective": {"theta": "1.21", "phidot": _SQRT_25G, "psidot": _SQRT_25G},
}
