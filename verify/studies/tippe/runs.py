"""The tippe top run under the smooth friction law and under exact Coulomb friction, and what each ends in.

Every start is the standard one of :mod:`.theory`: tilt theta0 = 0.1 rad, spin n about the axis
(theta-dot = phi-dot = 0, psi-dot = n), the centre of mass at rest (``velocity = (0, 0)``: the contact
slips at |omega x r_P| = n R sin theta0 at t = 0), friction mu = 0.3, g = 980 (R = 1 cm).

**What "inverts" rests on**:

* ``t_theta``: the first output time where theta (the state) exceeds :data:`THETA_INVERTED` = 2.5 rad;
* ``t_height``: the first output time where the height of C, evaluated by the model's own z_C expression
  (heyoka cfunc of the state), is within :data:`HEIGHT_MARGIN` = 0.01 R of its inverted value R + c.  For a
  sphere z_C = R - c cos(theta) is a function of theta alone, so this is *not* an independent measure of the
  motion (it checks the compiled z_C against theta, and always comes after ``t_theta``); the independent
  route is the energy: a run settled at a minimum theta* of V_lambda has lost to friction exactly
  E0 - V_lambda(theta*), the work quadrature W (a state of the run) against the closed form of :mod:`.theory`.

* ``t_spin``, the second measure, computed from the rates and not from the tilt: the first output time where the
  angle gamma between the angular momentum about C and the body's axis, cos(gamma) = L_C . e3 / |L_C| =
  I3 omega3 / sqrt(I1^2 (thetadot^2 + phidot^2 sin^2 theta) + I3^2 omega3^2), omega3 = psidot + phidot cos theta,
  exceeds the same 2.5 rad (:func:`spin_axis_angle`).  It is the classical signature of the inversion: L_C stays
  near the vertical (friction turns it slowly) while the body's axis turns over, so the spin about the axis,
  omega3, reverses against L_C.  It is a function of theta and the rates together; theta alone does not give it
  (at the tilted steady motions gamma is not theta: :func:`.theory.steady_spin_axis_angle`, 2.06 rad where
  theta = 1.837 for n = 100).

The verdict ``inverts`` needs theta and gamma both past 2.5 rad over the run's last tenth (and ``t_height``); when
one measure says inverted and the other does not, the verdict is ``disagree`` (naming which); ``turning`` has
passed 2.5 rad but not settled by the end; ``upright`` is a last tenth below 0.5 rad; anything else ends
``tilted`` at the mean theta of the last tenth.  The work done by friction is checked too: a run that has settled at a minimum of
V_lambda has lost exactly E0 - V_lambda(theta*) (:mod:`.theory`).  Exact Coulomb runs
(:func:`verify.engine.hybrid.solve`) are read the same way, with their phases (slides, sticks, rolls).
"""
from __future__ import annotations

import numpy as np
import sympy as sp

from models import get_model
from models.symbols import STATE

from ...engine import hybrid, smooth
from . import theory

#: theta beyond which the top counts as turned over (rad), and the margin of C's inverted height (units of R)
THETA_INVERTED = 2.5
HEIGHT_MARGIN = 0.01
START_TILT = "0.1"
FRICTION = "0.3"


def _first(t, mask):
    idx = np.flatnonzero(mask)
    return float(t[idx[0]]) if len(idx) else None


def spin_axis_angle(y, params) -> np.ndarray:
    """gamma, the angle between L_C and the body's axis e3 (rad), on 8-row (or longer) states: the second measure."""
    th, thd, phd, psd = (np.asarray(y[i], dtype=float) for i in (0, 3, 4, 5))
    I1, I3 = float(params["I1"]), float(params["I3"])
    w3 = psd + phd * np.cos(th)
    return np.arccos(np.clip(I3 * w3 / np.sqrt(I1 ** 2 * (thd ** 2 + (phd * np.sin(th)) ** 2) + (I3 * w3) ** 2), -1, 1))


def measures(t, theta, height, top: theory.Top, gamma=None) -> dict:
    """The inversion times by both measures, the end tilt (mean over the last tenth of the outputs) and the
    verdict; ``gamma`` (:func:`spin_axis_angle`) the second measure."""
    t = np.asarray(t, dtype=float)
    theta = np.asarray(theta, dtype=float)
    height = np.asarray(height, dtype=float)
    gamma = np.asarray(gamma, dtype=float)
    inverted_height = float(top.R + top.c)
    t_theta = _first(t, theta > THETA_INVERTED)
    t_height = _first(t, height >= inverted_height - HEIGHT_MARGIN * float(top.R))
    t_spin = _first(t, gamma > THETA_INVERTED)
    n_tail = max(len(theta) // 10, 1)
    tail, gamma_tail = theta[len(theta) - n_tail:], gamma[len(gamma) - n_tail:]
    end = float(np.mean(tail))
    by_theta = t_theta is not None and t_height is not None and tail.min() > THETA_INVERTED
    by_spin = t_spin is not None and gamma_tail.min() > THETA_INVERTED
    if by_theta and by_spin:
        verdict = "inverts"
    elif by_theta or by_spin:
        verdict = "disagree:" + ("theta inverted, gamma not" if by_theta else "gamma inverted, theta not")
    elif t_theta is not None:
        verdict = "turning"  # passed 2.5 rad, not yet settled inverted at the end of the run
    elif tail.max() < 0.5:
        verdict = "upright"
    else:
        verdict = "tilted"
    return {"t_theta": t_theta, "t_height": t_height, "t_spin": t_spin, "end_theta": end,
            "end_spread": float(tail.max() - tail.min()), "end_gamma": float(np.mean(gamma_tail)),
            "max_theta": float(theta.max()), "verdict": verdict}


def _stopped(m: dict, outcome: str) -> dict:
    """A run stopped by an event before t_end (contact lost, the rows jam, the axis vertical) gets no verdict of
    its motion: its verdict says where it stopped."""
    return m if outcome == "ok" else {**m, "verdict": f"stopped:{outcome}"}


def smooth_case(body: str, spin, eps, t_end="40", n_eval: int = 4001, precision: str = "double") -> dict:
    """One smooth-law run of the standard start: measures, E + W and Jellett's drift (in eps), steps."""
    top = theory.top(body)
    sol = smooth.solve(body, t_end, {"theta": START_TILT, "psidot": str(spin)}, friction=FRICTION, slip_scale=str(eps),
                       velocity=("0", "0"), n_eval=n_eval, precision=precision)
    return {"body": body, "law": "smooth", "spin": float(spin), "eps": float(eps), "t_end": float(t_end),
            "outcome": sol.outcome, "steps": sol.steps,
            **_stopped(measures(sol.t, sol["theta"], sol.height, top, spin_axis_angle(sol.y, sol.params)), sol.outcome),
            "energy_plus_work_in_eps": sol.energy_plus_work_drift_in_eps, "jellett_in_eps": sol.jellett_drift_in_eps,
            "end_slip": float(np.max(sol.slip_speed[-max(len(sol.t) // 10, 1):])),
            "min_theta": float(np.min(np.asarray(sol["theta"], dtype=float))),
            "work": float(sol.work[-1]), "energy0": float(sol.energy[0])}


def coulomb_case(body: str, spin, t_end="5", n_eval: int = 1001) -> dict:
    """One exact-Coulomb run (the hybrid) of the standard start: phases, measures, E + W and Jellett (in eps)."""
    top = theory.top(body)
    sol = hybrid.solve(f"body:{body}+coulomb", t_end, {"theta": START_TILT, "psidot": str(spin)}, friction=FRICTION,
                       velocity=("0", "0"), n_eval=n_eval)
    theta = np.asarray(sol["theta"], dtype=float)
    height = float(top.R) - float(top.c) * np.cos(theta)  # z_C = R - c cos(theta) (models.profiles, sphere)
    return {"body": body, "law": "coulomb", "spin": float(spin), "t_end": float(t_end), "outcome": sol.outcome,
            "steps": sol.steps, "phases": [(p.kind, float(p.t_start), float(p.t_end), p.ended) for p in sol.phases],
            **_stopped(measures(sol.t, theta, height, top, spin_axis_angle(sol.y, sol.params)), sol.outcome),
            "energy_plus_work_in_eps": sol.energy_plus_work_drift_in_eps,
            "jellett_in_eps": jellett_drift_in_eps(body, sol.y, sol.params), "min_theta": float(theta.min())}


def jellett_drift_in_eps(body: str, y, params) -> float:
    """max |lambda - lambda(0)| over eps (double) times lambda's term scale up to each output, on 8-row states."""
    model = get_model(f"body:{body}")
    expr = next(i.expr for i in model.invariants if i.name == "jellett")
    values = {p.symbol: float(params[p.name]) for p in model.parameters}
    terms = sp.Add.make_args(sp.expand(expr.subs(values)))
    f = sp.lambdify(STATE, [expr.subs(values)] + list(terms), "numpy")
    rows = [np.asarray(r, dtype=float) for r in y]
    out = [np.broadcast_to(np.asarray(v, dtype=float), rows[0].shape) for v in f(*rows)]
    lam = out[0]
    scale = np.maximum.accumulate(np.sum(np.abs(np.array(out[1:])), axis=0))
    return float(np.max(np.abs(lam - lam[0]) / (scale * np.finfo(float).eps)))


#: the spins of the study (s^-1): below the energy bound, between it and n_s, and above n_s (theta0 = 0.1)
SPINS = (50, 100, 200)
#: the slip scales of the inversion-time scan (in R/s; the start slips at n R sin(0.1) = 20 R/s at n = 200)
SCALES = (0.03, 0.1, 0.3, 1, 3, 10, 30, 100)


def study(quick: bool = False) -> dict:
    """Every run of the tippe-top study and the theory it is checked against (``quick``: fewer slip scales,
    shorter runs; the verdicts are the same)."""
    shipped, stable, hanging = theory.top("tippe-top"), theory.top("tippe-top-stable"), theory.top("tippe-top-hanging")
    thresholds = {t.name: theory.thresholds(t, START_TILT) for t in (shipped, stable, hanging)}
    scales = (1, 10) if quick else SCALES
    t_long = "10" if quick else "40"
    runs = []
    for eps in scales:  # the inversion time against eps, above n_s
        runs.append(smooth_case("tippe-top", 200, eps, "60" if eps < 0.1 else t_long))
    for spin in (50, 100):  # below n_E, and between n_E and n_s: the negative controls on the spin
        runs.append(smooth_case("tippe-top", spin, 10, t_long))
    runs.append(smooth_case("tippe-top-stable", 200, 10, t_long))  # the negative control on the inertia
    runs.append(smooth_case("tippe-top-hanging", 200, 10, t_long))
    coulomb = [coulomb_case(b, s, "2" if quick else "5") for b, s in
               (("tippe-top", 200), ("tippe-top", 100), ("tippe-top-stable", 200))]
    predictions = {}
    for r in runs + coulomb:
        key = f"{r['body']}@{r['spin']:g}"
        if key not in predictions:
            p = theory.predict(theory.top(r["body"]), str(int(r["spin"])), START_TILT)
            predictions[key] = {"verdict": p["verdict"], "theta": None if p["theta"] is None else float(p["theta"]),
                                "gamma": None if p["theta"] is None else float(theory.steady_spin_axis_angle(
                                    theory.top(r["body"]), p["theta"], p["lambda"])),
                                "reach": [float(x) for x in p["reach"]], "lambda": float(p["lambda"]),
                                "energy": float(p["energy"]), "V_pi": float(p["V_pi"])}
    return {"thresholds": {k: {"energy_bound": _f(v.energy_bound), "inverted_minimum": _f(v.inverted_minimum),
                               "upright_unstable": _f(v.upright_unstable),
                               "exact": {a: str(b) for a, b in v.exact.items()}} for k, v in thresholds.items()},
            "groups": {t.name: {"ratio": float(t.ratio), "window": [float(w) for w in t.window], "group": t.group}
                       for t in (shipped, stable, hanging)},
            "smooth": runs, "coulomb": coulomb, "predictions": predictions}


def _f(x):
    return None if x is None else float(x)


def expected_verdict(prediction: str) -> str:
    """The run verdict a prediction of :func:`theory.predict` stands for."""
    return {"inverted": "inverts", "tilted": "tilted", "upright": "upright"}.get(prediction, "?")


def text(result: dict) -> str:
    """The study as a table (what ``python -m verify tippe-top`` prints)."""
    lines = []
    for name, th in result["thresholds"].items():
        grp = result["groups"][name]
        ns = "never" if th["inverted_minimum"] is None else f"{th['inverted_minimum']:.6f}"
        nu = "never" if th["upright_unstable"] is None else f"{th['upright_unstable']:.6f}"
        lines.append(f"{name}: I1/I3 = {grp['ratio']:.4g}, window ({grp['window'][0]:.3g}, {grp['window'][1]:.3g}): "
                     f"{grp['group']}")
        lines.append(f"  theta0 = {START_TILT}: energy bound n_E = {th['energy_bound']:.6f} s^-1, inverted spin a minimum "
                     f"above n_s = {ns}, upright spin unstable above n_u = {nu}")
    lines.append("")
    lines.append("predicted: by Jellett's integral and the energy (the only minimum of V_lambda within the start's reach), "
                 "for a law under which the contact slips until the motion is steady")
    lines.append("law      body               spin    eps   verdict  (predicted)   t(theta>2.5)  t(z_C>R+c-0.01)  "
                 "t(gamma>2.5)  end theta  end gamma (steady)  min theta   E+W [eps]  Jellett [eps]  steps")
    for r in result["smooth"] + result["coulomb"]:
        p = result["predictions"][f"{r['body']}@{r['spin']:g}"]
        pred = p["verdict"] + (f" {p['theta']:.4f}" if p["verdict"] == "tilted" else "")
        eps = f"{r['eps']:g}" if r["law"] == "smooth" else "-"
        fmt = (lambda x: "-" if x is None else f"{x:.3f}")
        steady = "" if p.get("gamma") is None else f"({p['gamma']:.4f})"
        lines.append(f"{r['law']:8} {r['body']:18} {r['spin']:5g} {eps:>6}  {r['verdict']:8} ({pred:15}) "
                     f"{fmt(r['t_theta']):>12}  {fmt(r['t_height']):>15}  {fmt(r['t_spin']):>12}  {r['end_theta']:9.4f}  "
                     f"{r['end_gamma']:9.4f} {steady:>9}  {r['min_theta']:9.2g}  "
                     f"{r['energy_plus_work_in_eps']:9.3g}  {r['jellett_in_eps']:13.3g}  {r['steps']:6d}")
        if r["law"] == "coulomb":
            phases = ", ".join(f"{k} {a:.4g}-{b:.4g} s ({e})" for k, a, b, e in r["phases"])
            lines.append(f"{'':9}phases: {phases}; theta stays in [{r['min_theta']:.4f}, {r['max_theta']:.4f}]")
    return "\n".join(lines)


__all__ = ["FRICTION", "HEIGHT_MARGIN", "SCALES", "SPINS", "START_TILT", "THETA_INVERTED", "coulomb_case",
           "expected_verdict", "jellett_drift_in_eps", "measures", "smooth_case", "spin_axis_angle", "study", "text"]
