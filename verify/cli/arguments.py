"""Reading the command line's values: numbers, NAME=VALUE pairs, precisions; bad input is a :class:`UsageError`."""
from __future__ import annotations

import re

# --- minimum MPFR precision -----------------------------------------------------------------
#: verify.precision.MIN_MPFR_BITS (53, double's significand; the argument is there), written out so
#: that the parser's help needs no heyoka (tests/test_cli_speed.py checks the two agree).  The CLI
#: checks it first so that mp:2, mp:0 and mp:-5 get the same one line.
MP_MIN_BITS = 53
N_EVAL_MAX = 1_000_000
_DECIMAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_NON_FINITE = re.compile(r"[+-]?(inf|infinity|nan)", re.IGNORECASE)


class UsageError(Exception):
    """Bad input on the command line (exit status 2)."""


class RunFailed(Exception):
    """The run finished, but not as ok or at a terminal event (exit status 1); the record is printed."""


def _shown(text) -> str:
    text = "" if text is None else str(text)
    return text if text and not any(c.isspace() for c in text) and text.isprintable() else repr(text)


def _decimal(text, what: str, example: str = "1.2 or -3e-4") -> str:
    """``text`` if it is a finite decimal number (1.2, -3e-4, .5); else UsageError naming it and ``example``."""
    s = str(text).strip()
    if _NON_FINITE.fullmatch(s):
        raise UsageError(f"{what}: {s!r} is not a finite number; allowed: a finite decimal number such as {example}")
    if not _DECIMAL.fullmatch(s) or not s.isascii():
        raise UsageError(f"{what}: {str(text)!r} is not a number; allowed: a decimal number such as {example}")
    return s


def _positive(text, option: str, example: str) -> str:
    """A positive finite decimal for ``option`` (sign and finiteness only: reading it at the run's
    precision, and underflow there, are solve's)."""
    s = str(text).strip()
    bad = UsageError(f"{option} {_shown(text)}: allowed a positive finite number such as {example}")
    if not _DECIMAL.fullmatch(s) or not s.isascii():
        raise bad
    mantissa = s.lstrip("+-").split("e")[0].split("E")[0]
    if s.startswith("-") or not any(c in "123456789" for c in mantissa):
        raise bad
    return s


def _positive_int(text, what: str, top: int | None = None, low: int = 1) -> int:
    s = str(text).strip()
    allowed = f"an integer from {low}{f' to {top}' if top else ' upwards'}"
    if not re.fullmatch(r"[+-]?\d+", s) or not s.isascii():
        raise UsageError(f"{what} {_shown(text)} is not an integer; allowed: {allowed}")
    value = int(s)
    if value < low:
        raise UsageError(f"{what} {s} must be at least {low}; allowed: {allowed}")
    if top is not None and value > top:
        raise UsageError(f"{what} {s} is too large; allowed: {allowed}")
    return value


def _precision(text, option: str = "--precision"):
    """parse_precision, with the MPFR floor (verify.precision.MIN_MPFR_BITS) checked first."""
    from ..precision import FIXED, max_mpfr_bits, parse_precision  # lazy: heyoka; the CLI's supervisor forks first

    s = str(text).strip()
    allowed = f"double, long, quad or mp:BITS (MPFR, BITS an integer from {MP_MIN_BITS} to {max_mpfr_bits()})"
    m = re.fullmatch(r"mp:\s*([+-]?\d+)", s)
    if m:
        bits = int(m.group(1))
        if not MP_MIN_BITS <= bits <= max_mpfr_bits():
            why = (f"below the MPFR minimum of {MP_MIN_BITS} bits (double's significand)" if bits < MP_MIN_BITS
                   else "above MPFR's largest precision")
            raise UsageError(f"{option} {_shown(text)}: {why}; allowed: {allowed}")
        s = f"mp:{bits}"
    elif s not in FIXED:
        raise UsageError(f"unknown precision {text!r}; allowed: {allowed}")
    try:
        return parse_precision(s)
    except ValueError as err:
        raise UsageError(f"{option} {_shown(text)}: {err}") from None


def _pairs(items, what: str) -> dict:
    out = {}
    for item in items or []:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise UsageError(f"--{what} {item!r} is not NAME=VALUE")
        if name.strip() in out:
            raise UsageError(f"--{what} {name.strip()} is given twice")
        out[name.strip()] = value.strip()
    return out


def _numeric_pairs(items, what: str) -> dict:
    """NAME=VALUE pairs whose values are decimal numbers (the names are checked by the computation)."""
    pairs = _pairs(items, what)
    for name, value in pairs.items():
        _decimal(value, f"--{what} {name}={_shown(value)}")
    return pairs


def _value_pairs(items, what: str) -> dict:
    """NAME=VALUE pairs whose values are decimals or simple expressions (``pi/2``, ``sqrt(980/1.25)``,
    ``16720/33489``): plain decimals stay text, expressions become exact sympy numbers
    (:func:`verify.expressions.read_value`); the names are checked by the computation."""
    pairs = _pairs(items, what)
    if all(_DECIMAL.fullmatch(v) and v.isascii() for v in pairs.values()):
        for name, value in pairs.items():  # the decimal checks (and messages) of before
            _decimal(value, f"--{what} {name}={_shown(value)}")
        return pairs
    from ..expressions import ExpressionError, read_value  # lazy: only for a value that is not a plain decimal

    out = {}
    for name, value in pairs.items():
        if _NON_FINITE.fullmatch(value):
            _decimal(value, f"--{what} {name}={_shown(value)}")
        try:
            out[name] = read_value(value, f"--{what} {name}=")
        except ExpressionError as err:
            raise UsageError(str(err).replace("= '", "='", 1)) from None
    return out
