"""A validated Taylor integrator: balls that provably contain the exact solution at given times.

Each step from Y (eight balls) over an exact dyadic step h:

1. the Taylor coefficients c_k(Y), k < n, of the flow from Y (:mod:`.taylor`): balls holding
   the exact coefficients of the solution from every point of Y;
2. an a-priori enclosure B of every such solution over [0, h] (:mod:`.enclosure`);
3. the Lagrange remainder: y_i(h) = sum_{k<n} c_ik h^k + c_in(y(xi_i)) h^n for some xi_i in
   (0, h), and y(xi_i) ∈ B, so the coefficient c_n computed from B encloses it;
4. Y <- sum_{k<n} c_k(Y) h^k + c_n(B) h^n, in Arb.

With ``method="direct"`` the step evaluates the Taylor polynomial on the ball vector Y
directly (interval Taylor method), so each step's balls grow with |Dphi| (absolute values of
the step's Jacobian) instead of the flow's own conditioning: the wrapping effect.  With
``method="lohner"`` the set is carried as a point plus a rotated box (:mod:`.lohner`), step 4
applies to the point only and the rest goes through the flow's enclosed Jacobian.  The step
size is predicted from the previous step's remainder bound and halved until the enclosure
validates and the remainder is small enough; times are exact rationals and every output time
is hit exactly.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from dataclasses import field as dc_field
from fractions import Fraction

from flint import arb, ctx

from .enclosure import NoEnclosure
from .lohner import Parallelepiped, lohner_step
from .taylor import validated_step


@dataclass
class Enclosure:
    """The result of :func:`enclose` (scipy ``solve_ivp`` style).

    Attributes
    ----------
    t : list of Fraction
        The output times (exact).
    y : list of list of arb
        ``y[i][j]`` is a ball containing component i of the exact solution at ``t[j]``.
    steps : int
        Taylor steps taken.
    order : int
        Taylor order n (the remainder term is of order n).
    prec : int
        Arb's working precision in bits.
    halvings : int
        Steps whose size was halved because the enclosure did not validate or its
        remainder was too wide.
    """

    t: list
    y: list
    steps: int
    order: int
    prec: int
    halvings: int = 0
    radius: list = dc_field(default_factory=list)

    def proved_digits(self, j: int = -1) -> float:
        """The fewest significant digits the balls at ``t[j]`` prove, over the nonzero components."""
        out = math.inf
        for row in self.y:
            b = row[j]
            mid, rad = abs(float(b.mid())), float(b.rad())
            if mid == 0:
                continue
            out = min(out, math.inf if rad == 0 else math.log10(mid / rad))
        return out


def enclose(field, start: list, times: list, *, order: int = 24, prec: int = 320,
            remainder_bits: int | None = None, method: str = "direct", jacobian_order: int = 12,
            jacobian_prec: int = 64) -> Enclosure:
    """Enclose the solution of dy/dt = field(y), y(0) = start, at every time of ``times``.

    Parameters
    ----------
    field : VectorField
        The right-hand side in ball arithmetic.
    start : list
        The exact initial state (eight rationals: strings, Fractions or fmpq).
    times : list
        Increasing exact output times (rationals), the first 0.
    order : int
        Taylor order n.
    prec : int
        Arb's working precision in bits.
    remainder_bits : int, optional
        A step's remainder is kept below 2^-remainder_bits relative to the state's size
        (default ``prec``); the step is halved until it is.
    method : {"direct", "lohner"}
        ``"direct"``: the Taylor polynomial evaluated on the balls (no wrapping control);
        ``"lohner"``: the set carried as a point plus a rotated box (:mod:`.lohner`).
    jacobian_order, jacobian_prec : int
        For ``"lohner"``: Taylor order and working precision of the flow's Jacobian
        (:mod:`.variational`).
    """
    from .equations import exact

    if method not in ("direct", "lohner"):
        raise ValueError(f"unknown method {method!r}")
    remainder_bits = prec if remainder_bits is None else remainder_bits
    times = [Fraction(str(t)) for t in times]
    if times[0] != 0 or any(b <= a for a, b in zip(times, times[1:])):
        raise ValueError("times must start at 0 and increase")
    saved = ctx.prec, ctx.cap
    ctx.prec, ctx.cap = prec, order + 2  # cap: Arb's series length limit (python-flint's default is 10)
    try:
        y = [arb(exact(v)) for v in start]
        state = Parallelepiped.point(y) if method == "lohner" else y
        out = [[b] for b in y]
        steps = halvings = 0
        now = Fraction(0)
        h_guess = None
        for previous, target in zip(times, times[1:]):
            interval = target - previous
            h = _dyadic_below(interval, h_guess if h_guess is not None else interval)
            while now < target:
                while True:
                    try:
                        allowed = _remainder_target(y, remainder_bits, relax=method == "direct")
                        if method == "lohner":
                            state, bound = lohner_step(field, state, h, order, allowed, jacobian_order=jacobian_order,
                                                       jacobian_prec=jacobian_prec)
                            y = state.hull()
                        else:
                            y, bound = validated_step(field, y, h, order, allowed)
                            state = y
                        break
                    except NoEnclosure:
                        h /= 2
                        halvings += 1
                        if h < interval / 2 ** 40:
                            raise RuntimeError(f"no step validated at t = {float(now)}") from None
                now, steps = now + h, steps + 1
                # next step: where the remainder would reach the target, from this step's bound (order n)
                grow = (allowed / max(bound, 1e-300)) ** (1.0 / order)
                h_next = float(h) * min(2.0, max(0.5, 0.9 * grow))
                # the next step: interval / 2^j, doubled only where the rest of the interval stays a multiple
                h_guess = h_next
                while 2 * h <= h_next and ((target - now) / (2 * h)).denominator == 1:
                    h *= 2
                while h > h_next and h > interval / 2 ** 40 and (h / 2) > 0:
                    h /= 2
            for row, b in zip(out, y):
                row.append(b)
        return Enclosure(t=times, y=out, steps=steps, order=order, prec=prec, halvings=halvings)
    finally:
        ctx.prec, ctx.cap = saved


def _remainder_target(y: list, remainder_bits: int, relax: bool) -> float:
    """The largest remainder worth a step: 2^-remainder_bits of the state's size; with ``relax``, no
    point in one far below the balls' own radius (the direct method's wrapping has already set it).
    Not relaxed for Lohner's method: there a remainder of a fixed fraction of the width would make
    the width grow geometrically, step after step."""
    scale = max(1.0, max(abs(float(b.mid())) for b in y))
    floor = scale * 2.0 ** -remainder_bits
    return max(floor, max(float(b.rad()) for b in y) / 16) if relax else floor


def _dyadic_below(gap: Fraction, guess) -> Fraction:
    """The largest gap / 2^j (j >= 0) not above ``guess``: steps that land exactly on the output time."""
    h = gap
    while h > guess:
        h /= 2
    return h
