"""The engine room: the only place that builds and runs heyoka integrators.

* :mod:`.compile` -- a model's sympy equations as heyoka expressions, parameters as ``par[i]``;
* :mod:`.validation` -- one check of a start, wherever it arrives;
* :mod:`.problem` -- a run's question (model, parameters, start, precision, tolerance, events)
  resolved and validated once;
* :mod:`.integrators` -- integrators built once per compiled system and lent out, reset;
* :mod:`.single` -- one trajectory (``solve``), every public name of the four below importable from it:
* :mod:`.trajectory` -- its record (invariants on demand) and :class:`IntegrationError`;
* :mod:`.segments` -- fixed segments with continuous angles (heyoka's error control kept tight);
* :mod:`.failures` -- how a run ends: ``ok``, a terminal event, or a named failure;
* :mod:`.auxiliary` -- runs with extra states (``propagate_in_turns``) and auxiliary systems
  (``through_grid``) for the studies;
* :mod:`.invariants` -- the invariants along a run and their drifts;
* :mod:`.conditioning` -- variational equations: how errors in the start grow;
* :mod:`.ensemble` -- many runs of one model at once (:class:`Ensemble`, the batch road's front door);
* :mod:`.lanes` -- the SIMD batch width and a model's lane system (:func:`compile_lanes`), parameters by name;
* :mod:`.batch` -- SIMD lanes on threads, freezing events, per-run evaluation;
* :mod:`.heyoka_log` -- heyoka's log lines collected instead of printed.
"""
