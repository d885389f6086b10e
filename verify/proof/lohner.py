"""Lohner's wrapping control: the set carried as a point plus a rotated box.

The solutions at a step's start are held as {c + A r : r ∈ R}, c a point (eight exact balls of
radius 0), A a point matrix and R a box (eight balls) that contains 0.  One step of size h:

1. φ_h(c) ⊆ T(c) + c_n(tube) h^n: the Taylor polynomial from the single point c and its
   Lagrange remainder on the validated tube of that one solution (:mod:`.taylor`);
2. the mean-value form: φ_h(x) − φ_h(c) = (∫_0^1 Dφ_h(c + s(x − c)) ds)(x − c), the segment
   lies in the set's hull (a box, convex, holding c and x), and the integral lies in
   J ⊇ Dφ_h(hull), the flow's Jacobian enclosed over the hull (:mod:`.variational`); with
   x − c = A r the image lies in φ_h(c) + (J A) R;
3. the new centre c' = mid φ_h(c), e = φ_h(c) − c' (a small box holding 0); A' = Q, an
   orthonormal point matrix from Gram–Schmidt on mid(J A) with its columns taken longest-side
   first (Lohner's QR), and R' = (Q^{-1} J A) R + Q^{-1} e with Q^{-1} enclosed by Arb (Q is
   exact, its inverse a ball matrix), so every image point is c' + Q r' with r' ∈ R'.

The box R' grows with the flow's own conditioning instead of with |Dφ| applied to an
axis-aligned box each step (the wrapping effect of the direct method).

Wrapping is not gone, only slowed: where the flow stretches along a direction that turns (the
disk's fast phases at low θ), |Q^{-1} J A| R overestimates a little each step, and that excess
never shrinks back when the stretching undoes itself.  So the box is frozen every ``block``
steps: its errors are then carried as P b, P ⊇ J_k ⋯ J_{j+1} Q_j an interval matrix (a
product of the steps' enclosed Jacobians, which is the chain rule's enclosure of the flow's
Jacobian from step j on) and b the frozen box, and a new box starts from 0.  A matrix times a
matrix does not wrap; the product meets the box once, when the hull is formed.  The set is

    {c + Σ_β P_β b_β + Q r : b_β ∈ frozen boxes, r ∈ R},

and the mean-value step applies to each term (the segment from c to any point of the set lies
in the hull, a box).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from flint import arb, arb_mat, ctx

from .taylor import TaylorExpansion
from .variational import FlowJacobian


@dataclass
class Parallelepiped:
    """{centre + Σ frozen P b + basis r : r ∈ box}: centre eight arb points; basis an arb_mat of
    points; box an 8x1 arb_mat; frozen a list of (interval arb_mat P, 8x1 box b)."""

    centre: list
    basis: arb_mat
    box: arb_mat
    frozen: list = field(default_factory=list)
    age: int = 0

    @classmethod
    def point(cls, y: list) -> Parallelepiped:
        n = len(y)
        return cls(list(y), _identity(n), arb_mat(n, 1, [arb(0)] * n))

    def hull(self) -> list:
        """Eight balls containing the set (the interval sum, used only for output and enclosures)."""
        offset = self.basis * self.box
        for p, b in self.frozen:
            offset = offset + p * b
        return [c + offset[i, 0] for i, c in enumerate(self.centre)]


def _identity(n: int) -> arb_mat:
    return arb_mat(n, n, [arb(1 if i == j else 0) for i in range(n) for j in range(n)])


class LohnerExpansion:
    """What one Lohner step needs from its start, computed once for any step size.

    The centre's Taylor coefficients (at the working precision) and the flow Jacobian's over the
    hull (low order and precision); :meth:`advance` then takes a step of size h, and a rejected h
    costs only the tubes.
    """

    def __init__(self, field, state: Parallelepiped, order: int, *, jacobian_order: int, jacobian_prec: int,
                 tube_prec: int, block: int = 16):
        self.state, self.block, self.jacobian_prec = state, block, jacobian_prec
        self.centre = TaylorExpansion(field, state.centre, order, tube_prec=tube_prec)
        self.jacobian = FlowJacobian(field, state.hull(), order=jacobian_order, prec=jacobian_prec)

    def suggested_step(self, allowed: float, inflation: float = 1.0) -> float:
        return self.centre.suggested_step(allowed, inflation)

    def inflation(self, h: float, bound: float) -> float:
        return self.centre.inflation(h, bound)

    def advance(self, h: arb, allowed: float):
        """(the Parallelepiped at h, the centre's remainder bound); :class:`NoEnclosure` as in
        :meth:`.TaylorExpansion.advance`."""
        image_of_centre, bound = self.centre.advance(h, allowed)
        jacobian = self.jacobian.at(h)
        state = self.state
        n = len(image_of_centre)
        image_of_basis = jacobian * state.basis
        q = _orthonormal_columns(image_of_basis.mid(), [state.box[i, 0].rad() for i in range(n)])
        q_inverse = q.inv()
        centre = [arb(b.mid()) for b in image_of_centre]
        error = arb_mat(n, 1, [b - c for b, c in zip(image_of_centre, centre)])
        box = (q_inverse * image_of_basis) * state.box + q_inverse * error
        saved = ctx.prec
        ctx.prec = self.jacobian_prec  # the frozen factors only multiply tiny boxes
        try:
            frozen = [(jacobian * p, b) for p, b in state.frozen]
        finally:
            ctx.prec = saved
        if state.age + 1 < self.block:
            return Parallelepiped(centre, q, box, frozen, state.age + 1), bound
        frozen.append((q, box))
        return Parallelepiped(centre, _identity(n), arb_mat(n, 1, [arb(0)] * n), frozen, 0), bound


def _orthonormal_columns(m: arb_mat, widths: list) -> arb_mat:
    """Gram–Schmidt (modified) on m's columns, the longest side (column norm × box radius) first.

    Computed on midpoints; the result is rounded to an exact point matrix (orthonormal to the
    working precision, which is all Lohner's method needs: its inverse is enclosed rigorously).
    """
    n = m.nrows()
    columns = [[m[i, j].mid() for i in range(n)] for j in range(n)]
    length = [sum(x * x for x in col).sqrt().mid() * arb(w).mid() for col, w in zip(columns, widths)]
    order = sorted(range(n), key=lambda j: -float(length[j]))
    basis = []
    for j in order:
        v = list(columns[j])
        for u in basis:
            dot = sum(a * b for a, b in zip(u, v))
            v = [a - dot * b for a, b in zip(v, u)]
        norm = sum(x * x for x in v).sqrt()
        basis.append([arb((x / norm).mid()) for x in v])
    return arb_mat(n, n, [basis[j][i] for i in range(n) for j in range(n)])
