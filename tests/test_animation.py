"""The animation of the rolling bodies: geometry properties, the writers, bad input.

Runs here are synthetic (closed-form angles on a dense grid), so no model is integrated.
"""
from __future__ import annotations

import io
import os
import re
import shutil
import warnings

import numpy as np
import pytest
import sympy as sp
from PIL import Image

from verify.animation import AnimationError, AnimationRun, animate, build
from verify.animation import geometry, shapes, timing

RNG_SEED = 20240601
#: Each body's theta domain (models' DOMAIN) and its parameters.
BODIES = {
    "disk": ("disk", (0.0, np.pi), {"k": 0.25}),
    "hoop": ("disk", (0.0, np.pi), {"k": 0.5}),
    "ring": ("ring", (0.0, np.pi / 2), {"h": 0.4344}),
    "hurricane": ("hurricane", (0.0, np.pi / 2), {}),
}


def synthetic_run(label="spin", model="disk", params=None, seconds=0.4, n=401, rate=6.0) -> AnimationRun:
    """A body precessing at ``rate`` rad/s with a slow rolling spin (not a solution; for drawing)."""
    t = np.linspace(0.0, seconds, n)
    return AnimationRun(label, model, dict(params or {"k": 0.25}), t, 1.2 + 0.1 * np.sin(3 * t), rate * t,
                        -2 * rate * t, 0.3 * np.cos(t), 0.3 * np.sin(t))


def random_states(n, domain, seed):
    rng = np.random.default_rng(seed)
    lo, hi = domain
    theta = rng.uniform(lo + 1e-3, hi - 1e-3, n)
    return theta, rng.uniform(-20, 20, n), rng.uniform(-20, 20, n), rng.uniform(-5, 5, n), rng.uniform(-5, 5, n)


# ---------------------------------------------------------------------------------------------
# geometry


def test_rotation_matches_verify_frames():
    from models.symbols import phi, psi, theta
    from verify.frames import rotation_matrix

    f = sp.lambdify((theta, phi, psi), rotation_matrix(), "numpy")
    th, ph, ps, _, _ = random_states(20, (0, np.pi), RNG_SEED)
    r = geometry.rotation(th, ph, ps)
    for i in range(len(th)):
        np.testing.assert_allclose(r[i], np.asarray(f(th[i], ph[i], ps[i]), float), atol=1e-14)


@pytest.mark.parametrize("model", ["disk", "ring", "hurricane"])
def test_centre_height_matches_contact_vector_of_verify_frames(model):
    from models.symbols import phi, theta
    from verify.frames import contact_vector

    params = {"k": 0.25, "h": 0.4344}
    expr = -contact_vector(model)[2].subs(sp.Symbol("h", nonnegative=True), params["h"])
    f = sp.lambdify((theta, phi), expr, "numpy")
    th, ph, _, _, _ = random_states(50, (0, np.pi / 2), RNG_SEED + 1)
    kind = geometry.body_kind(model)
    np.testing.assert_allclose(geometry.centre_height(kind, th, params), np.broadcast_to(f(th, ph), th.shape),
                               atol=1e-14)


@pytest.mark.parametrize("body", list(BODIES))
def test_contact_point_is_on_the_plane_and_on_the_body(body):
    kind, domain, params = BODIES[body]
    th, ph, ps, x, y = random_states(200, domain, RNG_SEED + 2)
    p = geometry.contact_point(kind, th, ph, x, y, params)
    np.testing.assert_allclose(p[:, 2], 0.0, atol=1e-14)
    c = geometry.centre(kind, th, x, y, params)
    _, e2, e3 = geometry.frame(th, ph)
    d = p - c
    if kind == "disk":  # on the rim, in the disk's plane (Eq. 7)
        np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0, atol=1e-14)
        np.testing.assert_allclose(np.einsum("ni,ni->n", d, e3), 0.0, atol=1e-14)
    elif kind == "ring":  # on the rim edge at -h e3 (Eq. 47)
        np.testing.assert_allclose(np.einsum("ni,ni->n", d, e3), -params["h"], atol=1e-14)
        radial = d + params["h"] * e3
        np.testing.assert_allclose(np.linalg.norm(radial, axis=1), 1.0, atol=1e-14)
    else:  # straight below the lower ball's centre C - e3, one radius down (Eq. 63)
        np.testing.assert_allclose(p - (c - e3), np.tile([0, 0, -1.0], (len(th), 1)), atol=1e-14)


@pytest.mark.parametrize("body", list(BODIES))
def test_drawn_body_touches_the_plane_at_the_contact_and_not_below(body):
    kind, domain, params = BODIES[body]
    mesh = shapes.mesh_for(kind, params)
    chord_sag = 1 - np.cos(np.pi / min(shapes.SECTORS, shapes.SPHERE_MERIDIANS, shapes.SPHERE_PARALLELS))
    for th, ph, ps, x, y in zip(*random_states(100, domain, RNG_SEED + 3)):
        r = geometry.rotation(np.array(th), np.array(ph), np.array(ps))
        c = geometry.centre(kind, np.array(th), np.array(x), np.array(y), params)
        quads, _ = mesh.placed(r, c)
        lowest = quads[..., 2].min()
        assert lowest >= -1e-12, (th, lowest)
        assert lowest <= chord_sag + 1e-12, (th, lowest)


def test_mark_is_on_the_rim_at_body_angle_psi():
    th, ph, ps, x, y = random_states(50, (0, np.pi), RNG_SEED + 4)
    e1, e2, _ = geometry.frame(th, ph)
    r = geometry.rotation(th, ph, ps)
    mark = np.einsum("nij,j->ni", r, shapes.mark_point("disk", {"k": 0.25}))
    expected = np.cos(ps)[:, None] * e1 + np.sin(ps)[:, None] * e2  # b1 (verify/frames.py)
    np.testing.assert_allclose(mark, expected, atol=1e-14)
    mesh = shapes.mesh_for("disk", {"k": 0.25})
    marked = mesh.quads[mesh.mark]
    assert np.allclose(marked.mean(axis=(0, 1))[1:], 0.0, atol=1e-12)  # the marked sector is centred on b1
    assert marked.mean(axis=(0, 1))[0] > 0


def test_hoop_is_an_annulus_and_disk_is_full():
    assert np.linalg.norm(shapes.mesh_for("disk", {"k": 0.5}).quads[..., :2], axis=-1).min() == pytest.approx(
        1 - shapes.HOOP_BAND)
    assert np.linalg.norm(shapes.mesh_for("disk", {"k": 0.25}).quads[..., :2], axis=-1).min() == 0


def test_gyroscope_pivot_fixed_for_a_consistent_motion():
    t = np.linspace(0, 1, 200)
    th, ph = 1.0 + 0.2 * np.sin(5 * t), 3 * t
    e3 = geometry.frame(th, ph)[2]
    x, y = 0.7 + 2 * e3[:, 0], -0.2 + 2 * e3[:, 1]  # C = pivot + 2 e3 (paper: r_B = -2a e3)
    height = geometry.gyroscope_pivot_height(th)
    p = geometry.pivot_point(th, ph, x, y, height)
    np.testing.assert_allclose(p - p[0], 0.0, atol=1e-14)
    mesh = shapes.mesh_for("gyroscope", {})
    for i in range(0, 200, 20):
        quads, _ = mesh.placed(geometry.rotation(th[i], ph[i], 0.0),
                               geometry.centre("gyroscope", th[i], x[i], y[i], {}, height))
        assert quads[..., 2].min() > 0


# ---------------------------------------------------------------------------------------------
# clock


def test_default_speed_rule_and_raise():
    run = synthetic_run(rate=6.0)
    arrays = {n: np.asarray(getattr(run, n), float) for n in ("t", "theta", "phi", "psi", "x", "y")}
    c = timing.clock([arrays], 25, None, 20.0)
    fastest = timing.angular_speed(arrays).max()
    assert 0.9 * min(1, 2 * np.pi / fastest) <= c.speed <= 2 * np.pi / fastest and not c.raised
    assert c.speed == float(f"{c.speed:.2g}")
    c2 = timing.clock([arrays], 25, None, 0.5)
    assert c2.raised and 0.4 / c2.speed <= 0.5
    assert len(c.times) == int(np.ceil(0.4 / (c.speed / 25) - 1e-9)) + 1 and c.times[-1] == 0.4
    with pytest.raises(AnimationError, match="max_seconds"):
        timing.clock([arrays], 25, 0.001, 20.0)


def test_coarse_grid_is_refused_with_one_line():
    run = synthetic_run(n=5, rate=30.0)
    with pytest.raises(AnimationError) as err:
        build([run], width_px=40)
    assert "\n" not in str(err.value) and "n_eval" in str(err.value)


# ---------------------------------------------------------------------------------------------
# writers


def _animate_quietly(*args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return animate(*args, **kwargs)


def test_gif_frames_and_size(tmp_path):
    out = tmp_path / "a.gif"
    rec = _animate_quietly([synthetic_run()], out, speed=0.1, fps=25, width_px=120)
    assert rec.frames == 101 and rec.size == (120, 108)
    with Image.open(out) as im:
        assert im.size == (120, 108)
        durations = []
        for i in range(im.n_frames):
            im.seek(i)
            durations.append(im.info["duration"])
        assert im.n_frames == rec.frames  # every frame differs (the body moves)
        assert sum(durations) == rec.frames * 40
    assert [p.name for p in tmp_path.iterdir()] == ["a.gif"]  # no temporary left
    umask = os.umask(0)
    os.umask(umask)
    assert out.stat().st_mode & 0o777 == 0o666 & ~umask  # an ordinary file's mode, not mkstemp's 0600


def test_gif_is_reproducible(tmp_path):
    runs = [synthetic_run(seconds=0.1, n=101)]
    a = _animate_quietly(runs, tmp_path / "a.gif", speed=0.1, width_px=60)
    b = _animate_quietly(runs, tmp_path / "b.gif", speed=0.1, width_px=60)
    assert a.file.read_bytes() == b.file.read_bytes()


def test_html_is_self_contained_and_reproducible(tmp_path):
    runs = [synthetic_run(seconds=0.1, n=101)]
    a = _animate_quietly(runs, tmp_path / "a.html", speed=0.1, width_px=60)
    text = a.file.read_text()
    assert "data:image/png;base64" in text
    assert not re.search(r"(src|href)\s*=\s*[\"']?(https?:)?//", text) and "<link" not in text
    assert 'class="fa' not in text  # the CDN's icons are written as characters
    b = _animate_quietly(runs, tmp_path / "b.html", speed=0.1, width_px=60)
    assert text == b.file.read_text()


@pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="ffmpeg is not on PATH (apt-get install ffmpeg)")
def test_mp4_written(tmp_path):
    rec = _animate_quietly([synthetic_run(seconds=0.1, n=101)], tmp_path / "a.mp4", speed=0.1, width_px=64)
    assert rec.file.stat().st_size > 0


def test_mp4_without_ffmpeg_says_how_to_get_it(tmp_path, monkeypatch):
    monkeypatch.setattr(shutil, "which", lambda name: None)
    with pytest.raises(AnimationError) as err:
        animate([synthetic_run()], tmp_path / "a.mp4")
    assert "apt-get install ffmpeg" in str(err.value) and "\n" not in str(err.value)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("name, needle", [("a.avi", ".avi"), ("missing/a.gif", "missing"), ("a", "none")])
def test_bad_output_raises_one_line_and_writes_nothing(tmp_path, name, needle):
    with pytest.raises(AnimationError) as err:
        animate([synthetic_run()], tmp_path / name, width_px=40)
    message = str(err.value)
    assert needle in message and "allowed" in message and "\n" not in message
    assert isinstance(err.value, ValueError)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("model, params", [("effective", {}), ("no-such-body", {}), ("ring", {"k": 0.25})])
def test_undrawable_model_or_missing_parameter(tmp_path, model, params):
    with pytest.raises(AnimationError) as err:
        animate([synthetic_run(model=model, params=params)], tmp_path / "a.gif", width_px=40)
    assert "\n" not in str(err.value)
    assert list(tmp_path.iterdir()) == []


def test_two_runs_side_by_side_share_one_clock():
    runs = [synthetic_run("stable"), synthetic_run("unstable", seconds=0.2, n=201, rate=3.0)]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig, panels, clock, draw = build(runs, width_px=80, speed=0.1)
        assert len(panels) == 2 and len(fig.axes) == 2
        assert [ax.get_title() for ax in fig.axes] == ["stable", "unstable"]
        assert clock.times[-1] == 0.4  # the longer run sets the clock; the shorter holds its end
        draw(len(clock.times) - 1)


@pytest.mark.parametrize("model, params", [("ring", {"h": 0.4344}), ("hurricane", {}), ("gyroscope", {}),
                                           ("disk+coulomb", {"k": 0.5})])
def test_every_body_draws_a_frame(model, params):
    run = synthetic_run(model=model, params=params, seconds=0.1, n=101)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig, panels, clock, draw = build([run], width_px=60, speed=0.1)
        draw(len(clock.times) // 2)
        fig.savefig(io.BytesIO(), format="png")  # rendered, not only laid out
