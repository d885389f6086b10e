"""The a-priori enclosure of a step: a box that holds every solution over the whole step.

Picard-Lindelöf on a box: if B is a box of balls with Y0 + [0, h] f(B) ⊆ B (in every
component), the solution from any point of Y0 exists on [0, h] and stays in B there
(the Picard operator maps the continuous functions with values in B into themselves; f is
analytic on B, which Arb confirms by returning finite balls).  B is found by the usual
iteration from Y0 + [0, h] f(Y0), widened a little each pass.
"""
from __future__ import annotations

from flint import arb


class NoEnclosure(Exception):
    """No box was validated for this step size (the caller halves the step)."""


def a_priori_box(field, start: list, h, passes: int = 12) -> list:
    """A box B ⊇ {y(t) : y(0) ∈ start, t ∈ [0, h]} (eight arb), or :class:`NoEnclosure`.

    ``h`` is an exact (dyadic) arb; [0, h] is the ball h/2 ± h/2.
    """
    half = h / 2
    span = half + arb(0, half.mid() + half.rad())  # ⊇ [0, h]
    rates = field(start)
    box = [y + span * r for y, r in zip(start, rates)]
    for _ in range(passes):
        box = [_widen(b, y) for b, y in zip(box, start)]
        try:
            rates = field(box)
        except (ZeroDivisionError, ValueError):
            raise NoEnclosure("the right-hand side is undefined on the candidate box") from None
        image = [y + span * r for y, r in zip(start, rates)]
        if not all(r.is_finite() for r in rates):
            raise NoEnclosure("the right-hand side is unbounded on the candidate box")
        if all(_inside(i, b) for i, b in zip(image, box)):
            return image  # image ⊆ B and the operator maps B into image: image holds the solutions too
        box = [b.union(i) for b, i in zip(box, image)]
    raise NoEnclosure(f"no box validated in {passes} passes")


def _widen(b, y):
    """b with its radius grown by a tenth, by y's radius and by a relative 2^-200 (any widening is valid)."""
    grow = b.rad() / 10 + y.rad() + abs(b.mid()) * arb(2) ** -200 + arb(2) ** -1000
    return b + arb(0, grow.mid() + grow.rad())


def _inside(inner, outer) -> bool:
    """inner ⊆ outer (Arb's containment of balls: every point of inner lies in outer)."""
    return outer.contains(inner)
