"""The shipped bodies' steady motions and their stability thresholds, each checked by a second route, as
report rows (REPORT.md's "Bodies of revolution" section).

The thresholds come from the generic linearisation of :mod:`verify.studies.steady_bodies` (any body of
revolution: straight-line rolling, the diameter spin, sleeping at the ends of the domain). Each is then
checked by a route that shares nothing with it but the body's equations:

* every threshold by the full nonlinear equations (:func:`verify.studies.steady_confirm.confirm`): runs 10 %
  below and above it from the steady motion with theta perturbed by 1e-4; the side it calls stable must stay
  within 1000 tilts for 10 s and the other grow. A motion stable (or unstable) at every rate is run at 1, 30
  and 300 s^-1 (:func:`~verify.studies.steady_confirm.confirm_every_rate`);
* for the paper's bodies also the built-in model's own threshold (:func:`verify.studies.thresholds.threshold`:
  paper Eqs. 30-41 for the disk and hoop, 59-62 for the ring, 80-82 for the hurricane balls), compared
  to 19 digits.

A curve body (the egg) is left out: sympy's analysis of its trigonometric polynomials ran for more than ten
minutes (docs/bodies.md).
"""
from __future__ import annotations

import mpmath

from models.bodies import load, shipped

from .steady_bodies import thresholds
from .steady_confirm import confirm, confirm_every_rate
from .thresholds import threshold

#: the paper's bodies among the shipped files: the built-in model, its parameters, and the motions it names
#: as the generic study does (the built-in thresholds of the ring and hurricane take the model's defaults)
PAPER_MODELS = {"disk": ("disk", {"k": "0.25"}), "hoop": ("disk", {"k": "0.5"}), "ring": ("ring", {}),
                "hurricane": ("hurricane", {})}
#: digits compared between the generic threshold (its record keeps 30 significant digits, from 45-digit
#: arithmetic) and the built-in one (30-digit arithmetic, kept here to 20 significant digits: half a unit of
#: the 20th is its rounding, so 19 must agree)
COMPARED_DIGITS = 19


def _paper_value(name: str, motion: str):
    """The built-in model's threshold for ``motion`` (a decimal string) or None where it has none."""
    model, params = PAPER_MODELS[name]
    value = threshold(model, motion, params).value  # bad parameters raise: never read as "no threshold"
    with mpmath.workdps(30):
        return None if value is None else mpmath.nstr(value, 20)


def _agree(a: str, b: str) -> bool:
    with mpmath.workdps(40):
        x, y = mpmath.mpf(a), mpmath.mpf(b)
        return abs(x - y) <= abs(y) * mpmath.mpf(10) ** (1 - COMPARED_DIGITS)


def rows() -> list:
    """One JSON-ready row per steady motion of every shipped body that is not a curve."""
    out = []
    for name in shipped():
        if load(name).kind == "curve":
            continue
        model = f"body:{name}"
        for record in thresholds(model):
            row = {"body": name, "motion": record.motion, "theta0": record.theta0_exact or record.theta0,
                   "rate": record.rate, "threshold": record.value, "stable": record.stable,
                   "closed_form": record.closed_form}
            if record.value is not None:
                c = confirm(model, record)
                row["nonlinear"] = {"rates": [c.below.rate, c.above.rate], "grows": [c.below.grows, c.above.grows],
                                    "agrees": c.agrees}
            elif record.theta0 != "-":
                runs = confirm_every_rate(model, record)
                expected = record.stable == "no rate"
                row["nonlinear"] = {"rates": [r.rate for r in runs], "grows": [r.grows for r in runs],
                                    "agrees": all(r.grows == expected for r in runs)}
            if name in PAPER_MODELS:
                paper = _paper_value(name, record.motion)
                row["built_in"] = {"model": PAPER_MODELS[name][0], "threshold": paper,
                                   "agrees": (paper is None) == (record.value is None)
                                   and (paper is None or _agree(record.value, paper))}
            out.append(row)
    return out


def failures(table: list) -> list:
    """The rows whose second route disagrees: each a line naming the body, the motion and the route."""
    bad = []
    for r in table:
        if "nonlinear" in r and not r["nonlinear"]["agrees"]:
            bad.append(f"{r['body']} {r['motion']}: the nonlinear runs at {r['nonlinear']['rates']} grow "
                       f"{r['nonlinear']['grows']}, not as 'stable {r['stable']}' says")
        if "built_in" in r and not r["built_in"]["agrees"]:
            bad.append(f"{r['body']} {r['motion']}: {r['threshold']} from the profile, {r['built_in']['threshold']} "
                       f"from the built-in {r['built_in']['model']}")
    return bad
