"""The a-priori enclosure of a step: a tube that holds every solution over the whole step.

High-order enclosure (Corliss & Rihm 1996; Nedialkov, Jackson & Corliss 1999, sec. 5): with
P(t) = sum_{k<n} c_k(Y) t^k the Taylor polynomial from the starting balls Y and T = [0, h],
if a box B satisfies

    P(T) + c_n(B) T^n ⊆ interior(B)                                        (*)

then every solution from Y stays in B on [0, h].  Proof: let t* be the first time a solution
y leaves B (t* <= h).  On [0, t*] it lies in B, so by Taylor's theorem with Lagrange's remainder
in each component, y(t*) = P(t*) + c_n(y(xi)) t*^n with y(xi) ∈ B: y(t*) lies in the left of
(*), in B's interior, so it has not left B at t*, a contradiction (f is analytic on B, which
Arb confirms by finite balls, so y cannot blow up inside B either).  The same argument shows
the solutions lie in the left side of (*) itself, which is returned: a tube that follows the
trajectory, so the remainder's coefficient on it is close to its value on the trajectory, not
on a box as wide as first-order Picard-Lindelöf's (|f| h wide about the start).

Only widths depend on the working precision (every Arb operation rounds outward), so the tube
is computed at a low ``prec``: the remainder it bounds is already far below the state's own
rounding, and a 64-bit bound of it is as valid as a 256-bit one.
"""
from __future__ import annotations

from flint import arb, ctx


class NoEnclosure(Exception):
    """No tube was validated for this step size (the caller shortens the step)."""


def unit_interval() -> arb:
    """A ball containing [0, 1] (1/2 ± 1/2, the radius rounded up by Arb: a hair wider, which is harmless)."""
    return arb(0.5, 0.5)


def polynomial_range(coeffs: list, span: arb) -> arb:
    """A ball containing sum_k coeffs[k] t^k for every t in ``span`` (Horner, by inclusion)."""
    acc = coeffs[-1]
    for c in reversed(coeffs[:-1]):
        acc = acc * span + c
    return acc


def taylor_tube(expand, coeffs: list, h: arb, *, prec: int = 64, tries: int = 6):
    """A validated tube holding every solution from the start over [0, h], and c_n over it.

    Returns ``(tube, top)``: one ball per component, and balls containing c_n(y) for every y of
    a box B ⊇ tube (the B of (*)), so c_n(y(xi)) ∈ top for every xi in [0, h]: the Lagrange
    remainder's coefficient.

    Parameters
    ----------
    expand : callable
        ``expand(box)`` -> the Taylor coefficients c_0..c_n of the solutions from every point of
        ``box`` (a list per component); only c_n is used.
    coeffs : list of list of arb
        c_0..c_n(Y) from the start Y, per component (c_n sizes the first guess).
    h : arb
        The step (a ball; its upper bound is used).
    """
    saved = ctx.prec
    ctx.prec = prec
    try:
        n = len(coeffs[0]) - 1
        span = unit_interval() * arb(h.upper())
        power = arb(h.upper()) ** n * unit_interval()
        polys = [polynomial_range(c[:n], span) for c in coeffs]
        # Arb keeps radii to 30 bits: a slack below 2^-24 of P(T)'s radius would be lost in rounding
        slack = [abs(c[n]).upper() * power.upper() * 2 + arb(p.rad()) * arb(2) ** -24
                 + abs(p).upper() * arb(2) ** -(prec - 4) + arb(2) ** -1070 for c, p in zip(coeffs, polys)]
        for _ in range(tries):
            box = [p + _ball(s) for p, s in zip(polys, slack)]
            try:
                top = [row[n] for row in expand(box)]
            except (ZeroDivisionError, ValueError):
                raise NoEnclosure("the right-hand side is undefined on the candidate tube") from None
            if not all(t.is_finite() for t in top):
                raise NoEnclosure("the right-hand side is unbounded on the candidate tube")
            image = [p + t * power for p, t in zip(polys, top)]
            if all(b.contains_interior(i) for b, i in zip(box, image)):
                return image, top
            slack = [max(s * 2, abs(t * power).upper() * 4) for s, t in zip(slack, top)]
        raise NoEnclosure(f"no tube validated in {tries} tries")
    finally:
        ctx.prec = saved


def _ball(radius: arb) -> arb:
    """0 ± radius (radius an upper bound, taken as a midpoint of an exact ball)."""
    return arb(0, radius.upper())

