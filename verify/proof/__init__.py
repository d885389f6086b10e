"""Validated enclosures of the rolling models' solutions, in Arb's ball arithmetic (python-flint).

* :mod:`.equations` -- the model's right-hand side (the same sympy expressions heyoka compiles)
  on arb balls and arb_series, parameters exact, read once into a straight-line program;
* :mod:`.taylor` -- Taylor coefficients of the flow by Picard iteration on truncated series, and
  one validated step (polynomial plus Lagrange remainder);
* :mod:`.enclosure` -- the a-priori enclosure of a step: a high-order tube (Corliss-Rihm);
* :mod:`.variational` -- the flow's Jacobian enclosed over a box (variational equations, forward mode);
* :mod:`.lohner` -- the mean-value form with deferred wrapping: the set as a point plus a sum of
  parallelepipeds with point matrices;
* :mod:`.integrator` -- the steps (``method="lohner"`` or ``"direct"``), step-size control, exact
  output times;
* :mod:`.case` -- a reference case read exactly (start, grid, parameters as rationals).

What is proved: each ball contains the exact solution of the stated equations from the stated
start at its time (the equations as derived and compiled for heyoka; that they are the paper's
physics is the claims' business, not the proof's).  The proofs of the reference set are written
by :mod:`verify.reference.proved`.
"""
from .case import enclose_case
from .equations import VectorField
from .integrator import Enclosure, enclose

__all__ = ["Enclosure", "VectorField", "enclose", "enclose_case"]
