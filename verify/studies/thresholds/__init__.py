"""The threshold study: linear stability of steady motions, exactly, and its confirmations.

* :mod:`~verify.studies.thresholds.linear` -- the exact threshold spin rate of each steady motion from the
  reduced Jacobian's stability coefficient w2 (:func:`threshold`, :class:`Threshold`), the sleeping motion's
  complex-tilt form (:func:`sleeping_coefficients`);
* :mod:`~verify.studies.thresholds.growth` -- the growth protocol on the full nonlinear equations and on the
  linearisation (:func:`grows`, :func:`linear_grows`), and the bisection of the rate between them
  (:func:`bracket`);
* :mod:`~verify.studies.thresholds.variational` -- w2 from heyoka's variational equations
  (:func:`variational_w2`).

The names below are the study's public API (the CLI's ``threshold`` command, the report's studies, the maps).
"""
from __future__ import annotations

import mpmath

from .growth import (
    CRITERIA, GROWTH, bracket, grows, linear_deviation, linear_grows, linear_path, nonlinear_deviation, nonlinear_path,
)
from .linear import (
    MOTIONS, OMEGA, OMEGA3, Threshold, check_reading, jacobian_entries, sleeping_coefficients, stability_coefficient,
    steady_state, threshold,
)
from .variational import Variational, variational_w2

__all__ = [
    "CRITERIA", "GROWTH", "MOTIONS", "OMEGA", "OMEGA3", "Threshold", "Variational", "bracket", "check_reading",
    "grows", "jacobian_entries", "linear_deviation", "linear_grows", "linear_path", "nonlinear_deviation",
    "nonlinear_path", "sleeping_coefficients", "stability_coefficient", "steady_state", "threshold", "to_record",
    "variational_w2",
]


def to_record(t: Threshold, nonlinear=None) -> dict:
    """The JSON object of ``python -m verify threshold --format json``; ``nonlinear`` is (tilt, (lo, hi))."""
    return {
        "model": t.model,
        "motion": t.motion,
        "params": t.params,
        "threshold": {"name": t.name, "value": None if t.value is None else mpmath.nstr(t.value, 20, strip_zeros=False)},
        "closed_form": t.closed_form,
        "method": t.method,
        "bracket": None if not nonlinear or nonlinear[1] is None else {
            "tilt": nonlinear[0], "low": mpmath.nstr(nonlinear[1][0], 12), "high": mpmath.nstr(nonlinear[1][1], 12),
            "method": f"bisection on the rate; theta perturbed by the tilt, grows = leaves the domain or moves more than "
                      f"{GROWTH} x the tilt within 10 s (double, derived equations)"},
    }
