"""A run's question, resolved and validated once: model, parameters, start, precision, tolerance, events.

:func:`problem` is where input enters the engine: it reads every value at the run's precision,
checks the start (:func:`verify.engine.validation.validate`) and the settings, and returns a
:class:`Problem` that the propagators (:mod:`.single`) take as it is.  Parameters are kept by
name and laid out for heyoka's ``par[i]`` by :meth:`CompiledModel.parameter_vector`, never by
the order of a mapping.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Optional, Sequence

import numpy as np

from models import get_model
from models.base import Model

from . import validation
from .compile import CompiledModel, compile_model, compile_with_friction
from ..precision import Precision, parse_precision


@dataclass(frozen=True)
class Problem:
    """One start of one model at one precision, checked.

    Attributes
    ----------
    model : Model
    precision : Precision
    params : dict
        Every parameter of the model by name, at ``precision`` (defaults filled in).
    y0 : ndarray
        The eight-component start at ``precision`` (STATE_NAMES order).
    tol : number
        The Taylor tolerance at ``precision``; 0 is the precision's epsilon (heyoka's reading).
    events : bool
        Whether the model's terminal events (the domain's ends, loss of contact) stop the run.
    high_accuracy : bool
        heyoka's high-accuracy mode.
    friction : number or None
        A friction coefficient at ``precision``: the run also stops at the terminal event ``slips``,
        where the friction the rolling motion needs reaches it
        (:func:`verify.engine.compile.slip_event_function`).  None: unlimited friction.
    """

    model: Model
    precision: Precision
    params: dict
    y0: np.ndarray
    tol: object
    events: bool = True
    high_accuracy: bool = False
    friction: object = None

    @cached_property  # once per Problem: the lookup hashes the whole Model (~5 us a time)
    def compiled(self) -> CompiledModel:
        if self.friction is not None:
            return compile_with_friction(self.model, self.precision)
        return compile_model(self.model, self.precision)

    @property
    def par_vector(self) -> np.ndarray:
        """The values of the system's ``par[i]``, by name (then the friction coefficient, if any)."""
        if self.friction is None:
            return self.compiled.parameter_vector(self.params)
        values = self.compiled.parameter_vector(self.params, every=True)
        return np.append(values, self.precision.array([self.friction]))

    @property
    def max_step(self):
        return max_step(self.y0, self.params, self.precision)


def resolve_model(model, equations: str = "derived") -> Model:
    """A Model from a name (``python -m verify models``) or a Model (``equations`` then ignored)."""
    if isinstance(model, str):
        return get_model(model, equations)
    if not isinstance(model, Model):
        raise ValueError(f"model={model!r}: allowed: a model name (python -m verify models) or a models.Model")
    return model


def problem(model, state=None, params=None, *, precision="double", equations: str = "derived", tol=None,
            events: bool = True, high_accuracy: bool = False, friction=None) -> Problem:
    """Resolve and validate a run's start and settings once (arguments as for :func:`.single.solve`).

    Raises ``ValueError`` (an :class:`verify.engine.validation.InvalidStart` for the start) naming
    the first bad value and what is allowed.
    """
    prec = parse_precision(precision)
    model = resolve_model(model, equations)
    tol_value = validation.tolerance(tol, prec)
    events = validation.flag("events", events)
    high_accuracy = validation.flag("high_accuracy", high_accuracy)
    friction = validation.friction(model, friction, events, prec)
    y0, pars = validation.validate(model, state, params, prec, friction=friction)
    return Problem(model, prec, pars, y0, tol_value, events, high_accuracy, friction)


def max_step(y0, pars: dict, prec: Precision):
    """The largest step: one radian of the fastest initial rate (or of sqrt(g)).

    heyoka's step-size rule assumes that Taylor coefficients decay geometrically.  On
    an exactly steady motion (the Eq. 45 spin-down, a steady precession) every
    coefficient of theta and the rates vanishes, phi and psi are linear in t, and only
    x, y keep round-off-sized coefficients that grow like Omega^n/n! before decaying;
    the rule then takes steps with Omega h of tens or hundreds of radians and sums a
    truncated series far outside its range (seen: x = -1.2e4 instead of 0 after 1 s of
    the Eq. 45 state at theta = 0.1 in quad).  Capping Omega h at 1 keeps the truncated
    terms below 1/p!.  On ordinary motions the cap does not bind (typical Omega h ~ 0.03).
    """
    return prec.number(1) / prec.number(fastest_rate([y0[i] for i in (3, 4, 5)], pars.get("g", 1)))


def fastest_rate(rates: Sequence[float], g: Optional[float] = None) -> float:
    """The fastest of |rates| and sqrt(g) (rad/s): the rate the step cap is one radian of."""
    values = [abs(float(r)) for r in rates]
    if g is not None:
        values.append(math.sqrt(float(g)))
    return max(values)


def step_cap(rates: Sequence[float], g: Optional[float] = None) -> float:
    """The largest step in double: one radian of :func:`fastest_rate` (see
    :func:`max_step` for why heyoka's steps need a cap)."""
    return 1.0 / fastest_rate(rates, g)
