"""The study: predict, run and fit each law (what the report runs)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from models.dissipative import LAW_NAMES, law as get_law

from .family import FamilyLaw, family_law
from .fit import ExponentFit, fit_exponents
from .prediction import Prediction, predict
from .protocol import STUDY_C, THETA0, THETA_STOP
from .work_run import WorkRun, integrate_with_work


@dataclass(frozen=True)
class LawStudy:
    """One law: its closed-form family law, the predictions, the run and the fit."""

    law: str
    family: FamilyLaw
    prediction: Prediction
    run: WorkRun
    fit: ExponentFit


def sample_times(pred: Prediction) -> np.ndarray:
    """The transported drift's level times, then a tail past its t0 (should the run be slower)."""
    t = np.asarray(pred.t_levels, float)
    t = t[np.concatenate([[True], np.diff(t) > 0])]
    tail = pred.t0_transported * (1 + np.geomspace(1e-6, 0.5, 40))
    return np.concatenate([t, tail[tail > t[-1]]])


def study(name: str, c=None, theta_stop: str = THETA_STOP) -> LawStudy:
    """Predict, run and fit one law from THETA0 (default coefficient: :data:`STUDY_C`)."""
    c = STUDY_C[get_law(name).name] if c is None else c
    pred = predict(name, c, THETA0, theta_stop)
    run = integrate_with_work(name, sample_times(pred), c, theta_stop=theta_stop)
    return LawStudy(name, family_law(name), pred, run, fit_exponents(run, pred))


def dissipation_study(laws=LAW_NAMES, progress=None) -> tuple:
    """Both laws (what the report runs; ~30 s on a 2-core machine)."""
    out = []
    for name in laws:
        if progress:
            progress(f"dissipation {name}")
        out.append(study(name))
    return tuple(out)
