"""The precision ladder: double, long (x87 80-bit), quad (real128) and MPFR at any bits.

A :class:`Precision` knows its heyoka ``fp_type``, its epsilon, how to read a number
*at that precision* (``"1.3"`` in quad is the quad number nearest 1.3, not the double
nearest 1.3), how to convert exactly to mpmath, and how to print every digit.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from fractions import Fraction

import heyoka as hy
import mpmath
import numpy as np
import sympy as sp

FIXED = {"double": (float, 53), "long": (np.longdouble, 64), "quad": (hy.real128, 113)}

#: The fewest MPFR bits a run may use: 53, double's significand.
#:
#: What a run needs of its precision, and how many bits that takes:
#:
#: * an output grid that is strictly increasing once rounded (heyoka refuses a
#:   non-monotonic grid, and below about 4 bits ``mp:BITS`` leaked its "non-monotonic time
#:   grid" error or never returned).  t_k = k t_end / n and t_(k+1) differ by t_end / n, and
#:   near t_end one ulp is 2^(1 - bits) t_end, so distinct grid times need
#:   bits >= log2(n) + 2: 17 bits for the largest grid a solve() of the suite asks for (20001
#:   points, the claims' dense runs), 18 for the sweeps' 48001 samples.  The segment ends k 2 pi h_max
#:   of ``integrate._propagate`` need the same of the segment count (at most ~10^4: 100 s at
#:   650 rad/s), 16 bits;
#: * the model's constants representable to well below the effects the suite measures:
#:   g = 980 needs 8 bits exactly; the ring's exact 16720/33489 is representable at no
#:   precision, and its rounding must stay far below the smallest offsets the claims resolve
#:   (5e-5 rad, 1e-6 in a threshold rate): 2^(1 - bits) << 1e-6, i.e. bits >= 30 with a margin;
#: * a Taylor method that is a Taylor method: heyoka's order is ~ -ln(tol)/2 + 1 with tol =
#:   2^(1 - bits), which is 2 or 3 below ~10 bits, where its step-size rule no longer holds.
#:
#: Each asks for at most ~30 bits.  Between 30 and 53 bits MPFR would only be a slower,
#: less accurate double (double is hardware and has 53), so nothing the suite checks is
#: better served below 53: MPFR is the rung above quad, and ``mp:BITS`` below 53 is refused
#: naming this minimum.  ``integrate._grid`` also refuses any grid that is not strictly
#: increasing at the run's precision, so a grid larger than these arguments assume is caught
#: by the same rule.
MIN_MPFR_BITS = 53
ALLOWED = f"double, long, quad or mp:BITS (MPFR, BITS an integer from {MIN_MPFR_BITS} upwards)"
_MP = re.compile(r"^mp:(\d+)$")


@dataclass(frozen=True)
class Precision:
    """A floating-point type of the ladder.

    Attributes
    ----------
    name : str
        ``"double"``, ``"long"``, ``"quad"`` or ``"mp:BITS"``.
    bits : int
        Significand bits (53, 64, 113 or BITS).
    """

    name: str
    bits: int

    @property
    def fp_type(self):
        return hy.real if self.is_mpfr else FIXED[self.name][0]

    @property
    def is_mpfr(self) -> bool:
        return self.name.startswith("mp:")

    @property
    def eps(self) -> float:
        """Machine epsilon 2^(1 - bits) as a float (ratios of errors to it are what we print)."""
        return math.ldexp(1.0, 1 - self.bits)

    @property
    def digits(self) -> int:
        """Significant decimal digits that identify every number of this precision."""
        return math.ceil(self.bits * math.log10(2)) + 1

    @property
    def compact_mode(self) -> bool:
        # Full (non-compact) JIT of the rolling equations takes seconds in quad and
        # minutes in MPFR (HEYOKA.md); in double it is 1.6x faster per step.
        return self.name != "double"

    def integrator_kwargs(self) -> dict:
        kw = {"fp_type": self.fp_type, "compact_mode": self.compact_mode}
        if self.is_mpfr:
            kw["prec"] = self.bits
        return kw

    # --- numbers -----------------------------------------------------------------
    def number(self, value):
        """``value`` (decimal string, int, float, Fraction, sympy or mpmath number) at this precision.

        Strings are rounded once, directly to this precision.  Exact values (ints,
        Fractions, sympy rationals) are rounded once as well.  A Python float is taken
        as the exact binary number it is.
        """
        if isinstance(value, str):
            text = value.strip()
            try:
                check = float(text)
            except ValueError:
                raise ValueError(f"{value!r} is not a number") from None
            if not math.isfinite(check):
                raise ValueError(f"{value!r} is not a finite number")
            return self._from_decimal(text)
        if isinstance(value, (sp.Basic, Fraction, int)) and not isinstance(value, bool):
            frac = Fraction(int(value.p), int(value.q)) if isinstance(value, sp.Basic) and value.is_Rational else None
            if frac is None and isinstance(value, (Fraction, int)):
                frac = Fraction(value)
            if frac is not None:
                return self._from_fraction(frac)
            return self._from_decimal(str(sp.N(value, self.digits + 30)))
        if isinstance(value, mpmath.mpf):
            return self._from_decimal(mpmath.nstr(value, self.digits + 30, strip_zeros=False))
        if isinstance(value, (float, np.floating)):
            if not math.isfinite(float(value)):
                raise ValueError(f"{value!r} is not a finite number")
            return self._from_fraction(Fraction(*value.as_integer_ratio()))
        if isinstance(value, (hy.real128, hy.real)):
            return self._from_decimal(str(value))
        raise TypeError(f"cannot read {value!r} of type {type(value).__name__} as a number")

    def _from_decimal(self, text: str):
        if self.name == "double":
            return float(text)
        if self.name == "long":
            return np.longdouble(text)
        if self.name == "quad":
            return hy.real128(text)
        return hy.real(text, self.bits)

    def _from_fraction(self, frac: Fraction):
        if frac.denominator & (frac.denominator - 1) == 0 and abs(frac.numerator).bit_length() <= self.bits:
            exact = True  # dyadic with a short numerator: representable exactly
        else:
            exact = False
        if exact and self.name in ("double", "long"):
            return self.fp_type(frac.numerator) / self.fp_type(frac.denominator)
        with mpmath.workprec(self.bits + 64):
            return self.number(mpmath.mpf(frac.numerator) / frac.denominator)

    def zero(self):
        return self.number(0)

    def array(self, values) -> np.ndarray:
        """A 1-D numpy array of this precision's dtype."""
        vals = [v if _is_of(v, self) else self.number(v) for v in values]
        if self.name == "double":
            return np.array(vals, dtype=float)
        if self.name == "long":
            return np.array(vals, dtype=np.longdouble)
        return np.array(vals)

    def to_mpf(self, value) -> mpmath.mpf:
        """The exact value as an mpmath number (mpmath's working precision must hold it)."""
        if self.name in ("double", "long"):
            p, q = np.longdouble(value).as_integer_ratio() if self.name == "long" else float(value).as_integer_ratio()
            with mpmath.workprec(max(self.bits, abs(p).bit_length()) + 8):
                return mpmath.mpf(p) / q
        with mpmath.workprec(self.bits + 8):
            return mpmath.mpf(str(value))

    def to_text(self, value) -> str:
        """Every digit: the shortest decimal that reads back to the same number."""
        if self.name == "double":
            return repr(float(value))
        if self.name == "long":
            return np.format_float_scientific(np.longdouble(value), unique=True)
        return str(value)

    def to_json(self, value):
        """A JSON number in double, a decimal string carrying every digit otherwise."""
        return float(value) if self.name == "double" else self.to_text(value)


def _is_of(value, precision: Precision) -> bool:
    if precision.name == "double":
        return isinstance(value, float)
    if precision.name == "long":
        return isinstance(value, np.longdouble)
    if precision.name == "quad":
        return isinstance(value, hy.real128)
    return isinstance(value, hy.real) and value.prec == precision.bits


def max_mpfr_bits() -> int:
    """The most bits an MPFR number of this heyoka build may have (``mp:BITS`` above it is refused)."""
    return int(hy.real_prec_max())


def heyoka_version() -> str:
    """The version of heyoka the precisions run on (for records that name the engine)."""
    return str(hy.__version__)


def parse_precision(text) -> Precision:
    """``"double" | "long" | "quad" | "mp:BITS"`` (or a Precision) -> Precision."""
    if isinstance(text, Precision):
        return text
    if text in FIXED:
        return Precision(text, FIXED[text][1])
    m = _MP.match(str(text))
    if m:
        bits = int(m.group(1))
        lo, hi = max(MIN_MPFR_BITS, hy.real_prec_min()), hy.real_prec_max()
        if bits < lo:
            raise ValueError(f"precision {text!r}: {bits} bits is below the minimum of {lo} bits for MPFR "
                             f"(verify.precision.MIN_MPFR_BITS: double's significand); allowed: {ALLOWED}")
        if bits > hi:
            raise ValueError(f"precision {text!r}: {bits} bits is above heyoka's maximum of {hi}; allowed: {ALLOWED}")
        return Precision(f"mp:{bits}", bits)
    raise ValueError(f"unknown precision {text!r}; allowed: {ALLOWED}")
