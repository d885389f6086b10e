"""Steady motions of the bodies (thetadot = 0, constant rates): which each body has, and the state at a rate.

A steady motion is named by the body and the motion ("diameter-spin", "straight-line",
"precession", "sleeping") and parametrised by one rate (:data:`RATE_NAMES`); its state is
exact to 36 digits, beyond quad.  The sweeps, the stability maps and the threshold study
(:mod:`verify.studies.thresholds`) all start from :func:`steady_state`.

>>> from models.steady import steady_state
>>> steady_state("disk", "diameter-spin", "30", {})["theta"][:8]
'1.570796'
"""
from __future__ import annotations

from functools import lru_cache
from typing import Optional

import mpmath
import sympy as sp

from . import get_model
from .symbols import phidot, psidot, theta, thetadot

#: The steady motions each body has.
MOTIONS = {
    "disk": ("diameter-spin", "straight-line"),
    "sliding-disk": ("diameter-spin",),
    "ring": ("diameter-spin", "straight-line"),
    "hurricane": ("precession", "sleeping"),
    "gyroscope": ("sleeping",),
}
#: The rate that parametrises each motion.
RATE_NAMES = {"diameter-spin": "phidot0", "straight-line": "psidot0", "precession": "phidot0",
              "sleeping": "phidot+psidot"}


def exact_parameters(model, values: dict) -> dict:
    """The model's parameters as exact sympy numbers, symbol -> value: ``values`` (decimal strings read by
    ``sp.nsimplify``, or numbers) over the defaults."""
    out = {}
    for p in model.parameters:
        v = values.get(p.name, p.default)
        out[p.symbol] = _decimal(v) if isinstance(v, str) else sp.sympify(v)
    return out


@lru_cache(maxsize=1024)
def _decimal(text: str):
    """A decimal string as an exact sympy number (``sp.nsimplify``, ~1.5 ms a call: kept; sympy numbers are immutable)."""
    return sp.nsimplify(text)


def steady_state(name: str, motion: str, rate, params: dict) -> dict:
    """The steady motion at ``rate`` as decimal strings (theta, phidot, psidot), 36 digits (beyond quad).

    Parameters
    ----------
    name, motion : str
        A body and one of its :data:`MOTIONS`.
    rate
        The motion's rate (:data:`RATE_NAMES`), a decimal string or a number.
    params : dict
        Parameter overrides (decimal strings), read at 40 digits.

    Returns
    -------
    dict
        ``theta``, ``phidot``, ``psidot``: the disk and the sliding disk stand upright (theta = pi/2);
        the ring's straight line leans at cot^-1 h; the ring's diameter spin leans at the root of row 1
        of the derived equations with psidot = 0 (Eq. 62); the hurricane balls precess with
        psidot = phidot at cos(theta0) = (I3 - g/Omega^2)/(I1 - I3) (Eq. 72); the sleeping motion is
        upright (theta = 0, phidot = 0, psidot = rate; the caller adds the tilt).
    """
    model = get_model(name)
    subs = exact_parameters(model, params)
    with mpmath.workdps(40):  # parameters read at 40 digits, not at mpmath's default 15
        pv = {p.name: mpmath.mpf(sp.N(subs[p.symbol], 40)) for p in model.parameters}
    with mpmath.workdps(40):
        rate = mpmath.mpf(rate)
        if motion == "sleeping":  # upright; the tilt is added by the caller, with phidot = 0
            th, phd, psd = mpmath.mpf(0), 0, rate
        elif name in ("disk", "sliding-disk"):
            th, phd, psd = mpmath.pi / 2, (rate if motion == "diameter-spin" else 0), (rate if motion == "straight-line" else 0)
        elif motion == "straight-line":
            th, phd, psd = mpmath.acot(pv["h"]), 0, rate
        elif name == "ring":
            row1 = model.accelerations[0].subs({thetadot: 0, psidot: 0}).subs(subs)
            f = sp.lambdify((theta, phidot), sp.numer(sp.together(row1)), "mpmath")
            th = mpmath.findroot(lambda t: f(t, rate), (mpmath.acot(pv["h"]), mpmath.pi / 2 - mpmath.mpf("1e-9")),
                                 solver="anderson")
            phd, psd = rate, 0
        else:
            th = mpmath.acos((pv["I3"] - pv["g"] / rate**2) / (pv["I1"] - pv["I3"]))
            phd = psd = rate
        return {"theta": mpmath.nstr(th, 36), "phidot": mpmath.nstr(mpmath.mpf(phd), 36),
                "psidot": mpmath.nstr(mpmath.mpf(psd), 36)}


def ring_theta0_limits(params: Optional[dict] = None, dps: int = 30) -> dict:
    """The ends of the ring's diameter-spin branch theta0(phidot0) (Eq. 62) for ``params``.

    Parameters
    ----------
    params : dict, optional
        Ring parameters (decimal strings or exact numbers; unset: the defaults, the annular set
        of :mod:`models.ring`).
    dps : int
        Working digits.

    Returns
    -------
    dict
        ``"slow"``: cot^-1 h (phidot0 -> 0: the centre of mass above the contact);
        ``"fast"``: the root of the phidot0^2 term of Eq. 62, sin(2 theta) (1 + I3 - I1 - h^2)/2 +
        h cos(2 theta) = 0, i.e. 2 theta0 = atan2(2h, -(1 + I3 - I1 - h^2));
        ``"fast_as_printed"``: the same with the paper's + h^2 (text after Eq. 62, an erratum).
        mpmath numbers at ``dps`` digits.
    """
    model = get_model("ring")
    subs = exact_parameters(model, dict(params or {}))
    with mpmath.workdps(dps):
        pv = {p.name: mpmath.mpf(sp.N(subs[p.symbol], dps + 10)) for p in model.parameters}
        h, I1, I3 = pv["h"], pv["I1"], pv["I3"]
        return {"slow": mpmath.acot(h),
                "fast": mpmath.atan2(2 * h, -(1 + I3 - I1 - h**2)) / 2,
                "fast_as_printed": mpmath.atan2(2 * h, -(1 + I3 - I1 + h**2)) / 2}
