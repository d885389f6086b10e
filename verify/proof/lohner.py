"""Lohner's mean-value form with deferred wrapping: the set as a point plus a sum of parallelepipeds.

The solutions at a step's start are held as {c + Σ_β P_β b_β : b_β ∈ B_β}: c a point (eight
exact balls of radius 0), each P_β a point matrix and each B_β a box (8x1 balls).  One step of
size h:

1. φ_h(c) ⊆ T(c) + c_n(tube) h^n: the Taylor polynomial from the single point c and its
   Lagrange remainder on the validated tube of that one solution (:mod:`.taylor`);
2. the mean-value form: φ_h(x) − φ_h(c) = (∫_0^1 Dφ_h(c + s(x − c)) ds)(x − c); the segment
   lies in the set's hull (a box: convex, holding c and x), and the integral lies in
   J ⊇ Dφ_h(hull), the flow's Jacobian enclosed over the hull (:mod:`.variational`).  So the
   image lies in φ_h(c) + Σ_β (J P_β) B_β;
3. each J P_β (an interval matrix) is split into its midpoint P'_β, a point matrix that carries
   B_β on unchanged, and the rest (J P_β − P'_β) B_β, a box of width ~ w(J) |P_β| |B_β|; the new
   centre is c' = mid φ_h(c), and e = φ_h(c) − c' plus the rests is this step's *new error*;
4. the new error joins the youngest parallelepiped: B ← B + P'^{-1} e, P'^{-1} enclosed by Arb;
   every ``block`` steps the youngest is frozen and a new one starts (P = I, B = e).

A point matrix times a box wraps nothing: a frozen box is carried by the product of the steps'
Jacobians' midpoints for good, and the boxes meet the matrices only when the hull is formed.
What wraps is each step's new error, once, into the youngest P' (whose conditioning the freeze
keeps modest).  The widths therefore grow like the flow's own conditioning times the errors
committed, the ideal of a linear error propagation.  The variant that re-orthogonalises the box
every step (Lohner's QR) or carries the products as interval matrices was measured to keep the
excess of every fast phase of the disk's nutation (27 digits lost in the first second against
4 here; docs/reference.md, proofs).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from flint import arb, arb_mat, ctx

from .taylor import TaylorExpansion
from .variational import FlowJacobian


@dataclass
class Parallelepiped:
    """{centre + Σ P b : b ∈ box} over ``blocks`` (pairs of a point arb_mat P and an 8x1 arb_mat box);
    the last block is the youngest, ``age`` its steps."""

    centre: list
    blocks: list = field(default_factory=list)
    age: int = 0

    @classmethod
    def point(cls, y: list) -> Parallelepiped:
        return cls(list(y))

    @classmethod
    def from_balls(cls, y: list) -> Parallelepiped:
        """The set of points of the balls y: centre their midpoints, one box of their radii (a resumed start)."""
        n = len(y)
        if all(b.rad() == 0 for b in y):
            return cls(list(y))
        return cls([arb(b.mid()) for b in y], [(_identity(n), arb_mat(n, 1, [arb(0, b.rad()) for b in y]))])

    def hull(self) -> list:
        """Eight balls containing the set and its centre (the interval sum; the mean-value step needs
        the segment from the centre to each point inside it, so the centre is joined explicitly
        rather than left to every box's containing 0)."""
        n = len(self.centre)
        offset = arb_mat(n, 1, [arb(0)] * n)
        for p, b in self.blocks:
            offset = offset + p * b
        return [(c + offset[i, 0]).union(c) for i, c in enumerate(self.centre)]


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
        n = len(image_of_centre)
        centre = [arb(b.mid()) for b in image_of_centre]
        error = arb_mat(n, 1, [b - c for b, c in zip(image_of_centre, centre)])
        blocks = []
        saved = ctx.prec
        ctx.prec = self.jacobian_prec  # the matrices only multiply tiny boxes: their own precision is enough
        try:
            for p, b in self.state.blocks:
                image = jacobian * p
                carried = image.mid()
                error = error + (image - carried) * b
                blocks.append((carried, b))
            age = self.state.age + 1
            if blocks and age < self.block:
                p, b = blocks[-1]
                try:
                    blocks[-1] = (p, b + p.inv() * error)
                    return Parallelepiped(centre, blocks, age), bound
                except ZeroDivisionError:
                    pass  # the youngest P is numerically singular: freeze it and start another
            blocks.append((_identity(n), error))
            return Parallelepiped(centre, blocks, 1), bound
        finally:
            ctx.prec = saved


