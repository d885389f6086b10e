"""Many runs of one model at once: the batch road's front door, beside :class:`verify.engine.problem.Problem`.

An :class:`Ensemble` holds what every batch run of a model shares, resolved once:

* the model (``get_model`` once per ensemble: :func:`ensemble` keeps one per name and settings);
* its lane system (:func:`verify.engine.lanes.compile_lanes`), whose per-lane parameters are laid
  out by name (:meth:`Ensemble.parameters`), never by the order of a mapping or by offsets;
* the step cap, one radian of the fastest rate or of sqrt(g) with g the model's own parameter
  (:meth:`Ensemble.step_cap`, as ``solve`` caps its steps: :func:`verify.engine.problem.max_step`);
* the terminal events of the single road (the domain's ends, the loss of contact, ``slips`` with a
  friction coefficient), freezing their own lane (:class:`verify.engine.batch.Freeze`);
* the guards (:meth:`Ensemble.guard`, :meth:`Ensemble.failure`): what heyoka reports of a lane
  (a non-finite state, a step budget spent, a failed event detection) and what its samples show
  (a sample before the lane's stop that is not finite, outside the domain, below its
  ``theta_stop``, at N <= 0 or needing more than its friction coefficient: an event that should
  have stopped it and did not).  A lane that breaks one is reported failed, never kept;
* the compiled functions the reductions read (:meth:`Ensemble.energy_terms`, the normal force,
  the friction needed), evaluated bit for bit as one call per run (:func:`verify.engine.batch.per_lane`).

The sweeps (:mod:`verify.sweep.engine`) and the stability maps (:mod:`verify.studies.map_runs`) are
its clients: neither imports heyoka.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import Optional

import heyoka as hy
import numpy as np
import sympy as sp

from models import get_model
from models.base import Model
from models.symbols import STATE_NAMES, phidot, psidot, theta

from . import batch
from .compile import friction_function, symbol_map, to_heyoka
from .failures import SLIP_SLACK_EPS
from .lanes import LaneSystem, compile_lanes
from .problem import fastest_rate
from ..precision import parse_precision

TH = STATE_NAMES.index("theta")


@dataclass(frozen=True, eq=False)
class Ensemble:
    """A model's batch runs: the model resolved once, its lane system, step cap, events and guards."""

    model: Model
    form: str = "full"
    batch_size: int = 4
    cooldown: float = 1.0
    stop: bool = False
    friction: bool = False

    @cached_property
    def lanes(self) -> LaneSystem:
        """The lane system, compiled when first run (checking starts needs only the model's functions)."""
        return compile_lanes(self.model, self.form, self.batch_size, self.cooldown, self.stop, self.friction)

    # --- the lanes' inputs, by name ---------------------------------------------------------------

    def parameters(self, n: int, values: Mapping) -> np.ndarray:
        """Every lane's parameters, (n_lane_parameters, n), by name (:meth:`LaneLayout.columns`)."""
        return self.lanes.layout.columns(n, values)

    def model_columns(self, values: Mapping, n: Optional[int] = None) -> np.ndarray:
        """The model's parameters as rows in model order, from a name -> value (or column) mapping.

        The rows the compiled functions read; every parameter of the model must be given, no other.
        """
        names = self.model.parameter_names
        unknown = [k for k in values if k not in names]
        if unknown:
            raise KeyError(f"{unknown[0]!r} is not a parameter of {self.model.name!r} ({', '.join(names)})")
        missing = [k for k in names if k not in values]
        if missing:
            raise KeyError(f"no value for the parameter {missing[0]!r} of {self.model.name!r}")
        rows = [np.asarray(values[k], dtype=float) for k in names]
        width = n if n is not None else max([r.size for r in rows if r.ndim] or [1])
        return np.stack([np.broadcast_to(r, (width,)) for r in rows]) if rows else np.zeros((0, width))

    def model_values(self, pars: np.ndarray) -> dict:
        """name -> row of the model's parameters from rows in model order (:meth:`model_columns`'s layout);
        lane parameters are read by name with :meth:`record`."""
        return {name: pars[i] for i, name in enumerate(self.model.parameter_names)}

    def default(self, name: str) -> float:
        """A model parameter's default, in double."""
        p = next((p for p in self.model.parameters if p.name == name), None)
        if p is None:
            raise KeyError(f"{name!r} is not a parameter of {self.model.name!r} ({', '.join(self.model.parameter_names)})")
        return float(sp.N(p.default))

    def fastest_rate(self, rates, g) -> float:
        """The fastest of |rates| and sqrt(g) (rad/s), g the model's own (a value or the lanes' values: the largest)."""
        return fastest_rate(rates, float(np.max(g)))

    def step_cap(self, rates, g) -> float:
        """One radian of :meth:`fastest_rate`: the largest step in double."""
        return 1.0 / self.fastest_rate(rates, g)

    def record(self, pars: np.ndarray, name: str) -> np.ndarray:
        """The row of the lane parameter (or record) ``name`` among the lanes' ``pars``."""
        return pars[self.lanes.layout[name]]

    # --- running ----------------------------------------------------------------------------------

    def propagate(self, states, pars, grid, threads: int, chunk: Optional[int] = None,
                  max_delta_t: Optional[float] = None, max_steps: Optional[int] = None):
        """:func:`verify.engine.batch.propagate_grid` on the lane system: (batches, heyoka's messages) per chunk.

        ``states`` (n_states, n_lanes) and ``pars`` (:meth:`parameters`), n_lanes a multiple of the
        batch size (:func:`verify.engine.batch.pad_lanes`).
        """
        return batch.propagate_grid(self.lanes.template, states, pars, grid, threads, chunk, max_delta_t, max_steps)

    def alone(self, grid, state_col, pars_col, max_delta_t=None, max_steps=None) -> tuple:
        """One lane alone in a batch of copies of itself (:func:`verify.engine.batch.alone`)."""
        return batch.alone(self.lanes.template, grid, state_col, pars_col, max_delta_t, max_steps)

    def failure(self, one: batch.Batch, lane: int, warned) -> Optional[tuple]:
        """(outcome, time) when heyoka failed the lane (:func:`verify.engine.batch.lane_failure`), else None."""
        return batch.lane_failure(one, lane, self.lanes.records, warned)

    def event_name(self, reason: int) -> str:
        """The name of the event whose code a lane recorded in ``reason``."""
        return self.lanes.events[reason - 1]

    # --- compiled functions of the full state (double) ----------------------------------------------

    @cached_property
    def energy_terms(self) -> batch.ScalarTwin:
        """(omega . Z = phidot + psidot cos theta, the energy's additive terms...) of the eight states."""
        variables = list(hy.make_vars(*STATE_NAMES))
        fmap = symbol_map(self.model, variables)
        terms = sp.Add.make_args(sp.expand(self.model.energy))  # the drift is judged against the sum of their magnitudes
        omega_z = phidot + psidot * sp.cos(theta)
        return batch.ScalarTwin.of([to_heyoka(omega_z, fmap)] + [to_heyoka(t, fmap) for t in terms], variables)

    @cached_property
    def normal_force(self) -> Optional[batch.ScalarTwin]:
        """N/(Mg) of the eight states, or None (no contact)."""
        if self.model.normal_force is None:
            return None
        variables = list(hy.make_vars(*STATE_NAMES))
        exprs = [to_heyoka(self.model.normal_force, symbol_map(self.model, variables))]
        return batch.ScalarTwin(hy.cfunc(exprs, variables), hy.cfunc(exprs, variables, batch_size=1))

    @cached_property
    def friction_required(self) -> Optional[batch.ScalarTwin]:
        """(N/(Mg), mu_req = |F_h|/N) of the eight states: the cfunc ``solve`` reads ``friction_required``
        with, and its scalar build; None without rolling contact."""
        dbl = parse_precision("double")
        simd = friction_function(self.model, dbl)
        return None if simd is None else batch.ScalarTwin(simd.function, friction_function(self.model, dbl, 1).function)

    def normal_force_columns(self, states, model_pars) -> Optional[np.ndarray]:
        """N/(Mg) at each column of ``states`` (8, n) with the model's parameters per column (one call)."""
        if self.normal_force is None:
            return None
        f = self.normal_force.simd
        states = np.ascontiguousarray(states[:8], dtype=float)
        if f.nparams == 0:
            return f(states)[0]
        return f(states, pars=np.ascontiguousarray(model_pars[: f.nparams], dtype=float))[0]

    def friction_needed(self, states, model_pars) -> np.ndarray:
        """mu_req = |F_h|/N at each column of ``states`` (8, n); NaN where N <= 0."""
        fn = friction_function(self.model, parse_precision("double"))
        kwargs = {"pars": np.ascontiguousarray(model_pars[: fn.n_pars], dtype=float)} if fn.n_pars else {}
        normal, need = fn.function(np.ascontiguousarray(states[:8], dtype=float), **kwargs)
        return np.where(normal > 0, need, np.nan)

    # --- the guards on the samples ------------------------------------------------------------------

    def sample_row(self, n_grid: int) -> int:
        """A lane's row of samples in whole SIMD groups of the compiled functions: ``n_grid`` rounded up.

        Samples laid out (states, lanes, :meth:`sample_row`), the padding after each lane's last sample,
        reach :func:`verify.engine.batch.per_lane` without a copy."""
        width = int(self.energy_terms.simd.batch_size)
        return n_grid + (-n_grid) % width

    def guard(self, grid, samples, model_pars, stopped, t_stop, theta_stop=None, friction=None) -> list:
        """Per lane, (outcome, time) of the first sample that should not exist, or None.

        ``samples`` (states, lanes, grid or more: :meth:`sample_row`) of the full form.  Every sample before the lane's stop must
        be finite, inside the domain, above ``theta_stop``, at N > 0 and, with a coefficient
        (``friction``, per lane), need no more than it (within
        :data:`verify.engine.failures.SLIP_SLACK_EPS`, as ``solve``'s guard); at a sample on the stop
        time itself the stopping event's own function is ~0, so the samples checked are those
        strictly before it.  ``failed:non_finite`` for a sample that is not finite,
        ``failed:event_detection`` for the others (an event that should have stopped the lane).
        """
        n_lanes, g = samples.shape[1], len(grid)
        checked = np.where(stopped, np.maximum(1, np.searchsorted(grid, t_stop, side="left")), g)
        inside = np.arange(g)[None, :] < checked[:, None]  # (lanes, grid)
        finite = np.isfinite(samples[:8, :, :g]).all(axis=0) | ~inside
        out = [None] * n_lanes
        for k in np.flatnonzero(~finite.all(axis=1)):
            out[k] = ("failed:non_finite", float(grid[np.argmin(finite[k])]))
        lo, hi = float(self.model.domain.theta_min), float(self.model.domain.theta_max)
        th = samples[TH, :, :g]
        with np.errstate(invalid="ignore"):
            ok = (lo < th) & (th < hi)
            if theta_stop is not None:
                ok &= th > theta_stop
        finite_lanes = finite.all(axis=1)
        if self.normal_force is not None and finite_lanes.any():
            # every lane is evaluated (a lane with a non-finite sample is judged above and its values are not
            # read; per_lane keeps each lane in its own SIMD groups, so it changes no other lane's bits)
            with np.errstate(invalid="ignore"):
                ok &= batch.per_lane(self.normal_force, samples[:8], model_pars, checked)[0, :, :g] > 0
                if friction is not None:
                    need = batch.per_lane(self.friction_required, samples[:8], model_pars, checked)[1, :, :g]
                    mu = np.asarray(friction, dtype=float)[:, None]  # NaN where N <= 0, refused above
                    ok &= ~(need > mu + SLIP_SLACK_EPS * np.finfo(float).eps * np.maximum(1.0, mu))
        ok |= ~inside
        for k in np.flatnonzero(finite_lanes & ~ok.all(axis=1)):
            out[k] = ("failed:event_detection", float(grid[np.argmin(ok[k])]))
        return out


def ensemble(model, form: str, batch_size: int, cooldown: float, stop: bool = False, friction: bool = False) -> Ensemble:
    """The :class:`Ensemble` of ``model`` (a name, e.g. ``"disk"`` or ``"body:hoop"``, or a Model) and settings.

    By name, one per process and settings (the model is resolved by ``get_model`` the first time
    only); a Model is taken as it is.  ``form``, ``stop``, ``friction``: as
    :func:`verify.engine.lanes.compile_lanes`.
    """
    if isinstance(model, str):
        return _by_name(model, form, int(batch_size), float(cooldown), bool(stop), bool(friction))
    if not isinstance(model, Model):
        raise ValueError(f"model={model!r}: allowed: a model name (python -m verify models) or a models.Model")
    if form == "reduced" and (stop or friction):
        raise ValueError("the reduced lane system has no theta_stop or slips event; allowed: form='full'")
    return Ensemble(model, form, int(batch_size), float(cooldown), bool(stop), bool(friction))


@lru_cache(maxsize=64)
def _by_name(name: str, form: str, batch_size: int, cooldown: float, stop: bool, friction: bool) -> Ensemble:
    return ensemble(resolve(name), form, batch_size, cooldown, stop, friction)


def clear() -> None:
    """Forget every ensemble and compiled lane system (tests that patch what a lane system is built from)."""
    _by_name.cache_clear()
    compile_lanes.cache_clear()


@lru_cache(maxsize=None)
def resolve(name: str) -> Model:
    """The model called ``name``, resolved once per process (``get_model``; a body file's model is derived
    once and kept on disk, but building its Model again costs ~5 ms a call)."""
    return get_model(name)


def g_of(model: Model, values: Mapping) -> float:
    """The model's own g from a name -> value mapping of its parameters (its default when not given)."""
    if "g" not in model.parameter_names:
        raise KeyError(f"model {model.name!r} has no parameter g; the step cap needs one (sqrt(g) is a rate)")
    if "g" in values:
        return float(values["g"])
    return float(sp.N(next(p for p in model.parameters if p.name == "g").default))

