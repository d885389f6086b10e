"""What :func:`verify.engine.single.solve` returns: a :class:`Trajectory`, or an :class:`IntegrationError`."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from models.symbols import STATE_NAMES

from . import invariants as inv
from .errors import IntegrationError  # noqa: F401  (re-exported: where a run's failure has always been imported from)
from ..precision import Precision


@dataclass(frozen=True)
class Trajectory:
    """A run: grid times, states, outcome, invariants.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Times reached on the grid, plus the event time if a terminal event stopped the run.
    y : ndarray, shape (8, n)
        States, rows in the order of ``state_names``; phi, psi continuous.
    status : int
        0 when ``t_end`` was reached, 1 when a terminal event stopped the run, 2 when a run
        without events reached t_end after its theta left the domain (-1 only on the partial
        record an :class:`IntegrationError` carries).
    outcome : str
        ``"ok"`` or ``"event:<name>"`` (``lies_flat``, ``rim_switch``, ``contact_lost``, ...);
        ``"outside_domain"`` (status 2, ``events=False`` only); ``"failed:<reason>"`` only on an
        :class:`IntegrationError`'s partial record.
    steps : int
        Taylor steps taken.
    invariants : dict of name -> InvariantTrace (property)
        Energy first, then the model's other conserved quantities; each with its values and
        ``max_abs_drift``, ``max_rel_drift`` (over |I(0)|) and ``max_drift_vs_terms`` (over
        the magnitudes of I's terms), see :class:`verify.engine.invariants.InvariantTrace`.
        Evaluated when first read (Chaplygin's closed form costs milliseconds a point), then
        kept; the drifts cover every output of the run.
    normal_force : ndarray or None (property)
        N / (M g) on the grid (contact holds while it is positive); None without a contact.
    friction_required : ndarray or None (property)
        mu_req = |F_h| / N on the grid, in the run's precision: the smallest coefficient of
        friction with which the body rolls as computed (F_h the horizontal contact force,
        paper Eq. 6); NaN where N <= 0.  None for a model without rolling contact.  Evaluated
        when first read (a cfunc compiled for it then), apart from the invariants.
    friction : number or None
        The friction coefficient the run was given (``solve(friction=...)``; the terminal event
        ``slips`` stops it where mu_req reaches it), or None: unlimited friction.
    """

    model: str
    equations: str
    precision: Precision
    params: dict
    t_end: object
    t: np.ndarray
    y: np.ndarray
    status: int
    message: str
    outcome: str
    t_events: dict
    steps: int
    tol: object
    evaluation: inv.OnDemand = field(repr=False, compare=False)
    state_names: tuple = STATE_NAMES
    friction: object = None

    def __repr__(self) -> str:  # the arrays are for reading, not for printing
        t = self.t
        span = f"t = {float(t[0]):g} to {float(t[-1]):g} s, {len(t)} outputs" if len(t) else "no outputs"
        return (f"Trajectory(model={self.model!r}, equations={self.equations!r}, precision={self.precision.name!r}, "
                f"outcome={self.outcome!r}, {span}, steps={self.steps})")

    @property
    def invariants(self) -> dict:
        return self.evaluation.traces

    @property
    def normal_force(self):
        return self.evaluation.normal_force

    @property
    def friction_required(self):
        return self.evaluation.friction_required

    @property
    def success(self) -> bool:
        return self.status >= 0

    def __getitem__(self, name: str) -> np.ndarray:
        return self.y[STATE_NAMES.index(name)]

    @property
    def final_state(self) -> dict:
        return {n: self.y[i, -1] for i, n in enumerate(STATE_NAMES)}

    # --- the run as a time series (verify.series) -------------------------------------------------
    def columns(self) -> dict:
        """Every column of the run by name (t, the state, invariants, N/(Mg), mu_req ...): :mod:`verify.series`."""
        from ..series import run_columns  # lazy: verify.series (10 ms) only to save or draw, not for 'threshold'

        return dict(run_columns(self).values)

    def save(self, path, **meta):
        """Write the run to ``path`` as CSV, JSON or NPZ (by its extension), atomically, with units and metadata."""
        from ..series import run_columns, write_run  # lazy: as columns()

        return write_run(run_columns(self, meta), path)

    def to_csv(self, path, **meta):
        """The run as CSV: ``# key: value`` metadata lines, then ``name [unit]`` headings and every digit."""
        return self._save_as(path, ".csv", meta)

    def to_json(self, path, **meta):
        """The run as JSON: ``meta``, ``units`` and ``columns`` (arrays)."""
        return self._save_as(path, ".json", meta)

    def plot(self, path):
        """Draw the run (path and contact trace, theta, phi, omega3, energy, N/(Mg)) into a PNG, SVG or PDF."""
        from ..series import run_columns  # lazy: as columns()
        from ..series.plot import write_plot  # lazy: as columns()

        return write_plot(run_columns(self), path)

    def animate(self, path, label=None, **options):
        """The body rolling in 3D into a GIF, MP4 or HTML (:func:`verify.animation.animate` and its options)."""
        from ..animation import AnimationRun, animate  # lazy: verify.animation (14 ms) only to animate

        run = AnimationRun.from_solution(label or self.model, self.model, self,
                                         {k: float(v) for k, v in self.params.items()})
        return animate([run], path, **options)

    def _save_as(self, path, suffix: str, meta: dict):
        if Path(path).suffix.lower() != suffix:
            raise ValueError(f"{str(path)!r}: a {suffix} file name is expected (save() picks the format by extension)")
        return self.save(path, **meta)


@dataclass(frozen=True)
class End:
    """Where the integrator stopped (read before it is given back to the pool)."""

    time: object
    state: list
    tol: object
