"""The onset of slip from rolling where mu_req reaches mu exactly: the formal power series there.

At the ``slips`` event of a rolling phase the slip starts from s = 0 at the rate lambda = 0: the
slip's acceleration du/dt vanishes (the friction the rolling needs is mu N exactly, in the
direction alpha0 of -F_req), s grows like sigma t^2 / 2 (t from the event), and the direction's
equation s d(alpha)/dt = B(alpha, x) (``models.coulomb``'s ``slip_rate_across``; B ~ B_alpha
(alpha - alpha_slow)) has an irregular singular point: deviations from the slow solution decay
like exp(-A_s / t), A_s = 2 |B_alpha| / sigma.  An explicit Taylor method started at a small t
pays about A_s / t steps for that stiffness.

Here the slow solution is built as a formal power series in t, order by order (paper Eqs. 5-7
through :mod:`models.coulomb`'s sliding rows, evaluated on ``flint.arb_series`` at the run's
precision plus guard bits, by :class:`verify.proof.equations.BallExpressions`):

    (k+1) x_{k+1} = [f(x, s, alpha)]_k,    (k+1) s_{k+1} = [A(alpha, x)]_k,
    [s d(alpha)/dt]_k = [B(alpha, x)]_k    (linear in alpha_k, coefficient B_alpha - k s_1),
    (k+1) W_{k+1} = [mu g N s]_k.

The series is expected to be Gevrey-1 (divergent, its terms ~ k! (t / A_s)^k); it is summed to
the first order whose terms are below eps / 16 of each component's largest, at a time t1 where
there is one (:func:`series_start`), and the sliding phase is integrated by heyoka from there.
Measured on the perturbed steady circle of ``tests/test_coulomb.py`` (A_s = 1.995 s, sigma = 6481
cm/s^2, B_alpha = -6465 s^-1): up to order 80 the terms fall geometrically, by about the ratio of t
to 0.028 s per order (the eight's own radius of convergence; the factorial growth does not show
before order 80 at these t), so t1 is the step cap itself (6.9e-3 s, A_s / t1 = 288): double sums
27 of 34 orders, quad 54 of 64, in 0.3 s and 1.2 s.  The coefficients' midpoints lose about two
bits per order to cancellation (117 against 217 working bits: 1e-20 relative at order 30, 3e-10 at
order 40), hence :data:`GUARD_BITS` plus two bits per order.
"""
from __future__ import annotations

import mpmath
from flint import arb, arb_series, ctx, fmpq

from models import coulomb
from models.symbols import STATE

from ..proof.equations import BallExpressions

_SLIP, _DIRECTION, _WORK = 8, 9, 10
#: Guard bits of the series arithmetic over the run's precision.
GUARD_BITS = 64


class _SlidingRates(BallExpressions):
    """The eight rates, A = e . du/dt, B = e_perp . du/dt and dW/dt = mu g N s on arb_series.

    Not d(alpha)/dt = B / s: that quotient is what the series resolves."""

    def __init__(self, name: str, par_values: dict):
        _, sliding, parameters = coulomb.body(name)
        exprs = list(sliding.rhs[:8]) + [sliding.slip_rate_along, sliding.slip_rate_across, sliding.rhs[_WORK]]
        super().__init__(STATE + (coulomb.slip_speed, coulomb.slip_direction), exprs,
                         {p.symbol: par_values[p.name] for p in parameters})


def to_arb(prec, value) -> arb:
    """The exact value of a number at ``prec`` as an arb."""
    with mpmath.workprec(prec.bits + 64):
        m = prec.to_mpf(value)
    sign, man, exp, _ = m._mpf_  # value = (-1)^sign man 2^exp
    man, exp = (-1) ** sign * int(man), int(exp)
    return arb(fmpq(man * 2 ** exp) if exp >= 0 else fmpq(man, 2 ** -exp))


def from_arb(prec, value: arb):
    """The midpoint of ``value`` rounded once to ``prec``."""
    return prec.number(value.mid().str(prec.digits + 12, radius=False))


class OnsetSeries:
    """The formal power series of the slow solution from the onset state ``y8`` (t from the onset).

    Parameters
    ----------
    name : {"disk+coulomb", "ring+coulomb"}
    prec : Precision
        The run's precision (the state's numbers are read exactly from it).
    y8 : sequence
        The eight at the onset.
    alpha0 : number
        A first guess of the slip direction (the direction of -F_req); :meth:`refine_direction` makes it
        the root of B(alpha, x0).
    par_values : dict
        Parameter name -> arb (the rolling model's, then ``mu``).
    bits : int
        Working precision of the series arithmetic.

    Attributes
    ----------
    x : list of 8 lists of arb
        The eight's coefficients, x[i][k] of t^k.
    s, alpha, w : lists of arb
        The slip speed's, the direction's and the work's (W - W(onset)) coefficients.
    gradient : list of arb
        d/d(alpha) of the eight rates, A, B and dW/dt at the onset (:meth:`refine_direction`).
    """

    def __init__(self, name, prec, y8, alpha0, par_values: dict, bits: int):
        self.prec, self.bits = prec, bits
        self.rates = _SlidingRates(name, par_values)
        self.x = [[to_arb(prec, v)] for v in y8]
        self.s = [arb(0)]
        self.w = [arb(0)]
        self.alpha = [arb(alpha0) if isinstance(alpha0, arb) else to_arb(prec, alpha0)]
        self.order = 0

    def _series(self, coeffs, n):
        c = list(coeffs[:n]) + [arb(0)] * (n - len(coeffs))
        return arb_series(c, prec=self.bits)

    def evaluate(self, n, alpha_last=None):
        """The first ``n`` coefficients of the eleven rates on the series so far (``alpha_last``: alpha's next)."""
        alpha = list(self.alpha)
        if alpha_last is not None:
            alpha = alpha + [alpha_last]
        y = [self._series(c, n) for c in self.x] + [self._series(self.s, n), self._series(alpha, n)]
        return [_coeffs(r, n) for r in self.rates(y)]

    def refine_direction(self, iterations=8):
        """alpha0: the root of B(alpha, x0) by Newton's method from the given one; returns (A, B, B_alpha) there."""
        for _ in range(iterations):
            y = [arb_series([c[0]], prec=self.bits) for c in self.x] + [
                arb_series([0], prec=self.bits), arb_series([self.alpha[0], 1], prec=self.bits)]
            r = [_coeffs(v, 2) for v in self.rates(y)]
            b, b_alpha = r[9]
            self.alpha[0] = self.alpha[0] - b / b_alpha
        self.gradient = [v[1] for v in r]  # d/d(alpha) of every rate at t = 0
        return r[8][0], r[9][0], r[9][1]

    def extend(self, order: int):
        """Coefficients up to t^order of x, s and W, and up to t^(order-1) of alpha."""
        old = ctx.cap
        ctx.cap = order + 2
        try:
            while self.order < order:
                k = self.order
                n = k + 1
                if k >= 1:
                    # alpha_k enters order k of every rate linearly, through the rate's alpha-gradient at the
                    # onset: one evaluation with alpha_k = 0, then alpha_k from B's equation, then the rates
                    r0 = self.evaluate(n, arb(0))
                    # [s alpha']_k with alpha_k = 0 (alpha_k enters it as k s_1 alpha_k)
                    sa = sum((self.s[i] * (k - i + 1) * self.alpha[k - i + 1]
                              for i in range(1, k + 1) if k - i + 1 < k), arb(0))
                    coeff = self.gradient[9] - k * self.s[1]
                    a_k = (sa - r0[9][k]) / coeff
                    self.alpha.append(a_k)
                    rates = [r0[j][k] + self.gradient[j] * a_k for j in range(11)]
                else:
                    r0 = self.evaluate(n)
                    rates = [r0[j][0] for j in range(11)]
                for i in range(8):
                    self.x[i].append(rates[i] / (k + 1))
                self.s.append(rates[8] / (k + 1))
                self.w.append(rates[10] / (k + 1))
                self.order += 1
        finally:
            ctx.cap = old


def _coeffs(v, n):
    """The first ``n`` coefficients of an arb_series (or of a constant)."""
    if isinstance(v, arb_series):
        c = v.coeffs()[:n]
        return c + [arb(0)] * (n - len(c))
    return [v] + [arb(0)] * (n - 1)


class SeriesDoesNotSettle(ArithmeticError):
    """The onset's series does not reach eps of the state at any start time tried."""


def series_start(name: str, prec, y8, alpha0, work0, par_vector, cap, orders: int | None = None):
    """(t1, state at t1, series): the sliding state a time t1 after a ``slips`` onset at ``y8``.

    The series (:class:`OnsetSeries`) is computed to ``orders`` terms (default bits/2 + 8) and summed
    at the largest t1 = cap 2^-j (j = 0 .. 12) at which every component's term of some order J is below
    2^-4 eps of its largest term and the terms before J fall (the optimal truncation of a divergent
    series, or the tail of a convergent one).  ``alpha0`` is refined to the root of B(alpha, x0).
    """
    _, _, parameters = coulomb.body(name)
    bits = prec.bits
    orders = orders or bits // 2 + 8
    work_bits = bits + GUARD_BITS + 2 * orders  # measured: the coefficients lose about a bit per order
    old = ctx.prec
    ctx.prec = work_bits
    try:
        par_values = {p.name: to_arb(prec, v) for p, v in zip(parameters, par_vector)}
        series = OnsetSeries(name, prec, y8, alpha0, par_values, work_bits)
        _, _, b_alpha = series.refine_direction()
        if not b_alpha < 0:
            raise SeriesDoesNotSettle(f"the direction's slope B_alpha = {b_alpha} is not restoring")
        series.extend(orders)
        if not series.s[2] > 0:
            raise SeriesDoesNotSettle(f"the slip does not grow: sigma = {2 * series.s[2]}")
        components = series.x + [series.s, series.alpha, series.w]
        limit = prec.eps / 16
        for j in range(13):
            t1 = to_arb(prec, cap) * arb(2) ** -j
            truncation = _truncation(components, t1, limit, len(series.alpha) - 1)
            if truncation is not None:
                break
        else:
            raise SeriesDoesNotSettle(f"no start time down to 2^-12 of the step cap {cap} reaches eps in "
                                      f"{orders} orders")
        t1 = from_arb(prec, t1)
        return t1, series_state(series, prec, t1, truncation, work0), series, truncation
    finally:
        ctx.prec = old


def series_state(series: OnsetSeries, prec, tau, truncation: int, work0) -> list:
    """The eleven sliding components a time ``tau`` (a number of ``prec``, 0 < tau <= t1) after the onset:
    the series summed to ``truncation`` (at tau <= t1 its terms are smaller than at t1, where they reached
    eps), the work from ``work0``."""
    old = ctx.prec
    ctx.prec = series.bits
    try:
        t = to_arb(prec, tau)
        components = series.x + [series.s, series.alpha, series.w]
        values = [sum((c[k] * t ** k for k in range(min(truncation, len(c) - 1) + 1)), arb(0)) for c in components]
        return [from_arb(prec, v) for v in values[:10]] + [from_arb(prec, to_arb(prec, work0) + values[10])]
    finally:
        ctx.prec = old


def _truncation(components, t1, limit, last):
    """The order J at which to stop the series at t1, or None: the first J whose terms are below ``limit``
    of each component's largest term, with the terms falling up to there."""
    terms = [[float((abs(c[k]) * t1 ** k).mid()) for k in range(last + 1)] for c in components]
    for J in range(3, last + 1):  # two terms in a row, so that a coefficient that happens to be small is not taken
        # against the largest term *up to J*: the sum's own scale.  Not the largest of all orders computed:
        # where t1 is beyond the series' reach its later terms grow without bound, and against them any
        # early term looks small (measured: J = 3 taken at t1 = 0.0185 s, a start 153 off in E + W)
        if all(max(row[J - 1], row[J]) <= limit * max(row[: J + 1]) or max(row[: J + 1]) == 0 for row in terms):
            return J
    return None
