"""Sympy expressions of a run's rows, evaluated by one heyoka cfunc at the run's precision.

A model's eight states, a few extra states of its own system (the slip, the work) and its parameters
are mapped to heyoka variables and ``par[i]`` by name (:func:`verify.engine.compile.symbol_map`), the
expressions compiled once per call, and evaluated over every output row at once. The command line's
friction runs use it for C's horizontal velocity (:mod:`verify.cli.friction_run`), so that no module
outside the engine room builds heyoka expressions.
"""
from __future__ import annotations

import heyoka as hy
import numpy as np

from .compile import symbol_map, to_heyoka


def evaluate_rows(model, extra: tuple, parameters: tuple, expressions, rows, values: dict, precision):
    """The ``expressions`` (sympy) at every column of ``rows``.

    Parameters
    ----------
    model : Model
        The rolling model whose eight state symbols the expressions use (paper Eqs. 5-8).
    extra : tuple of sympy symbols
        The further states, in the order of ``rows[8:]``.
    parameters : tuple
        Every parameter the expressions may read (objects with ``.symbol`` and ``.name``), the model's
        own first; laid out as ``par[i]`` in this order.
    expressions : sequence of sympy expressions
    rows : array, shape (8 + len(extra), n)
        The states at the n outputs, in ``precision``'s type.
    values : dict
        Parameter values by name.
    precision : Precision

    Returns
    -------
    array, shape (len(expressions), n)
    """
    variables = tuple(hy.make_vars(*(f"v{i}" for i in range(8 + len(extra)))))
    mapping = symbol_map(model, variables[:8])
    mapping.update(dict(zip(extra, variables[8:])))
    n_own = len(model.parameters)
    mapping.update({q.symbol: hy.par[n_own + i] for i, q in enumerate(parameters[n_own:])})
    function = hy.cfunc([to_heyoka(e, mapping) for e in expressions], list(variables), **precision.integrator_kwargs())
    pars = precision.array([values[q.name] for q in parameters])[: function.nparams]  # only those the expressions read
    n = rows.shape[1]
    return function(np.ascontiguousarray(rows), pars=np.ascontiguousarray(np.repeat(pars[:, None], n, axis=1)))
