"""Lohner's wrapping control: the set carried as a point plus a rotated box.

The solutions at a step's start are held as {c + A r : r ∈ R}, c a point (eight exact balls of
radius 0), A a point matrix and R a box (eight balls).  One step of exact size h:

1. φ_h(c) ⊆ T(c) + c_n(B_c) h^n: the Taylor polynomial from the single point c and its
   Lagrange remainder on the a-priori enclosure B_c of that one solution (:mod:`.integrator`);
2. the mean-value form: φ_h(x) − φ_h(c) = (∫_0^1 Dφ_h(c + s(x − c)) ds)(x − c) and the
   integral lies in J ⊇ Dφ_h(hull), the flow's Jacobian enclosed over the set's hull
   (:mod:`.variational`); with x − c = A r, the new image lies in φ_h(c) + (J A) R;
3. the new centre c' = mid φ_h(c), e = φ_h(c) − c' (a small box); A' = Q, an orthonormal point
   matrix from Gram–Schmidt on mid(J A) with its columns taken longest-side first (Lohner's
   QR), and R' = (Q^{-1} J A) R + Q^{-1} e with Q^{-1} enclosed by Arb (Q is exact, its
   inverse a ball matrix), so every image point is c' + Q r' with r' ∈ R'.

The box R' grows with the flow's own conditioning instead of with |Dφ| applied to an
axis-aligned box each step (the wrapping effect of the direct method).
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from flint import arb, arb_mat

from .taylor import validated_step
from .variational import flow_jacobian


@dataclass
class Parallelepiped:
    """{centre + basis r : r ∈ box} (centre: eight arb; basis: arb_mat of points; box: 8x1 arb_mat)."""

    centre: list
    basis: arb_mat
    box: arb_mat

    @classmethod
    def point(cls, y: list) -> Parallelepiped:
        n = len(y)
        return cls(list(y), arb_mat(n, n, [arb(1 if i == j else 0) for i in range(n) for j in range(n)]),
                   arb_mat(n, 1, [arb(0)] * n))

    def hull(self) -> list:
        """Eight balls containing the set (the interval product, used only for output and enclosures)."""
        offset = self.basis * self.box
        return [c + offset[i, 0] for i, c in enumerate(self.centre)]


def lohner_step(field, state: Parallelepiped, h: Fraction, order: int, allowed: float, *, jacobian_order: int,
                jacobian_prec: int):
    """One step of exact size h from ``state``: (the new Parallelepiped, the centre's remainder bound).

    Raises :class:`NoEnclosure` when that bound exceeds ``allowed`` (the caller halves the step).
    """
    # the Jacobian first: its enclosure is the cheaper one to fail, and the likelier at a given h
    jacobian = flow_jacobian(field, state.hull(), h, order=jacobian_order, prec=jacobian_prec)
    image_of_centre, bound = validated_step(field, state.centre, h, order, allowed)
    n = len(image_of_centre)
    image_of_basis = jacobian * state.basis
    q = _orthonormal_columns(image_of_basis.mid(), [state.box[i, 0].rad() for i in range(n)])
    q_inverse = q.inv()
    centre = [arb(b.mid()) for b in image_of_centre]
    error = arb_mat(n, 1, [b - c for b, c in zip(image_of_centre, centre)])
    box = (q_inverse * image_of_basis) * state.box + q_inverse * error
    return Parallelepiped(centre, q, box), bound


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
