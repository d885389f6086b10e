"""The engine room: the only place that builds and runs heyoka integrators.

* :mod:`.compile` -- a model's sympy equations as heyoka expressions, parameters as ``par[i]``;
* :mod:`.validation` -- one check of a start, wherever it arrives;
* :mod:`.problem` -- a run's question (model, parameters, start, precision, tolerance, events)
  resolved and validated once;
* :mod:`.integrators` -- integrators built once per compiled system and lent out, reset;
* :mod:`.single` -- one trajectory (``solve``): segments with continuous angles, events, failures,
  invariants on demand; runs with extra states (``propagate_in_turns``) and auxiliary systems
  (``through_grid``) for the studies;
* :mod:`.invariants` -- the invariants along a run and their drifts;
* :mod:`.conditioning` -- variational equations: how errors in the start grow;
* :mod:`.lanes` -- the SIMD batch width;
* :mod:`.heyoka_log` -- heyoka's log lines collected instead of printed.
"""
