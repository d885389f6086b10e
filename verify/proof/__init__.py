"""Validated enclosures of the rolling models' solutions, in Arb's ball arithmetic (python-flint).

* :mod:`.equations` -- the model's right-hand side (the same sympy expressions heyoka compiles)
  on arb balls and arb_series, parameters exact;
* :mod:`.taylor` -- Taylor coefficients of the flow by Picard iteration on truncated series;
* :mod:`.enclosure` -- the a-priori enclosure of a step (Picard-Lindelöf on a box);
* :mod:`.variational` -- the flow's Jacobian enclosed over a box (variational equations, forward mode);
* :mod:`.lohner` -- Lohner's wrapping control: the set as a point plus a rotated box, QR each step;
* :mod:`.integrator` -- the steps (``method="direct"`` or ``"lohner"``), the Lagrange remainder
  bounded on the enclosure, exact output times;
* :mod:`.case` -- a reference case read exactly (start, grid, parameters as rationals) and its
  stored values checked against the proved balls.

What is proved: each ball contains the exact solution of the stated equations from the stated
start at its time.  What is not yet done: enclosures of the cases beyond ``disk-standard-1``
and of its full second (Lohner's method is too slow for it so far: thousands of steps, each
with two Taylor expansions and a Jacobian), and a proved radius in the reference files.
"""
from .case import enclose_case, excess_over_stored
from .equations import VectorField
from .integrator import Enclosure, enclose

__all__ = ["Enclosure", "VectorField", "enclose", "enclose_case", "excess_over_stored"]
