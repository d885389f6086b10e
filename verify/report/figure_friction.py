"""mu_req of every run a paper figure shows, as the figure's claims make them (the report's friction jobs).

The claims own their figure runs (:mod:`verify.claims.simulations`); this module records the
trajectories those runs make and reads each one's required friction with
:func:`verify.studies.friction.run_friction`.  It lives with the report's jobs, above both the claims
and the studies, because it drives the one and reads through the other.
"""
from __future__ import annotations

from contextlib import contextmanager

import numpy as np

from ..claims import simulations
from ..claims.simulations import disk, hurricane, ring, runs
from ..studies.friction import run_friction


@contextmanager
def recorded_runs():
    """The trajectories the figure runs of :mod:`verify.claims.simulations` make, recorded in order.

    The claims own their runs (:func:`verify.claims.simulations.runs.run`); this wraps the
    ``solve`` that function calls, for the duration, and empties the claims' run caches before
    and after, so every figure run is made (and recorded) here, never taken from an earlier
    evaluation in the same process.
    """
    def clear():
        for module in (runs, disk, ring, hurricane):
            for obj in list(vars(module).values()):
                if callable(getattr(obj, "cache_clear", None)):
                    obj.cache_clear()

    recorded = []
    real = runs.solve

    def recording(*args, **kwargs):
        sol = real(*args, **kwargs)
        recorded.append(sol)
        return sol

    clear()
    runs.solve = recording
    try:
        yield recorded
    finally:
        runs.solve = real
        clear()


def _matches(data, sol) -> bool:
    """Whether the figure's RunData was made from the trajectory ``sol`` (the same samples of t and theta)."""
    t = np.asarray(sol.t, float)
    return len(t) == len(data.t) and np.array_equal(t, np.asarray(data.t)) and np.array_equal(
        np.asarray(sol["theta"], float), np.asarray(data.theta))


def figure_claims(figure: int) -> list:
    """The simulation claims of paper figure ``figure`` (their ids are fig-N or fig-N-...)."""
    return [c for c in simulations.claims() if c.id == f"fig-{figure}" or c.id.startswith(f"fig-{figure}-")]


def figure_numbers() -> tuple:
    """The paper figures the simulation claims draw."""
    return tuple(sorted({int(c.id.split("-")[1]) for c in simulations.claims()}))


def figure_rows(figure: int) -> list:
    """mu_req of every run the figure(s) of paper figure ``figure`` show, one row per run.

    The figure's claims are evaluated with their runs recorded (:func:`recorded_runs`); each run
    a figure shows is the recorded trajectory with its samples.  A run drawn from another's
    samples (Fig. 12's point A is the CM run's) is marked ``same_run_as``.
    """
    with recorded_runs() as recorded:  # check(), not evaluate(): evaluate() keeps an earlier evaluation's figures
        figures = [fig for claim in figure_claims(figure) if claim.reason_not_checkable is None
                   for fig in claim.check().figures]
    rows, seen = [], {}
    for fig in figures:
        for data in fig.runs:
            match = [s for s in recorded if _matches(data, s)]
            if not match:
                raise RuntimeError(f"{fig.name}: the run {data.label!r} is none of the recorded trajectories")
            sol = match[-1]
            row = {"figure": fig.name, "title": fig.title, "run": data.label, **run_friction(sol)}
            if id(sol) in seen:
                row["same_run_as"] = seen[id(sol)]
            seen.setdefault(id(sol), data.label)
            rows.append(row)
    return rows
