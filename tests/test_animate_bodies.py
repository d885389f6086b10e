"""Bodies of revolution animated from their profiles (body files), and the tippe top turning over.

* Every shipped body: the drawn surface (revolved meridian) touches the plane at the body file's contact
  point, to the mesh's resolution (:func:`verify.animation.revolution.resolution`, argued there), at random
  states, at the default and at a fine resolution; a mesh placed with another contact fails the same check.
* The tippe top under the smooth law (the preset of ``animate --body tippe-top --friction 0.3 --friction-law
  smooth --slip-scale 10``) and the exact Coulomb run beside it, through the command's own run making: at
  every frame the drawn ball touches the plane and the drawn-only stem is not below it; the frames' data
  show the inversion (theta crosses pi/2 and ends above 2.5 rad; the drawn stem's tip ends below C), the
  Coulomb panel does not (its negative control).
* Rendering frames of a body (GIF; MP4 skipped without ffmpeg), and bad input: one line, exit 2, nothing written.
"""
from __future__ import annotations

import io
import shutil
import warnings

import numpy as np
import pytest
from PIL import Image

from models.bodies import DIRECTORY, load, shipped
from verify.animation import AnimationRun, animate, build, geometry, revolution
from verify.cli import main
from verify.cli.animate_command import source
from verify.cli.parser import parser
from verify.guard import Session

SEED = 20240611
#: A placed vertex's height is z_C (r2 sin + r3 cos: 2 products, 1 sum, sin/cos within an ulp) plus R[2] . v
#: (3 products, 3 sums), every term at most 3 (the bodies reach <= 2.2 from C, z_C <= 1.3): each operation
#: rounds by eps/2 of at most 3, about 10 of them, so |error| <= 15 eps; 64 eps x 3 leaves a margin of ~13.
HEIGHT_TOL = 64 * np.finfo(float).eps * 3
#: A fine mesh for the strong check: its resolution is below 2e-2 L (asserted; printed on a failure).
FINE = {"meridians": 360, "samples": 180}
SMALL = ["--width", "96", "--max-seconds", "1", "--fps", "10"]


#: the shipped bodies animate draws: all but a curve (the egg), which it refuses in one line (tested below)
DRAWN = [n for n in shipped() if load(n).kind != "curve"]


def _states(profile_domain, n, seed):
    rng = np.random.default_rng(seed)
    lo, hi = profile_domain
    return (rng.uniform(lo + 1e-3, hi - 1e-3, n), rng.uniform(-20, 20, n), rng.uniform(-20, 20, n),
            rng.uniform(-5, 5, n), rng.uniform(-5, 5, n))


def _domain(body):
    from models.profiles import check_domain, contact

    lo, hi = check_domain(contact(body.kind, body.values), body.theta_min, body.theta_max)
    return float(lo), float(hi)


def touching(profile, quads, theta, phi, x, y, bound, centre_height=None) -> tuple:
    """(ok, lowest height, distance from the contact point P to the nearest vertex) of a mesh placed at one state.

    ``ok``: never below the plane (HEIGHT_TOL), lowest point at most ``bound`` above it, and a vertex within
    ``bound`` of P (the body file's contact point): the drawn body touches the plane at P."""
    _, e2, e3 = geometry.frame(np.array(theta), np.array(phi))
    r2, r3 = revolution.contact_radii(profile, np.array(theta))
    z = revolution.centre_height(profile, theta) if centre_height is None else centre_height
    p = np.array([x, y, z]) + r2 * e2 + r3 * e3
    vertices = quads[:, [0, 2]].reshape(-1, 3)  # corners 0 and 2 of the quads are every vertex of the mesh
    lowest = float(vertices[:, 2].min())  # a flat face's lowest point is a corner
    nearest = float(np.min(np.linalg.norm(vertices - p, axis=1)))
    return lowest >= -HEIGHT_TOL and lowest <= bound and nearest <= bound, lowest, nearest


def _placed_mesh(profile, state, mesh, centre_height=None):
    th, ph, ps, x, y = state
    r = geometry.rotation(np.array(th), np.array(ph), np.array(ps))
    z = revolution.centre_height(profile, th) if centre_height is None else centre_height
    return mesh.placed(r, np.array([x, y, float(z)]))[0]


@pytest.mark.parametrize("name", DRAWN)
@pytest.mark.parametrize("resolution", ["default", "fine"])
def test_drawn_body_touches_the_plane_at_the_contact_point(name, resolution):
    body = load(name)
    profile = revolution.profile_of(body)
    kw = FINE if resolution == "fine" else {}
    mesh, _ = revolution.mesh(profile, **kw)
    bound = revolution.resolution(profile, **kw)
    assert bound < (0.02 if resolution == "fine" else 0.25), bound  # the check means something
    for i, state in enumerate(zip(*_states(_domain(body), 12 if resolution == "fine" else 60, SEED))):
        quads = _placed_mesh(profile, state, mesh)
        ok, lowest, nearest = touching(profile, quads, state[0], state[1], state[3], state[4], bound)
        assert ok, (name, i, state[0], lowest, nearest, bound)


@pytest.mark.parametrize("name, wrong", [("tippe-top", {"centre_height": -0.3}), ("ring", {"half_thickness": 0.3}),
                                         ("prolate-ellipsoid", {"a": 0.8}), ("rounded-coin", {"radius": 1.05})])
def test_a_mesh_placed_with_another_contact_fails_the_check(name, wrong):
    """The negative control: the drawn surface placed by a contact formula with other numbers."""
    body = load(name)
    profile = revolution.profile_of(body)
    other = revolution.profile_of(body, wrong)
    mesh, _ = revolution.mesh(profile, **FINE)
    bound = revolution.resolution(profile, **FINE)
    failed = 0
    for state in zip(*_states(_domain(body), 10, SEED + 1)):
        quads = _placed_mesh(profile, state, mesh, revolution.centre_height(other, state[0]))
        failed += not touching(other, quads, state[0], state[1], state[3], state[4], bound)[0]
    assert failed >= 8, failed  # at nearly every state (a wrong contact can agree at an isolated tilt)


def test_profile_values_follow_the_run_and_stem_rule():
    top = revolution.profile_of(load("tippe-top"), {"centre_height": 0.2, "I1": 0.5, "g": 980.0})
    assert top.numbers == {"radius": 1.0, "centre_height": 0.2} and top.I1 == 0.5 and top.stem
    assert not revolution.profile_of(load("hurricane")).stem  # the centre below C: no stem
    ring = revolution.meridian(revolution.profile_of(load("ring")))
    assert ring.rho.min() == pytest.approx(1 - 0.5 / 3.66, abs=1e-12)  # the paper's wall from I3 (module docstring)


def test_a_bad_profile_is_one_line():
    with pytest.raises(ValueError) as err:
        revolution.profile_of(load("tippe-top"), {"centre_height": 1.5})
    assert "\n" not in str(err.value) and "centre_height" in str(err.value)


# ---------------------------------------------------------------------------------------------
# the tippe top: the command's runs, the frames' data

TIPPE = ["animate", "--body", "tippe-top", "--friction", "0.3", "--friction-law", "smooth", "--slip-scale", "10",
         "--t-end", "1.5", "--n-eval", "6001"]


@pytest.fixture(scope="module")
def tippe_panels():
    """The panels built from the runs ``animate`` makes for the preset (smooth law, Coulomb beside), 1.5 s."""
    args = parser().parse_args(TIPPE)
    runs_of, name, start = source(args)
    runs = runs_of(Session(False))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig, panels, clock, draw = build(runs, width_px=200, fps=20)
    return runs, panels, clock, start


def _stem_down(panel, k) -> bool:
    """The drawn stem's far end below C at frame k (from the drawn quads, not from theta)."""
    quads, _, _ = panel.placed(k)
    stem = quads[len(panel.mesh.quads):]
    far = stem.reshape(-1, 3)[np.argmax(np.linalg.norm(stem.reshape(-1, 3) - panel.centres[k], axis=1))]
    return far[2] < panel.centres[k, 2]


def test_the_preset_starts_the_study_start_and_compares_coulomb(tippe_panels):
    runs, panels, clock, start = tippe_panels
    assert [r.model for r in runs] == ["body:tippe-top+smooth", "body:tippe-top+coulomb"]
    assert "C at rest" in start and "[start]" in start
    for r in runs:
        assert r.theta[0] == 0.1  # the start itself, as given
        # C at rest, omega = n e3: u = omega x r_P = -n r2 e1, |u| = n R sin(theta0) (docs/tippe-top.md); the
        # run's slip comes through the compiled contact velocity (a handful of roundings): 16 eps relative
        assert np.hypot(r.slip_x[0], r.slip_y[0]) == pytest.approx(200 * np.sin(0.1), rel=16 * np.finfo(float).eps)
    assert "\u03b5 = 10" in runs[0].label and "Coulomb" in runs[1].label


def test_every_frame_touches_the_plane_and_the_stem_is_not_below_it(tippe_panels):
    _, panels, clock, _ = tippe_panels
    for panel in panels:
        bound = revolution.resolution(panel.profile)
        n_body = len(panel.mesh.quads)
        for k in range(len(clock.times)):
            quads, _, _ = panel.placed(k)
            th = panel.frame_theta[k]
            x, y = panel.frame_path[k]
            ok, lowest, nearest = touching(panel.profile, quads[:n_body], th, _phi_of(panel.rotations[k]), x, y, bound)
            assert ok, (panel.kind, k, th, lowest, nearest, bound)
            assert quads[n_body:, :, 2].min() >= -HEIGHT_TOL, (k, th)  # the stem is cut at the floor
        fine, _ = revolution.mesh(panel.profile, **FINE)  # the panel's placement, with the strong bound
        fine_bound = revolution.resolution(panel.profile, **FINE)
        for k in range(0, len(clock.times), 20):
            quads = fine.placed(panel.rotations[k], panel.centres[k])[0]
            x, y = panel.frame_path[k]
            ok, lowest, nearest = touching(panel.profile, quads, panel.frame_theta[k], _phi_of(panel.rotations[k]),
                                           x, y, fine_bound)
            assert ok, ("fine", panel.kind, k, panel.frame_theta[k], lowest, nearest, fine_bound)


def _phi_of(rotation) -> float:
    """phi from the rotation's third column e3 = (sin phi sin theta, -cos phi sin theta, cos theta)."""
    return float(np.arctan2(rotation[0, 2], -rotation[1, 2]))


def test_the_frames_show_the_smooth_law_inverting_and_coulomb_not(tippe_panels):
    runs, (smooth, coulomb), clock, _ = tippe_panels
    last = len(clock.times) - 1
    # measure 1: theta at the frames crosses pi/2 and ends turned over (above 2.5 rad, the study's threshold)
    assert smooth.frame_theta.max() > np.pi / 2 and smooth.frame_theta[-1] > 2.5
    # measure 2: the drawn stem points up at the first frame and down at the last
    assert not _stem_down(smooth, 0) and _stem_down(smooth, last)
    # the negative control, the exact Coulomb run from the same start: no crossing, the stem up throughout
    assert coulomb.frame_theta.max() < np.pi / 2
    assert not any(_stem_down(coulomb, k) for k in range(0, last + 1, 5))
    # and the phases it shows: slides, then rolls
    assert coulomb.phase[0] == "sliding" and coulomb.phase[-1] == "rolling"


# ---------------------------------------------------------------------------------------------
# rendering, and the command line


def _synthetic(name, n=101, seconds=0.1):
    body = load(name)
    lo, hi = _domain(body)
    t = np.linspace(0, seconds, n)
    theta = lo + (hi - lo) * (0.3 + 0.4 * t / seconds)
    return AnimationRun(name, f"body:{name}", {}, t, theta, 3 * t, 20 * t, 0 * t, 0 * t, slip_x=np.cos(t),
                        slip_y=np.sin(t), phase=np.full(n, "sliding"))


@pytest.mark.parametrize("name", DRAWN)
def test_every_shipped_body_renders_a_frame(name):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig, panels, clock, draw = build([_synthetic(name)], width_px=120, speed=0.1)
        draw(len(clock.times) // 2)
        buffer = io.BytesIO()
        fig.savefig(buffer, format="png")
    with Image.open(buffer) as im:  # not blank: the body and the floor differ from the background
        assert len(np.unique(np.asarray(im.convert("RGB")).reshape(-1, 3), axis=0)) > 20


def test_a_body_gif_is_written(tmp_path):
    rec = animate([_synthetic("rounded-coin")], tmp_path / "coin.gif", speed=0.1, width_px=96, fps=10)
    with Image.open(rec.file) as im:
        assert im.n_frames >= 2 and im.size == (96, 86)


@pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="ffmpeg is not on PATH (apt-get install ffmpeg)")
def test_a_body_mp4_is_written(tmp_path):
    rec = animate([_synthetic("tippe-top")], tmp_path / "top.mp4", speed=0.1, width_px=96, fps=10)
    assert rec.file.stat().st_size > 0


def test_the_command_draws_a_body_file(capsys, tmp_path):
    out = tmp_path / "coin.gif"
    code = main(["animate", "--body", "rounded-coin", "--t-end", "0.3", "--out", str(out), *SMALL])
    text, err = capsys.readouterr()
    assert code == 0, err
    assert "rounded-coin: rolling without slipping" in text and "start" in text
    with Image.open(out) as im:
        assert im.n_frames >= 2


def test_a_body_file_that_is_not_shipped_and_its_saved_run(capsys, tmp_path):
    """A body file elsewhere (the disk's profile under another name), live and from a saved run's metadata."""
    path = tmp_path / "my-disk.toml"
    path.write_text((DIRECTORY / "disk.toml").read_text().replace('name = "disk"', 'name = "my-disk"'))
    run = tmp_path / "run.csv"
    assert main(["trajectory", "--body", str(path), "--state", "theta=1.2", "--state", "psidot=10", "--t-end", "0.3",
                 "--output", str(run)]) == 0, capsys.readouterr().err
    capsys.readouterr()
    for argv in (["--body", str(path), "--state", "theta=1.2", "--state", "psidot=10", "--t-end", "0.3"], [str(run)]):
        out = tmp_path / "a.gif"
        code = main(["animate", *argv, "--out", str(out), *SMALL])
        assert code == 0, capsys.readouterr().err
        capsys.readouterr()
        with Image.open(out) as im:
            assert im.n_frames >= 2
        out.unlink()


@pytest.mark.parametrize("argv, message", [
    (["--body", "no-such-body", "--out", "{d}/x.gif"], "no-such-body"),
    (["--body", "tippe-top", "--figure", "5", "--out", "{d}/x.gif"], "--figure draws the figure's own starts"),
    (["--body", "tippe-top", "--compare", "none", "--out", "{d}/x.gif"], "--compare none is for"),
    (["disk", "--compare", "coulomb", "--out", "{d}/x.gif"], "--compare coulomb is for"),
    (["--body", "tippe-top", "--friction", "0.3", "--friction-law", "smooth", "--out", "{d}/x.gif"], "--slip-scale"),
    (["--body", "tippe-top", "--friction", "-1", "--out", "{d}/x.gif"], "--friction"),
    (["--body", "egg", "--out", "{d}/x.gif"], "is not drawn yet"),
    (["--body", "tippe-top", "--state", "theta=4", "--t-end", "0.1", "--out", "{d}/x.gif"], "theta"),
    (["--body", "tippe-top", "--out", "{d}/x.avi"], ".avi"),
])
def test_bad_body_input_is_one_line_exit_2_and_nothing_written(capsys, tmp_path, argv, message):
    (tmp_path / "b.toml").write_text((DIRECTORY / "tippe-top.toml").read_text())  # a body file that is not shipped
    before = sorted(p.name for p in tmp_path.iterdir())
    argv = [a.replace("{d}", str(tmp_path)) for a in argv]
    code = main(["animate", *argv])
    out, err = capsys.readouterr()
    assert code == 2 and len(err.strip().splitlines()) == 1 and message in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == before

