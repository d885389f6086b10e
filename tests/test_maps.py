"""Stability maps (verify/studies/maps.py): batch + ensemble runs against independent routes.

* Point by point against ``verify.engine.single.solve``: the full 8-dimensional derived equations,
  one scalar integrator per point, with solve's own segments and step cap, from the same
  double initial state.  The classification must be the same, and so must the time a run
  leaves (to one sample).  For runs that stay, the maxima over the same sample times differ by
  at most max_k |theta_map(t_k) - theta_scalar(t_k)|.  Both are double integrations of one
  flow at tol = eps, each step committing an error of ~eps |y| that the flow carries forward
  with its state-transition matrix Phi, so that difference is bounded by

      eps sqrt(N) max_k |Phi(t_k, 0)| |y0|

  (N the scalar run's steps, Phi the reduced 4x4 block from heyoka's variational equations
  along the same run, 2-norms), the bound the README states for double against quad (measured
  there at 0.003-0.13 of it; here at most ~0.1, on a run that grows by 1e5).  Near and below
  the threshold |Phi| reaches 1e8, and the bound loosens accordingly.  The map runs without a
  step cap and solve with its own, so the comparison also covers the cap (and a capped map is
  held to the same bound).
* The growth/no-growth switch at the smallest tilt against the exact linear thresholds
  g/(k+1) (rolling) and g/k (frictionless plane), computed here from the closed forms.
* Negative controls: the smooth-plane map against the rolling threshold, and against the
  rolling disk's scalar runs, must fail the same checks.
"""
from __future__ import annotations

import math
from dataclasses import replace

import heyoka as hy
import mpmath
import numpy as np
import pytest

from models import get_model
from verify.engine.compile import compile_model
from verify.engine.single import max_step, resolve_parameters, resolve_state, solve
from verify.precision import parse_precision
from verify.report.study_figures import render_map
from verify.studies import maps
from models.steady import steady_state
from verify.studies.thresholds import GROWTH

FACTORS = np.array([0.5, 0.8, 0.95, 1.05, 1.25, 2.0])  # rates / linear threshold
TILTS = (1e-6, 1e-3, 1e-1)
G = 980.0
ROLLING = math.sqrt(G / (0.25 + 1))  # disk diameter spin, rolling: phidot0^2 = g/(k+1) -> 28
SMOOTH = math.sqrt(G / 0.25)  # disk diameter spin, frictionless plane: g/k -> 62.61 (Olsson)
STRAIGHT = math.sqrt(G / (2 * (2 * 0.25 + 1)))  # disk rolling straight: psidot0^2 = g/(2(2k+1))


@pytest.fixture(scope="module")
def disk_map():
    return maps.stability_map("disk", "diameter-spin", rates=FACTORS * ROLLING, tilts=TILTS)


@pytest.fixture(scope="module")
def smooth_map():
    return maps.stability_map("sliding-disk", "diameter-spin", rates=FACTORS * SMOOTH, tilts=TILTS)


def scalar_runs(name: str, motion: str, smap: maps.StabilityMap, with_conditioning: bool = True) -> dict:
    """Each point of ``smap`` by ``solve`` (full equations), with the conditioning bound of the module docstring."""
    prec = parse_precision("double")
    model = get_model(name)
    fast = replace(model, chaplygin=None)  # same equations; skips the Chaplygin invariants the map does not read
    grid = maps.sample_times(smap.t_end, max(float(smap.rates.max()), math.sqrt(G)))
    assert len(grid) == smap.n_samples
    pars = resolve_parameters(model, {}, prec)
    compiled = compile_model(model, prec)
    vsys = hy.var_ode_sys(list(compiled.system), hy.var_args.vars, order=1)
    parr = compiled.parameter_vector(pars)
    red = (0, 3, 4, 5)  # theta, thetadot, phidot, psidot
    out = {"deviation": np.zeros(smap.left.shape), "left": np.zeros(smap.left.shape, bool),
           "t_cross": np.full(smap.left.shape, np.nan), "bound": np.full(smap.left.shape, np.nan)}
    for i, tilt in enumerate(smap.tilts):
        for j, rate in enumerate(smap.rates):
            state = steady_state(name, motion, repr(float(rate)), {})
            with mpmath.workdps(40):
                th0 = mpmath.mpf(state["theta"])
                state["theta"] = repr(float(th0 + mpmath.mpf(float(tilt))))
            sol = solve(fast, smap.t_end, state, t_eval=grid)
            dev = np.abs(np.asarray(sol["theta"], dtype=float) - float(th0))
            beyond = np.nonzero(dev >= smap.cap)[0]
            out["deviation"][i, j] = dev.max()
            out["left"][i, j] = sol.outcome != "ok" or beyond.size > 0
            if beyond.size:
                out["t_cross"][i, j] = float(sol.t[beyond[0]])
            if with_conditioning and not out["left"][i, j]:
                y0 = resolve_state(model, state, prec)
                ta = hy.taylor_adaptive(vsys, y0, pars=parr, compact_mode=True)
                phi = ta.propagate_grid(grid, max_delta_t=max_step(y0, pars, prec))[-1][:, 8:].reshape(-1, 8, 8)
                norm = max(np.linalg.norm(p[np.ix_(red, red)], 2) for p in phi)
                out["bound"][i, j] = (np.finfo(float).eps * math.sqrt(sol.steps) * norm
                                      * np.linalg.norm([float(y0[k]) for k in red]))
    return out


def disagreements(smap: maps.StabilityMap, scalar: dict) -> list:
    """Points where the map and the scalar runs disagree (the check used by the tests and the control)."""
    bad = []
    scalar_grows = scalar["left"] | (scalar["deviation"] > GROWTH * smap.tilts[:, None])
    spacing = smap.t_end / (smap.n_samples - 1)
    for i, j in np.ndindex(smap.left.shape):
        where = f"rate {smap.rates[j]:.6g}, tilt {smap.tilts[i]:.0e}"
        if smap.grows[i, j] != scalar_grows[i, j] or smap.left[i, j] != scalar["left"][i, j]:
            bad.append(f"{where}: map grows={smap.grows[i, j]} left={smap.left[i, j]}, "
                       f"scalar grows={scalar_grows[i, j]} left={scalar['left'][i, j]}")
        elif smap.left[i, j]:
            # the map freezes the run at theta_steady + cap; the scalar run's first sample beyond it follows
            if not (0 <= scalar["t_cross"][i, j] - smap.t_left[i, j] <= spacing):
                bad.append(f"{where}: left at {smap.t_left[i, j]}, scalar crosses the cap at {scalar['t_cross'][i, j]}")
        else:
            diff = abs(smap.max_deviation[i, j] - scalar["deviation"][i, j])
            if not diff <= scalar["bound"][i, j]:
                bad.append(f"{where}: max deviations differ by {diff:.3g} > bound {scalar['bound'][i, j]:.3g}")
    return bad


@pytest.fixture(scope="module")
def disk_scalar(disk_map):
    return scalar_runs("disk", "diameter-spin", disk_map)


def test_disk_map_matches_scalar_full_equations(disk_map, disk_scalar):
    scalar = disk_scalar
    assert disagreements(disk_map, scalar) == []
    stayed = ~disk_map.left
    ratio = np.abs(disk_map.max_deviation - scalar["deviation"])[stayed] / scalar["bound"][stayed]
    assert ratio.max() < 0.5  # measured 0.11 at most (a growing run); 1e-3 or less on stable ones
    assert disk_map.left.any() and (~disk_map.left).any()


def test_smooth_plane_map_matches_scalar_full_equations(smooth_map):
    assert disagreements(smooth_map, scalar_runs("sliding-disk", "diameter-spin", smooth_map)) == []


@pytest.mark.parametrize("fixture,exact", [("disk_map", ROLLING), ("smooth_map", SMOOTH)])
def test_switch_at_smallest_tilt_brackets_exact_threshold(fixture, exact, request):
    smap = request.getfixturevalue(fixture)
    assert smap.linear_threshold == pytest.approx(exact, rel=1e-14)
    lo, hi = maps.switch_bracket(smap, tilt_index=0)
    assert (lo, hi) == pytest.approx((0.95 * exact, 1.05 * exact), rel=1e-12)
    assert maps.consistent_with_threshold(smap, exact)
    assert smap.grows[0, :3].all() and not smap.grows[0, 3:].any()


def test_straight_line_and_hoop_switch_at_their_thresholds():
    line = maps.stability_map("disk", "straight-line", rates=FACTORS * STRAIGHT, tilts=[1e-6])
    assert maps.consistent_with_threshold(line, STRAIGHT)
    hoop_rate = math.sqrt(G / 1.5)  # k = 1/2
    hoop = maps.stability_map("disk", "diameter-spin", rates=FACTORS * hoop_rate, tilts=[1e-6], params={"k": "0.5"})
    assert hoop.params["k"].startswith("0.5") and hoop.linear_threshold == pytest.approx(hoop_rate, rel=1e-14)
    assert maps.consistent_with_threshold(hoop, hoop_rate)
    assert not maps.consistent_with_threshold(hoop, ROLLING)  # k = 1/4's threshold lies outside the hoop's switch


@pytest.mark.parametrize("batch_size", [4, 8])  # the SIMD widths of AVX2 and AVX-512 machines, on any CPU
def test_step_cap_changes_nothing_beyond_conditioning(disk_map, disk_scalar, batch_size):
    """The cap changes the step sequence, not the result beyond the conditioning bound.

    How many steps the cap adds depends on which points share a batch (and so on the batch
    size); what holds for every batch size is that a capped batch whose lanes run the whole
    t_end takes at least t_end / cap steps -- the stable points (rates above the threshold)
    do -- and that the classification is unchanged.
    """
    free = maps.stability_map("disk", "diameter-spin", rates=FACTORS * ROLLING, tilts=TILTS, batch_size=batch_size)
    capped = maps.stability_map("disk", "diameter-spin", rates=FACTORS * ROLLING, tilts=TILTS, step_cap=True,
                                batch_size=batch_size)
    assert capped.step_cap == pytest.approx(1 / (2 * ROLLING)) and free.step_cap is None
    assert capped.batch_size == free.batch_size == batch_size
    assert capped.n_steps >= capped.t_end / capped.step_cap
    assert np.array_equal(capped.grows, disk_map.grows) and np.array_equal(capped.left, disk_map.left)
    assert np.array_equal(free.grows, disk_map.grows) and np.array_equal(free.left, disk_map.left)
    stayed = ~disk_map.left  # two step sequences of one flow: the same bound as against the scalar runs
    for other in (capped, free):
        assert np.all(np.abs(other.max_deviation - disk_map.max_deviation)[stayed] <= disk_scalar["bound"][stayed])


def test_negative_control_wrong_threshold_and_wrong_model(disk_map, smooth_map):
    # the frictionless map does not switch at the rolling threshold, nor the rolling map at Olsson's
    assert not maps.consistent_with_threshold(smooth_map, ROLLING)
    assert not maps.consistent_with_threshold(disk_map, SMOOTH)
    # the frictionless map compared with the rolling disk's scalar runs at the same rates
    wrong = scalar_runs("disk", "diameter-spin", smooth_map, with_conditioning=False)
    wrong["bound"] = np.full(wrong["left"].shape, 1e-9)
    assert len(disagreements(smooth_map, wrong)) >= 5


def test_deterministic_whatever_the_threads(disk_map):
    again = maps.stability_map("disk", "diameter-spin", rates=FACTORS * ROLLING, tilts=TILTS, threads=1)
    for name in ("max_deviation", "left", "reason", "t_left", "theta_steady"):
        assert getattr(again, name).tobytes() == getattr(disk_map, name).tobytes(), name
    assert again.n_steps == disk_map.n_steps
    assert render_map(again) == render_map(disk_map)


def test_point_independent_of_its_batch_partners(disk_map):
    reversed_ = maps.stability_map("disk", "diameter-spin", rates=FACTORS[::-1] * ROLLING, tilts=TILTS)
    assert reversed_.max_deviation[:, ::-1].tobytes() == disk_map.max_deviation.tobytes()
    assert reversed_.t_left[:, ::-1].tobytes() == disk_map.t_left.tobytes()


def test_left_runs_report_cap_reason_and_time(disk_map):
    assert np.all(disk_map.max_deviation[disk_map.left] == disk_map.cap)
    assert np.all(disk_map.reason[disk_map.left] > 0) and np.all(disk_map.reason[~disk_map.left] == 0)
    assert np.all(np.isnan(disk_map.t_left[~disk_map.left]))
    assert np.all((disk_map.t_left[disk_map.left] > 0) & (disk_map.t_left[disk_map.left] < disk_map.t_end))
    assert disk_map.n_trajectories == disk_map.left.size
    assert disk_map.max_deviation.shape == (len(TILTS), len(FACTORS))


def test_render_map_png(disk_map):
    image = render_map(disk_map)
    assert image.filename == "map-disk-diameter-spin.png" and "linear threshold" in image.alt
    assert image.data[:8] == b"\x89PNG\r\n\x1a\n" and len(image.data) > 5000
    assert image == render_map(disk_map)  # same bytes, same alt text


@pytest.mark.parametrize("kwargs,message", [
    ({"model": "cube"}, "unknown model 'cube'"),
    ({"motion": "tumbling"}, "unknown motion 'tumbling'"),
    ({"rates": []}, "rates must be a non-empty"),
    ({"rates": [10.0, -1.0]}, "rates contains -1.0"),
    ({"tilts": [0.0]}, "tilts contains 0.0"),
    ({"tilts": [1.5]}, "tilt 1.5"),
    ({"t_end": 0}, "t_end=0"),
    ({"params": {"mass": "1"}}, "unknown parameter 'mass'"),
    ({"model": "hurricane", "motion": "precession", "rates": [20.0]}, "rate 20.0 has no steady precession"),
])
def test_bad_input_raises_value_error(kwargs, message):
    args = {"model": "disk", "motion": "diameter-spin", "rates": [30.0], "tilts": [1e-3], "t_end": 1.0}
    args.update(kwargs)
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(".", r"\.")):
        maps.stability_map(**args)
