"""The terminal event contact_lost: the same zero as the model's normal force, at a fraction of its cost.

:func:`verify.engine.compile.contact_event` writes N/(Mg) = 1 + a_C . Z / g with the right-hand
side's own expressions for the accelerations.  Against the simplified ``Model.normal_force`` it
must be the same function (symbolically), fire at the same events at the same times (to a few eps
of the precision), and leave the run alone where N does not set heyoka's step size.
"""
from __future__ import annotations

import heyoka as hy
import numpy as np
import pytest
import sympy as sp

from models import ALL_NAMES, get_model, sources
from models.symbols import ACCELERATIONS
from verify.engine.compile import compile_model, contact_event_function, symbol_map, to_heyoka
from verify.engine.problem import problem
from verify.precision import parse_precision
from verify.standard import STANDARD_STATES

WITH_CONTACT = [(name, eq) for name in ALL_NAMES for eq in sources(name)
                if get_model(name, eq).normal_force is not None]


@pytest.mark.parametrize("name,equations", WITH_CONTACT)
def test_the_event_function_is_the_normal_force_on_shell(name, equations):
    model = get_model(name, equations)
    on_shell = dict(zip(ACCELERATIONS, model.accelerations))
    event = contact_event_function(model)
    assert event.has(*ACCELERATIONS)  # off shell: the accelerations are read from the right-hand side
    assert sp.cancel(sp.together(event.subs(on_shell) - model.normal_force)) == 0


def test_models_without_a_contact_have_no_contact_event():
    for name in ("gyroscope", "effective"):
        model = get_model(name)
        assert model.normal_force is None and contact_event_function(model) is None
        assert "contact_lost" not in [n for n, _, _ in compile_model(model, parse_precision("double")).events]


def _old_events(compiled):
    """The events as compiled before: the simplified N/(Mg) for contact_lost."""
    fp = compiled.precision.fp_type
    mapping = symbol_map(compiled.model, compiled.variables)
    events = [hy.t_event(ex, direction=d, fp_type=fp) for name, ex, d in compiled.events if name != "contact_lost"]
    events.append(hy.t_event(to_heyoka(compiled.model.normal_force, mapping), direction=hy.event_direction.negative,
                             fp_type=fp))
    return events


def _run(p, events, t_end):
    ta = hy.taylor_adaptive(list(p.compiled.system), p.y0, pars=p.par_vector, t_events=events,
                            **p.precision.integrator_kwargs())
    res = ta.propagate_until(p.precision.number(t_end))
    code = int(res[0]) if res[0] != hy.taylor_outcome.time_limit else 0
    return code, int(res[3]), ta.time, np.array(ta.state)


def test_the_shared_form_adds_fewer_terms_to_the_decomposition():
    """What the change is for: heyoka computes each term of the decomposition on every step.  The disk
    has 20 more terms with the simplified N than without events, 6 with the shared form (heyoka
    7.13); asserted only as fewer, so that another heyoka version's decomposition does not matter."""
    p = problem(get_model("disk"), STANDARD_STATES["disk"])
    c = p.compiled

    def size(events):
        return len(hy.taylor_adaptive(list(c.system), p.y0, pars=p.par_vector, t_events=events).decomposition)

    bare = size([])
    assert size(c.t_events()) - bare < (size(_old_events(c)) - bare) / 2


# (model, start, event the run must end with, or None for a run to t_end)
CASES = [
    ("disk", STANDARD_STATES["disk"], None),
    ("disk", {"theta": "1.5", "thetadot": "-5"}, "contact_lost"),
    ("disk", {"theta": "2.0", "thetadot": "5"}, "contact_lost"),
    ("disk", {"theta": "1.0"}, "lies_flat"),
    ("ring", {"theta": "1.5"}, "rim_switch"),
    ("ring", {"theta": "1.0", "thetadot": "-9"}, "lies_flat"),
    ("hurricane", {"theta": "1.4"}, "upper_ball_contact"),
    ("hurricane", {"theta": "0.3", "thetadot": "-30"}, "upright"),
    ("sliding-disk", {"theta": "1.0"}, "lies_flat"),
    ("disk+moffatt", {"theta": "1.5", "thetadot": "-5"}, "contact_lost"),
]


@pytest.mark.parametrize("precision", ["double", "quad"])
@pytest.mark.parametrize("name,state,event", CASES)
def test_same_events_at_the_same_times(name, state, event, precision):
    """Old and new events stop the same runs with the same event, after the same steps, at times
    within 4 eps (relative to max(1, t)) of each other.

    The two functions are N/(Mg) evaluated two ways: their Taylor coefficients differ by rounding, a
    few eps of N's terms (order 1 at these starts), and N' is order 1 to 100 per second at the
    zeros here, so the root moves by less than an eps (0.2 eps at most was seen); 4 eps leaves room.
    A domain event's function is the same in both, so its time is the same bits as long as the
    steps before it are.
    """
    t_end = "2" if precision == "double" else "0.3"
    p = problem(get_model(name), state, precision=precision)
    c = p.compiled
    names = [n for n, _, _ in c.events]
    old = _run(p, _old_events(c), t_end)
    new = _run(p, c.t_events(), t_end)
    assert (names[-new[0] - 1] if new[0] else None) == event
    # _old_events puts contact_lost last, as compile_model does
    assert old[0] == new[0] and old[1] == new[1]
    eps = float(p.precision.eps)
    t_old, t_new = float(old[2]), float(new[2])
    assert abs(t_new - t_old) <= 4 * eps * max(1.0, t_old)
    if name == "disk" and event != "contact_lost":
        # the disk's N never sets the step size at these starts: the very same bits
        assert old[2] == new[2] and old[3].tobytes() == new[3].tobytes()


def test_negative_control_a_shifted_zero_is_told_apart():
    """The time bound of the test above can fail: N/(Mg) - 1e-12 (a zero moved by about 1e-12 / N'
    seconds) is caught, and so is an event on another function."""
    p = problem(get_model("disk"), {"theta": "1.5", "thetadot": "-5"})
    c = p.compiled
    mapping = symbol_map(c.model, c.variables)
    shifted = [hy.t_event(ex, direction=d) for name, ex, d in c.events if name != "contact_lost"]
    shifted.append(hy.t_event(to_heyoka(c.model.normal_force, mapping) - 1e-12, direction=hy.event_direction.negative))
    new, moved = _run(p, c.t_events(), "2"), _run(p, shifted, "2")
    assert new[0] == moved[0] == -3
    assert abs(float(moved[2]) - float(new[2])) > 4 * float(p.precision.eps) * max(1.0, float(new[2]))
