"""The engine room: the only place that builds and runs heyoka integrators.

* :mod:`.compile` -- a model's sympy equations as heyoka expressions, parameters as ``par[i]``;
* :mod:`.validation` -- one check of a start, wherever it arrives;
* :mod:`.single` -- one trajectory (``solve``): segments with continuous angles, events, failures;
* :mod:`.invariants` -- the invariants along a run and their drifts;
* :mod:`.conditioning` -- variational equations: how errors in the start grow;
* :mod:`.lanes` -- the SIMD batch width;
* :mod:`.heyoka_log` -- heyoka's log lines collected instead of printed.
"""
