"""Claims of the thin disk and hoop part of the paper (Eqs. 1-46, Fig. 1, Fig. 6 numbers, footnote 2).

The section's claims, in the paper's order, from three modules by topic:

* :mod:`verify.claims.disk_equations` -- Eqs. 1-24 and Fig. 1: inertia, the vector equations, the frame,
  the rows of motion, the steady circle's torque balance, the tipping disk;
* :mod:`verify.claims.disk_stability` -- Eqs. 25-41 and footnote 2: straight-line rolling and spinning on
  a diameter, linearised, and their thresholds from eigenvalues;
* :mod:`verify.claims.disk_spindown` -- the text after Eq. 41 to Eq. 46 and Fig. 6's numbers: spin-down
  and energy.

Independent routes: the rows derived from the vectors (models/rolling.py, itself checked
against Kane's method in the tests), with m and R kept wherever the paper keeps them;
rotation matrices for the angular velocities; the contact force F = m (a_C + g Z) for the
torques of the steady circle; direct integration for the moments of inertia; linearisation
and eigenvalues by sympy.
"""
from __future__ import annotations

from . import disk_equations, disk_spindown, disk_stability
from .disk_equations import SECTION

__all__ = ["SECTION", "claims"]


def claims() -> list:
    """Every claim of the section, Eqs. 1-46, Fig. 1, Fig. 6's numbers and footnote 2, in the paper's order."""
    return disk_equations.claims() + disk_stability.claims() + disk_spindown.claims()
