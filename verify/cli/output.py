"""What a command prints: the trajectory record, its text form, JSON without NaN, and when a finished run is no success."""
from __future__ import annotations

import json
import math

from models.catalogue import STATE_NAMES


def trajectory_record(sol) -> dict:
    """The JSON object of ``python -m verify trajectory --format json``."""
    p = sol.precision
    return {
        "model": sol.model,
        "equations": sol.equations,
        "precision": p.name,
        "params": {k: p.to_json(v) for k, v in sol.params.items()},
        "t_end": p.to_json(sol.t_end),
        "outcome": sol.outcome,
        "t": p.to_json(sol.t[-1]),
        "steps": sol.steps,
        "state": {n: p.to_json(sol.y[i, -1]) for i, n in enumerate(STATE_NAMES)},
        "invariants": {name: _drifts(p, tr) for name, tr in sol.invariants.items()},
        "friction_required": _friction(p, sol),
        "friction": None if sol.friction is None else p.to_json(sol.friction),
    }


def coulomb_record(sol, failed=None) -> dict:
    """The JSON object of a Coulomb run (``trajectory disk+coulomb|ring+coulomb``): phases, switches, E + W."""
    p = sol.precision
    return {
        "model": sol.model, "precision": p.name, "params": {k: p.to_json(v) for k, v in sol.params.items()},
        "outcome": failed.outcome if failed is not None else sol.outcome, "message": str(failed or sol.message),
        "phases": [{"kind": ph.kind, "t_start": p.to_json(ph.t_start), "t_end": p.to_json(ph.t_end), "ended": ph.ended}
                   for ph in sol.phases if ph.t_end is not None],
        "switch_times": [p.to_json(t) for t in sol.switch_times if t is not None],
        "t": p.to_json(sol.t[-1]), "state": {n: p.to_json(sol.y[i, -1]) for i, n in enumerate(STATE_NAMES)},
        "energy_plus_work_drift_in_eps": sol.energy_plus_work_drift_in_eps,
    }


def coulomb_text(record: dict) -> str:
    lines = [f"{record['model']} ({record['precision']}), mu = {record['params']['mu']}: {record['outcome']}"]
    lines += [f"  {ph['kind']:<8} {ph['t_start']} -> {ph['t_end']}  ({ph['ended']})" for ph in record["phases"]]
    lines += [f"  {n:<9} {v}" for n, v in record["state"].items()]
    lines.append(f"  E + W drift: {record['energy_plus_work_drift_in_eps']:.3g} eps of E's term scale")
    if not str(record["outcome"]).startswith(("ok", "event:")):
        lines.append(f"  {record['message']}")
    return "\n".join(lines)


def _friction(p, sol) -> dict | None:
    """The largest friction coefficient the run needs (mu_req = |F_h| / N) and when; None without rolling
    contact.  Points where N <= 0 (NaN) are left out; ``max`` is null if every point is one."""
    values = sol.friction_required
    if values is None:
        return None
    finite = [i for i, v in enumerate(values) if not math.isnan(float(v))]
    if not finite:
        return {"max": None, "t_max": None}
    i = max(finite, key=lambda j: values[j])  # compared in the run's precision; the first of equal maxima
    return {"max": p.to_json(values[i]), "t_max": p.to_json(sol.t[i])}


def _drifts(p, tr) -> dict:
    """initial, final and the drifts of one invariant (verify.engine.invariants.InvariantTrace); an
    undefined ratio (NaN: I(0) negligible, or a zero term scale) is null."""
    def ratio(x):
        return None if math.isnan(x) else x

    return {
        "initial": p.to_json(tr.initial),
        "final": p.to_json(tr.final),
        "max_abs_drift": tr.max_abs_drift,
        "max_rel_drift": ratio(tr.max_rel_drift),
        "term_scale": tr.term_scale,
        "max_drift_vs_terms": ratio(tr.max_drift_vs_terms),
        "max_drift_vs_terms_in_eps": ratio(tr.max_drift_vs_terms_in_eps),
    }


def _text(record: dict) -> str:
    lines = [
        f"model       {record['model']} ({record['equations']} equations), precision {record['precision']}",
        "params      " + ", ".join(f"{k}={v}" for k, v in record["params"].items()),
        f"outcome     {record['outcome']} at t = {record['t']} after {record['steps']} steps",
        "state",
    ]
    lines += [f"  {n:<9} {v}" for n, v in record["state"].items()]
    lines.append("invariants  (initial, final; max |I - I(0)|, that / |I(0)|, that / term scale in eps)")
    lines += [f"  {n:<12} {v['initial']}  {v['final']}  {_num(v['max_abs_drift'], '.3e')}  {_num(v['max_rel_drift'], '.3e')}"
              f"  {_num(v['max_drift_vs_terms_in_eps'], '.3g')}"
              for n, v in record["invariants"].items()]
    if record.get("friction") is not None:
        lines.append(f"friction    mu = {record['friction']}: the run stops at the event slips where mu_req reaches it")
    friction = record.get("friction_required")
    if friction is not None:
        lines.append(f"friction    mu_req = |F_h| / N needed to roll: max {_num(friction['max'], '')} at t = {_num(friction['t_max'], '')}")
    return "\n".join(lines)


def _num(x, fmt: str) -> str:
    if x is None:
        return "n/a"
    try:
        return format(x, fmt)
    except (TypeError, ValueError):
        return str(x)


def _finite(value) -> bool:
    try:
        return math.isfinite(float(value))
    except (TypeError, ValueError, OverflowError):
        return False


def _not_ok(sol, model) -> str | None:
    """Why a finished run must not be reported as a success, or None.

    The integrator names its own failures (``status < 0``, an outcome other than ``ok`` and
    ``event:<name>``).  On top of that, a run labelled ``ok`` whose final state is not finite or
    whose theta left the model's domain (heyoka's event detection failed and the run went on
    below the plane) is not a success whatever its label.
    """
    outcome = str(sol.outcome)
    if getattr(sol, "status", 0) < 0 or not (outcome == "ok" or outcome.startswith("event:")):
        return f"the integration of {sol.model!r} failed: {getattr(sol, 'message', '') or outcome} (outcome {outcome})"
    if outcome != "ok":
        return None
    final = [sol.y[i, -1] for i in range(len(STATE_NAMES))]
    if not all(_finite(v) for v in final):
        bad = next(n for n, v in zip(STATE_NAMES, final) if not _finite(v))
        return (f"the run of {sol.model!r} reached t = {_num(_float(sol.t[-1]), '.6g')} with a non-finite state "
                f"({bad} = {final[STATE_NAMES.index(bad)]}); the result is not reliable")
    if not model.domain.contains(final[0]):
        return (f"the run of {sol.model!r} ended at theta = {float(final[0]):.6g}, outside its domain "
                f"{float(model.domain.theta_min):.6g} < theta < {float(model.domain.theta_max):.6g}, without its "
                "terminal event (heyoka's event detection failed); the result is not reliable")
    return None


def _float(x) -> float:
    try:
        return float(x)
    except (TypeError, ValueError, OverflowError):
        return math.nan


# --- JSON -------------------------------------------------------------------------------------

def _json_safe(obj):
    """NaN and infinities (which JSON has no numbers for) as null, recursively."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_json_safe(v) for v in obj]
    return obj


def _dumps(obj) -> str:
    return json.dumps(_json_safe(obj), indent=2, allow_nan=False)
