"""The batch propagator (verify.engine.batch): lanes, threads and chunks change no bit; compiled
functions evaluated over many runs give the bits of one call per run; frozen lanes record why and when."""
from __future__ import annotations

import math

import heyoka as hy
import numpy as np
import pytest

from verify.engine import batch

X, V = hy.make_vars("x", "v")


def _oscillator(batch_size: int):
    """x'' = -w^2 x (w = par[0]) with the freezing factor par[1]; event: x falls through par[4]."""
    alive = hy.par[1]
    system = [(X, V * alive), (V, -hy.par[0] ** 2 * hy.sin(X) * alive)]
    events = [("below", X - hy.par[4], hy.event_direction.negative)]
    return batch.batch_system(system, events, batch.Lanes(alive=1, reason=2, t_stop=3), 5, batch_size, 100.0,
                              [0.5, 0.0], [1.0], park=((1, 0.0),))


def _lanes(n: int, batch_size: int):
    rng = np.random.default_rng(7)
    pad = batch.pad_lanes(n, batch_size)
    states = np.stack([rng.uniform(0.1, 1.5, n), rng.uniform(-1, 1, n)])[:, pad]
    pars = np.zeros((5, len(pad)))
    pars[0] = rng.uniform(1, 3, n)[pad]
    pars[1] = 1.0
    pars[3] = np.nan
    pars[4] = rng.uniform(-1.2, 0.0, n)[pad]
    return np.ascontiguousarray(states), pars


def _run(ta, states, pars, grid, threads, chunk):
    outputs, finals = [], []
    for batches, messages in batch.propagate_grid(ta, states, pars, grid, threads, chunk):
        assert not messages
        for b in batches:
            assert b.complete(len(grid))
            outputs.append(b.output)
            finals.append(b.local.pars)
    return np.concatenate(outputs, axis=2), np.concatenate(finals, axis=1)


def test_threads_and_chunks_change_no_bit():
    ta = _oscillator(4)
    states, pars = _lanes(37, 4)
    grid = np.linspace(0.0, 6.0, 121)
    out1, fin1 = _run(ta, states, pars, grid, 1, None)
    out2, fin2 = _run(ta, states, pars, grid, 2, 3)
    assert out1.tobytes() == out2.tobytes() and fin1.tobytes() == fin2.tobytes()
    assert (fin1[2] > 0).any() and (fin1[2] == 0).any()  # some lanes froze, some did not: both paths ran


def test_frozen_lane_records_its_event_and_stops_moving():
    ta = _oscillator(4)
    states, pars = _lanes(8, 4)
    grid = np.linspace(0.0, 6.0, 121)
    out, fin = _run(ta, states, pars, grid, 1, None)
    assert (fin[2] == 1.0).any()  # some lanes did freeze: the loop below is not empty
    for k in np.flatnonzero(fin[2] == 1.0):
        t_stop = fin[3, k]
        after = grid > t_stop
        assert fin[1, k] == 0.0 and 0 < t_stop < grid[-1]
        frozen_x = out[after, 0, k]
        assert np.all(frozen_x == frozen_x[0]) and np.all(out[after, 1, k] == 0.0)  # parked: v = 0, x held
        assert abs(frozen_x[0] - pars[4, k]) < 1e-12  # where the event found x = its threshold
        before = grid < t_stop
        assert np.all(out[before, 0, k] > pars[4, k])  # above its threshold until the event


def test_a_lane_alone_gets_the_bits_it_had_in_a_mixed_batch():
    ta = _oscillator(4)
    states, pars = _lanes(8, 4)
    grid = np.linspace(0.0, 6.0, 61)
    out, fin = _run(ta, states, pars, grid, 1, None)
    for k in (1, 6):
        one, messages = batch.alone(ta, grid, states[:, k], pars[:, k])
        assert not messages
        assert one.output[:, :, 0].tobytes() == out[:, :, k].tobytes()
        assert batch.lane_failure(one, 0, batch.Lanes(1, 2, 3), []) is None


def test_per_lane_evaluation_has_the_bits_of_one_call_per_run():
    fn = batch.ScalarTwin.of([hy.cos(X) * V + hy.sin(X) ** 2, hy.sqrt(X * X + V * V) * hy.par[0]], [X, V])
    rng = np.random.default_rng(3)
    lengths = np.array([1, 2, 3, 4, 5, 7, 9, 13, 401, 402, 403])
    points = rng.uniform(0.1, 3.0, (2, len(lengths), 403))  # lane l's run: its first lengths[l] samples
    pars = rng.uniform(1, 2, (1, len(lengths)))
    got = batch.per_lane(fn, points, pars, lengths)
    for lane, n in enumerate(lengths):
        one = fn.simd(np.ascontiguousarray(points[:, lane, :n]), pars=np.repeat(pars[:, lane:lane + 1], n, axis=1))
        assert got[:, lane, :n].tobytes() == one.tobytes()
    # the lengths leave a scalar tail at any SIMD width (4 or 8): 401, 402, 403 are not multiples of either
    assert any(n % fn.simd.batch_size for n in lengths) or fn.simd.batch_size == 1
    # negative control, the same on any CPU: one input of one run moved by one ulp changes the bytes
    moved = points.copy()
    moved[0, 8, 5] = np.nextafter(moved[0, 8, 5], np.inf)
    assert batch.per_lane(fn, moved, pars, lengths)[:, 8, :401].tobytes() != got[:, 8, :401].tobytes()


def test_a_lane_of_nan_or_huge_values_changes_no_other_lanes_bits():
    """heyoka's vector sine and cosine reduce a whole SIMD group's arguments another way when one of them is
    NaN, infinite or huge; per_lane keeps each lane in groups of its own, so a failed lane's samples (NaN)
    or a lane far out (1e16) leave every other lane with the bits of a call on it alone.  Negative control:
    the same samples flattened across lanes into one call do change some of them."""
    fn = batch.ScalarTwin.of([hy.sin(X) * V + hy.cos(X)], [X, V])
    width = int(fn.simd.batch_size)
    if width == 1:
        pytest.skip("scalar compiled functions: no SIMD groups to share")
    rng = np.random.default_rng(5)
    n_lanes, n = 400, 101  # 101 samples: not whole groups at width 4 or 8
    points = rng.uniform(-3.0, 3.0, (2, n_lanes, n))
    points[0, ::2, 60:] = np.nan
    points[0, 1::4, 90:] = 1e16
    lengths = np.full(n_lanes, n)
    lengths[::2] = 60
    lengths[1::4] = 90
    got = batch.per_lane(fn, points, None, lengths)
    for lane in range(1, n_lanes, 2):
        m = lengths[lane]
        assert got[:, lane, :m].tobytes() == fn.simd(np.ascontiguousarray(points[:, lane, :m])).tobytes()
    # negative control: the same samples flattened across lanes into one call, so that groups hold two lanes
    flat = fn.simd(np.ascontiguousarray(points.reshape(2, -1))).reshape(1, n_lanes, n)
    moved = any(flat[:, lane, :lengths[lane] // width * width].tobytes()
                != got[:, lane, :lengths[lane] // width * width].tobytes() for lane in range(1, n_lanes, 2))
    if not moved:  # measured here (AVX-512) at widths 2, 4 and 8: 2, 6 and 11 values moved by a neighbour
        pytest.skip("this CPU's vector sine and cosine do not depend on the other lanes of a group: the layout "
                    "above passed, but nothing here can show what it guards against")


def test_step_cap_is_one_radian_of_the_fastest_rate():
    assert batch.fastest_rate([3.0, -40.0, 0.0], 980.0) == 40.0
    assert batch.fastest_rate([3.0], 980.0) == math.sqrt(980.0)  # sqrt, correctly rounded
    assert batch.step_cap([-40.0], 980.0) == 1.0 / 40.0


def test_pad_lanes_repeats_the_last_point():
    assert batch.pad_lanes(5, 4).tolist() == [0, 1, 2, 3, 4, 4, 4, 4]
    assert batch.pad_lanes(8, 4).tolist() == list(range(8))
