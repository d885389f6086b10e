"""How a run fails: :class:`IntegrationError` (no heavy imports: the command line catches it before
anything is computed)."""
from __future__ import annotations


class IntegrationError(RuntimeError):
    """The integration failed; ``outcome`` says how (one of :data:`verify.engine.failures.FAILURES`).

    ``t`` and ``state`` are where the failure was seen; ``trajectory`` is the run up to its last
    valid output (a :class:`~verify.engine.trajectory.Trajectory` with that outcome and
    ``status = -1``), or None.
    """

    def __init__(self, message: str, outcome: str = "failed", t=None, state=None, trajectory=None):
        super().__init__(message)
        self.outcome, self.t, self.state, self.trajectory = outcome, t, state, trajectory
