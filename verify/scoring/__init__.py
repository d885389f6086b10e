"""Scoring another simulator against the reference set (``python -m verify score RUN --case NAME``).

* :mod:`verify.contact_geometry` -- the documented forms of a run (Euler angles; rotation matrix or quaternion
  with the centre of mass and the angular velocity), the conversion between them, the contact
  point and the energies, in numpy (the symbolic definitions are :mod:`verify.frames`);
* :mod:`.casefiles` -- reading the reference set's JSON files;
* :mod:`.runs` -- reading a run from CSV or JSON;
* :mod:`.agreement` -- digits of agreement per component, energy drift, constraint drift, a verdict.

Importing this package and scoring a run on the case's grid times needs numpy and mpmath only
(no sympy, no heyoka: docs/scoring.md, "A light install").

>>> from verify import score
>>> s = score("my_run.csv", "disk-standard-1")      # doctest: +SKIP
>>> s.min_digits, s.components["psi"].median_digits, s.energy_rel_drift, s.verdict   # doctest: +SKIP
>>> from verify.scoring import assert_scores
>>> assert_scores("my_run.csv", "disk-standard-1", min_digits=6)   # in a pytest test: fails below 6 digits  # doctest: +SKIP
"""
from ..contact_geometry import BODIES_ON_PLANE, FORMS
from .runs import InvalidRun, read_run
from .agreement import DIGITS_RESOLVED, START_TOLERANCE, ComponentScore, Score, assert_scores, score

__all__ = ["BODIES_ON_PLANE", "DIGITS_RESOLVED", "FORMS", "START_TOLERANCE", "ComponentScore", "InvalidRun", "Score",
           "assert_scores", "read_run", "score"]
