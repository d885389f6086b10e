"""The SIMD width of batch runs (verify/lanes.py) and what must not depend on it.

heyoka recommends 4 lanes on AVX2 machines and 8 on AVX-512 ones; the suite must give the
same verdicts on both.  These tests run the batch engines at widths 4 and 8 on whatever CPU
runs them (heyoka emulates a width the CPU lacks), so a property that holds for one width only
fails here and not on someone else's machine.
"""
from __future__ import annotations

import numpy as np
import pytest

from verify.engine.lanes import ENV, simd_width
from verify.studies import maps

RATES = np.array([0.8, 0.95, 1.05, 1.25]) * np.sqrt(980.0 / 1.25)  # around the disk's diameter-spin threshold 28
TILTS = (1e-4, 1e-2)


def test_width_from_environment(monkeypatch):
    monkeypatch.setenv(ENV, "8")
    assert simd_width() == 8
    monkeypatch.setenv(ENV, "4")
    assert simd_width() == 4
    monkeypatch.delenv(ENV)
    assert simd_width() >= 1


@pytest.mark.parametrize("bad", ["0", "-4", "eight", "1e9", "65"])
def test_bad_width_is_named(monkeypatch, bad):
    monkeypatch.setenv(ENV, bad)
    with pytest.raises(ValueError, match=ENV):
        simd_width()


@pytest.fixture(scope="module")
def maps_by_width():
    return {w: maps.stability_map("disk", "diameter-spin", rates=RATES, tilts=TILTS, t_end=5.0, batch_size=w)
            for w in (4, 8)}


def test_map_classification_is_the_same_at_widths_4_and_8(maps_by_width):
    a, b = maps_by_width[4], maps_by_width[8]
    assert a.batch_size == 4 and b.batch_size == 8
    assert np.array_equal(a.grows, b.grows) and np.array_equal(a.left, b.left)
    # at the small tilt the runs below the threshold grow and those above do not: the verdict the map exists for
    assert list(a.grows[0]) == [True, True, False, False]


def test_map_deviations_agree_across_widths_to_round_off_growth(maps_by_width):
    """Same flow, different lane groupings: the deviations of runs that stay may differ only by
    round-off amplified by the flow; relative 1e-6 is far above that (|Phi| <= 1e4 over 5 s at
    these rates, times eps sqrt(N), N ~ 2e3 steps: ~1e-10) and far below any physical difference."""
    a, b = maps_by_width[4], maps_by_width[8]
    stayed = ~a.left
    assert stayed.any()
    assert np.allclose(a.max_deviation[stayed], b.max_deviation[stayed], rtol=1e-6, atol=0)


def test_default_map_width_follows_the_setting(monkeypatch):
    monkeypatch.setenv(ENV, "8")
    m = maps.stability_map("disk", "diameter-spin", rates=RATES[:2], tilts=TILTS[:1], t_end=1.0)
    assert m.batch_size == 16  # two SIMD registers a lane group
