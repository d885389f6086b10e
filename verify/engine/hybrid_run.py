"""The record of one rolling-and-sliding run (:mod:`verify.engine.hybrid`): its phases, outputs and result.

The phases (:mod:`~verify.engine.hybrid_rolling`, :mod:`~verify.engine.hybrid_sliding`) append their outputs
to a :class:`Run`, the switches (:mod:`~verify.engine.hybrid_switches`) read it, the guards
(:mod:`~verify.engine.hybrid_guards`) check it and, on a failure, hand out the run up to there
(:meth:`Run.result`, a :class:`HybridSolution`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from models.symbols import STATE_NAMES

from . import hybrid_system as system
from .hybrid_guards import balance_drift_in_eps
from .trajectory import IntegrationError, Trajectory
from ..precision import Precision


class UnsupportedTransition(IntegrationError):
    """The run reached a switch this driver does not integrate (a slip onset whose direction is not unique,
    or whose series at mu_req = mu does not settle)."""


@dataclass(frozen=True)
class Phase:
    """One phase of a run: ``kind`` 'rolling' or 'sliding', its times and how it ended
    ('ok' at t_end, 'sticks', 'slips', or the rolling model's events: 'event:lies_flat', ...)."""

    kind: str
    t_start: object
    t_end: object
    ended: str


@dataclass(frozen=True)
class HybridSolution:
    """A run of a body that rolls or slides, shaped like scipy's ``solve_ivp`` result.

    Attributes
    ----------
    t : ndarray (n,)
        Output times: the grid points of every phase, and every switch time (once per phase it
        ends or starts, so a switch time appears twice: the end of one phase, the start of the next).
    y : ndarray (8, n)
        The eight components of ``STATE_NAMES``.
    slip_speed, slip_direction : ndarray (n,)
        s = |u| and alpha (inertial) where sliding; 0 and NaN where rolling.
    phase_index : ndarray (n,)
        The index in ``phases`` each output belongs to.
    energy, work : ndarray (n,)
        E per m R^2, and W = int mu N s dt (constant in rolling phases).
    energy_scale : float
        The largest term scale of E on the run (sum of the absolute values of its terms).
    energy_plus_work_drift_in_eps : float
        max over the outputs of |E + W - E(0)| / (eps times the largest term scale of E up to that output):
        the energy balance at the precision (:func:`verify.engine.hybrid_guards.balance_drift_in_eps`); a
        run is handed out only if it is within :func:`~verify.engine.hybrid_guards.balance_bound_in_eps`.
    switch_times : tuple
        Times where a phase ended and the next began.
    steps : int
        heyoka's Taylor steps over every phase.
    outcome, status, message
        'ok' (status 0), the last phase's terminal event ('event:lies_flat', 'event:contact_lost', status 1),
        or, on the partial run an :class:`IntegrationError` carries, its named failure
        (:mod:`verify.engine.hybrid_guards`: 'failed:outside_domain', 'failed:energy_balance',
        'failed:switch_constraint', 'painleve:jam'; 'unsupported:slip_onset'; heyoka's 'failed:...').
    """

    model: str
    precision: Precision
    params: dict
    t: np.ndarray
    y: np.ndarray
    slip_speed: np.ndarray
    slip_direction: np.ndarray
    phase_index: np.ndarray
    phases: tuple
    energy: np.ndarray
    work: np.ndarray
    energy_scale: float
    energy_plus_work_drift_in_eps: float
    switch_times: tuple
    outcome: str
    status: int
    message: str
    rolling_runs: tuple  # the engine's Trajectory of each rolling phase
    steps: int = 0  # Taylor steps of every phase

    def __getitem__(self, name):
        return self.y[STATE_NAMES.index(name)]

    def __repr__(self) -> str:  # the arrays are for reading, not for printing
        span = f"t = {float(self.t[0]):g} to {float(self.t[-1]):g} s, {len(self.t)} outputs" if len(self.t) else "no outputs"
        kinds = [ph.kind for ph in self.phases]
        return (f"HybridSolution(model={self.model!r}, precision={self.precision.name!r}, outcome={self.outcome!r}, "
                f"{span}, {len(kinds)} phases ({kinds.count('rolling')} rolling, {kinds.count('sliding')} sliding), "
                f"steps={self.steps})")

    # the same time-series methods as a rolling run's
    columns, save, to_csv, to_json, plot, animate, _save_as = (
        Trajectory.columns, Trajectory.save, Trajectory.to_csv, Trajectory.to_json, Trajectory.plot, Trajectory.animate,
        Trajectory._save_as)


def grid_rows(sol, grid: list, prec) -> list:
    """The index in the run's outputs of each grid time (its first output at that time: a switch time
    appears twice, the end of one phase and the start of the next)."""
    wanted = [prec.number(g) for g in grid]
    rows, j = [], 0
    for g in wanted:
        while j < len(sol.t) and sol.t[j] < g:
            j += 1
        if j == len(sol.t) or sol.t[j] != g:
            raise RuntimeError(f"the hybrid run has no output at the grid time {float(g):.9g} (it stopped at "
                               f"{float(sol.t[-1]):.9g}: {sol.outcome})")
        rows.append(j)
    return rows


def switch_kinds(sol) -> list:
    """The run's switches in order: 'rolling -> sliding', 'sliding -> rolling', ..."""
    kinds = [ph.kind for ph in sol.phases]
    return [f"{a} -> {b}" for a, b in zip(kinds, kinds[1:])]


class Run:
    """One run's settings and its outputs so far, phase after phase.

    Parameters
    ----------
    name : str
        ``disk+coulomb``, ``ring+coulomb`` or ``body:NAME+coulomb``.
    prec : Precision
    c : verify.engine.hybrid_system.SlidingSystem
        The body's compiled sliding system at ``prec``.
    pars : dict
        The rolling model's parameters at ``prec``.
    par_vector : ndarray
        Those parameters in the compiled order, then mu.
    mu : number
        The Coulomb coefficient at ``prec``.
    grid : list
        The output times, from 0 to ``t_end``.
    t_end : number
    """

    def __init__(self, name, prec, c, pars, par_vector, mu, grid, t_end):
        self.name, self.prec, self.c, self.pars, self.par_vector, self.mu = name, prec, c, pars, par_vector, mu
        self.grid, self.t_end = grid, t_end
        self.t, self.y, self.slip, self.direction, self.index, self.energy, self.work, self.scale = ([] for _ in range(8))
        self.phases, self.rolling_runs = [], []
        self.outcome, self.message = "ok", "t_end reached"
        self.work_so_far = prec.zero()
        self.steps = 0  # Taylor steps of every phase so far (the energy balance's bound grows with them)
        dom = system.rolling_model(name).domain
        self.domain_events = (dom.below, dom.above)
        self.theta_bounds = tuple(system.domain_end(e, prec) for e in (dom.theta_min, dom.theta_max))

    def grid_after(self, t0):
        """The output times after ``t0``."""
        return [g for g in self.grid if g > t0]

    def outputs_before(self, t, t0, state_at):
        """[(g, state)] for the output times g in (t, t0], between an onset at t and its start at t0, from the
        onset's own solution ``state_at(g - t)`` (its series or Taylor polynomial, exact there to the same
        order: g - t <= t0 - t).  Without them a run whose t_end falls there would end at the onset."""
        return [(g, state_at(g - t)) for g in self.grid if t < g <= t0]

    def truncate(self, n: int) -> None:
        """Keep the first ``n`` outputs (a guard that failed keeps the run through the output it failed at)."""
        for rows in (self.t, self.y, self.energy, self.scale, self.slip, self.direction, self.work, self.index):
            del rows[n:]

    def record(self, times, states, energy, scale, slip, direction, work):
        """Append a phase's outputs (the last phase of :attr:`phases`)."""
        k = len(self.phases) - 1
        self.t += list(times)
        self.y += [np.asarray(s[:8]) for s in states]
        self.energy += list(energy)
        self.scale += list(scale)
        self.slip += list(slip)
        self.direction += list(direction)
        self.work += list(work)
        self.index += [k] * len(times)

    def unsupported(self, t, message):
        """The :class:`UnsupportedTransition` at ``t``, with the run up to there (its outcome set first)."""
        self.outcome, self.message = "unsupported:slip_onset", message
        return UnsupportedTransition(message, "unsupported:slip_onset", t, None, self.result())

    def result(self) -> HybridSolution:
        """The run so far as a :class:`HybridSolution` (E + W's drift from :mod:`~verify.engine.hybrid_guards`)."""
        prec = self.prec
        y = np.array(self.y).T if self.y else np.zeros((8, 0))
        energy, work = np.array(self.energy), np.array(self.work)
        scale = max(float(s) for s in self.scale) if self.scale else float("nan")
        drift = float(np.max(balance_drift_in_eps(energy, work, self.scale, prec.eps))) if len(energy) else float("nan")
        switches = tuple(p.t_end for p in self.phases[:-1])
        status = 0 if self.outcome == "ok" else 1
        return HybridSolution(
            model=self.name, precision=prec, params={**self.pars, "mu": self.mu}, t=np.array(self.t), y=y,
            slip_speed=np.array(self.slip), slip_direction=np.array(self.direction, dtype=system.output_dtype(prec)),
            phase_index=np.array(self.index), phases=tuple(self.phases), energy=energy, work=work,
            energy_scale=scale, energy_plus_work_drift_in_eps=drift, switch_times=switches,
            outcome=self.outcome, status=status, message=self.message, rolling_runs=tuple(self.rolling_runs),
            steps=self.steps,
        )
