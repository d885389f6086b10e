"""The paths along which a batch integrator is called (verify.engine.call_paths): every path gives the
same bits, with and without a step cap and a step limit; the chooser tries each path once, skips
batches too short to time, then keeps the fastest."""
from __future__ import annotations

import copy

import numpy as np
import pytest

from verify.engine import call_paths
from verify.engine.ensemble import resolve
from verify.engine.lanes import compile_lanes

BS = 4


@pytest.fixture(scope="module")
def disk_lanes():
    model = resolve("disk")
    lanes = compile_lanes(model, "full", BS, 100.0)
    rng = np.random.default_rng(11)
    states = np.zeros((8, BS))
    states[0] = rng.uniform(0.9, 1.4, BS)
    states[4] = rng.uniform(-2, 2, BS)
    states[5] = rng.uniform(4, 12, BS)
    values = {**{p.name: float(p.default) for p in model.parameters}, "theta_max": float(model.domain.theta_max)}
    return lanes, states, lanes.layout.columns(BS, values)


def _along_every_path(disk_lanes, cap, limit) -> list:
    lanes, states, pars = disk_lanes
    grid = np.ascontiguousarray(np.repeat(np.linspace(0.0, 3.0, 31)[:, None], BS, axis=1))
    results = []
    for path in call_paths.PATHS:
        ta = copy.deepcopy(lanes.template)
        ta.state[:] = states
        ta.pars[:] = pars
        out = call_paths.propagate_grid(ta, grid, path, cap, limit)[-1]
        results.append((out.tobytes(), ta.state.tobytes(), [tuple(r) for r in ta.propagate_res]))
    return results


# heyoka's own steps here are ~0.011 s: a cap of 0.003 s binds (checked below), a limit of 1e5 steps does not
@pytest.mark.parametrize("cap, limit", [(None, None), (0.003, None), (0.003, 100_000)])
def test_every_path_gives_the_same_bits(disk_lanes, cap, limit):
    results = _along_every_path(disk_lanes, cap, limit)
    assert all(r == results[0] for r in results[1:])
    assert np.isfinite(np.frombuffer(results[0][0])).all()
    if cap is not None:  # the cap reached heyoka along every path: it changed the steps
        assert results[0][0] != _along_every_path(disk_lanes, None, None)[0][0]


def test_a_step_limit_is_passed_on(disk_lanes):
    """The limit reaches heyoka along every path (a run stopped by it is not a completed one)."""
    lanes, states, pars = disk_lanes
    grid = np.ascontiguousarray(np.repeat(np.linspace(0.0, 3.0, 31)[:, None], BS, axis=1))
    for path in call_paths.PATHS:
        ta = copy.deepcopy(lanes.template)
        ta.state[:] = states
        ta.pars[:] = pars
        call_paths.propagate_grid(ta, grid, path, None, 5)
        assert max(int(r[3]) for r in ta.propagate_res) <= 5
        assert any(str(r[0]).endswith("step_limit") for r in ta.propagate_res)


def test_the_chooser_tries_each_path_then_keeps_the_fastest():
    chooser = call_paths.PathChooser(min_steps=10)
    seconds = {path: 1.0 + i for i, path in enumerate(call_paths.PATHS)}
    fastest = call_paths.PATHS[2]
    seconds[fastest] = 0.5
    seen = []
    for _ in range(len(call_paths.PATHS)):
        path = chooser.path()
        seen.append(path)
        chooser.record(path, 3.0, 5)  # too short to time: tried again
        assert chooser.path() == path
        chooser.record(path, seconds[path] * 100, 100)
    assert seen == list(call_paths.PATHS)
    assert chooser.chosen == fastest
    chooser.record(fastest, 1e9, 100)  # once chosen, kept
    assert chooser.path() == fastest
