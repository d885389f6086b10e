"""Proved enclosures of the reference cases (``reports/reference/proved/``): balls beside the agreed digits.

``python -m verify reference --prove`` encloses each case's exact solution with
:mod:`verify.proof` (Lohner's method in Arb) and writes, per case, a ball per component and grid
time: ``mid`` and ``rad`` are decimal strings, and the real interval [mid - rad, mid + rad]
contains the exact solution of the case's equations from its start, parameters and start read
exactly as rationals (checked in Arb when the file is written: the decimal ball contains the
computed one).  The case files themselves are not touched: they have their own writer and
sha256 fingerprints that outside readers pin; each proof names the sha256 of the case file it
proves.

A run has a wall-clock budget per case.  It writes after every grid time (atomically), so an
interrupted or budget-limited run keeps what it proved, and the next run resumes from the last
balls (as a box: the resumed set is wrapped once, which the file records).  Where a case is not
enclosed to its end, the file says how far it got, how wide the balls were there and why it
stopped.

Digits: a component's *proved digits* are log10(|mid| / rad), the significant digits the ball
leaves, counted as the agreed digits are (:func:`verify.reference.agreement.digits_of`); a ball
that contains 0 proves only its radius (``None``).
"""
from __future__ import annotations

import json
import math
import time
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import flint
from flint import arb, ctx

from models.symbols import STATE_NAMES

from ..provenance import source_commit, versions, write_atomic
from .agreement import digits_of
from ..proof.case import case_problem
from ..proof.integrator import enclose
from .make import equations_fingerprint
from .store import DIRECTORY, file_sha256, read_case, read_index, read_json

FORMAT = "rolling-verify proved enclosures, format 1"
INDEX_FORMAT = "rolling-verify proved enclosures index, format 1"
PROVED = "proved"

#: Settings of a proof: 128 bits reach the goal of 30 digits at 10 s where the flow allows it; the
#: Taylor order is about the bits / 3 that minimises a step's cost per unit time (tube factor aside).
DEFAULT_SETTINGS = {"method": "lohner", "prec": 128, "order": 40, "jacobian_order": 16, "jacobian_prec": 64,
                    "tube_prec": 64, "block": 16}
STATEMENT = ("each ball [mid - rad, mid + rad] contains the exact solution of the case's equations (the model's "
             "right-hand side named by equations_sha256, the parameters and the start read exactly as rationals) "
             "at its grid time")


class OutOfBudget(Exception):
    """The case's wall-clock budget ran out at a grid time (what was proved is written)."""


def proved_directory(directory: Path = DIRECTORY) -> Path:
    return Path(directory) / PROVED


def proof_path(directory: Path, case: str, bits: int) -> Path:
    """``proved/<case>.<bits>bit.json``: one proof per case and working precision."""
    return proved_directory(directory) / f"{case}.{bits}bit.json"


def settings_of(prec: int | None = None, order: int | None = None) -> dict:
    """The default settings, with the precision and order given (order ~ prec / 3 when only prec is)."""
    out = dict(DEFAULT_SETTINGS)
    if prec is not None:
        out["prec"] = prec
        out["order"] = max(20, round(prec / 3.2))
    if order is not None:
        out["order"] = order
    return out


def prove_case(record: dict, *, directory: Path = DIRECTORY, budget: float = math.inf, until=None,
               settings: dict | None = None, progress=None) -> dict:
    """Enclose ``record``'s case on its grid (to ``until``, default its end), resuming a stored proof.

    Returns the proof record written to ``proved/<case>.json``.  The budget is wall-clock
    seconds for this call; at the first grid time past it the run stops and writes.
    """
    settings = dict(settings or DEFAULT_SETTINGS)
    name = record["name"]
    if "friction" in record:
        raise ValueError(f"{name} rolls and slides with Coulomb friction: the proofs enclose smooth flows only (each "
                         "switch's time would need an enclosure of its own); its digits are agreed, not proved")
    case_file = Path(directory) / f"{name}.json"
    path = proof_path(directory, name, settings["prec"])
    stop = Fraction(record["t_end"] if until is None else str(until))
    grid = [s for s in record["grid"] if Fraction(s) <= stop]
    if len(grid) < 2:
        raise ValueError(f"--until {float(stop):g}: before {name}'s first grid time after 0 ({record['grid'][1]} s); allowed: "
                         "a time at or after it")
    if record["model"]["equations_sha256"] != equations_fingerprint(record["model"]["name"]):
        raise ValueError(f"{name}: the model's equations changed since the case was made (equations_sha256 "
                         "differs); run 'python -m verify reference --make' first")
    proof = _resumable(path, record, case_file, settings)
    field, start = case_problem(record)
    if proof is None:
        proof = _new_proof(record, case_file, settings)
        _append_exact(proof, grid[0], start)
    done = len(proof["times"])
    if done >= len(grid):
        return proof
    say = progress or (lambda s: None)
    t0 = time.monotonic()
    if done > 1:
        start = _balls_at(proof, -1, settings["prec"])
    offset = Fraction(proof["times"][-1])
    times = [Fraction(s) - offset for s in grid[done - 1:]]
    if done > 1:
        proof["resumed_at"].append(proof["times"][-1])
    proof.setdefault("segments", []).append({"from": proof["times"][-1], "source_commit": source_commit()["commit"],
                              "python-flint": _versions()["python-flint"]})

    def keep(t, enclosure):
        j = len(enclosure.t) - 1
        _append(proof, grid[done - 1 + j], [row[j] for row in enclosure.y], settings["prec"])
        proof["steps"] += enclosure.steps - keep.steps
        keep.steps = enclosure.steps
        proof["wall_seconds"] = round(keep.wall + time.monotonic() - t0, 1)
        proof["stopped"] = None
        _write(path, proof)
        say(f"  {name}: t = {grid[done - 1 + j]}, {proof['proved_digits_min'][-1]} proved digits, "
            f"{proof['steps']} steps, {proof['wall_seconds']:.0f} s")
        if time.monotonic() - t0 > budget and done - 1 + j < len(grid) - 1:
            raise OutOfBudget

    keep.steps, keep.wall = 0, proof["wall_seconds"]
    try:
        enclose(field, start, times, progress=keep, **_enclose_options(settings))
    except OutOfBudget:
        proof["stopped"] = f"the wall-clock budget of {budget:.0f} s for one run ran out"
    except (RuntimeError, ArithmeticError) as err:
        proof["stopped"] = f"the enclosure failed: {err}"
    proof["complete"] = proof["times"][-1] == record["t_end"]
    _write(path, proof)
    return proof


def _enclose_options(settings: dict) -> dict:
    return {k: settings[k] for k in ("method", "prec", "order", "jacobian_order", "jacobian_prec", "tube_prec",
                                     "block")}


def _new_proof(record: dict, case_file: Path, settings: dict) -> dict:
    return {"format": FORMAT, "case": record["name"], "case_sha256": file_sha256(case_file),
            "equations_sha256": record["model"]["equations_sha256"], "statement": STATEMENT,
            "settings": settings, "t_end": record["t_end"], "complete": False, "stopped": None,
            "resumed_at": [], "segments": [], "steps": 0, "wall_seconds": 0.0, "times": [],
            "state": {n: {"mid": [], "rad": []} for n in STATE_NAMES}, "proved_digits": {n: [] for n in STATE_NAMES},
            "proved_digits_min": [],
            "provenance": {"versions": _versions(), "source_commit": source_commit()["commit"]}}


def _versions() -> dict:
    return {**versions(), "python-flint": flint.__version__}


def _resumable(path: Path, record: dict, case_file: Path, settings: dict):
    """The stored proof to continue, or None: a proof of another case file or other settings restarts."""
    if not path.exists():
        return None
    proof = read_proof(path)
    if proof["case_sha256"] != file_sha256(case_file) or proof["settings"] != settings or not proof["times"]:
        return None
    return proof


def _append(proof: dict, time_text: str, balls: list, prec: int) -> None:
    proof["times"].append(time_text)
    digits = []
    for n, b in zip(STATE_NAMES, balls):
        mid, rad = decimal_ball(b, prec)
        proof["state"][n]["mid"].append(mid)
        proof["state"][n]["rad"].append(rad)
        d = None if Decimal(rad) >= abs(Decimal(mid)) else round(digits_of(mid, rad), 1)
        proof["proved_digits"][n].append(d)
        digits.append(d)
    known = [d for d in digits if d is not None]
    proof["proved_digits_min"].append(min(known) if known else None)


def balls_record(record: dict, enclosure) -> dict:
    """An enclosure (:class:`verify.proof.Enclosure`) of ``record``'s case written as a proof's times and
    decimal balls, the form :func:`claims` reads: the one way stored values are set against balls."""
    texts = {Fraction(t): t for t in record["grid"]}
    out = {"times": [texts[t] for t in enclosure.t], "state": {n: {"mid": [], "rad": []} for n in STATE_NAMES}}
    for n, row in zip(STATE_NAMES, enclosure.y):
        for b in row:
            mid, rad = decimal_ball(b, enclosure.prec)
            out["state"][n]["mid"].append(mid)
            out["state"][n]["rad"].append(rad)
    return out


def _append_exact(proof: dict, time_text: str, start: list) -> None:
    """The start, exactly as the case states it (decimal strings, radius 0)."""
    proof["times"].append(time_text)
    for n, v in zip(STATE_NAMES, start):
        proof["state"][n]["mid"].append(str(v))
        proof["state"][n]["rad"].append("0")
        proof["proved_digits"][n].append(None)
    proof["proved_digits_min"].append(None)


def decimal_ball(b: arb, prec: int) -> tuple:
    """(mid, rad) decimal strings whose interval [mid - rad, mid + rad] contains the ball ``b``.

    In exact rational arithmetic: the ball's ends are read exactly (Arb's midpoint and radius are
    binary floating-point numbers), mid is the midpoint to the digits worth keeping, rad the
    distance to the farther end rounded up to two significant digits, and the containment is
    checked exactly before the strings are returned.
    """
    centre_b, radius_b = exact_fraction(b.mid()), exact_fraction(b.rad())  # exact, whatever ctx.prec is
    lower, upper = centre_b - radius_b, centre_b + radius_b
    digits = max(10, min(int(prec * 0.30103) + 3, _digits_needed(b) + 6))
    mid = "0" if b.mid() == 0 else b.mid().str(digits, radius=False)
    centre = Fraction(Decimal(mid))
    rad = _round_up(max(upper - centre, centre - lower, Fraction(0)))
    if not (centre - Fraction(Decimal(rad)) <= lower and upper <= centre + Fraction(Decimal(rad))):
        raise ArithmeticError(f"decimal ball {mid} +/- {rad} does not contain {b}")
    return mid, rad


def exact_fraction(point: arb) -> Fraction:
    """The exact value of an arb of radius 0 (a ball's ``mid()`` or ``rad()``)."""
    man, exp = point.mid().man_exp()
    man, exp = int(man), int(exp)
    return Fraction(man * 2 ** exp) if exp >= 0 else Fraction(man, 2 ** -exp)


def _digits_needed(b: arb) -> int:
    mid, rad = abs(float(b.mid())), float(b.rad())
    if rad == 0 or mid == 0:
        return 80
    return max(1, int(math.log10(mid / rad)) + 1)


def _round_up(x: Fraction) -> str:
    """The least 2-significant-digit decimal >= x >= 0, in exact arithmetic."""
    if x == 0:
        return "0"
    exponent = len(str(x.numerator // x.denominator)) - 2 if x >= 1 else -_leading_zeros(x) - 2
    scaled = x / Fraction(10) ** exponent  # in [10, 100) up to one decade
    digits = -(-scaled.numerator // scaled.denominator)
    while digits >= 100:
        exponent += 1
        scaled = x / Fraction(10) ** exponent
        digits = -(-scaled.numerator // scaled.denominator)
    return f"{digits}e{exponent}"


def _leading_zeros(x: Fraction) -> int:
    """For 0 < x < 1: the k with 10^-(k+1) <= x < 10^-k."""
    k = 0
    while x * 10 ** (k + 1) < 1:
        k += 1
    return k


def _balls_at(proof: dict, j: int, prec: int) -> list:
    return [ball(proof, n, j, prec) for n in STATE_NAMES]


def ball(proof: dict, component: str, j: int, prec: int = 320) -> arb:
    """The stored ball of ``component`` at the proof's j-th time, as an arb (rigorous: it contains the decimal interval)."""
    saved = ctx.prec
    ctx.prec = prec
    try:
        return arb(proof["state"][component]["mid"][j]) + arb(0, arb(proof["state"][component]["rad"][j]).upper())
    finally:
        ctx.prec = saved


def read_proof(path: Path) -> dict:
    return read_json(path, FORMAT, "no proof file {path}; run 'python -m verify reference --prove'")


def load_proofs(directory: Path = DIRECTORY) -> dict:
    """Case name -> list of its proofs (any precision), those whose case file is unchanged since."""
    folder = proved_directory(directory)
    out = {}
    for entry in read_index(directory)["cases"]:
        for path in sorted(folder.glob(f"{entry['name']}.*bit.json")):
            proof = read_proof(path)
            if proof["case"] == entry["name"] and proof["case_sha256"] == file_sha256(Path(directory) / entry["file"]):
                out.setdefault(entry["name"], []).append(proof)
    return out


def _write(path: Path, proof: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, json.dumps(proof, indent=1) + "\n")


def claims(record: dict, proof: dict) -> dict:
    """How the stored agreed values stand against the proof, over every component and proved time.

    ``proved``: the ball lies inside value ± abs_error, so the stored claim |value - exact| <=
    abs_error is now proved; ``consistent``: they overlap (the ball is wider than abs_error);
    ``contradicted``: they are disjoint, the stored digits are wrong (never expected: a finding).
    Decided in exact rational arithmetic (every end is a decimal string).
    """
    out = {"proved": 0, "consistent": 0, "contradicted": 0, "contradictions": []}
    for j, t in enumerate(proof["times"]):
        index = record["grid"].index(t)
        for n in STATE_NAMES:
            mid = Fraction(Decimal(proof["state"][n]["mid"][j]))
            rad = Fraction(Decimal(proof["state"][n]["rad"][j]))
            value = Fraction(Decimal(record["state"][n]["value"][index]))
            allowed = Fraction(Decimal(record["state"][n]["abs_error"][index]))
            if value - allowed <= mid - rad and mid + rad <= value + allowed:
                out["proved"] += 1
            elif mid - rad <= value + allowed and value - allowed <= mid + rad:
                out["consistent"] += 1
            else:
                out["contradicted"] += 1
                out["contradictions"].append(f"{n} at t = {t}")
    return out


def summary(record: dict, proof: dict) -> dict:
    """One proof's line of the index: how far, how wide (at 1 s and at its last time), how long, the claims."""
    def at(t_text):
        """Digits at one time, the fewest over the components that are not agreed zeros (as the case
        index counts them: a component whose runs agree it is 0 to within abs_error has no significant
        digits), each with its component."""
        if t_text not in proof["times"]:
            return None
        j, index = proof["times"].index(t_text), record["grid"].index(t_text)
        counted = [n for n in STATE_NAMES if not _agreed_zero(record["state"][n], index)]
        agreed = {n: record["state"][n]["digits"][index] for n in counted}
        proved = {n: proof["proved_digits"][n][j] for n in counted if proof["proved_digits"][n][j] is not None}
        weakest = min(proved, key=proved.get, default=None)
        least = min(agreed, key=agreed.get, default=None)
        return {"t": t_text, "proved_digits_fewest": proved[weakest] if weakest else None, "proved_weakest": weakest,
                "agreed_digits_fewest": agreed[least] if least else None, "agreed_weakest": least}

    one = next((t for t in proof["times"] if Fraction(t) == 1), None)
    verdict = claims(record, proof)
    return {"case": proof["case"], "bits": proof["settings"]["prec"], "order": proof["settings"]["order"],
            "t_end": proof["t_end"], "t_proved": proof["times"][-1], "complete": proof["complete"],
            "stopped": proof["stopped"], "resumed_at": proof["resumed_at"], "steps": proof["steps"],
            "wall_seconds": proof["wall_seconds"], "at_1s": at(one) if one else None, "at_last": at(proof["times"][-1]),
            "claims_proved": verdict["proved"], "claims_consistent": verdict["consistent"],
            "claims_contradicted": verdict["contradicted"], "contradictions": verdict["contradictions"][:10],
            "file": f"{proof['case']}.{proof['settings']['prec']}bit.json"}


def _agreed_zero(column: dict, index: int) -> bool:
    """The case file's rule (:func:`.store.final_summary`): no digits, or 0 digits of a value within abs_error of 0."""
    digits = column["digits"][index]
    return digits is None or (digits == 0 and abs(column["double"][index]) <= float(column["abs_error"][index]))


def write_summary(directory: Path = DIRECTORY) -> dict:
    """Rewrite ``proved/index.json`` and ``proved/README.md`` from the proof files on disk."""
    proofs = load_proofs(directory)
    rows = []
    for name, items in proofs.items():
        record = read_case(Path(directory) / f"{name}.json")
        rows.extend(summary(record, p) for p in sorted(items, key=lambda p: p["settings"]["prec"]))
    index = {"format": INDEX_FORMAT, "statement": STATEMENT,
             "digits": "at_1s and at_last: proved_digits_fewest is the fewest significant digits the balls prove "
                       "(log10 |mid|/rad) and agreed_digits_fewest the fewest the case file's runs agree on, each over "
                       "the components that are not agreed zeros (the case index's rule), with the component; a proof "
                       "file's own proved_digits_min is over every component whose ball excludes 0",
             "proofs": rows}
    folder = proved_directory(directory)
    folder.mkdir(parents=True, exist_ok=True)
    write_atomic(folder / "index.json", json.dumps(index, indent=1) + "\n")
    write_atomic(folder / "README.md", _readme(rows))
    return index


def _readme(rows: list) -> str:
    def digits(entry):
        if entry is None:
            return "–"
        p, a = entry["proved_digits_fewest"], entry["agreed_digits_fewest"]
        return f"{'–' if p is None else f'{p:.1f}'} / {'–' if a is None else a}"

    lines = [f"| `{r['case']}` | {r['bits']} | {r['t_proved']} of {r['t_end']} | {digits(r['at_1s'])} | "
             f"{digits(r['at_last'])} | {r['steps']} | {r['wall_seconds']:.0f} | {r['claims_proved']} / "
             f"{r['claims_consistent']} / {r['claims_contradicted']} | {r['stopped'] or ''} |" for r in rows]
    return f"""# Proved enclosures of the reference cases

Generated by `python -m verify reference --prove` (do not edit by hand). {STATEMENT[0].upper() + STATEMENT[1:]}.
The enclosures come from `verify/proof/` (a validated Taylor integrator in Arb ball arithmetic,
python-flint): a high-order tube validates each step, the Lagrange remainder is bounded on it,
and the mean-value form with deferred wrapping carries the errors (`verify/proof/lohner.py`).

Digits are significant digits, the fewest over the components that are not agreed zeros (the
case index's rule: a component whose runs agree it is 0 to within abs_error has none): proved
(log10 |mid|/rad of the ball) / agreed (the case file's digits, on which its MPFR-128 and MPFR-256
runs agree). Claims: the stored values' claim |value − exact| ≤ abs_error at every proved component and
time, counted as proved (ball inside value ± abs_error) / consistent (overlapping) / contradicted
(disjoint: the stored digits would be wrong). Wall seconds are of a shared 2-core machine.

| case | bits | proved to t (s) | digits at 1 s, proved / agreed | digits at the last proved t | steps | wall s | claims proved / consistent / contradicted | stopped |
|---|---:|---|---|---|---:|---:|---|---|
""" + "\n".join(lines) + "\n"
