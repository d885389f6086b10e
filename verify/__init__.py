"""The verification suite: integration at a chosen precision, invariants, and (later) claims.

>>> from verify import solve
>>> sol = solve("disk", t_end=2.0, state={"theta": 1.2, "psidot": 10.0}, precision="quad")
>>> sol.outcome, sol.invariants["energy"].max_rel_drift
"""
from .integrate import IntegrationError, InvariantTrace, Trajectory, solve
from .precision import Precision, parse_precision

__all__ = ["IntegrationError", "InvariantTrace", "Precision", "Trajectory", "parse_precision", "solve"]
