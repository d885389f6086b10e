"""Validated enclosures of the rolling models' solutions, in Arb's ball arithmetic (python-flint).

* :mod:`.equations` -- the model's right-hand side (the same sympy expressions heyoka compiles)
  on arb balls and arb_series, parameters exact;
* :mod:`.taylor` -- Taylor coefficients of the flow by Picard iteration on truncated series;
* :mod:`.enclosure` -- the a-priori enclosure of a step (Picard-Lindelöf on a box);
* :mod:`.integrator` -- the steps, the Lagrange remainder bounded on the enclosure, exact output times;
* :mod:`.case` -- a reference case read exactly (start, grid, parameters as rationals) and its
  stored values checked against the proved balls.

What is proved: each ball contains the exact solution of the stated equations from the stated
start at its time.  What is not yet done: a mean-value form or a QR (Lohner) parallelepiped
against wrapping (the balls are propagated directly), enclosures of the cases beyond
``disk-standard-1``, and a proved radius in the reference files.
"""
from .case import enclose_case, excess_over_stored
from .equations import VectorField
from .integrator import Enclosure, enclose

__all__ = ["Enclosure", "VectorField", "enclose", "enclose_case", "excess_over_stored"]
