"""A reference case enclosed: its start and parameters read exactly, on its grid.

The case file stores the start and the output times as decimal strings and the parameters as
exact rationals; all are read as rationals (``fractions.Fraction``), so the enclosure is of
the exact initial-value problem the file states, not of a rounded one.
"""
from __future__ import annotations

from fractions import Fraction

from models import get_model
from models.symbols import STATE_NAMES

from .equations import VectorField
from .integrator import Enclosure, enclose


def enclose_case(record: dict, *, t_stop=None, order: int = 24, prec: int = 256, start=None,
                 params=None, **options) -> Enclosure:
    """Enclose a reference case's solution on its grid (up to ``t_stop``, default its end).

    ``start`` and ``params`` (mappings of name -> exact value) replace the file's, for
    negative controls; ``options`` go to :func:`~verify.proof.integrator.enclose` (``method``).
    """
    field, state = case_problem(record, start=start, params=params)
    stop = Fraction(record["t_end"] if t_stop is None else str(t_stop))
    times = [Fraction(t) for t in record["grid"] if Fraction(t) <= stop]
    return enclose(field, state, times, order=order, prec=prec, **options)


def case_problem(record: dict, *, start=None, params=None) -> tuple:
    """(the right-hand side in ball arithmetic, the start as the case's exact decimal strings), with
    ``start`` and ``params`` (name -> exact value) replacing the file's."""
    model = get_model(record["model"]["name"])
    values = {k: v["exact"] for k, v in record["model"]["parameters"].items()}
    values.update(params or {})
    state = dict(record["initial_state"])
    state.update(start or {})
    return VectorField(model, values), [state[n] for n in STATE_NAMES]
