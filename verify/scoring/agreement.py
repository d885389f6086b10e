"""Score another simulator's run of a reference case: digits of agreement, energy, constraints.

Digits of agreement of component y at time t are ``-log10(|y_run - y_ref| / scale)``, with

* angles theta, phi, psi: scale pi, phi and psi compared modulo 2 pi (the difference is
  reduced to [-pi, pi]): 0 digits is the worst possible disagreement of an angle, and a tool
  that reports angles in (-pi, pi] scores as one that keeps them continuous;
* rates thetadot, phidot, psidot: one scale, the largest |rate| of the reference over the
  whole case (a per-component scale would make thetadot of a steady motion, exactly 0,
  infinitely demanding);
* positions x, y: the largest horizontal distance of C from the origin over the whole case,
  and at least 1 (lengths are in units of R, or a: a body that stays near its start is judged
  against its own size).

The scales are the case's (its stored grid from 0 to t_end), never the run's: a run's digits do not
depend on which output times it reports, and a run that stops early is judged on the same scale.

The start is checked component by component against that component's *own* scale (the largest
|value| of that component over the case, or the shared scale above where the component stays 0):
at :data:`START_TOLERANCE` = 1e-12 by default.  The reference's start is an exact decimal; a double
read from it is within 2^-53 relative, and form (b) read back to Euler angles adds a few roundings of
trigonometric functions whose condition here is O(1): 1e-12 leaves three orders of magnitude for
that and refuses a start given to 7 digits, in single precision, in other units or from another
case.  ``start_tolerance`` loosens it by request, and the verdict says by how much.

A run that stops before the case's t_end is *partial*: scored on what it covers, said in the verdict,
and never passes a ``min_digits`` (:func:`assert_scores`, ``verify score --min-digits``).

A double holds a value to about 16 digits; an error below one unit roundoff of the scale
(2^-53) is shown as ``DIGITS_RESOLVED`` = 15.95 digits, the most a run of doubles can score.

The reference at the run's times is the stored grid (agreeing digits) where every time of the run
is a grid time, otherwise the case re-integrated by this suite in quad precision (113 bits,
its own epsilon) at exactly the run's times (``verify.reference --check`` bounds that run's
error at 10^-27 or below on every case, far beyond a double).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Optional

import mpmath
import numpy as np

from .casefiles import DIRECTORY, load_set
from ..contact_geometry import CONTACT, STATE_NAMES, b_to_euler, contact_point, energy as state_energy, rotation_defect
from .runs import InvalidRun, exact_decimal, read_run

DIGITS_RESOLVED = -math.log10(2.0 ** -53)
#: A start (and, for form (b), the constraints and the rotation at t = 0) must agree with the
#: case to this fraction of each component's own scale (argued in the module's docstring).
START_TOLERANCE = 1e-12
ANGLES = ("theta", "phi", "psi")
WRAPPED = ("phi", "psi")
RATES = ("thetadot", "phidot", "psidot")


@dataclass(frozen=True)
class ComponentScore:
    """Digits of agreement of one state component over the run's times."""

    name: str
    min_digits: float
    t_min: float  # the time of the fewest digits
    median_digits: float
    final_digits: float
    scale: float
    scale_is: str

    def to_record(self) -> dict:
        return {"min_digits": round(self.min_digits, 2), "t_min": self.t_min,
                "median_digits": round(self.median_digits, 2), "final_digits": round(self.final_digits, 2),
                "scale": self.scale, "scale_is": self.scale_is}


@dataclass(frozen=True)
class Score:
    """The score of one run against one reference case (scipy-style named result).

    Attributes
    ----------
    case, model, form : str
        The case, its model, and the run's form ('euler', 'matrix' or 'quaternion').
    t : ndarray
        The run's times.
    reference_source : str
        'stored grid' or 'quad re-integration'.
    digits : dict of ndarray
        Digits of agreement of every state component at every time (see the module).
    components : dict of ComponentScore
    min_digits : float
        The fewest digits of any component at any time; ``worst`` names where.
    energy_rel_drift : float
        max |E(t) - E(t0)| / |E(t0)| of the run's own states (E from the model's expression, in double).
        For a Coulomb case this is the share of the energy friction took (and the run's own errors), not a drift.
    energy_rel_error, slip_speed_error, slip_speed_max : float or None
        Coulomb cases: max |E_run(t) - E_ref(t)| / |E_ref(0)|, with E_run from the run's own velocity, height and
        angular velocity; max | |u_run(t)| - s_ref(t) | of the contact point's slip speed (length unit per second);
        and the reference's largest slip speed at the run's times, for scale.  None for the other cases.
    switches : tuple
        Coulomb cases: the reference's switches, (kind, time) ('sliding -> rolling', ...).
    contact_height, contact_velocity : float or None
        max |z of the contact point| (length unit) and max |velocity the constraint sets to 0|
        (length unit per second) along the run; None for form (a), which holds them by construction.
    rotation_defect : float or None
        max over the run of |R^T R - I| and |det R - 1| (matrix) or | |q| - 1 | (quaternion).
    verdict : str
        One line.
    """

    case: str
    model: str
    form: str
    t: np.ndarray
    reference_source: str
    digits: dict
    components: dict
    min_digits: float
    worst: str
    energy_rel_drift: float
    contact_height: Optional[float]
    contact_velocity: Optional[float]
    rotation_defect: Optional[float]
    verdict: str = field(default="")
    t_end: float = math.nan  # the case's end time
    start_tolerance: float = START_TOLERANCE
    energy_rel_error: Optional[float] = None  # Coulomb cases: max |E_run(t) - E_ref(t)| / |E_ref(0)|
    slip_speed_error: Optional[float] = None  # Coulomb cases: max | |u_run(t)| - s_ref(t) | (length unit / s)
    slip_speed_max: Optional[float] = None  # Coulomb cases: the reference's largest slip speed over the run's times
    switches: tuple = ()  # Coulomb cases: the reference's (kind, time) of each switch

    @property
    def partial(self) -> bool:
        """True when the run stops before the case's t_end (by more than rounding: 1e-12 relative)."""
        return bool(self.t[-1] < self.t_end * (1 - 1e-12))

    def passes(self, min_digits: float) -> bool:
        """At least ``min_digits`` everywhere, over the whole case."""
        return not self.partial and self.min_digits >= min_digits

    def failure(self, min_digits: float) -> Optional[str]:
        """Why the run does not pass ``min_digits`` (one line naming the weakest component and time), or None."""
        if self.partial:
            return (f"partial run: it stops at t = {self.t[-1]:g} s, the case {self.case} runs to {self.t_end:g} s "
                    f"({self.min_digits:.1f} digits on what it covers)")
        if self.min_digits < min_digits:
            return (f"{self.min_digits:.2f} digits, below the {min_digits:g} required: the weakest is {self.worst}")
        return None

    def to_record(self) -> dict:
        def num(v):
            return None if v is None else float(f"{v:.3e}")

        return {"case": self.case, "model": self.model, "form": self.form, "points": int(len(self.t)),
                "t_first": float(self.t[0]), "t_last": float(self.t[-1]), "reference_source": self.reference_source,
                "min_digits": round(self.min_digits, 2), "worst": self.worst,
                "components": {n: c.to_record() for n, c in self.components.items()},
                "energy_rel_drift": num(self.energy_rel_drift), "contact_height": num(self.contact_height),
                "contact_velocity": num(self.contact_velocity), "rotation_defect": num(self.rotation_defect),
                "t_end_case": self.t_end, "partial": self.partial, "start_tolerance": self.start_tolerance,
                **({"energy_rel_error": num(self.energy_rel_error), "slip_speed_error": num(self.slip_speed_error),
                    "slip_speed_max": num(self.slip_speed_max),
                    "switches": [{"kind": k, "t": t} for k, t in self.switches]} if self.switches else {}),
                "verdict": self.verdict}

    def table(self) -> str:
        lines = [f"case {self.case} ({self.model}), run in form {self.form}, {len(self.t)} times from "
                 f"{self.t[0]:g} to {self.t[-1]:g} s; reference: {self.reference_source}",
                 f"{'component':<10} {'min digits':>10} {'at t':>10} {'median':>7} {'final':>7}  scale"]
        for c in self.components.values():
            lines.append(f"{c.name:<10} {c.min_digits:>10.2f} {c.t_min:>10.4g} {c.median_digits:>7.2f} "
                         f"{c.final_digits:>7.2f}  {c.scale:.4g} ({c.scale_is})")
        if self.switches:
            lines.append("the reference switches: " + ", ".join(f"{k} at t = {t:.6g}" for k, t in self.switches))
            lines.append(f"energy error max |E - E_ref| / |E_ref(0)|: {self.energy_rel_error:.2e} (the run's own E lost "
                         f"{self.energy_rel_drift:.2e} of E(0) to friction and error); slip speed error max: "
                         f"{self.slip_speed_error:.2e} (the reference's slip reaches {self.slip_speed_max:.3g})")
        else:
            lines.append(f"energy drift max |E - E(t0)| / |E(t0)|: {self.energy_rel_drift:.2e}")
        if self.contact_height is None:
            lines.append("constraints: held by construction in form (a) (not measurable)")
        else:
            lines.append(f"contact height max |z_P|: {self.contact_height:.2e}; contact velocity max: "
                         f"{self.contact_velocity:.2e}{' (the slip, where it slides)' if self.switches else ''}; "
                         f"rotation defect: {self.rotation_defect:.2e}")
        lines.append(self.verdict)
        return "\n".join(lines)


def score(run, case: str, *, directory: Path = DIRECTORY, start_tolerance: float = START_TOLERANCE) -> Score:
    """Score a run of another simulator against the reference case ``case``.

    Parameters
    ----------
    run : path or mapping
        A CSV or JSON file, or a mapping of column names to sequences, in one of the forms of
        :mod:`verify.frames` (Euler angles; rotation matrix or quaternion with the centre
        of mass's position and velocity and the inertial angular velocity).
    case : str
        A reference case (``reports/reference/index.json``).
    directory : path
        The reference set (default ``reports/reference``).
    start_tolerance : float
        How closely the run's start must match the case, as a fraction of each component's
        scale (default :data:`START_TOLERANCE`).

    Raises
    ------
    InvalidRun
        Bad or inconsistent input, named: unreadable file, wrong columns, times not increasing,
        not from 0 or beyond the case's end, a start that is not the case's, a rotation that is
        not one or a constraint violated at t = 0.
    ValueError
        An unknown case.
    """
    (record,) = load_set(directory, [case])
    model = record["model"]["name"]
    form, columns = read_run(run)
    t = columns["t"]
    if t[0] != 0:
        raise InvalidRun(f"the run starts at t = {float(t[0])!r}; case {case} starts at t = 0")
    if t[-1] > float(record["t_end"]):
        raise InvalidRun(f"the run goes to t = {float(t[-1])!r}, beyond case {case}'s t_end = {record['t_end']}")
    params = {k: float(v["decimal"]) for k, v in record["model"]["parameters"].items()}
    friction = record.get("friction")
    R = w = None
    if friction and form == "euler":
        raise InvalidRun(f"case {case} rolls and slides with Coulomb friction: give the run in form (b) (rotation "
                         "matrix or quaternion with C's position and velocity and omega): the Euler angles do not "
                         "hold the centre of mass's velocity, which sets the slip")
    if form == "euler":
        state = {n: columns[n] for n in STATE_NAMES}
    else:
        if model not in CONTACT:
            raise InvalidRun(f"form {form} is defined for the bodies on the plane ({', '.join(CONTACT)}); "
                             f"case {case} is a {model} run: give it in form euler")
        state, R, w = b_to_euler(columns)

    ref, source, extra = _reference(record, t)
    case_states = _case_states(record)
    scales = _scales(case_states)
    own = _own_scales(case_states, scales)
    height = speed = defect = None
    if form != "euler":
        defect_t = rotation_defect(R, columns)
        height_t, speed_t = contact_point(model, columns, state, w, params)
        if not defect_t[0] <= start_tolerance:
            raise InvalidRun(f"the orientation at t = 0 is not a rotation (defect {defect_t[0]:.1e}: a reflection, "
                             f"a left-handed frame, unnormalised entries, or R and q that disagree)")
        starts = [("height of the contact point", height_t[0], 0.0, 1.0)]
        skid = bool(friction and friction["initial_velocity_xy"])  # C's velocity is the case's, the contact slides
        if skid:
            starts += [(f"{c} of the centre of mass", float(columns[c][0]), float(v), scales["phidot"][0])
                       for c, v in zip(("vx", "vy"), friction["initial_velocity_xy"])]
        else:
            starts.append(("velocity of the contact point", speed_t[0], 0.0, scales["phidot"][0]))
        for what, value, wanted, scale in starts:
            if not abs(value - wanted) <= start_tolerance * scale:
                if what.endswith("centre of mass"):
                    raise InvalidRun(f"the start does not match case {case}: {what} {value!r} at t = 0, the case's "
                                     f"{wanted!r} (off by more than {start_tolerance:g} x {scale:.4g}; the contact "
                                     f"slides from the start)")
                raise InvalidRun(f"a constraint is violated at t = 0: {what} {value:.3e}, more than {start_tolerance:g} "
                                 f"x {scale:.4g} (the frame must have Z up, the plane at z = 0 and C's position and "
                                 f"velocity; see verify.frames)")
        height, speed, defect = (float(np.max(np.abs(height_t))), float(np.max(speed_t)), float(np.max(defect_t)))

    for n in STATE_NAMES:
        start = float(record["initial_state"][n])
        err = abs(_difference(n, state[n][0], start)) / own[n]
        if not err <= start_tolerance:
            raise InvalidRun(f"the start does not match case {case}: {n}(0) = {float(state[n][0])!r}, the case's {start!r} "
                             f"(off by {err:.1e} of its own scale {own[n]:.4g}, more than {start_tolerance:g}; "
                             "--start-tol loosens the check by request)")
    digits, components = {}, {}
    for n in STATE_NAMES:
        rel = np.abs(_difference(n, state[n], ref[n])) / scales[n][0]
        d = -np.log10(np.maximum(rel, 2.0 ** -53))
        digits[n] = d
        j = int(np.argmin(d))
        components[n] = ComponentScore(n, float(d[j]), float(t[j]), float(np.median(d)), float(d[-1]), *scales[n])
    worst = min(components.values(), key=lambda c: c.min_digits)
    if form == "euler":
        energy = state_energy(model, state, params)
    else:
        energy = own_energy(model, columns, R, w, params)
    energy = np.broadcast_to(energy, t.shape)
    drift = float(np.max(np.abs(energy - energy[0])) / abs(energy[0]))
    coulomb = {}
    if friction:
        coulomb = {"energy_rel_error": float(np.max(np.abs(energy - extra["energy"])) / abs(extra["energy"][0])),
                   "slip_speed_error": float(np.max(np.abs(speed_t - extra["slip_speed"]))),
                   "slip_speed_max": float(np.max(extra["slip_speed"])),
                   "switches": tuple((k, float(v)) for k, v in zip(record["switches"]["kinds"],
                                                                   record["switches"]["times"]["value"]))}
    result = Score(case, model, form, t, source, digits, components, worst.min_digits,
                   f"{worst.name} at t = {worst.t_min:g}", drift, height, speed, defect, t_end=float(record["t_end"]),
                   start_tolerance=start_tolerance, **coulomb)
    return _with_verdict(result)


def own_energy(model: str, columns: dict, R: np.ndarray, w: np.ndarray, params: dict) -> np.ndarray:
    """E per M L^2 from a form (b) run's own quantities: its velocity, height and angular velocity.

    E = |v|^2 / 2 + (I1 (w1^2 + w2^2) + I3 w3^2) / 2 + g z, with w_i = (R^T w)_i the body components
    and I1, I3 the case's moments of inertia in units of M L^2 (M the whole mass: the hurricane balls'
    2 m; the disk's I1 = k, I3 = 2 k).  Not the energy of the run's state converted to Euler angles:
    that would hide a run whose velocity or height is not the one its orientation implies.
    """
    i1, i3 = (params["k"], 2 * params["k"]) if "k" in params else (params["I1"], params["I3"])
    body = np.einsum("jin,jn->in", R, w)  # R^T w at every time
    v = np.array([columns["vx"], columns["vy"], columns["vz"]], float)
    return (0.5 * np.sum(v * v, axis=0) + 0.5 * (i1 * (body[0] ** 2 + body[1] ** 2) + i3 * body[2] ** 2)
            + params["g"] * np.asarray(columns["z"], float))


def _with_verdict(s: Score) -> Score:
    constraints = ("constraints held by construction (form euler)" if s.contact_height is None else
                   f"contact height {s.contact_height:.1e}" if s.switches else  # the contact's velocity is its slip
                   f"contact height {s.contact_height:.1e}, contact velocity {s.contact_velocity:.1e}")
    shown = f">= {DIGITS_RESOLVED:.2f} (a double's resolution)" if s.min_digits >= DIGITS_RESOLVED else f"{s.min_digits:.1f}"
    cover = (f"PARTIAL: only t in [{s.t[0]:g}, {s.t[-1]:g}] of the case's [0, {s.t_end:g}]" if s.partial
             else f"over the whole case, t in [{s.t[0]:g}, {s.t[-1]:g}]")
    start = (f"start within {s.start_tolerance:g} of each component's scale"
             + ("" if s.start_tolerance == START_TOLERANCE else f" (loosened by request from {START_TOLERANCE:g})"))
    energy = (f"energy error {s.energy_rel_error:.1e} of E(0) against the reference's, slip speed error "
              f"{s.slip_speed_error:.1e} (reference slip up to {s.slip_speed_max:.3g})" if s.switches
              else f"energy drift {s.energy_rel_drift:.1e}")
    line = (f"verdict: agrees with {s.case} to {shown} digits {cover} (fewest: {s.worst}); "
            f"{energy}; {constraints}; {start}")
    return replace(s, verdict=line)


def assert_scores(run, case: str, min_digits: float, **options) -> Score:
    """Score ``run`` and raise AssertionError (for pytest) unless it has ``min_digits`` over the whole case.

    The message names the weakest component and its time, or says the run is partial.  Returns the
    :class:`Score` when it passes.  ``options`` go to :func:`score` (``start_tolerance``, ``directory``).
    """
    result = score(run, case, **options)
    why = result.failure(min_digits)
    if why is not None:
        raise AssertionError(f"{case}: {why}. {result.verdict}")
    return result


def _difference(name: str, a, b):
    d = np.asarray(a, float) - np.asarray(b, float)
    if name in WRAPPED:
        d = np.remainder(d + np.pi, 2 * np.pi) - np.pi
    return d


def _case_states(record: dict) -> dict:
    """The case's stored state over its whole grid, as float arrays."""
    return {n: np.array([float(v) for v in record["state"][n]["value"]]) for n in STATE_NAMES}


def _scales(ref: dict) -> dict:
    """The scales of the digits, from the case's own states over its whole grid (see the module)."""
    rate = max(float(np.max(np.abs(ref[n]))) for n in RATES)
    length = max(1.0, float(np.max(np.hypot(ref["x"], ref["y"]))))
    out = {n: (math.pi, "pi") for n in ANGLES}
    out.update({n: (rate, "largest |rate| of the case") for n in RATES})
    out.update({n: (length, "largest horizontal distance of C from the origin over the case, at least 1")
                for n in ("x", "y")})
    return out


def _own_scales(ref: dict, scales: dict) -> dict:
    """Each component's own scale for the start check: its largest |value| over the case (pi for the
    wrapped angles), the shared scale where it stays at 0."""
    out = {}
    for n in STATE_NAMES:
        largest = math.pi if n in WRAPPED else float(np.max(np.abs(ref[n])))
        out[n] = largest if largest > 0 else scales[n][0]
    return out


def _reference(record: dict, t: np.ndarray) -> tuple:
    """(the reference's state at the run's times as float arrays, where it came from).

    phi and psi are reduced modulo 2 pi at 40 digits before they are rounded to doubles: a
    continuous angle of 10^3 rad holds only 13 digits after the point in a double, so reducing
    the double would cost a run that reports its angles in (-pi, pi] the digits it has.
    """
    index = {float(s): j for j, s in enumerate(record["grid"])}
    hybrid = "friction" in record
    extra_names = ("energy", "slip_speed") if hybrid else ()
    if all(float(v) in index for v in t):
        rows = [index[float(v)] for v in t]
        exact = {n: [record["state"][n]["value"][j] for j in rows] for n in STATE_NAMES}
        exact.update({n: [record["columns"][n]["value"][j] for j in rows] for n in extra_names})
        source = "stored grid"
    else:
        try:  # the quad re-integration needs the full suite; a light install (numpy, mpmath) scores grid times only
            from ..precision import parse_precision  # lazy: heyoka: the full suite only

            import sympy as sp  # lazy: the full suite only (a light install, numpy and mpmath, scores grid times)
        except ImportError as err:
            off = next(float(v) for v in t if float(v) not in index)
            raise InvalidRun(f"the run's times are not the case's grid times (t = {off!r} is not one); without "
                             f"{err.name} this install cannot re-integrate the case at other times: give the grid "
                             f"times (listed in the case file, key 'grid') or install the full suite") from None
        from ..engine.single import solve  # lazy: heyoka, the full suite only (as parse_precision above)

        quad = parse_precision("quad")
        params = {k: sp.Rational(v["exact"]) for k, v in record["model"]["parameters"].items()}
        times = [exact_decimal(float(v)) for v in t]
        if hybrid:
            sol, rows = _hybrid_reference(record, params, times, quad)
        else:
            sol = solve(record["model"]["name"], times[-1], record["initial_state"], params, precision=quad, t_eval=times)
            rows = range(len(sol.t))
        if sol.outcome != "ok" or len(rows) != len(t):
            raise RuntimeError(f"the quad re-integration of {record['name']} stopped early: {sol.outcome}")
        exact = {n: [quad.to_mpf(sol.y[i][j]) for j in rows] for i, n in enumerate(STATE_NAMES)}
        if hybrid:
            exact["energy"] = [quad.to_mpf(sol.energy[j]) for j in rows]
            exact["slip_speed"] = [quad.to_mpf(sol.slip_speed[j]) for j in rows]
        source = "quad re-integration"
    out = {}
    with mpmath.workdps(40):
        turn = 2 * mpmath.pi
        for n in STATE_NAMES:
            values = [mpmath.mpf(v) for v in exact[n]]
            if n in WRAPPED:
                values = [v - turn * mpmath.nint(v / turn) for v in values]
            out[n] = np.array([float(v) for v in values])
        extra = {n: np.array([float(mpmath.mpf(v)) for v in exact[n]]) for n in extra_names}
    return out, source, extra


def _hybrid_reference(record: dict, params: dict, times: list, quad):
    """A Coulomb case re-run by the hybrid in quad at ``times``: (the run, the index of each time's output).

    A run that switches differently from the stored reference is not its motion: that raises."""
    from ..engine.hybrid import solve as solve_hybrid  # lazy: heyoka, the full suite only
    from ..engine.hybrid_run import grid_rows, switch_kinds  # lazy: as solve_hybrid

    friction = record["friction"]
    sol = solve_hybrid(friction["model"], times[-1], record["initial_state"], params, friction=friction["mu"],
                       velocity=friction["initial_velocity_xy"], precision=quad, t_eval=times)
    kinds = switch_kinds(sol)
    if sol.outcome != "ok" or kinds != record["switches"]["kinds"][:len(kinds)]:
        raise RuntimeError(f"the quad re-integration of {record['name']} does not switch as the reference "
                           f"({kinds} against {record['switches']['kinds']}; {sol.outcome})")
    return sol, grid_rows(sol, times, quad)

