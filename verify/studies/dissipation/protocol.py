"""The dissipation study's protocol: its start, its stop, its coefficients and its fit window."""
from __future__ import annotations

#: Start of every run: the exact steady centre-of-mass-at-rest state at this tilt.
THETA0 = "0.1"
#: Terminal event of every run.
THETA_STOP = "1e-4"
#: The study's coefficients (s^-1): the smallest the ~60 s budget of ``make report`` allows.
#: Moffatt 1e-8: 4.7e5 turns of phi to the singularity, 2.5e6 Taylor steps (~13 s), breakdown
#: at theta = 3.5e-4; contact-rate 2e-7: 3.9e5 turns, 1.9e6 steps (~9 s), no breakdown above
#: theta_stop = 1e-4.  Both are far below physical values (Moffatt's default, air under a
#: 5-g, 1-cm coin, is 5.7e-5); the exponents do not depend on c, only the window does.
STUDY_C = {"moffatt": "1e-8", "contact-rate": "2e-7"}
#: The fit window ends where the predicted adiabatic parameter a(theta) reaches this.
A_MAX = 1e-3
#: ... and starts here: above it the drift's local slopes stray by more than ~3e-3 from the
#: leading powers (O(theta^2) terms of the family law, O(theta^1/2 .. theta^3/2) ones of omega3).
FIT_TOP = 0.05
#: Sample levels per decade of theta (Sampling, in the package docstring).
LEVELS_PER_DECADE = 40
