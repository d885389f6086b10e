"""Thick ring or coin rolling on one rim (paper Eqs. 47-62).

r_P = -e2 - h e3 (paper Fig. 7), valid for 0 < theta < pi/2: at theta = pi/2 the contact
switches to the other rim.

Parameters: two named sets
--------------------------
The paper's in-hand ring (text after Eq. 62) is R = 7.32/2 = 3.66 cm, half-thickness
h = 3.18/2 = 1.59 cm, wall w = 0.5 cm, an annular cylinder, for which the paper gives
I3 = (1 + (1 - w/R)^2)/2, I1 = (3 (1 + (1 - w/R)^2) + (2h/R)^2)/12 and h/R, and prints them
to four digits: I1 = 0.4993, I3 = 0.8727, h = 0.4344.  Two parameter sets follow:

``ANNULAR`` (the defaults)
    The three formulas evaluated exactly on R = 3.66, h = 1.59, w = 0.5:
    I1 = 16720/33489 = 0.4992684..., I3 = 58453/66978 = 0.8727194..., h = 53/122 = 0.4344262...
    Every run that does not set I1, I3, h uses these, and so does the reference set in
    reports/reference/ (computed with them).
``PRINTED``
    The paper's own four-digit numbers, 0.4993, 0.8727, 0.4344 (read as exact decimals).
    The annular values round to them; the report's numbers about "the paper's ring"
    (stability thresholds, Figs. 10 and 11) are computed for this set, with the annular
    value beside where the digits shown differ.

The difference is in the fourth digit of the inputs and moves, e.g., the straight-line
threshold from 18.67497 (annular) to 18.67560 (printed) and cot^-1 h from 1.160969 to
1.160991 (both 1.161 as printed): see :func:`verify.studies.summary.ring_parameter_rows`.
"""
from __future__ import annotations

from dataclasses import replace
from functools import lru_cache
from types import MappingProxyType
from typing import Mapping, Optional

import sympy as sp

from .base import Domain, Parameter
from .build import paper_variant, rolling_model
from .common import AXIAL_BOUND, GRAVITY, inertia_parameters
from .paper import eq50_rows
from .ring_chaplygin import THETA_REF, chaplygin_closed_form

_R, _H, _W = sp.Rational(366, 100), sp.Rational(159, 100), sp.Rational(1, 2)
I3_DEFAULT = (1 + (1 - _W / _R) ** 2) / 2  # annulus about its axis
I1_DEFAULT = (3 * (1 + (1 - _W / _R) ** 2) + (2 * _H / _R) ** 2) / 12  # about a diameter
H_DEFAULT = _H / _R

#: The annular-cylinder values as exact rationals (sympy): the defaults.
ANNULAR: Mapping = MappingProxyType({"I1": I1_DEFAULT, "I3": I3_DEFAULT, "h": H_DEFAULT})
#: The paper's printed four-digit values (text after Eq. 62), as decimal strings.
PRINTED: Mapping = MappingProxyType({"I1": "0.4993", "I3": "0.8727", "h": "0.4344"})
PARAMETER_SETS: Mapping = MappingProxyType({"annular": ANNULAR, "printed": PRINTED})
#: One line per set, for report labels.
SET_LABELS: Mapping = MappingProxyType({
    "annular": "annular (defaults: exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm)",
    "printed": "printed (the paper's I1 = 0.4993, I3 = 0.8727, h = 0.4344)",
})


def parameter_set(name: str) -> dict:
    """The ring's inertia and half-thickness of a named parameter set.

    Parameters
    ----------
    name : {"annular", "printed"}
        ``"annular"``: the exact annular-cylinder values of the paper's in-hand ring
        (R = 3.66 cm, h = 1.59 cm, w = 0.5 cm), which are the model's defaults.
        ``"printed"``: the paper's four-digit values I1 = 0.4993, I3 = 0.8727, h = 0.4344.

    Returns
    -------
    dict
        A new dict ``{"I1": ..., "I3": ..., "h": ...}``: sympy rationals for ``"annular"``,
        decimal strings for ``"printed"``.  Either is accepted wherever parameters are
        (``verify.solve(params=...)``, ``verify.studies.thresholds.threshold``,
        ``models.steady.steady_state``, ...); g is left at its default.

    Raises
    ------
    ValueError
        ``name`` is not a known set (the message lists the allowed names).

    Examples
    --------
    >>> from models.ring import parameter_set
    >>> parameter_set("printed")
    {'I1': '0.4993', 'I3': '0.8727', 'h': '0.4344'}
    >>> parameter_set("annular")["h"]
    53/122
    """
    if name not in PARAMETER_SETS:
        raise ValueError(f"unknown ring parameter set {name!r}; allowed: {', '.join(PARAMETER_SETS)}")
    return dict(PARAMETER_SETS[name])


def parameter_set_name(params: Optional[Mapping] = None) -> Optional[str]:
    """The name of the set that ``params`` (unset names: the defaults) is, else None.

    Parameters
    ----------
    params : mapping, optional
        Ring parameters as decimal strings or exact numbers; g is ignored.  A decimal string
        of 15 or more decimals also matches a value it rounds (so the 20-digit strings that
        :func:`verify.studies.thresholds.threshold` reports name their set); a shorter one must
        be exact (0.4993 is the printed set, not a rounding of the annular one).

    Returns
    -------
    str or None
        ``"annular"``, ``"printed"``, or None when I1, I3, h match neither set.
    """
    params = dict(params or {})

    def matches(given, value) -> bool:
        target = sp.Rational(value)
        try:
            exact = sp.Rational(given.strip() if isinstance(given, str) else given)
        except (TypeError, ValueError):
            return False
        if not isinstance(given, str):
            return exact == target
        decimals = len(given.strip().lower().partition(".")[2].partition("e")[0])
        if exact == target:
            return True
        return decimals >= 15 and abs(exact - target) <= sp.Rational(1, 2) * sp.Rational(10) ** -decimals

    for name, values in PARAMETER_SETS.items():
        if all(matches(params.get(k, ANNULAR[k]), v) for k, v in values.items()):
            return name
    return None


_NOTE = ("default {approx}...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; "
         "the paper prints {printed}: models.ring.PRINTED")
_I1, _I3 = inertia_parameters(
    I1_DEFAULT, I3_DEFAULT, "m R^2",
    notes=tuple(_NOTE.format(approx=sp.N(ANNULAR[k], 7), printed=PRINTED[k]) for k in ("I1", "I3")),
)
h = sp.Symbol("h", nonnegative=True)
PARAMETERS = (
    _I1, _I3,
    Parameter("h", h, H_DEFAULT, "half-thickness of the ring in units of R ("
              + _NOTE.format(approx=sp.N(H_DEFAULT, 7), printed=PRINTED["h"]) + ")",
              lower=0.0, lower_inclusive=True),
    GRAVITY,
)
I1, I3 = _I1.symbol, _I3.symbol
R2, R3 = sp.Integer(-1), -h
DOMAIN = Domain(sp.Integer(0), sp.pi / 2, "lies_flat", "rim_switch")


@lru_cache(maxsize=None)
def model(equations: str = "derived"):
    derived = rolling_model(
        "ring", "thick ring or coin rolling on one rim", PARAMETERS, I1, I3, R2, R3, DOMAIN,
        unit="m R^2", theta_ref=THETA_REF, chaplygin_closed_form=chaplygin_closed_form,
    )
    derived = replace(derived, relations=(AXIAL_BOUND,))
    if equations == "derived":
        return derived
    return paper_variant(derived, eq50_rows(I1, I3, h), "paper Eq. 50 as printed (explicit middle form)", I1, I3, R2, R3)
