"""Validated enclosures (verify.proof): they contain the stored reference values, a perturbed
problem's do not, and only ball arithmetic enters them.

A short prefix of ``disk-standard-1`` (its first grid interval, 1/32 s) at 128 bits keeps the
tests fast; the full second is measured outside the tests (README, proof section).
"""
from __future__ import annotations

import pytest
from flint import arb, arb_series, ctx

from models import get_model
from models.symbols import STATE_NAMES
from verify.proof.case import enclose_case
from verify.proof.equations import VectorField
from verify.proof.taylor import taylor_coefficients
from verify.reference.proved import balls_record, claims
from verify.reference.store import DIRECTORY, read_case

PREFIX = "0.03125"
SETTINGS = {"t_stop": PREFIX, "order": 20, "prec": 128}
METHODS = ("direct", "lohner")


@pytest.fixture(scope="module")
def record():
    return read_case(DIRECTORY / "disk-standard-1.json")


@pytest.fixture(scope="module", params=METHODS)
def proved(record, request):
    return enclose_case(record, **SETTINGS, method=request.param)


def test_the_enclosure_contains_the_stored_values(record, proved):
    """The stored 256-bit values and the proved balls agree: no stored claim |value - exact| <=
    abs_error is refuted by a ball (:func:`verify.reference.proved.claims`, exact rationals).  The balls
    are narrow enough for that to mean something: at least 30 proved digits at the prefix's end (the
    stored values keep 35+), each method on its own."""
    verdict = claims(record, balls_record(record, proved))
    assert verdict["contradicted"] == 0, verdict["contradictions"]
    assert proved.proved_digits() >= 30, proved.proved_digits()


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("change", [{"start": {"theta": "1.2000000000000000000001"}},
                                    {"params": {"g": "980.00000000000000000001"}}],
                         ids=["start-theta+1e-22", "rhs-g+1e-20"])
def test_a_perturbed_problem_excludes_the_stored_values(record, change, method):
    """Negative controls: a start or a right-hand side changed far below double's resolution gives
    balls that refute some stored claim (a component's ball and value ± abs_error are disjoint)."""
    enclosure = enclose_case(record, **SETTINGS, **change, method=method)
    assert claims(record, balls_record(record, enclosure))["contradicted"] > 0


@pytest.mark.slow
def test_lohner_is_narrower_than_direct_at_an_eighth_of_a_second(record):
    """Measured, not assumed: at t = 1/8 s (128 bits, order 20) the wrapping of the direct method has
    set its width, and the mean-value form's balls are narrower in every component; both still hold
    the stored values."""
    settings = {"t_stop": "0.125", "order": 20, "prec": 128}
    direct = enclose_case(record, **settings)
    lohner = enclose_case(record, **settings, method="lohner")
    for name, d, w in zip(STATE_NAMES, direct.y, lohner.y):
        assert w[-1].rad() < d[-1].rad(), (name, w[-1], d[-1])
    for enc in (direct, lohner):
        assert claims(record, balls_record(record, enc))["contradicted"] == 0


def test_the_flow_jacobian_contains_the_difference_quotient():
    """The enclosed Jacobian of the flow over a box contains the exact Jacobian at the box's centre,
    checked against a central difference quotient of two point enclosures (a ball of its own truncation
    error: delta^2 |d3 phi| / 6 with delta^2 = 8.7e-19 and third derivatives of the flow over 1/1024 s
    below 10, so 1e-16 holds it with room; measured 2e-19), and is narrow (width < 1e-12)."""
    from fractions import Fraction

    from verify.proof.integrator import enclose
    from verify.proof.variational import flow_jacobian

    field = VectorField(get_model("disk"), {"k": "1/4", "g": "980"})
    start = [Fraction(6, 5), 0, 0, 0, 1, 10, 0, 0]
    h = Fraction(1, 1024)
    saved = ctx.prec, ctx.cap
    ctx.prec, ctx.cap = 128, 22
    try:
        jac = flow_jacobian(field, [arb(Fraction(v).numerator) / Fraction(v).denominator for v in start], h)
    finally:
        ctx.prec, ctx.cap = saved
    delta = Fraction(1, 2 ** 30)
    for j in (0, 3, 5):
        plus, minus = list(start), list(start)
        plus[j] += delta
        minus[j] -= delta
        up = enclose(field, plus, [0, h], order=20, prec=128)
        down = enclose(field, minus, [0, h], order=20, prec=128)
        for i in range(8):
            quotient = (up.y[i][-1] - down.y[i][-1]) / (2 * arb(delta.numerator) / delta.denominator)
            assert jac[i, j].rad() < 1e-12
            assert (quotient + arb(0, 1e-16)).overlaps(jac[i, j]), (i, j, quotient, jac[i, j])


def test_every_coefficient_and_ball_is_arb(proved):
    """Ball arithmetic throughout: the Taylor coefficients from a ball start and the output are arb."""
    ctx_saved = ctx.prec, ctx.cap
    ctx.prec, ctx.cap = 128, 12
    try:
        field = VectorField(get_model("disk"), {"k": "1/4", "g": "980"})
        start = [arb("1.2"), arb(0), arb(0), arb(0), arb(1), arb(10), arb(0), arb(0)]
        coeffs = taylor_coefficients(field, start, 10)
        assert all(type(c) is arb for row in coeffs for c in row)
        assert all(type(v) is arb_series for v in field([arb_series([s], prec=3) for s in start]))
    finally:
        ctx.prec, ctx.cap = ctx_saved
    assert all(type(b) is arb for row in proved.y for b in row)
    assert len(proved.y) == len(STATE_NAMES)


def test_a_float_in_the_equations_is_refused():
    """A floating-point constant would enter the balls unbounded: the reader refuses it when it reads the model."""
    from dataclasses import replace

    import sympy as sp

    model = get_model("disk")
    bad = replace(model, velocity_xy=(model.velocity_xy[0] * sp.Float("1.0000001"), model.velocity_xy[1]))
    with pytest.raises(ValueError, match="not read into ball arithmetic"):
        VectorField(bad, {"k": "1/4", "g": "980"})
