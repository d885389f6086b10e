"""``threshold`` and ``spindown`` for a body file (``--body FILE`` or ``body:NAME[@HASH]`` in the model's place).

The thresholds are the generic study of :mod:`verify.studies.steady_bodies` (every steady motion a body of revolution
has, from its own equations; it reproduces the disk's and the ring's closed forms to every digit), printed in the shape
of the models' ``threshold`` (:func:`verify.studies.thresholds.to_record`: ``model``, ``motion``, ``params``,
``threshold`` {``name``, ``value``: 20 significant digits}, ``closed_form``, ``method``, ``bracket``) with what a body
adds: ``theta0`` (the steady tilt), ``stable`` (on which side of the value) and ``branch``.  A body may have two motions
of one kind (sleeping at theta0 = 0 and at pi); ``--theta0`` picks one.  The spin-down is
:func:`verify.studies.spindown.body_spindown`.
"""
from __future__ import annotations

import mpmath
import sympy as sp

from .arguments import UsageError

#: significant digits of a printed threshold: the models' (verify.studies.thresholds.to_record)
DIGITS = 20
#: how near --theta0 must be to a motion's steady tilt to pick it (rad): the tilts are printed to 6 digits, and the
#: motions of one kind of a body lie apart by far more (0 and pi; the branches' thresholds on disjoint intervals)
THETA0_MATCH = 1e-3


def body_model(text: str, option: str):
    """The model of a body given as a file, a shipped name or ``body:NAME[@HASH]`` (bad input: UsageError)."""
    from models.bodies import InvalidBody, load, model_of  # lazy: sympy (0.6 s) only for a body, not 'threshold disk'

    try:
        body = load(text)
        model = model_of(body)
    except InvalidBody as err:
        raise UsageError(f"{option} {text}: {err}" if str(text) not in str(err) else str(err)) from None
    if body.kind == "curve":
        _CURVES.add(model.name)
    return model


#: Models of ``curve`` bodies loaded here: their steady motions are not built (sympy's analysis of the egg's
#: trigonometric curve ran past ten minutes: docs/bodies.md), so the studies of steady motions refuse them at once.
_CURVES: set = set()


def refuse_curve(model, study: str) -> None:
    """A one-line refusal of ``study`` for a curve body, before any sympy runs (UsageError)."""
    if model.name in _CURVES:
        raise UsageError(f"{model.name} is a curve body, whose steady motions are not built (docs/bodies.md, "
                         f"'Not built yet'), so it has no {study}; allowed: a body of another kind "
                         "(python -m verify models lists them)")


def check_params(model, params: dict, study: str) -> None:
    """Names, ranges and the profile's relations of ``--param`` values (as a run checks them), and their reading."""
    from ..engine.single import resolve_parameters  # lazy: heyoka: 'spindown' imports this first
    from ..precision import parse_precision  # lazy: as the line above
    from ..studies.thresholds import check_reading  # lazy: as the line above

    try:
        resolve_parameters(model, params, parse_precision("double"))
        check_reading(params, study)
    except ValueError as err:
        raise UsageError(str(err)) from None


def body_threshold(model, motion: str, params: dict, theta0=None) -> dict:
    """The record of ``threshold`` for one steady motion of a body (module docstring)."""
    from ..studies.steady_bodies import thresholds  # lazy: only for a body, not 'threshold disk'

    refuse_curve(model, "threshold")
    check_params(model, params, "threshold study")
    records = thresholds(model, params)
    kinds = sorted({r.motion for r in records})
    chosen = [r for r in records if r.motion == motion]
    if not chosen:
        raise UsageError(f"{model.name} has no steady motion {motion!r}; allowed: {', '.join(kinds) or 'none'}")
    if theta0 is not None:
        target = _tilt(theta0)
        chosen = [r for r in chosen if r.theta0 != "-" and abs(mpmath.mpf(r.theta0) - target) < THETA0_MATCH]
        if not chosen:
            raise UsageError(f"--theta0 {theta0}: no {motion} of {model.name} there; allowed: {_tilts(records, motion)}")
    if len(chosen) > 1:
        raise UsageError(f"{model.name} has {len(chosen)} {motion} motions; give --theta0 with one of: "
                         f"{_tilts(records, motion)}")
    r = chosen[0]
    with mpmath.workdps(45):  # the study's 30 digits rounded to the models' 20 (a second rounding: module DIGITS)
        value = None if r.value is None else mpmath.nstr(mpmath.mpf(r.value), DIGITS, strip_zeros=False)
    return {"model": model.name, "motion": motion, "params": r.params, "threshold": {"name": r.rate, "value": value},
            "closed_form": r.closed_form, "method": r.method, "bracket": None, "theta0": r.theta0_exact or r.theta0,
            "stable": r.stable, "branch": r.branch}


def _tilt(text):
    """--theta0 as an mpmath number: a decimal or an expression such as pi or pi/2 (verify.expressions)."""
    from ..expressions import ExpressionError, read_value  # lazy: verify.expressions only for --theta0

    bad = UsageError(f"--theta0 {text!r} is not a number; allowed: a tilt in rad such as 0, pi or 1.2049")
    try:
        value = read_value(str(text).strip(), "--theta0")
    except ExpressionError:
        raise bad from None
    with mpmath.workdps(45):
        try:
            number = mpmath.mpf(value if isinstance(value, str) else str(sp.N(value, 50)))
        except (ValueError, TypeError):
            raise bad from None
        if not mpmath.isfinite(number):
            raise bad
        return number


def _tilts(records, motion: str) -> str:
    return ", ".join(f"--theta0 {r.theta0_exact or mpmath.nstr(mpmath.mpf(r.theta0), 6)} ({r.rate})"
                     for r in records if r.motion == motion and r.theta0 != "-")


def threshold_text(rec: dict) -> str:
    """The text of a body's threshold (the models' lines, every rate in s^-1, and the steady tilt and the side)."""
    value = rec["threshold"]["value"]
    lines = [f"{rec['model']} {rec['motion']}: {rec['threshold']['name']} = {value + ' s^-1' if value else 'none'}"
             f"{'  (' + rec['closed_form'] + ')' if rec['closed_form'] else ''}",
             f"  theta0 = {rec['theta0']} rad ({rec['branch']}); stable {_side(rec['stable'], value)}",
             f"  {rec['method']}",
             f"next: python -m verify trajectory {rec['model']} --state theta=... --state phidot=... --state psidot=... "
             "(a run near the motion; rates in s^-1)"]
    return "\n".join(lines)


def _side(stable: str, value) -> str:
    return f"{stable} the threshold" if value else f"at {stable}"


def body_spindown_record(model, theta: str, family: str, params: dict) -> dict:
    """The record of ``spindown`` for a body (:func:`verify.studies.spindown.body_spindown`)."""
    from ..studies.spindown import body_spindown, to_record  # lazy: only for a body, not 'spindown disk'

    check_params(model, params, "spin-down study")
    try:
        return to_record(body_spindown(model, theta, family, params))
    except ValueError as err:
        raise UsageError(str(err)) from None
