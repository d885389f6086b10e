"""A validated Taylor integrator: balls that provably contain the exact solution at given times.

Each step from Y (eight balls) over a step h (an exact rational; a ball in Arb where it is not dyadic):

1. the Taylor coefficients c_k(Y), k <= n, of the flow from Y (:mod:`.taylor`): balls holding
   the exact coefficients of the solution from every point of Y;
2. a validated tube B of every such solution over [0, h] (:mod:`.enclosure`, high-order);
3. the Lagrange remainder: y_i(h) = sum_{k<n} c_ik h^k + c_in(y(xi_i)) h^n for some xi_i in
   (0, h), and y(xi_i) ∈ B, so the coefficient c_n computed over B encloses it;
4. Y <- sum_{k<n} c_k(Y) h^k + c_n(B) h^n, in Arb.

With ``method="direct"`` the step evaluates the Taylor polynomial on the ball vector Y
directly (interval Taylor method), so each step's balls grow with |Dphi| (absolute values of
the step's Jacobian) instead of the flow's own conditioning: the wrapping effect.  With
``method="lohner"`` the set is carried as a point plus a sum of parallelepipeds (:mod:`.lohner`),
step 4 applies to the point only and the rest goes through the flow's enclosed Jacobian.  The step
size is predicted from the start's own c_n (the remainder it would make) and shortened until
the tube validates and the remainder over it is small enough; times are exact rationals, a
step is a short dyadic rational (exact in Arb) except near an output time, where it is the
rest of the way or half of it (exact rationals that Arb holds as balls, and the step encloses
the solution at every time of that ball: the polynomial is evaluated on it, the tube taken to
its upper end).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from dataclasses import field as dc_field
from fractions import Fraction

from flint import arb, ctx, fmpq

from .enclosure import NoEnclosure
from .equations import exact
from .lohner import LohnerExpansion, Parallelepiped
from .taylor import TaylorExpansion


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
        """The fewest significant digits (log10 |mid|/rad) the balls at ``t[j]`` prove, over the components
        whose ball excludes 0 (a ball holding 0 proves only its radius, no significant digit)."""
        out = math.inf
        for row in self.y:
            b = row[j]
            mid, rad = abs(float(b.mid())), float(b.rad())
            if b.contains(0):
                continue
            out = min(out, math.inf if rad == 0 else math.log10(mid / rad))
        return out


def enclose(field, start: list, times: list, *, order: int = 24, prec: int = 320,
            remainder_bits: int | None = None, method: str = "direct", jacobian_order: int = 16,
            jacobian_prec: int = 64, tube_prec: int = 64, block: int = 16, progress=None) -> Enclosure:
    """Enclose the solution of dy/dt = field(y), y(0) = start, at every time of ``times``.

    Parameters
    ----------
    field : VectorField
        The right-hand side in ball arithmetic.
    start : list
        The initial state: eight exact rationals (strings, Fractions or fmpq), or balls (arb) that
        hold the start (a resumed enclosure's last balls).
    times : list
        Increasing exact output times (rationals), the first 0.
    order : int
        Taylor order n.
    prec : int
        Arb's working precision in bits.
    remainder_bits : int, optional
        A step's remainder is kept below 2^-remainder_bits relative to the state's size
        (default ``prec``); the step is shortened until it is.
    method : {"direct", "lohner"}
        ``"direct"``: the Taylor polynomial evaluated on the balls (no wrapping control);
        ``"lohner"``: the set carried as a point plus a sum of parallelepipeds (:mod:`.lohner`).
    jacobian_order, jacobian_prec : int
        For ``"lohner"``: Taylor order and working precision of the flow's Jacobian
        (:mod:`.variational`).
    tube_prec : int
        Working precision of the tubes (:mod:`.enclosure`).
    block : int
        For ``"lohner"``: steps between freezes of the wrapped box (:mod:`.lohner`).
    progress : callable, optional
        Called as ``progress(t, enclosure_so_far)`` after each output time.
    """
    if method not in ("direct", "lohner"):
        raise ValueError(f"unknown method {method!r}")
    remainder_bits = prec if remainder_bits is None else remainder_bits
    if not 16 <= remainder_bits <= 1000:
        raise ValueError(f"remainder_bits {remainder_bits}: allowed 16 to 1000 (the step control's targets are floats)")
    times = [Fraction(str(t)) for t in times]
    if times[0] != 0 or any(b <= a for a, b in zip(times, times[1:])):
        raise ValueError("times must start at 0 and increase")
    saved = ctx.prec, ctx.cap
    ctx.prec, ctx.cap = prec, max(order, jacobian_order) + 2  # python-flint's series cap defaults to 10
    try:
        y = [v if isinstance(v, arb) else arb(exact(v)) for v in start]
        state = Parallelepiped.from_balls(y) if method == "lohner" else y
        result = Enclosure(t=[Fraction(0)], y=[[b] for b in y], steps=0, order=order, prec=prec)
        now = Fraction(0)
        inflation = 1.0
        for target in times[1:]:
            while now < target:
                allowed = _remainder_target(y, remainder_bits, relax=method == "direct")
                if method == "lohner":
                    expansion = LohnerExpansion(field, state, order, jacobian_order=jacobian_order,
                                                jacobian_prec=jacobian_prec, tube_prec=tube_prec, block=block)
                else:
                    expansion = TaylorExpansion(field, y, order, tube_prec=tube_prec)
                h = _step_towards(target - now, 0.9 * expansion.suggested_step(allowed, inflation))
                while True:
                    try:
                        state, bound = expansion.advance(arb(fmpq(h.numerator, h.denominator)), allowed)
                        inflation = expansion.inflation(float(h), bound)
                        break
                    except NoEnclosure:
                        h = _dyadic_at_most(h / 2)
                        result.halvings += 1
                        if h < (target - now) / 2 ** 40:
                            raise RuntimeError(f"no step validated at t = {float(now)}") from None
                y = state.hull() if method == "lohner" else state
                now, result.steps = now + h, result.steps + 1
            result.t.append(target)
            for row, b in zip(result.y, y):
                row.append(b)
            if progress is not None:
                progress(target, result)
        return result
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


def _step_towards(remaining: Fraction, suggested: float) -> Fraction:
    """The next step: all that remains when the suggestion covers it, half of it when it covers more
    than half (no sliver of a last step), else the suggestion rounded down to a short dyadic."""
    if suggested >= remaining:
        return remaining
    if 2 * suggested >= remaining:
        return remaining / 2
    return _dyadic_at_most(Fraction(suggested))


def _dyadic_at_most(h: Fraction) -> Fraction:
    """The largest m / 2^e <= h with an 8-bit m (an exact, short Arb number)."""
    e = 0
    while h * 2 ** e < 128:
        e += 1
    return Fraction(int(h * 2 ** e), 2 ** e)
