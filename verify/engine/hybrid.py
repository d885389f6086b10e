"""Rolling and sliding with Coulomb friction, event-driven: ``disk+coulomb``, ``ring+coulomb``.

A run is a sequence of phases, each integrated by heyoka's Taylor method at the run's precision:

* **rolling**: the rolling model (``disk``, ``ring``; paper Eqs. 5-8) run by the engine,
  :func:`verify.engine.single.solve` with ``friction=mu``, whose terminal event ``slips`` fires
  where the required friction mu_req = |F_h| / N reaches mu;
* **sliding**: the equations of :mod:`models.coulomb` (F_h = -mu N u/|u|, slip speed and
  direction as state, the work W = int mu N s dt as a quadrature), integrated here with the
  terminal event ``sticks`` on the slip speed s (direction negative: Coulomb friction brings s to
  zero at a finite rate, so s changes sign there and heyoka locates the root to epsilon).

Switches and their maps:

* launch: a start with a centre-of-mass velocity ``velocity`` slides if the contact's slip
  u = v_C + omega x r_P is not zero (s = |u|, alpha = atan2(u_y, u_x)); without ``velocity``,
  or with u = 0 exactly, it rolls (v_C is then the rolling model's ``velocity_xy``);
* sliding -> rolling at ``sticks`` (s = 0): the eight components are handed over as they are
  (at s = 0 the CM velocity of the sliding state *is* the no-slip velocity), the slip state is
  dropped, W is kept.  If the rolling equations there need mu_req > mu the slip would go on
  from s = 0 in the direction of -F_req: that is the onset below;
* sliding from s = 0 where rolling needs mu_req > mu (a start, or a stick where rolling cannot
  hold): the slip starts at a finite rate lambda in the one direction alpha0 along which it then
  accelerates (:func:`onset_directions`); d(alpha)/dt = (e_perp . du/dt)/s is 0/0 there, a regular
  singular point whose one regular solution is started by a second-order Taylor polynomial over
  2^-ceil(bits/3) of the step cap (:func:`verify.engine.hybrid_switches.onset`), then heyoka takes over;
* rolling -> sliding at ``slips`` (mu_req reaches mu exactly): s = 0, alpha0 the direction of -F_req,
  but there lambda = 0: s grows like sigma t^2 / 2 and d(alpha)/dt = B/s has an irregular singular point
  (deviations from the slow solution die like exp(-A_s / t), A_s = 2 |B_alpha| / sigma), which an explicit
  Taylor method started at a small t pays for with ~ A_s / t steps.  The slow solution is carried from
  the event to t1 (the step cap, or 2^-j of it) by its power series in t, built order by order in ball
  arithmetic at the precision plus guard bits and summed where its terms are below eps / 16 of each
  component's largest (:mod:`verify.engine.slip_onset`, :func:`~verify.engine.hybrid_switches.slip_onset`); heyoka takes over at
  t1, where the pull-back's rate A_s / t1^2 is a few hundred per second on the examples.  A series that
  does not reach eps at any t1 tried (or a direction slope B_alpha that does not restore) raises
  :class:`UnsupportedTransition` naming the time, with the run up to there.

Guards: every phase and switch checks itself (:mod:`verify.engine.hybrid_guards`: the domain, E + W, each
switch's constraint, Painleve's jam, a run that stops short of t_end), and a run that breaks one raises
:class:`IntegrationError` with its named outcome and the run up to there.  Output times that fall between an
onset at s = 0 and heyoka's start take their states from the onset's own series or Taylor polynomial.

Error budget: each phase's Taylor integration at tolerance epsilon; each switch time located by
heyoka's event root finding to a few epsilon of t; the maps are exact (no rounding but the
handing over of the same numbers).  E + W is checked after every phase (:func:`~verify.engine.hybrid_guards.check_balance`) and reported
(:attr:`HybridSolution.energy_plus_work_drift_in_eps`).  The sliding phases are not cut into segments with phi, psi moved
out (as :mod:`verify.engine.segments` does for long rolling runs): a sliding phase lasts until
the slip dies out, a fraction of a second at the rates the suite uses; its steps are capped at one
radian of the fastest initial rate as every run's are (:func:`verify.engine.problem.max_step`).

The modules: this one reads the arguments, launches the run and passes it from phase to switch to phase
(:func:`drive`); :mod:`~verify.engine.hybrid_rolling` and :mod:`~verify.engine.hybrid_sliding` integrate a
phase each, :mod:`~verify.engine.hybrid_switches` starts a slip from s = 0, :mod:`~verify.engine.hybrid_system`
compiles the sliding system and the functions they evaluate, :mod:`~verify.engine.hybrid_run` keeps the run's
record (:class:`HybridSolution`), :mod:`~verify.engine.hybrid_guards` checks it.
"""
from __future__ import annotations

from models import coulomb

from . import hybrid_guards as guards, hybrid_rolling, hybrid_sliding, hybrid_switches
from .hybrid_run import HybridSolution, Phase, Run, UnsupportedTransition
from .hybrid_system import SLIDING_STATE_NAMES, compiled, launch_slip, sliding_expressions
from .validation import InvalidStart, first_problem, parameters as resolve_parameters, positive_number
from .validation import state as resolve_state
from ..precision import parse_precision

__all__ = ["solve", "drive", "HybridSolution", "Phase", "UnsupportedTransition", "SLIDING_STATE_NAMES",
           "compiled", "launch_slip", "sliding_expressions"]


def solve(
    name: str,
    t_end,
    state=None,
    params=None,
    *,
    friction,
    velocity=None,
    precision="double",
    n_eval: int = 101,
    t_eval=None,
) -> HybridSolution:
    """Integrate ``disk+coulomb`` or ``ring+coulomb`` from time 0 to ``t_end``.

    Parameters
    ----------
    name : {"disk+coulomb", "ring+coulomb"}
    t_end : number or decimal string, > 0
    state : mapping or sequence
        The eight components as for :func:`verify.engine.single.solve`.
    params : mapping, optional
        The rolling model's parameters (``disk``: k, g; ``ring``: I1, I3, h, g).
    friction : number or decimal string >= 0
        The Coulomb coefficient mu (static = kinetic).
    velocity : pair, optional
        The centre of mass's horizontal velocity (v_x, v_y) at t = 0; None: rolling (no slip).
    precision : {"double", "long", "quad", "mp:BITS"}
    n_eval : int
        Equally spaced output times from 0 to t_end (plus the switch times).
    t_eval : sequence, optional
        The output times instead (plus the switch times): increasing, from 0 to t_end, each read at
        ``precision`` (decimal strings exactly as written).

    Raises
    ------
    ValueError
        Bad input; :class:`~verify.engine.validation.InvalidStart` for a start outside the domain
        or with N <= 0.
    UnsupportedTransition
        The run reached the onset of slip from rolling where mu_req = mu (the ``slips`` event) and the
        onset's series does not settle, or a slip from s = 0 whose direction is not unique; ``t`` is
        its time, ``trajectory`` the
        :class:`HybridSolution` up to it.
    IntegrationError
        A sliding phase failed (non-finite state, event detection).
    """
    prec = parse_precision(precision)
    rolling, sliding, all_params = coulomb.body(name)
    t_end = positive_number("t_end", t_end, prec)
    try:
        mu = prec.number(friction)
    except (ValueError, TypeError) as err:
        raise ValueError(f"friction={friction!r}: {err}; allowed: a Coulomb coefficient >= 0") from None
    if not float(mu) >= 0:
        raise ValueError(f"friction={friction!r} must be >= 0 (the Coulomb coefficient)")
    pars = resolve_parameters(rolling, params, prec)
    y0 = resolve_state(rolling, state, prec)
    problem = first_problem(rolling, y0[:, None], None, [dict(state)] if isinstance(state, dict) else None)
    if problem is not None:  # the body's domain and constraints, as solve checks them (N waits for the phase)
        raise InvalidStart(problem[2], problem[1])
    c = compiled(name, prec)
    par_vector = prec.array([pars[p.name] for p in rolling.parameters] + [mu])
    if t_eval is not None:
        grid = [prec.number(v) for v in t_eval]
        if len(grid) < 2 or grid[0] != 0 or grid[-1] != t_end or any(not b > a for a, b in zip(grid, grid[1:])):
            raise ValueError(f"t_eval must increase from 0 to t_end = {float(t_end):.9g} (at least 2 times); "
                             f"got {len(grid)} times from {float(grid[0]) if grid else None!r}")
    else:
        n = int(n_eval) - 1
        if n < 1:
            raise ValueError(f"n_eval={n_eval} must be at least 2")
        grid = [t_end * prec.number(i) / prec.number(n) for i in range(n)] + [t_end]

    run = Run(name, prec, c, pars, par_vector, mu, grid, t_end)
    if velocity is None:
        drive(run, ("rolling", prec.zero(), y0))
    else:
        s, alpha = launch_slip(c, y0, [prec.number(v) for v in velocity], par_vector)
        if s == 0:
            drive(run, ("rolling", prec.zero(), y0))
        else:
            drive(run, ("sliding", prec.zero(), prec.array(list(y0) + [s, alpha, prec.zero()]), None))
    if run.outcome == "ok" and not (run.t and run.t[-1] == t_end):  # 'ok' means t_end was reached: say so
        raise guards.fail(run, guards.SHORT_RUN, f"{name}: the run ended ok at t = {float(run.t[-1]) if run.t else 0:.9g}"
                                                 f" before t_end = {float(t_end):.9g} (a bug of the driver)", None, None)
    return run.result()


def drive(run: Run, step) -> None:
    """Run ``run`` from ``step`` until it ends: each phase returns the switch it reached, each switch the next
    phase's start.

    ``step`` is ``("rolling", t0, y8)`` or ``("sliding", t0, y0, onset)``; a rolling phase returns
    ``("slips", t, y8)`` (the slip onset at mu_req = mu) or ``("cannot_roll", t, y8, why)`` (the onset from
    s = 0 with mu_req > mu), a sliding phase ``("sticks", t, y8)``; None ends the run (its outcome says how).
    The phases and switches are looked up on their modules at each call (tests replace them there).
    """
    while step is not None:
        kind, *args = step
        if kind == "rolling":
            step = hybrid_rolling.rolling_phase(run, *args)
        elif kind == "sliding":
            step = hybrid_sliding.sliding_phase(run, *args)
        elif kind == "sticks":
            step = hybrid_switches.after_stick(run, *args)
        elif kind == "slips":
            step = hybrid_switches.slip_onset(run, *args)
        elif kind == "cannot_roll":
            step = hybrid_switches.onset(run, *args)
        else:  # a bug of the driver, not of the run
            raise AssertionError(f"hybrid.drive: unknown step {kind!r}")
