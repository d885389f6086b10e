"""Run one chunk of a sweep: heyoka batch integrators over an ensemble of threads, then reductions.

The full state (theta, phi, psi, thetadot, phidot, psidot, x, y), plus the work W of a
dissipative term when the model has one, is integrated in double by
``ensemble_propagate_grid_batch``: SIMD lanes within a batch integrator, batches on threads.
Parameters are runtime ``par[i]`` (the model's, in model order, then four per-lane
bookkeeping values: alive, reason, t_stop, theta_stop), so one compiled integrator serves
every point of every sweep of the model.

Terminal events in batch mode (as in :mod:`verify.studies.maps`): heyoka 7.13 stops the whole
batch when one lane's terminal event fires, so the events here return "continue" and freeze
their own lane instead -- alive = 0 multiplies every right-hand side (x * 1.0 = x exactly
for live lanes), the reason and the time are recorded in the lane's parameters, and the
lane is moved to the middle of the model's domain (thetadot = psidot = 0, phidot = 1: a rocking
rate of exactly 0 would put |omega_perp| on the singular point of its square root) so that a
frozen lane never sits on a singular configuration.  Samples after a lane's stop time are discarded by the
reductions.  The events: the model's domain ends, the optional ``[stop] theta_below``, and
the loss of contact (N = 0) where the model has a contact.

Every point's result depends on its own inputs only (lanes do not interact; their step sizes
are their own), so a chunk gives the same rows in any process, on threads or on a Dask
worker, whatever ran before it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import heyoka as hy
import mpmath
import numpy as np
import sympy as sp

from models import get_model
from models.ring_dissipation import annulus_inertia
from models.symbols import STATE, STATE_NAMES, phidot, psidot, theta

from ..circling import circling, theta_maxima
from ..compile import to_heyoka
from ..lanes import simd_width
from .spec import SENSE_KEYS, SweepSpec

EXTRA = ("alive", "reason", "t_stop", "theta_stop")
WINDOWS = 20  # a run without nutation is read over 20 equal windows
NUTATIONS_PER_WINDOW = 12  # otherwise over windows of 12 nutations (see orbit_windows)
NUTATION_FLOOR = 1e-9  # rad: a theta spread below this is no nutation
TH, PH, PS, THD, PHD, PSD, X, Y = range(8)


@dataclass(frozen=True)
class System:
    """A model's batch system with freezing and its reductions, compiled once per process."""

    model: str
    events: tuple  # event names, reason code = index + 1
    n_model_pars: int
    n_states: int  # 8, or 9 with W
    safe_theta: float
    template: object  # taylor_adaptive_batch
    diagnostics: object  # cfunc: (omega_z, the energy's additive terms...) of the state


class _Freeze:
    """Terminal-event callback: freeze this lane, record why and when, let the batch run on."""

    def __init__(self, n_model_pars: int, code: int, safe_theta: float):
        self.n, self.code, self.safe = n_model_pars, float(code), safe_theta

    def __call__(self, ta, d_sgn, lane):
        n, pars, state = self.n, ta.pars, ta.state
        if pars[n, lane] == 0.0:  # already frozen: two events in one step
            return True
        pars[n, lane] = 0.0
        pars[n + 1, lane] = self.code
        pars[n + 2, lane] = ta.time[lane]
        state[TH, lane] = self.safe
        state[THD, lane] = state[PSD, lane] = 0.0
        state[PHD, lane] = 1.0  # not 0: |omega_perp| terms (sqrt) have no Taylor series at 0
        return True


@lru_cache(maxsize=None)
def system(model_name: str, batch_size: int, cooldown: float) -> System:
    model = get_model(model_name)
    variables = list(hy.make_vars(*STATE_NAMES))
    mapping = dict(zip(STATE, variables))
    n = len(model.parameters)
    mapping.update({p.symbol: hy.par[i] for i, p in enumerate(model.parameters)})
    alive, theta_stop = hy.par[n], hy.par[n + 3]
    rhs = [to_heyoka(r, mapping) * alive for _, r in model.rhs()]
    sys_ = list(zip(variables, rhs))
    if model.dissipation is not None:
        W = hy.make_vars("W")
        sys_.append((W, to_heyoka(model.dissipation, mapping) * alive))
        variables.append(W)
    th = variables[0]
    dom = model.domain
    lo, hi = float(dom.theta_min), float(dom.theta_max)
    exprs = [(dom.below, th - lo, hy.event_direction.negative), (dom.above, th - hi, hy.event_direction.positive),
             ("theta_stop", th - theta_stop, hy.event_direction.negative)]
    if model.normal_force is not None:
        exprs.append(("contact_lost", to_heyoka(model.normal_force, mapping), hy.event_direction.negative))
    safe = 0.5 * (lo + hi)
    events = [hy.t_event_batch(ex, direction=d, callback=_Freeze(n, i + 1, safe), cooldown=cooldown)
              for i, (_, ex, d) in enumerate(exprs)]
    state = np.zeros((len(variables), batch_size))
    state[TH] = safe
    pars = np.zeros((n + len(EXTRA), batch_size))
    pars[:n] = np.array([float(sp.N(p.default)) for p in model.parameters])[:, None]
    pars[n] = 1.0
    template = hy.taylor_adaptive_batch(sys_, state, pars=pars, t_events=events)
    energy = model.energy
    omega_z = phidot + psidot * sp.cos(theta)
    fmap = dict(zip(STATE, variables[:8]))
    fmap.update({p.symbol: hy.par[i] for i, p in enumerate(model.parameters)})
    terms = sp.Add.make_args(sp.expand(energy))  # the drift is judged against the sum of their magnitudes
    diag = hy.cfunc([to_heyoka(omega_z, fmap)] + [to_heyoka(t, fmap) for t in terms], variables[:8])
    return System(model_name, tuple(e[0] for e in exprs), n, len(variables), safe, template, diag)


# --- inputs of a chunk ---------------------------------------------------------------------------

def lane_inputs(spec: SweepSpec, indices) -> tuple:
    """(states (8, n), model parameters (n_pars, n), theta_ref (n)) of the points ``indices``.

    theta_ref is the start's theta before any tilt: the steady angle for ``[start] steady``.
    """
    from ..integrate import resolve_parameters
    from ..precision import parse_precision

    model = get_model(spec.model)
    prec = parse_precision("double")
    states, pars, refs = [], [], []
    for i in indices:
        point = spec.point(i)
        values = {**spec.params, **{k: v for k, v in point.items() if k in spec.params or k not in STATE_NAMES}}
        values.pop("tilt", None)
        if spec.geometry == "annulus":
            hh, ww = values.get("h"), values.pop("w")
            i1, i3 = annulus_inertia(hh, ww)
            values.update(I1=i1, I3=i3)
            if "w" in model.parameter_names:
                values["w"] = ww
        resolved = resolve_parameters(model, {k: repr(float(v)) for k, v in values.items()}, prec)
        start = {**spec.start, **{k: v for k, v in point.items() if k in STATE_NAMES}}
        ref = start.get("theta", 0.0)
        if spec.steady is not None:
            steady = _steady(spec.model, spec.steady, point, {k: repr(float(v)) for k, v in values.items()})
            start.update(steady)
            ref = steady["theta"]
        y = np.zeros(8)
        for k, v in start.items():
            y[STATE_NAMES.index(k)] = v
        y[TH] = ref + point.get("tilt", 0.0)
        states.append(y)
        pars.append([float(v) for v in resolved.values()])
        refs.append(ref)
    return np.array(states).T, np.array(pars).T, np.array(refs)


def _steady(model: str, motion: str, point: dict, params: dict) -> dict:
    from ..studies.thresholds import steady_state
    from .spec import RATE_AXIS

    s = steady_state(model, motion, repr(float(point[RATE_AXIS[motion]])), params)
    with mpmath.workdps(40):
        return {k: float(mpmath.mpf(v)) for k, v in s.items()}


def fastest_rate(spec: SweepSpec) -> float:
    """The largest initial rate over the whole sweep (or sqrt(g)): the step cap is 1 / it, as in solve()."""
    rates = [abs(spec.start.get(n, 0.0)) for n in ("thetadot", "phidot", "psidot")]
    for a in spec.axes:
        if a.name in ("thetadot", "phidot", "psidot"):
            rates += [abs(v) for v in a.values]
    g = spec.params.get("g", 980.0)
    for a in spec.axes:
        if a.name == "g":
            g = max(a.values)
    return max(rates + [math.sqrt(g)])


# --- a chunk ---------------------------------------------------------------------------------------

def run_chunk(spec: SweepSpec, chunk: int, threads: int = 1, batch_size: int = None) -> list:
    """The rows of chunk ``chunk``: one dict per point with its inputs, outcome and quantities."""
    indices = list(spec.chunk_points(chunk))
    if not indices:
        raise ValueError(f"chunk {chunk} is outside the sweep's {spec.n_chunks} chunks")
    bs = batch_size or simd_width()
    cooldown = 2.0 * spec.t_end + 1.0
    sysm = system(spec.model, bs, cooldown)
    states, model_pars, refs = lane_inputs(spec, indices)
    n = len(indices)
    padded = -(-n // bs) * bs
    idx = np.minimum(np.arange(padded), n - 1)
    lane_states = np.zeros((sysm.n_states, padded))
    lane_states[:8] = states[:, idx]
    lane_pars = np.zeros((sysm.n_model_pars + len(EXTRA), padded))
    lane_pars[: sysm.n_model_pars] = model_pars[:, idx]
    lane_pars[sysm.n_model_pars] = 1.0
    lane_pars[sysm.n_model_pars + 2] = np.nan
    lane_pars[sysm.n_model_pars + 3] = spec.theta_stop if spec.theta_stop is not None else -1.0
    grid = np.linspace(0.0, spec.t_end, spec.samples)

    def gen(ta, i):
        cols = slice(i * bs, (i + 1) * bs)
        ta.set_time(0.0)
        ta.state[:] = lane_states[:, cols]
        ta.pars[:] = lane_pars[:, cols]
        return ta

    results = hy.ensemble_propagate_grid_batch(sysm.template, grid, padded // bs, gen, max_workers=max(1, threads),
                                               max_delta_t=1.0 / fastest_rate(spec))
    rows = []
    for b, res in enumerate(results):
        local, out = res[0], res[-1]
        outcomes = [r[0] for r in local.propagate_res]
        if any(o != hy.taylor_outcome.time_limit for o in outcomes) or out.shape[0] != len(grid):
            raise RuntimeError(f"chunk {chunk}, batch {b} of sweep {spec.name!r} failed: {outcomes}")
        for lane in range(bs):
            k = b * bs + lane
            if k >= n:
                break
            rows.append(_reduce(spec, sysm, indices[k], grid, out[:, :, lane], local.pars[:, lane],
                                model_pars[:, k], refs[k]))
    return rows


def _reduce(spec: SweepSpec, sysm: System, index: int, grid, samples, lane_pars, model_pars, ref) -> dict:
    """One point's row from its dense output (samples: (n_grid, n_states))."""
    n = sysm.n_model_pars
    reason = int(lane_pars[n + 1])
    t_stop = float(lane_pars[n + 2]) if reason else spec.t_end
    keep = grid <= t_stop if reason else np.ones(len(grid), bool)
    keep[0] = True
    y = samples[keep]
    t = grid[keep]
    diag = sysm.diagnostics(np.ascontiguousarray(y[:, :8].T), pars=np.ascontiguousarray(
        np.repeat(model_pars[:sysm.diagnostics.nparams, None], len(t), axis=1)))
    omega_z, terms = diag[0], diag[1:]
    energy, scale = terms.sum(axis=0), np.abs(terms).sum(axis=0)
    work = y[:, 8] if sysm.n_states > 8 else 0.0
    drift = float(np.max(np.abs(energy + work - energy[0])) / np.max(scale))
    row = {"idx": index, **{f"in_{k}": v for k, v in spec.point(index).items()},
           "outcome": "ok" if not reason else sysm.events[reason - 1], "t_stop": t_stop, "energy_drift_vs_terms": drift}
    th = y[:, TH]
    q = {"max_theta": th.max(), "min_theta": th.min(), "final_theta": th[-1],
         "max_theta_deviation": np.max(np.abs(th - ref))}
    if "tilt" in spec.point(index):
        q["growth"] = q["max_theta_deviation"] / spec.point(index)["tilt"]
    for i, name in enumerate(STATE_NAMES):
        q[f"final_{name}"] = y[-1, i]
    if set(spec.record) & set(SENSE_KEYS):  # only where asked: the windows cost a filter each
        q.update(senses(t, y, omega_z))
    for name in spec.record:
        row[name] = float(q[name])
    return row


def orbit_windows(t, theta) -> list:
    """Index slices of the windows a run's senses are read over.

    A run that nutates is cut half-way between successive maxima of theta into windows of
    :data:`NUTATIONS_PER_WINDOW` nutations (the remainder spread evenly, so each window holds
    N to 2N - 1), less than a nutation and a half at either end left out.  Counting nutations
    rather than seconds keeps the filters of :mod:`verify.circling` the same in every window
    although the nutation period of a decaying ring shrinks fourfold (0.2-0.3 s at the start,
    0.05 s at theta = 0.1) and the period within one window stays nearly constant (the
    running mean uses one period per window).  A run whose theta does not move (no nutation)
    is cut into :data:`WINDOWS` equal windows instead.  Fewer than two windows: [].
    """
    t, theta = np.asarray(t, float), np.asarray(theta, float)
    if len(t) < 2:
        return []
    if np.ptp(theta) < NUTATION_FLOOR:
        if len(t) < 2 * WINDOWS:
            return []
        edges = np.linspace(0, len(t) - 1, WINDOWS + 1).round().astype(int)
        return [slice(a, b + 1) for a, b in zip(edges[:-1], edges[1:])]
    marks = theta_maxima(t, theta)
    cuts = 0.5 * (marks[:-1] + marks[1:])  # len(marks) - 1 cuts hold len(marks) - 2 whole nutations
    k = (len(cuts) - 1) // NUTATIONS_PER_WINDOW
    if k < 2:
        return []
    at = np.searchsorted(t, cuts[np.linspace(0, len(cuts) - 1, k + 1).round().astype(int)])
    return [slice(a, b + 1) for a, b in zip(at[:-1], at[1:])]


def senses(t, y, omega_z) -> dict:
    """The sense of the orbit (the slow path of the centre of mass) and of the spin, window by window.

    ``orbit`` is the sense in which the CM's *slow path* circles -- the path left when the
    nutation loops are filtered out -- read by :func:`verify.circling.circling` in each window of
    :func:`orbit_windows` by two measures that share nothing but the run (the CM once per
    nutation, its winding; the CM averaged over a nutation, its swept area).  A window's orbit
    sense is +1/-1 only where both measures decide (half a turn or more) with the same sign, and
    0 (undecided) otherwise: neither measure is preferred.  The nutation loops themselves -- and
    with them the turning of the line of nodes e1 -- do not enter.

    ``spin`` is the sign of the mean of omega . Z = phidot + psidot cos(theta) over a window.
    A decided window is prograde when its orbit goes with its own spin, retrograde when against.

    * ``orbit_start``/``orbit_end``: orbit sense in the first/last window that decides (NaN: none
      does); ``t_orbit_start``/``t_orbit_end`` where those windows begin/end; ``orbit_last`` the
      sense in the run's last window (0: the end state is not read);
    * ``orbit_reversal`` = 1 when a later decided window has the sense opposite to the first one
      (``t_orbit_reversal``: the start of the first such window), 0 when none has, NaN when fewer
      than two windows decide;
    * ``spin_start``/``spin_end``: the spin in the run's first/last window;
    * ``retrograde_turn``: the run ends against its spin after starting with it.  1 when the run's
      last window decides and is retrograde and the first window that decides is prograde; 0 when
      the last window decides and is prograde, or it and the run's first window are both
      retrograde; NaN otherwise (the end state, or the start before it, is not read);
    * ``retrograde_by_last_read``: the same with the last window that decides standing for the
      end (what the slow path shows as far as it can be read; NaN when fewer than two decide);
      ``retrograde_end``: that window is retrograde; ``t_retrograde``: start of the first
      retrograde decided window after a prograde first one;
    * ``windows``, ``windows_undecided``; ``strobe_last``/``mean_last``: the two measures (turns)
      in the run's last window, to show how they disagree when they do; ``points_per_nutation``:
      the output grid's resolution of the shortest nutation period in the run;
    * ``node_turn_*``: the former reading, the sign of phi(end) - phi(start) in the first/last window
      (it counts the turning of e1, i.e. the loops), and ``node_retrograde_turn`` the retrograde
      turn by that reading -- kept for comparison, not used for the verdict;
    * ``path_*``: the sign of the area the raw sampled path sweeps (loops included);
      ``roll_*``: the sign of the CM's displacement along e1, the direction it rolls (when it
      reverses so does the centripetal friction force).

    Every value is NaN for a run with fewer than two windows (too few nutations to read).
    """
    wins = orbit_windows(t, y[:, TH])
    if not wins:
        return dict.fromkeys(SENSE_KEYS, math.nan)
    t = np.asarray(t, float)
    phi, x, yy, th = y[:, PH], y[:, X], y[:, Y], y[:, TH]
    orbit, spin, node, path, roll, reads = [], [], [], [], [], []
    for s in wins:
        c = circling(t[s], x[s], yy[s], th[s], nutation_floor=NUTATION_FLOOR)
        reads.append(c)
        orbit.append(c.sign)
        spin.append(int(np.sign(np.mean(omega_z[s]))))
        p = phi[s]
        node.append(int(np.sign(p[-1] - p[0])))
        xs, ys = x[s] - x[s].mean(), yy[s] - yy[s].mean()
        path.append(int(np.sign(np.sum(xs[:-1] * np.diff(ys) - ys[:-1] * np.diff(xs)))))
        roll.append(int(np.sign(np.sum(np.diff(x[s]) * np.cos(p[:-1]) + np.diff(yy[s]) * np.sin(p[:-1])))))
    start = [float(t[s][0]) for s in wins]
    decided = [i for i, o in enumerate(orbit) if o != 0]
    pro = {i: spin[i] != 0 and orbit[i] == spin[i] for i in decided}
    retro = {i: spin[i] != 0 and orbit[i] == -spin[i] for i in decided}
    nan = math.nan
    out = {"windows": float(len(wins)), "windows_undecided": float(len(wins) - len(decided)),
           "orbit_last": float(orbit[-1]), "spin_start": float(spin[0]), "spin_end": float(spin[-1]),
           "strobe_last": reads[-1].strobe.turns, "mean_last": reads[-1].mean.turns,
           "points_per_nutation": _points_per_nutation(t, reads),
           "orbit_start": nan, "orbit_end": nan, "t_orbit_start": nan, "t_orbit_end": nan,
           "orbit_reversal": nan, "t_orbit_reversal": nan, "retrograde_end": nan, "retrograde_turn": nan,
           "retrograde_by_last_read": nan, "t_retrograde": nan}
    if decided:
        first, last = decided[0], decided[-1]
        flip = next((i for i in decided if orbit[i] == -orbit[first]), None)
        turned = next((i for i in decided if retro[i]), None) if pro[first] else None
        out.update(orbit_start=float(orbit[first]), orbit_end=float(orbit[last]), t_orbit_start=start[first],
                   t_orbit_end=float(t[wins[last]][-1]), retrograde_end=float(retro[last]),
                   t_retrograde=start[turned] if turned is not None else nan)
        if len(decided) >= 2:
            out.update(orbit_reversal=float(flip is not None), t_orbit_reversal=start[flip] if flip is not None else nan,
                       retrograde_by_last_read=float(pro[first] and retro[last]))
        end = len(wins) - 1
        if end in decided and len(decided) >= 2:
            if pro[end]:
                out["retrograde_turn"] = 0.0
            elif retro[end] and pro[first]:
                out["retrograde_turn"] = 1.0
            elif retro[end] and first == 0 and retro[0]:
                out["retrograde_turn"] = 0.0  # retrograde from its first window on: no turn
    node_retro = node[0] == spin[0] and node[-1] == -spin[-1] and spin[-1] != 0
    flip_roll = next((i for i, r in enumerate(roll) if r != roll[0]), None)
    out.update(node_turn_start=float(node[0]), node_turn_end=float(node[-1]), node_retrograde_turn=float(node_retro),
               path_start=float(path[0]), path_end=float(path[-1]), path_reversal=float(path[-1] != path[0]),
               roll_start=float(roll[0]), roll_end=float(roll[-1]), roll_reversal=float(roll[-1] != roll[0]),
               t_roll_reversal=start[flip_roll] if flip_roll is not None else nan)
    return out


def _points_per_nutation(t, reads) -> float:
    """Output points in the shortest nutation period of the run's windows (NaN: no nutation)."""
    periods = [c.nutation_period for c in reads if math.isfinite(c.nutation_period)]
    return min(periods) / float(t[1] - t[0]) if periods else math.nan
