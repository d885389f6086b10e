"""Run one chunk of a sweep through the batch road (:class:`verify.engine.ensemble.Ensemble`), then its rows.

The full state (theta, phi, psi, thetadot, phidot, psidot, x, y), plus the work W of a
dissipative term when the model has one, is integrated in double by the spec's ensemble
(:func:`ensemble_of`): SIMD lanes within a batch integrator, batches on threads.  Parameters are
runtime ``par[i]`` laid out by name (:class:`verify.engine.lanes.LaneLayout`: the model's, then the
per-lane records alive, reason, t_stop, and theta_stop with a ``[stop]`` or else theta_max), so one
compiled integrator serves every point of every sweep of the model; the model is resolved once
per process (one ``get_model``), g for the step cap is the model's own.

Terminal events freeze their own lane (:class:`verify.engine.batch.Freeze`): the lane is parked
in the middle of the model's domain (thetadot = psidot = 0, phidot = 1: a rocking rate of
exactly 0 would put |omega_perp| on the singular point of its square root), and samples after
its stop time are discarded by the reductions.  The events: the model's domain ends, ``[stop]
theta_below`` when the spec has one (only then is it compiled: an event costs on every step),
and the loss of contact (N = 0) where the model has a contact.

With a friction coefficient (``[params] friction`` or an axis) the system has one more event,
``slips``, built from the single engine's own function (:func:`verify.engine.compile.slip_event_function`)
on the same unscaled accelerations as ``contact_lost``, the coefficient in the lane parameter ``friction``;
the event's callback keeps theta at the event time in another before it parks the lane.  A run
records ``slipped`` (1 when ``slips`` stopped it, else 0), ``t_slip`` and ``theta_at_slip`` (NaN
when it did not slip); ``max_friction_required_on_grid`` is the largest mu_req = |F_h|/N on the
output samples up to the run's stop (NaN samples at N <= 0 skipped; a run that slipped needed its
coefficient at t_slip, between samples).  The guard then also fails a lane with a sample before its
stop needing more than its coefficient (the slack of :data:`verify.engine.failures.SLIP_SLACK_EPS`).

The reductions of a chunk are computed for all its lanes at once (numpy over the lanes' samples;
the diagnostics by one compiled call per chunk, bit for bit as one call per run), and only the
quantities asked for.  They are what the run holds -- extremes over the samples, the final state (at
t_end, or for a run a terminal event stopped, the state the event recorded at t_stop: the samples end
at the last grid time before it), the drift of E + W, the largest mu_req -- not what they mean: the senses of the orbit and the spin
(:data:`verify.sweep.spec.SENSE_KEYS`) are a study's reading of a run, :func:`verify.studies.orbits.senses`,
which the caller passes as ``senses=`` and this module calls run by run when one of them is
recorded (the sweep imports no study: :func:`check_readings` refuses the spec without it).

Every point's result depends on its own inputs only (lanes do not interact; their step sizes
are their own), so a chunk gives the same rows in any process, on threads or on a Dask
worker, whatever ran before it.

Validation and failures
-----------------------
Every point of the grid is checked as a start (:func:`validate_points`, by
:mod:`verify.engine.validation`, as ``solve`` checks one) before the store is created, and the first
invalid point refuses the whole sweep (:class:`verify.sweep.spec.InvalidPoint`, naming it).  Why
refuse rather than store ``invalid:<reason>`` rows: an invalid point is a start that does not
exist (theta outside the domain, N <= 0: the body is already off the plane, a parameter out of
its physical range), so a grid that contains one was mis-drawn -- its axes cross the edge of the
model -- and the fix is to redraw them; storing such rows would make every reader of a store
(the maps, the retrograde study, anyone's SQL) filter them out or mistake them for motions (the
former ``contact_lost at t ~ 0.01 s`` rows were exactly that), would tie the store's identity
to the mis-drawn spec, and would spend a chunk's work on points that have no dynamics.  A
refusal costs one pass over the grid's starts (no integration) and nothing on disk.

A valid start can still fail to integrate.  Such a run is stored, with its own outcome and NaN
quantities (white on a map, never data), as in ``solve``:

* ``failed:non_finite`` -- heyoka stopped the lane on a non-finite state, or a sample is not finite;
* ``failed:event_detection`` -- heyoka warned that event detection failed in the lane
  (:mod:`verify.engine.heyoka_log`), or a sample before the lane's stop lies outside the domain, below
  ``[stop] theta_below``, or at N <= 0, without the event that should have stopped it there;
* ``failed:step_size_collapse`` -- the run needed more than COLLAPSE_FACTOR (t_end x the fastest
  initial rate) steps, i.e. its steps averaged below 2^-15 of the step cap, as in ``solve``.

A batch in which any of these happens (or any heyoka warning in its group of :data:`REDUCE_GROUP`
batches, which names a lane but not its batch) is integrated again lane by lane, each lane alone in a
batch of copies of itself: lanes are independent, so a good lane gets the same bits it got in the mixed
batch, and a failed lane is told apart from its neighbours.  A chunk's groups are integrated one after
the other, each while the one before is reduced; before any lane is run again alone the remaining
groups are finished first, so that the messages heyoka writes during it are its own.
"""
from __future__ import annotations

import math
from functools import lru_cache

import mpmath
import numpy as np

from models.ring_dissipation import annulus_inertia
from models.steady import steady_state
from models.symbols import STATE_NAMES

from ..engine import batch, validation
from ..engine.ensemble import Ensemble, ensemble, g_of, resolve
from ..engine.lanes import simd_width
from ..engine.single import COLLAPSE_FACTOR
from ..precision import parse_precision
from .spec import FRICTION as FRICTION_AXIS
from .spec import RATE_AXIS, SENSE_KEYS, InvalidPoint, SpecError, SweepSpec

#: Batches integrated and reduced together, one group reduced while the next integrates: enough lanes
#: for numpy to pay, few enough that a chunk's samples are held about once (the store's memory estimate
#: assumes 1.5 times the dense output).
REDUCE_GROUP = 16
TH = STATE_NAMES.index("theta")  # theta's row of a chunk's states and column of a run's samples


def ensemble_of(spec: SweepSpec, batch_size: int) -> Ensemble:
    """The spec's :class:`verify.engine.ensemble.Ensemble`: the full form, the ``theta_stop`` event only with a
    ``[stop]``, ``slips`` only with a friction coefficient (an event costs on every step), a cooldown
    longer than the run; one per process and settings, so the model is resolved once."""
    return ensemble(spec.model, "full", batch_size, 2.0 * spec.t_end + 1.0, spec.theta_stop is not None, spec.slips)


# --- inputs of a chunk ---------------------------------------------------------------------------

_PARAMETER_AXES_EXCLUDE = set(STATE_NAMES) | {"tilt", FRICTION_AXIS}


def friction_column(spec: SweepSpec, indices):
    """The friction coefficient of each of the points ``indices`` (fixed or the axis), or None without one."""
    idx = np.asarray(indices, dtype=np.int64)
    if spec.friction is not None:
        return np.full(len(idx), spec.friction)
    if not spec.slips:
        return None
    return spec.columns(idx)[FRICTION_AXIS]


def lane_inputs(spec: SweepSpec, indices) -> tuple:
    """(states (8, n), model parameters (n_pars, n), theta_ref (n)) of the points ``indices``.

    theta_ref is the start's theta before any tilt: the steady angle for ``[start] steady``.
    Raises :class:`InvalidPoint` for the first point whose parameters are invalid (or whose
    steady motion does not exist); the start as a whole is checked by :func:`point_problems`.
    """
    states, pars, refs, problems = _inputs(spec, indices, ensemble_of(spec, simd_width()).model)
    if problems:
        raise _refusal(spec, np.asarray(indices, dtype=np.int64), problems[0])
    return states, pars, refs


def _inputs(spec: SweepSpec, indices, model) -> tuple:
    """lane_inputs without raising: (states, pars, refs, [(column, reason, message)]) -- the
    columns of points with bad parameters are NaN.  Vectorised over the points: the parameters
    are resolved once per distinct combination, the steady motion once per distinct rate."""
    idx = np.asarray(indices if isinstance(indices, np.ndarray) else list(indices), dtype=np.int64)
    n = len(idx)
    cols = spec.columns(idx)
    problems = []
    # parameters: [params], then the parameter axes (and w), once per distinct combination
    names = [a.name for a in spec.axes if a.name not in _PARAMETER_AXES_EXCLUDE]
    if names:
        stacked = np.stack([cols[k] for k in names], axis=1)
        combos, first, inverse = np.unique(stacked, axis=0, return_index=True, return_inverse=True)
        inverse = inverse.reshape(-1)
    else:
        combos, first, inverse = np.zeros((1, 0)), np.array([0]), np.zeros(n, dtype=np.int64)
    combo_pars = np.full((len(combos), len(model.parameters)), np.nan)
    texts = [None] * len(combos)
    for c in np.argsort(first, kind="stable"):
        items = tuple(spec.params.items()) + tuple(zip(names, (float(v) for v in combos[c])))
        try:
            values, texts[c] = _resolved(spec.model, spec.geometry, items)
        except validation.InvalidStart as err:
            problems.append((int(first[c]), err.reason, str(err)))
            continue
        combo_pars[c] = values
    pars = np.ascontiguousarray(combo_pars[inverse].T)
    states = np.zeros((8, n))
    for k, v in spec.start.items():
        states[STATE_NAMES.index(k)] = v
    for a in spec.axes:
        if a.name in STATE_NAMES:
            states[STATE_NAMES.index(a.name)] = cols[a.name]
    refs = states[TH].copy()  # start.get("theta", 0.0)
    if spec.steady is not None:
        rate = cols[RATE_AXIS[spec.steady]]
        keys = np.stack([inverse.astype(float), rate], axis=1)
        groups, gfirst, ginv = np.unique(keys, axis=0, return_index=True, return_inverse=True)
        ginv = ginv.reshape(-1)
        table = {}  # state name -> value per group
        for g in np.argsort(gfirst, kind="stable"):
            c = int(groups[g][0])
            if texts[c] is None:
                continue  # its parameters are already refused
            try:
                steady = _steady_cached(spec.model, spec.steady, repr(float(groups[g][1])), texts[c])
            except (ValueError, TypeError, ArithmeticError) as err:
                problems.append((int(gfirst[g]), "no_steady", f"no steady {spec.steady} of {spec.model!r} at "
                                 f"{RATE_AXIS[spec.steady]} = {float(groups[g][1])!r}: {err}"))
                combo_pars[c] = np.nan
                continue
            for k, v in steady.items():
                table.setdefault(k, np.full(len(groups), np.nan))[g] = v
        for k, column in table.items():
            states[STATE_NAMES.index(k)] = column[ginv]
        if "theta" in table:
            refs = table["theta"][ginv]
        pars = np.ascontiguousarray(combo_pars[inverse].T)
    bad = np.isnan(pars).any(axis=0) if len(model.parameters) else np.zeros(n, bool)
    states[TH] = refs + (cols["tilt"] if "tilt" in cols else 0.0)
    states[:, bad] = np.nan
    problems.sort()
    return states, pars, refs, problems


@lru_cache(maxsize=4096)
def _resolved(model_name: str, geometry, items: tuple) -> tuple:
    """(parameter values in model order, by name, and the parameters as decimal strings) of one combination."""
    model = resolve(model_name)
    values = dict(items)
    values.pop("tilt", None)
    if geometry == "annulus":
        hh, ww = values.get("h"), values.pop("w")
        i1, i3 = annulus_inertia(hh, ww)
        values.update(I1=i1, I3=i3)
        if "w" in model.parameter_names:
            values["w"] = ww
    text = {k: repr(float(v)) for k, v in values.items()}
    resolved = validation.parameters(model, text, parse_precision("double"))
    return tuple(float(resolved[name]) for name in model.parameter_names), tuple(text.items())


@lru_cache(maxsize=4096)
def _steady_cached(model: str, motion: str, rate: str, params: tuple) -> dict:
    s = steady_state(model, motion, rate, dict(params))
    with mpmath.workdps(40):
        return {k: float(mpmath.mpf(v)) for k, v in s.items()}


def point_problems(spec: SweepSpec, indices) -> list:
    """[(index, reason, message)] of the points ``indices`` that are not valid starts, in index order.

    The checks of :mod:`verify.engine.validation` (the parameters together, finite, theta in the
    domain, the model's constraints, N > 0), plus theta above ``[stop] theta_below``.
    """
    idx = np.asarray(indices if isinstance(indices, np.ndarray) else list(indices), dtype=np.int64)
    ens = ensemble_of(spec, simd_width())
    return _problems(spec, ens, idx, *_inputs(spec, idx, ens.model))


def _problems(spec: SweepSpec, ens: Ensemble, idx, states, pars, refs, problems) -> list:
    model = ens.model
    problems = list(problems)
    good = ~np.isnan(pars).any(axis=0) if len(model.parameters) else np.ones(len(idx), bool)
    cols = np.flatnonzero(good)
    if len(cols):
        sub, psub = states[:, cols], pars[:, cols]
        normal = ens.normal_force_columns(sub, psub)
        found = validation.start_problems(model, sub, normal)
        for j, reason, message in found:
            problems.append((int(cols[j]), reason, message))
        mu = friction_column(spec, idx)
        if mu is not None:  # as solve refuses a start that already needs the coefficient (validation._slip_problem)
            need = ens.friction_needed(sub, psub)
            bad = {j for j, _, _ in found}
            for j in np.flatnonzero(~(need < mu[cols])):
                if int(j) not in bad:
                    problems.append((int(cols[j]), "slips", f"the start needs the friction coefficient mu_req = "
                                     f"|F_h|/N = {need[j]:.9g} >= friction = {float(mu[cols[j]])!r}: it slips at t = 0 and "
                                     "cannot roll"))
        if spec.theta_stop is not None:
            below = np.flatnonzero(~(sub[TH] > spec.theta_stop))
            for j in below:
                problems.append((int(cols[j]), "below_stop", f"theta = {sub[TH, j]!r} is not above [stop] theta_below = "
                                 f"{spec.theta_stop!r}, so the run would never stop there"))
    problems.sort()
    return [(int(idx[c]), reason, message) for c, reason, message in problems]


def _refusal(spec: SweepSpec, idx, problem) -> InvalidPoint:
    col, reason, message = problem
    index = int(idx[col])
    return _invalid(spec, index, reason, message)


def _invalid(spec: SweepSpec, index: int, reason: str, message: str) -> InvalidPoint:
    point = spec.point(index)
    shown = ", ".join(f"{k} = {v!r}" for k, v in point.items())
    return InvalidPoint(f"sweep {spec.name!r}: point {index} of {spec.n_points} ({shown}) is not a valid start: "
                        f"{message} -- a sweep runs only if every point of its grid is a valid start: change the "
                        "axes' from/to/count, [start] or [params]", index, point, reason)


#: Points validated at a time by :func:`validate_points` (their inputs are ~100 bytes each).
VALIDATION_BLOCK = 1 << 16


def validate_points(spec: SweepSpec, block: int = VALIDATION_BLOCK) -> None:
    """Check every point of the grid as a start, a block at a time; raise :class:`InvalidPoint`
    naming the first invalid one (see the module docstring: a sweep with one is refused)."""
    for start in range(0, spec.n_points, block):
        idx = np.arange(start, min(start + block, spec.n_points), dtype=np.int64)
        problems = point_problems(spec, idx)
        if problems:
            index, reason, message = problems[0]
            raise _invalid(spec, index, reason, message)


def fastest_rate(spec: SweepSpec, ens: Ensemble = None) -> float:
    """The largest initial rate over the whole sweep, or sqrt(g) with the model's own largest g: the step
    cap is 1 / it, as in solve() (over the sweep, not the chunk, so that a row does not depend on the chunking)."""
    ens = ens or ensemble_of(spec, simd_width())
    rates = [spec.start.get(n, 0.0) for n in ("thetadot", "phidot", "psidot")]
    for a in spec.axes:
        if a.name in ("thetadot", "phidot", "psidot"):  # a monotone axis: its ends are its extremes
            rates += list(a.values.extremes)
    g = g_of(ens.model, spec.params)
    for a in spec.axes:
        if a.name == "g":
            g = a.values.extremes[1]
    return ens.fastest_rate(rates, g)


def step_budget(spec: SweepSpec, ens: Ensemble = None) -> int:
    """The most steps a run may take: COLLAPSE_FACTOR (t_end x the fastest rate) (see the module docstring)."""
    return int(COLLAPSE_FACTOR * spec.t_end * fastest_rate(spec, ens)) + COLLAPSE_FACTOR


# --- a chunk ---------------------------------------------------------------------------------------

def check_readings(spec: SweepSpec, senses) -> None:
    """Refuse, with a :class:`SpecError` naming the quantity, a spec that records a sense of the orbit
    (:data:`verify.sweep.spec.SENSE_KEYS`) when no reading of them, ``senses``, is given (module docstring)."""
    wanted = [q for q in spec.record if q in SENSE_KEYS]
    if wanted and senses is None:
        raise SpecError(f"sweep {spec.name!r} records {wanted[0]!r}, a sense of the orbit read from each run's "
                        "samples by a study: pass senses=verify.studies.orbits.senses to run_sweep or run_chunk "
                        "(python -m verify sweep does)")


def run_chunk(spec: SweepSpec, chunk: int, threads: int = 1, batch_size: int = None, senses=None) -> list:
    """The rows of chunk ``chunk``: one dict per point with its inputs, outcome and quantities.

    ``senses``: the reading of the orbit's and the spin's senses, ``senses(t, y, omega_z) -> dict`` over
    :data:`verify.sweep.spec.SENSE_KEYS` (:func:`verify.studies.orbits.senses`), called on each run's
    samples up to its stop; needed only when the spec records one of them (:func:`check_readings`).
    """
    check_readings(spec, senses)
    indices = list(spec.chunk_points(chunk))
    if not indices:
        raise ValueError(f"chunk {chunk} is outside the sweep's {spec.n_chunks} chunks")
    bs = batch_size or simd_width()
    ens = ensemble_of(spec, bs)
    idx = np.asarray(indices, dtype=np.int64)
    inputs = _inputs(spec, idx, ens.model)
    problems = _problems(spec, ens, idx, *inputs)  # validated before the store was made; a worker checks again
    if problems:
        raise _invalid(spec, *problems[0])
    states, model_pars, refs, _ = inputs
    n = len(indices)
    lanes = ens.lanes
    pad = batch.pad_lanes(n, bs)
    lane_states = np.zeros((len(lanes.states), len(pad)))
    lane_states[:8] = states[:, pad]
    settings = {**ens.model_values(model_pars[:, pad])}
    if spec.theta_stop is not None:
        settings["theta_stop"] = spec.theta_stop
    else:
        settings["theta_max"] = float(ens.model.domain.theta_max)
    if spec.slips:
        settings["friction"] = friction_column(spec, idx)[pad]
    lane_pars = ens.parameters(len(pad), settings)
    grid = np.linspace(0.0, spec.t_end, spec.samples)
    options = {"max_delta_t": 1.0 / fastest_rate(spec, ens), "max_steps": step_budget(spec, ens)}

    run = _GroupRun(spec, ens, idx, indices, grid, lane_states, lane_pars, model_pars, refs, options, senses)
    rows = []
    groups = ens.propagate(lane_states, lane_pars, grid, threads, REDUCE_GROUP, **options)
    for batches, messages in groups:  # a group at a time, the next one integrating meanwhile
        if messages or not all(_batch_ok(b, len(grid)) for b in batches):
            # some lane is run again alone (module docstring): only once nothing else runs, so that
            # heyoka's messages during it are its own
            for later, later_messages in [(batches, messages)] + list(groups):
                rows += run.rows(later, later_messages)
            break
        rows += run.rows(batches, messages)
    return rows


class _GroupRun:
    """The rows of one group of a chunk's batches: samples gathered (failed lanes run again alone), reduced."""

    def __init__(self, spec, ens, idx, indices, grid, lane_states, lane_pars, model_pars, refs, options, senses):
        self.spec, self.ens, self.idx, self.indices, self.grid = spec, ens, idx, indices, grid
        self.lane_states, self.lane_pars, self.model_pars, self.refs = lane_states, lane_pars, model_pars, refs
        self.options, self.senses, self.n = options, senses, len(indices)

    def rows(self, group, messages) -> list:
        ens, grid, n = self.ens, self.grid, self.n
        cols_group = np.arange(group[0].columns.start, min(group[-1].columns.stop, n))
        g = len(grid)  # (states, lanes, grid and each lane's padding to whole SIMD groups: Ensemble.sample_row)
        samples = np.empty((len(ens.lanes.states), len(cols_group), ens.sample_row(g)))
        final_pars = np.empty((self.lane_pars.shape[0], len(cols_group)))
        failed = {}  # lane -> (outcome, time)
        for b in group:
            cols = np.arange(b.columns.start, min(b.columns.stop, n))
            if not len(cols):
                continue  # padding only
            at = cols - cols_group[0]
            if not messages and _batch_ok(b, len(grid)):
                samples[:, at[0]:at[-1] + 1, :g] = np.transpose(b.output[:, :, : len(cols)], (1, 2, 0))
                final_pars[:, at] = b.local.pars[:, : len(cols)]
                continue
            for k, j in zip(cols, at):  # again, each lane alone (module docstring)
                one, warned = ens.alone(grid, self.lane_states[:, k], self.lane_pars[:, k], **self.options)
                failure = ens.failure(one, 0, warned)
                if failure is not None:
                    failed[j] = failure
                    continue
                samples[:, j, :g] = one.output[:, :, 0].T if one.output.shape[0] == g else np.nan
                final_pars[:, j] = one.local.pars[:, 0]
        samples[:, :, g:] = samples[:, :, g - 1:g]  # each lane's padding: its last sample
        good = np.array([j not in failed for j in range(len(cols_group))])
        kept = samples if good.all() else np.ascontiguousarray(samples[:, good])
        chosen = cols_group[good]
        reduced = iter(_reduce(self.spec, ens, self.idx[chosen], grid, kept, final_pars[:, good],
                               self.model_pars[:, chosen], self.refs[chosen], self.senses))
        return [_failed_row(self.spec, self.indices[cols_group[j]], *failed[j]) if j in failed else next(reduced)
                for j in range(len(cols_group))]


def _batch_ok(b: batch.Batch, n_grid: int) -> bool:
    """A batch whose rows are taken as they are: every lane ran to the end of the grid."""
    return b.complete(n_grid)


def _failed_row(spec: SweepSpec, index: int, outcome: str, t_stop: float) -> dict:
    row = {"idx": index, **{f"in_{k}": v for k, v in spec.point(index).items()}, "outcome": outcome,
           "t_stop": t_stop, "energy_drift_vs_terms": math.nan}
    for name in spec.record:
        row[name] = math.nan
    return row


def _reduce(spec: SweepSpec, ens: Ensemble, indices, grid, samples, final_pars, model_pars, refs, senses) -> list:
    """The rows of lanes that ran to their end, from their samples (states, lanes, grid) at once; a lane
    that breaks a guard (:meth:`verify.engine.ensemble.Ensemble.guard`) gets a failed row; ``senses``
    reads each run's samples when the spec records a sense (:func:`run_chunk`)."""
    reason = ens.record(final_pars, "reason").astype(int)
    stopped = reason != 0
    t_stop = ens.record(final_pars, "t_stop")
    kept = np.where(stopped, np.maximum(1, np.searchsorted(grid, t_stop, side="right")), len(grid))
    friction = ens.record(final_pars, "friction") if spec.slips else None
    guarded = ens.guard(grid, samples, model_pars, stopped, t_stop, spec.theta_stop, friction)
    rows = [None] * len(indices)
    for k, failure in enumerate(guarded):
        if failure is not None:
            rows[k] = _failed_row(spec, int(indices[k]), *failure)
    if all(r is not None for r in rows):
        return rows
    # every lane is reduced at once (a failed lane's values are not read); a run is its first kept samples
    lane = np.arange(len(indices))
    last = kept - 1
    run = np.arange(len(grid))[None, :] < kept[:, None]  # (lanes, grid)
    g = len(grid)  # samples may carry each lane's padding to whole SIMD groups (Ensemble.sample_row)
    with np.errstate(invalid="ignore"):
        diag = batch.per_lane(ens.energy_terms, samples[:8], model_pars, kept)
        omega_z, terms = diag[0], diag[1:]
        energy, scale = terms.sum(axis=0)[:, :g], np.abs(terms).sum(axis=0)[:, :g]
        work = samples[ens.lanes.row("W"), :, :g] if "W" in ens.lanes.states else 0.0
        drift = (np.where(run, np.abs(energy + work - energy[:, :1]), -np.inf).max(axis=1)
                 / np.where(run, scale, -np.inf).max(axis=1))
        th = samples[TH, :, :g]
        q = {"max_theta": np.where(run, th, -np.inf).max(axis=1), "min_theta": np.where(run, th, np.inf).min(axis=1),
             "max_theta_deviation": np.where(run, np.abs(th - refs[:, None]), -np.inf).max(axis=1)}
        # the state at the end: the last sample (at t_end), or for a run a terminal event stopped, the state
        # the event recorded at t_stop (its samples end at the last grid time before)
        for i, name in enumerate(STATE_NAMES):
            q[f"final_{name}"] = np.where(stopped, ens.record(final_pars, f"{name}_at_stop"), samples[i, lane, last])
        if "max_friction_required_on_grid" in spec.record:  # NaN where N <= 0 (fmax skips it); the slip itself
            # is between samples: a run that slipped needed its coefficient at t_slip, more than any sample before
            need = batch.per_lane(ens.friction_required, samples[:8], model_pars, kept)[:, :, :g]
            need = np.where(run & (need[0] > 0), need[1], np.nan)
            q["max_friction_required_on_grid"] = np.fmax.reduce(need, axis=1)
    wanted = set(spec.record) & set(SENSE_KEYS)  # only where asked: the windows cost a filter each
    points = spec.columns(np.asarray(indices, dtype=np.int64))
    for k in np.flatnonzero([r is None for r in rows]):
        index = int(indices[k])
        point = {name: float(column[k]) for name, column in points.items()}
        stop = float(t_stop[k]) if stopped[k] else spec.t_end
        row = {"idx": index, **{f"in_{a}": v for a, v in point.items()},
               "outcome": "ok" if not stopped[k] else ens.event_name(reason[k]), "t_stop": stop,
               "energy_drift_vs_terms": float(drift[k])}
        values = {name: column[k] for name, column in q.items()}
        if friction is not None:
            slipped = row["outcome"] == "slips"
            values.update(slipped=float(slipped), t_slip=stop if slipped else math.nan,
                          theta_at_slip=ens.record(final_pars, "theta_at_stop")[k] if slipped else math.nan)
        if "tilt" in point:
            values["growth"] = values["max_theta_deviation"] / point["tilt"]
        if wanted:
            values.update(senses(grid[: kept[k]], samples[:, k, : kept[k]].T, omega_z[k, : kept[k]]))
        for name in spec.record:
            row[name] = float(values[name])
        rows[k] = row
    return rows
