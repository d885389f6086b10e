"""The verification suite: integration at a chosen precision, invariants, and (later) claims.

>>> from verify import solve
>>> sol = solve("disk", t_end="2", state={"theta": "1.2", "psidot": "10"}, precision="quad")
>>> sol.outcome, sol.invariants["energy"].max_rel_drift   # max |E - E(0)| / |E(0)|
('ok', 5.187782963507209e-33)

Each invariant is a :class:`InvariantTrace` with ``values`` and three drifts:
``max_abs_drift`` = max |I(t) - I(0)|; ``max_rel_drift`` = that / |I(0)| (NaN where |I(0)| is
negligible against the magnitudes of I's terms); ``max_drift_vs_terms`` = that / the largest
sum of those magnitudes along the run (``max_drift_vs_terms_in_eps`` in units of epsilon; on
this run 3.0e-35 = 0.16 eps: the disk's |E| is 0.006 of its term scale).
"""
import importlib

# Imported on first use (PEP 562), not here: ``python -m verify`` imports this package before its
# __main__ runs, and the CLI's supervisor must fork while nothing (heyoka starts a thread) is loaded.
_LAZY = {"IntegrationError": "engine.single", "InvariantTrace": "engine.single", "Trajectory": "engine.single",
         "solve": "engine.single", "Precision": "precision", "parse_precision": "precision"}


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


def score(run, case, **options):
    """Score another simulator's run against a reference case: :func:`verify.scoring.agreement.score` (a :class:`Score`)."""
    from .scoring.agreement import score as _score  # lazy: numpy (0.2 s): the CLI forks before anything heavy loads

    return _score(run, case, **options)


__all__ = ["IntegrationError", "InvariantTrace", "Precision", "Trajectory", "parse_precision", "score", "solve"]
