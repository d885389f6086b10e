"""The report's figures: alt text, reproducible bytes, units on every axis, readable fonts.

Drawn from small synthetic data (a caption's runs, a retrograde sweep's rows) and one small
stability map, so the checks see every figure type without running the report; the spin-down
figure is checked in tests/test_dissipation.py on its fast runs.
"""
from __future__ import annotations

import math

import matplotlib
import numpy as np
import pytest

from verify.claims.base import FigureData, RunData
from verify import style
from verify.report import retrograde
from verify.report.figures import Image, draw, render, with_alt_text
from verify.report.study_figures import draw_map, render_map
from verify.studies import maps
from verify.studies.retrograde import spec_path
from verify.sweep import load

T = np.linspace(0.0, 10.0, 2001)


def _run(label, flat: bool) -> RunData:
    theta = 1.3 + (1e-12 * np.sin(T) if flat else 0.2 * np.sin(5 * T))
    omega3 = 18.0 + (0.0 * T if flat else 2 * np.cos(5 * T))
    f = lambda a: tuple(float(v) for v in a)
    return RunData(label, f(T), f(theta), f(3 * T), f(omega3), f(np.cos(T)), f(np.sin(T)), 3.5e-15, "ok")


CAPTIONS = (FigureData("fig-02", "Fig. 2: steady circle (Eq. 21)", (_run("Eq. 21 circle", True),)),
            FigureData("fig-03", "Fig. 3: two runs", (_run("1.001 x Eq. 32, alpha0 = 0.1, phidot0 = 0", False),
                                                      _run("0.9 x Eq. 32", True))),
            FigureData("fig-16", "Fig. 16: hurricane balls at phidot0 = sqrt(25 g)",
                       (_run("LHS", False), _run("RHS", False), _run("third", False))))


def _sweep_rows(spec):
    """One row per grid point of the air-drag sweep, cycling through yes, no, undecided, too short."""
    axes = {a.name: a.values for a in spec.axes}
    rows, k = [], 0
    for c in axes["c"]:
        for h in axes["h"]:
            for w in axes["w"]:
                value, windows = ((1.0, 5.0), (0.0, 5.0), (math.nan, 5.0), (math.nan, math.nan))[k % 4]
                rows.append({"in_c": c, "in_h": h, "in_w": w, "retrograde_turn": value, "windows": windows,
                             "roll_reversal": value if k % 4 < 2 else (0.0 if k % 4 == 2 else math.nan)})
                k += 1
    return rows


@pytest.fixture(scope="module")
def sweep():
    spec = load(spec_path("air-drag"))
    return spec, _sweep_rows(spec)


@pytest.fixture(scope="module")
def small_map():
    return maps.stability_map("disk", "diameter-spin", rates=[20.0, 28.0, 40.0], tilts=[1e-3, 1e-1], t_end=1.0)


def _figures(small_map, sweep):
    """(name, matplotlib Figure) of every figure type the report draws (inside the style)."""
    spec, rows = sweep
    yield from ((f.name, draw(f)) for f in CAPTIONS)
    yield "map", draw_map(small_map)
    for q in ("retrograde_turn", "roll_reversal"):
        yield q, retrograde.draw_yes_no(spec, rows, q)


def _images(small_map, sweep):
    return [render(f) for f in CAPTIONS] + [render_map(small_map)] + list(retrograde.figures("air-drag", *sweep).values())


def test_every_axis_label_names_its_unit(small_map, sweep):
    with matplotlib.rc_context(style.RC):
        for name, fig in _figures(small_map, sweep):
            assert style.labels_without_units(fig) == [], name
            matplotlib.pyplot.close(fig)


def test_a_label_without_unit_is_caught():
    """Negative control: the check is not vacuous."""
    for label in ("theta", "omega3", "t", "x", "log10(max deviation / tilt)", "phi / degrees"):
        assert not style.has_unit(label), label
    for label in (r"$\theta$ / rad", "t / s", r"$\omega_3$ / (rad/s)", "x / R", r"$\log_{10}$(initial tilt / rad)"):
        assert style.has_unit(label), label
    with matplotlib.rc_context(style.RC):
        fig = draw(CAPTIONS[1])
        fig.axes[2].set_ylabel("phi")
        assert style.labels_without_units(fig) == ["phi"]
        matplotlib.pyplot.close(fig)


def test_fonts_width_and_no_offset_labels(small_map, sweep):
    """Every text >= MIN_FONT_PT at the displayed size (900 px wide: 1 pt = 100/72 px), and no
    axis shows an offset such as 1e-12+1.3 (the flat series of fig-02 says its range instead)."""
    with matplotlib.rc_context(style.RC):
        for name, fig in _figures(small_map, sweep):
            assert style.small_texts(fig) == [], name
            assert fig.get_size_inches()[0] * fig.dpi == pytest.approx(900), name
            offsets = [a.get_offset_text().get_text() for ax in fig.axes for a in (ax.xaxis, ax.yaxis)]
            assert not any(offsets), (name, offsets)
            matplotlib.pyplot.close(fig)
        fig = draw(CAPTIONS[0])
        assert any("constant: range" in t.get_text() for t in fig.findobj(matplotlib.text.Text))
        matplotlib.pyplot.close(fig)
        # negative control: a figure outside the style has small fonts
        fig, ax = matplotlib.pyplot.subplots()
        ax.plot([0, 1], [0, 1])
        ax.set_title("small", fontsize=7)
        assert ("small", 7) in style.small_texts(fig)
        matplotlib.pyplot.close(fig)


def test_every_render_returns_images_with_alt_text_and_same_bytes(small_map, sweep):
    first, second = _images(small_map, sweep), _images(small_map, sweep)
    assert [i.filename for i in first] == ["fig-02.png", "fig-03.png", "fig-16.png", "map-disk-diameter-spin.png",
                                           "retrograde-air-drag.png", "retrograde-air-drag-roll.png"]
    for a, b in zip(first, second):
        assert isinstance(a, Image) and a.data[:8] == b"\x89PNG\r\n\x1a\n"
        assert a == b, a.filename  # same bytes, same alt text
        assert 40 < len(a.alt) < 1200 and "image of" not in a.alt.lower(), a.alt
    assert "3 runs" in first[2].alt and "ball radius a" in first[2].alt and "LHS: ok" in first[2].alt
    assert "radius R" in first[1].alt and "0 to 10 s" in first[1].alt


def test_hurricane_lengths_are_in_ball_radii():
    with matplotlib.rc_context(style.RC):
        fig = draw(CAPTIONS[2])
        assert fig.axes[0].get_xlabel() == "x / a"
        matplotlib.pyplot.close(fig)
        fig = draw(CAPTIONS[1])
        assert fig.axes[0].get_xlabel() == "x / R"
        matplotlib.pyplot.close(fig)


def test_yes_no_maps_label_every_cell(sweep):
    """Every run falls in one of the four labelled categories, NaN cells included (white before)."""
    spec, rows = sweep
    _, _, _, codes = retrograde.categorise(spec, rows, "retrograde_turn")
    assert sorted(np.unique(codes)) == [0, 1, 2, 3]
    assert (codes == 3).sum() == sum(math.isnan(r["windows"]) for r in rows)
    with matplotlib.rc_context(style.RC):
        fig = retrograde.draw_yes_no(spec, rows, "retrograde_turn")
        legend = [t.get_text() for t in fig.legends[0].get_texts()]
        matplotlib.pyplot.close(fig)
    assert [t.rsplit(" (", 1)[0] for t in legend] == [text for _, _, text in retrograde.CATEGORIES]
    assert sum(int(t.rsplit("(", 1)[1].rstrip(")")) for t in legend) == len(rows)
    with pytest.raises(ValueError, match="no run stored"):
        retrograde.draw_yes_no(spec, rows[1:], "retrograde_turn")


def test_alt_text_goes_into_the_markdown():
    md = "text\n![Fig. 2](figures/fig-02.png)\n![x](figures/other.png)"
    assert with_alt_text(md, {"fig-02.png": "Fig. 2 [steady]: one run."}) == \
        "text\n![Fig. 2 (steady): one run.](figures/fig-02.png)\n![x](figures/other.png)"
