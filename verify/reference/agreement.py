"""Agreeing digits: what two runs at different precisions agree on (agreement, not a proof).

A case is integrated twice, at a lower and a higher MPFR precision (128 and 256 bits by
default).  The higher run's own error is smaller than the lower run's by about the ratio
of their epsilons (2^-128 here), so ``|low - high|`` estimates a bound on the error of
``high`` with a wide margin, and a value is stored as ``high`` rounded to the largest number of
significant digits d for which

    |rounded - high| + |low - high|  <=  one unit in the d-th significant digit.

The stored decimal is then, on the assumption that the two runs do not share an error larger
than the lower run's own, within one unit of its last digit of the exact solution (``abs_error``
states that estimate explicitly).  Two runs of the same method can share an error, so this is
agreement, not a proof: proved enclosures are :mod:`verify.proof`'s.  The number of digits is capped at what the
lower run can resolve (its bits times log10 2): two runs that agree to the last bit of the
lower one agree on no more than that.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import mpmath


@dataclass(frozen=True)
class Agreed:
    """A value with its agreeing digits.

    Attributes
    ----------
    text : str
        The value rounded to ``digits`` significant digits ("0" for an exact zero).
    digits : int or None
        Significant digits on which the two runs agree (None: both runs gave exactly 0, a value the
        equations hold at zero).
    abs_error : str
        The estimated bound on |text - exact| (2 significant digits, rounded up): one unit in the
        last agreeing digit.
    """

    text: str
    digits: Optional[int]
    abs_error: str


def agree(low, high, low_bits: int, high_bits: int) -> Agreed:
    """The digits of ``high`` (an mpmath number from the high-precision run) that ``low`` agrees with."""
    with mpmath.workprec(high_bits + 32):
        a, b = mpmath.mpf(low), mpmath.mpf(high)
        diff = abs(a - b)
        if a == 0 and b == 0:
            return Agreed("0", None, "0")
        cap = math.floor(low_bits * math.log10(2))
        if b == 0 or diff >= abs(b):
            # not even the first digit is certain: the value is 0 within diff
            return Agreed(_round(b, 3), 0, _up(max(diff, abs(b))))
        exponent = int(mpmath.floor(mpmath.log10(abs(b))))
        d = min(cap, max(1, int(mpmath.floor(-mpmath.log10(diff / abs(b)))) + 1) if diff > 0 else cap)
        while d >= 1:
            text = _round(b, d)
            unit = mpmath.mpf(10) ** (_exponent_of(text, exponent) - d + 1)
            if abs(mpmath.mpf(text) - b) + diff <= unit:
                return Agreed(text, d, _up(unit))
            d -= 1
        return Agreed(_round(b, 3), 0, _up(diff + abs(b)))


def _round(x, digits: int) -> str:
    """``x`` to ``digits`` significant digits, in mpmath's exponent notation where it needs one."""
    return mpmath.nstr(x, digits, strip_zeros=False, min_fixed=-4, max_fixed=6)


def _exponent_of(text: str, fallback: int) -> int:
    """Decimal exponent of the leading digit of a rounded number (rounding can carry: 9.99 -> 10.0)."""
    v = abs(mpmath.mpf(text))
    return int(mpmath.floor(mpmath.log10(v))) if v > 0 else fallback


def _up(x) -> str:
    """A short decimal >= x (2 significant digits, rounded up)."""
    if x == 0:
        return "0"
    e = int(mpmath.floor(mpmath.log10(x)))
    m = mpmath.ceil(x / mpmath.mpf(10) ** (e - 1))
    return f"{int(m)}e{e - 1}"


def digits_of(value_text: str, abs_error_text: str) -> float:
    """Significant digits that ``abs_error`` leaves in ``value`` (log10 |value| / abs_error)."""
    v, e = abs(mpmath.mpf(value_text)), mpmath.mpf(abs_error_text)
    if v == 0 or e == 0:
        return math.inf if e == 0 else 0.0
    return float(mpmath.log10(v / e))
