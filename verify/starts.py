"""Named starts a person can type: every figure's start and every reference case, and each model's default.

``python -m verify trajectory --start fig5-lhs`` runs the start the report's Fig. 5 LHS was drawn
from (:mod:`verify.figure_starts`: the same numbers the claim's run uses); ``--start
disk-standard-1`` runs a reference case's start (``reports/reference``: its exact parameters and
initial state, as stored); ``python -m verify starts`` lists them all.  A model run without
``--state`` or ``--start`` takes its default start (:func:`default_start`): the start of the
model's standard reference case (for a dissipative or Coulomb body, that of the body it damps),
said on the output so that nobody mistakes it for their own.

Nothing here imports sympy, heyoka or numpy: the list answers at once.  Values are text (decimal
numbers, or exact fractions such as ``16720/33489`` and expressions such as ``pi/2``), read at the
run's precision by :func:`verify.expressions.read_value`.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path

from models.catalogue import ALIASES, ALL_NAMES, COULOMB_NAMES

#: The reference set (its index and case files); the report's own copy.
REFERENCE = Path(__file__).resolve().parent.parent / "reports" / "reference"
#: The Coulomb coefficient of a Coulomb body run without --friction (a table top: rolls for long, slips now and then).
DEFAULT_FRICTION = "0.5"


@dataclass(frozen=True)
class Start:
    """A named start: the model, its parameters, the state at t = 0 and how long to run.

    ``params`` and ``state`` map names to text (unset state components are 0, unset parameters
    the model's defaults); ``source`` says where the start comes from (a figure caption, a
    reference case) and ``note`` how the source's words became these numbers.
    """

    name: str
    model: str
    params: dict = field(default_factory=dict)
    state: dict = field(default_factory=dict)
    t_end: str = "2"
    source: str = ""
    note: str = ""
    friction: str | None = None
    kind: str = "reference"  # "figure", "reference" or "default"
    n_eval: int | None = None  # the output grid the source drew (a figure's), or None: the command's default
    events: bool = True  # False only where the source ran without the model's events (Fig. 12)


#: Each model's default start: the reference case whose start it takes.
DEFAULT_CASES = {
    "disk": "disk-standard-1", "hoop": "hoop-general-10", "ring": "ring-standard-10",
    "hurricane": "hurricane-fig18-lhs", "sliding-disk": "sliding-disk-standard-10",
    "gyroscope": "gyroscope-standard-10", "effective": "effective-standard-10",
}


@lru_cache(maxsize=None)
def reference_starts(directory: Path = REFERENCE) -> tuple:
    """Every reference case's start, read from its stored file (exact parameters, stored state)."""
    index = directory / "index.json"
    if not index.is_file():
        return ()
    out = []
    for case in json.loads(index.read_text(encoding="utf-8"))["cases"]:
        record = json.loads((directory / case["file"]).read_text(encoding="utf-8"))
        params = {k: v["exact"] for k, v in record["model"]["parameters"].items()}
        state = {k: v for k, v in record["initial_state"].items() if v not in ("0", "0.0")}
        out.append(Start(case["name"], record["model"]["name"], params, state, str(record["t_end"]),
                         f"reference case: {case['source']}", record["description"], kind="reference"))
    return tuple(out)


def figure_starts() -> tuple:
    """Every figure panel's start (:mod:`verify.figure_starts`), as :class:`Start`."""
    try:
        from . import figure_starts as figures  # lazy: not for 'trajectory body:X'
    except ImportError:  # pragma: no cover - the registry is part of the suite
        return ()
    return tuple(Start(f.name, f.model, dict(f.params), dict(f.state), f.t_end, f"paper Fig. {f.figure}"
                       + (f" {f.side.upper()}" if f.side else ""), f.reading, kind="figure", n_eval=f.n_eval,
                       events=f.events)
                 for f in figures.STARTS)


def all_starts() -> tuple:
    """Figure starts first, then the reference cases; names are unique."""
    return figure_starts() + reference_starts()


def find(name: str) -> Start:
    """The start called ``name``; ``KeyError`` naming what is allowed otherwise."""
    for start in all_starts():
        if start.name == name:
            return start
    names = [s.name for s in all_starts()]
    raise KeyError(f"unknown start {name!r}; allowed: {', '.join(names)} (python -m verify starts lists them)")


def default_start(model: str) -> Start:
    """The start a model runs from when none is given (see the module docstring)."""
    if model not in ALL_NAMES and model not in COULOMB_NAMES and model not in ALIASES:
        raise KeyError(f"unknown model {model!r}")
    body = model.split("+")[0]
    case = find(DEFAULT_CASES[model] if model in DEFAULT_CASES else DEFAULT_CASES[body])
    params = dict(case.params)
    if model in ALIASES:
        params.update(ALIASES[model][1])
    friction = DEFAULT_FRICTION if model in COULOMB_NAMES else None
    how = f"the start of the reference case {case.name}, {case.note}"
    if model != case.model and model not in ALIASES:
        how += f", with {model}'s own defaults for its other parameters"
    name = case.name if model in (case.model, "hoop") else f"{model}:{case.name}"
    return replace(case, name=name, model=ALIASES[model][0] if model in ALIASES else model, params=params,
                   friction=friction, note=how, kind="default")
