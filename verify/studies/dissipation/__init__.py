"""The dissipative spin-down of the disk towards theta -> 0: laws, runs, fitted exponents.

The disk of :mod:`models.dissipative` loses energy through a couple
``tau = -c sin^-n(theta) omega_perp`` (``moffatt``: n = 3, ``contact-rate``: n = 2).  This study

1. **predicts** with sympy, from the model's own expressions, what the couple does on the
   centre-of-mass-at-rest family (v_C = 0, omega3 = 0: the family on which the paper's Eq. 45,
   phidot^2 = g/(k sin theta), is exact): the family's energy E(theta), the dissipated power,
   hence ``dtheta/dt = -P / (dE/dtheta)``, its leading power ``-A theta^m`` at small theta, the
   exponents ``p = 1/(1 - m)`` of ``theta ~ (t0 - t)^p`` and ``q = p r`` of ``phidot ~ (t0 - t)^q``
   (``phidot ~ theta^r`` on the family), and the time and the number of turns of phi from a
   start theta0 to the singularity (:func:`family_law`, :func:`predict`);
2. refines that prediction: the drift does not stay on the family.  Row 3 of the rolling
   equations, ``(2k+1) d(omega3)/d(theta) = omega2`` (Chaplygin's, see :mod:`models.disk`), holds
   unchanged with the couple (it has no e3 component), so as theta falls omega3 grows from 0
   to ``-(1/(2k+1)) int omega2 dtheta`` (about -0.87 s^-1 from theta0 = 0.1) and the centre of
   mass starts to circle.  The *transported* prediction follows the steady motions with that
   omega3 (heyoka, theta as the independent variable); the exponents are the same (the
   omega3 terms are O(theta^1/2) relative), t0 and the turns move by ~1%;
3. **integrates** the model with heyoka from the exact steady state at theta0 (from
   :func:`verify.studies.spindown.spindown`), the work of the couple
   ``W(t) = int c sin^-n |omega_perp|^2 dt`` carried as a ninth variable, and checks the energy
   balance ``E(t) + W(t) = E(0)`` (:func:`integrate_with_work`);
4. **fits** the exponents without knowing t0: the slope s of log|dtheta/dt| against log theta
   gives ``p = 1/(1 - s)``, the slope of log phidot against log theta times p gives q; then t0
   and the turns to the singularity (:func:`fit_exponents`).

Where the run is trustworthy
----------------------------
The law is a statement about slow drift along steady motions: it holds while the drift rate
|dtheta/dt|/theta is small against the nutation frequency (sqrt(3/5) phidot at small theta
for k = 1/4, from the linearised equations).  Their ratio, the adiabatic parameter
``a(theta) = |dtheta/dt| / (theta phidot)``, grows like theta^-5/2 (Moffatt) and theta^-3/2
(contact-rate) as theta falls, so *every* run leaves the law before theta = 0, whatever c:
measured, the local slopes agree with the transported drift to ~1e-5 while a < 1e-4,
depart by ~1e-4 at a = 1e-3 (growing like a^2) and by ~1% at a = 1e-2; by a ~ 0.05-0.2 the
disk stops going round (phidot drops to 0 within a few nutations, nearly all the energy goes
into W) and then creeps flat, overdamped.  That is the model's physics, not round-off:
double keeps E + W = E(0) to ~600 epsilon of E(0) over 2.5e6 steps down to theta = 1e-4
(0.4-0.5 eps sqrt(N)).  A smaller c moves the breakdown down only slowly (the turns to the
singularity grow like 1/c, the breakdown angle only like c^(2/5) and c^(2/3)), so the runs
use the smallest c the time budget allows (:data:`STUDY_C`) and the fit window ends where
the predicted a(theta) reaches :data:`A_MAX`.  With the study's c the Moffatt run breaks
down at theta = 3.5e-4, above theta_stop; the contact-rate run reaches theta_stop = 1e-4 at
a = 7e-3, still on the law to 1e-3 in the local slopes.

Sampling
--------
The run is sampled where the transported prediction puts the levels
``theta0 * 10^(-j/LEVELS_PER_DECADE)``; between samples dtheta/dt and phidot are the secant
slopes ``dtheta/dt``, ``dphi/dt``, which average over the nutation (its period is ~140 a
times the time between samples).  The start, exactly on the family (thetadot = 0), excites a
nutation of relative size ~a(theta0) < 1e-6, damped by the couple.

Modules: :mod:`.protocol` (the study's numbers), :mod:`.family` (item 1), :mod:`.prediction`
(item 2), :mod:`.work_run` (item 3), :mod:`.fit` (item 4), :mod:`.study` (the four for each law:
:func:`study`, :func:`dissipation_study`), :mod:`.record` (results.json).
"""
from __future__ import annotations

from .family import FamilyLaw, family_law, theta0
from .fit import ExponentFit, fit_exponents, fit_window, secants
from .prediction import Prediction, level_grid, predict
from .protocol import A_MAX, FIT_TOP, LEVELS_PER_DECADE, STUDY_C, THETA0, THETA_STOP
from .record import to_record
from .study import LawStudy, dissipation_study, sample_times, study
from .work_run import WorkRun, integrate_with_work

__all__ = ["A_MAX", "FIT_TOP", "LEVELS_PER_DECADE", "STUDY_C", "THETA0", "THETA_STOP", "ExponentFit", "FamilyLaw",
           "LawStudy", "Prediction", "WorkRun", "dissipation_study", "family_law", "fit_exponents", "fit_window",
           "integrate_with_work", "level_grid", "predict", "sample_times", "secants", "study", "theta0", "to_record"]
