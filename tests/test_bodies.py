"""Bodies of revolution from their profile (models.profiles, models.bodies, ``--body FILE``).

The paper's bodies, derived again from their profiles, must be the shipped models (sympy identities, the
same bits where the parameterisation is the same); each profile's contact point must be the lowest point of
the profile (checked by brute force over the profile's points, not by the formula); bad bodies are refused
in one line; a new body's run keeps its invariants.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.bodies import body_from_mapping, body_of_revolution, load, model_of, shipped, to_toml
from models.profiles import InvalidBody, contact
from models.symbols import theta
from verify.cli import main
from verify.engine.single import solve


def _same(a, b) -> bool:
    return all(sp.simplify(x - y) == 0 for x, y in zip(a, b))


def test_the_paper_bodies_from_their_profiles_are_the_shipped_models():
    disk, ring, balls = get_model("disk"), get_model("ring"), get_model("hurricane")
    k = disk.parameter("k").symbol
    from_disk = model_of(load("disk"))
    I1, I3 = (p.symbol for p in from_disk.parameters[:2])
    assert _same([a.subs({I1: k, I3: 2 * k}) for a in from_disk.accelerations], disk.accelerations)
    from_ring = model_of(load("ring"))
    half = from_ring.parameter("half_thickness").symbol
    assert _same([a.subs(half, ring.parameter("h").symbol) for a in from_ring.accelerations], ring.accelerations)
    from_balls = model_of(load("hurricane"))
    assert from_balls.accelerations == balls.accelerations  # the same expressions, term for term
    assert [i.expr for i in from_balls.invariants] == [i.expr for i in balls.invariants]


def test_the_hurricane_balls_from_their_profile_give_the_same_bits_and_the_disk_agrees_to_rounding():
    start = {"theta": "1.21", "phidot": "70", "psidot": "70"}
    a = solve("hurricane", "0.5", start, n_eval=9)
    b = solve(model_of(load("hurricane")), "0.5", start, n_eval=9)
    assert np.array_equal(a.y, b.y)
    # the disk's file has I1, I3 where the model has k, 2 k: other roundings of the same equations, which differ
    # by about eps a step, carried by the flow's transition matrix (row sums ~1e3 by 0.5 s, HEYOKA.md) over ~60
    # steps: eps sqrt(N) |Phi| = 2.2e-16 x 8 x 1e3 = 2e-12 relative; 1e-11 leaves a factor 5
    start = {"theta": "1.2", "phidot": "1", "psidot": "10"}
    a = solve("disk", "0.5", start, n_eval=9)
    b = solve(model_of(load("disk")), "0.5", start, n_eval=9)
    assert not np.array_equal(a.y, b.y) and np.max(np.abs(a.y - b.y) / (1 + np.abs(a.y))) < 1e-11


PROFILES = {
    "point-rim": ({"radius": 1}, lambda s: (1, 0)),
    "two-rims": ({"radius": 1, "half_thickness": sp.Rational(2, 5)}, lambda s: (1, -sp.Rational(2, 5))),
    "sphere": ({"radius": 1, "centre_height": sp.Rational(3, 10)}, lambda s: (sp.cos(s), sp.Rational(3, 10) + sp.sin(s))),
    "torus-rim": ({"radius": 1, "half_thickness": sp.Rational(1, 10), "tube_radius": sp.Rational(1, 20)},
                  lambda s: (sp.Rational(19, 20) + sp.cos(s) / 20, -sp.Rational(1, 20) + sp.sin(s) / 20)),
    "ellipse": ({"a": sp.Rational(1, 2), "c": 1, "centre_height": sp.Rational(-1, 5)},
                lambda s: (sp.cos(s) / 2, -sp.Rational(1, 5) + sp.sin(s))),
}


@pytest.mark.parametrize("kind", list(PROFILES))
def test_the_contact_point_is_the_profiles_lowest_point(kind):
    """Brute force: the lowest of 20001 points of the (lower piece of the) profile, height = -rho sin(theta) +
    zeta cos(theta), lies within the sampling's resolution of the formula's contact point at several tilts."""
    values, point = PROFILES[kind]
    c = contact(kind, values)
    s = np.linspace(-math.pi / 2, math.pi / 2, 20001) if kind != "torus-rim" else np.linspace(-math.pi, 0, 20001)
    rho_zeta = sp.lambdify(sp.Symbol("s"), point(sp.Symbol("s")), "numpy")
    rho, zeta = (np.broadcast_to(np.asarray(v, float), s.shape) for v in rho_zeta(s))
    for th in (0.2, 0.7, 1.2, 1.5):
        if not float(c.theta_min) < th < float(c.theta_max):
            continue
        heights = -rho * math.sin(th) + zeta * math.cos(th)
        j = int(np.argmin(heights))
        r2, r3 = (float(sp.sympify(e).subs(theta, th)) for e in (c.r2, c.r3))
        assert heights[j] == pytest.approx(r2 * math.sin(th) + r3 * math.cos(th), abs=1e-7), (kind, th)
        assert math.hypot(rho[j] + r2, zeta[j] - r3) < 2e-3, (kind, th)


@pytest.mark.parametrize("change, words", [
    ({"inertia": {"I1": "1/4", "I3": "3/4"}}, "I3 = 3/4 > 2 I1"),
    ({"inertia": {"I1": "-1/4", "I3": "1/2"}}, "I1 = -1/4"),
    ({"profile": {"kind": "sphere", "radius": "1", "centre_height": "3/2"}}, "outside the sphere"),
    ({"profile": {"kind": "torus-rim", "radius": "1", "half_thickness": "1/20", "tube_radius": "1/10"}}, "tube_radius"),
    ({"profile": {"kind": "two-rims", "radius": "1", "half_thickness": "1/2"}, "domain": {"theta_max": "2"}},
     "domain"),
    ({"profile": {"kind": "cone", "radius": "1"}}, "allowed: point-rim"),
    ({"profile": {"kind": "point-rim", "radius": "0"}}, "radius = 0"),
    ({"profile": {"kind": "point-rim", "radius": "__import__('os')"}}, "not a number"),
    ({"profile": {"kind": "point-rim", "radius": 1.5}}, "give numbers as strings"),
    ({"profile": {"kind": "point-rim", "radius": 1}}, "give numbers as strings"),  # a TOML integer too
    ({"profile": {"kind": ["point-rim"], "radius": "1"}}, "profile.kind"),
    ({"inertia": {"I1": "9**9**9**9", "I3": "1/2"}}, "no powers"),  # would hang sympy
    ({"inertia": {"I1": "1e999999999", "I3": "1/2"}}, "exponent of at most 3 digits"),
])
def test_bad_bodies_are_refused_naming_the_value(change, words):
    data = {"name": "bad", "profile": {"kind": "point-rim", "radius": "1"}, "inertia": {"I1": "1/4", "I3": "1/2"}}
    data.update(change)
    with pytest.raises(InvalidBody, match=words.replace("(", "\\(").replace("*", "\\*")):
        body_from_mapping(data)


def test_every_shipped_body_loads_and_the_rounded_coin_passes_the_upright_smoothly():
    assert {"disk", "ring", "hurricane", "rounded-coin", "routh-sphere", "prolate-ellipsoid",
            "oblate-ellipsoid"} <= set(shipped())
    for name in shipped():
        model_of(load(name))
    coin = model_of(load("rounded-coin"))
    assert coin.domain.theta_max == sp.pi  # one rounded rim: no rim switch at pi/2
    r2 = sp.diff(coin.velocity_xy[0], theta)  # smooth through pi/2: nothing singular there
    assert sp.simplify(r2.subs(theta, sp.pi / 2)).is_finite is not False


def test_a_routh_sphere_keeps_energy_jellett_and_routh_and_a_run_through_the_upright():
    sphere = model_of(load("routh-sphere"))
    sol = solve(sphere, "2", {"theta": "0.5", "phidot": "3", "psidot": "30"}, n_eval=11)
    assert sol.outcome == "ok"
    for name in ("energy", "jellett", "routh"):
        # each step commits about eps of the invariant's term scale (the Taylor tolerance) plus a few roundings
        # of its terms: 16 eps a step at most, adding like a random walk over the steps, and a factor 4 to spare
        tr = sol.invariants[name]
        assert tr.max_drift_vs_terms <= 64 * 2.0 ** -52 * math.sqrt(sol.steps), (name, tr.max_drift_vs_terms)
    # a coin rocking through the upright: the rounded rim rolls over it, the paper's two rims (the ring model
    # with the same numbers) stop there at their rim switch (the negative control)
    start = {"theta": "pi/2 - 0.05", "thetadot": "3"}
    coin = body_of_revolution("torus-rim", "301/1200", "1/2", radius="1", half_thickness="1/20", tube_radius="1/20")
    run = solve(coin, "0.1", {"theta": math.pi / 2 - 0.05, "thetadot": 3}, n_eval=11)
    assert run.outcome == "ok" and np.max(run.y[0]) > math.pi / 2 + 0.1, run.outcome
    rims = body_of_revolution("two-rims", "301/1200", "1/2", radius="1", half_thickness="1/20")
    stopped = solve(rims, "0.1", {"theta": math.pi / 2 - 0.05, "thetadot": 3}, n_eval=11)
    assert stopped.outcome == "event:rim_switch" and stopped.t[-1] < 0.05, (stopped.outcome, start)


def test_a_body_file_that_is_not_text_is_refused(tmp_path):
    junk = tmp_path / "junk.toml"
    junk.write_bytes(bytes(range(128, 256)))
    with pytest.raises(InvalidBody, match="not UTF-8"):
        load(junk)


def test_the_command_line_runs_a_body_file_and_refuses_a_bad_one(tmp_path, capsys):
    out = tmp_path / "coin.csv"
    assert main(["trajectory", "--body", "rounded-coin", "--t-end", "0.25", "--output", str(out), "--no-progress"]) == 0
    assert "body:rounded-coin" in capsys.readouterr().out and out.exists()
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "bad"\n[profile]\nkind = "point-rim"\nradius = "1"\n[inertia]\nI1 = "1/4"\nI3 = "3/4"\n')
    assert main(["trajectory", "--body", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "I3 = 3/4 > 2 I1" in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_a_shipped_body_rolls_and_slides_with_coulomb_friction_keeping_jellett_through_every_phase():
    """The tippe top spun about its axis from rest (exact Coulomb, mu = 0.3): the slip dies in milliseconds and
    the top rolls; Jellett's L . r_P, evaluated on the run's own states in every phase, holds to the
    tolerance, and E + W is kept by the hybrid's own guard (it raises otherwise)."""
    from verify.engine.hybrid import solve as solve_hybrid

    sol = solve_hybrid("body:tippe-top+coulomb", "0.1", {"theta": "0.1", "psidot": "100"}, friction="0.3",
                       velocity=("0", "0"), n_eval=11)
    assert [p.kind for p in sol.phases] == ["sliding", "rolling"] and 0 < sol.switch_times[0] < 0.05
    rolling = get_model("body:tippe-top")
    jellett = next(i for i in rolling.invariants if i.name == "jellett")
    from models.symbols import STATE

    subs = {p.symbol: p.default for p in rolling.parameters}
    f = sp.lambdify(STATE, jellett.expr.subs(subs), "numpy")
    values = np.array([f(*sol.y[:, j].astype(float)) for j in range(sol.y.shape[1])])
    scale = float(sp.lambdify(STATE, jellett.scale.subs(subs), "numpy")(*sol.y[:, 0].astype(float)))
    assert np.max(np.abs(values - values[0])) <= 64 * 2.0 ** -52 * math.sqrt(sol.steps) * scale
    with pytest.raises(ValueError, match="unknown body"):
        get_model("body:no-such-body")


def test_the_first_derivation_is_the_tree_every_later_process_reads(tmp_path, monkeypatch):
    """The thin disk's derived model comes back from its pickle as another tree (``==`` tells them apart:
    the negative control), so the process that derives it returns what later processes read, and the
    first run on an empty cache compiles the same code as every run after it."""
    import pickle

    from models import bodies

    monkeypatch.setenv("HEYOKA_CACHE_DIR", str(tmp_path))
    body = load("disk")
    fresh = bodies._derive(body)
    assert pickle.loads(pickle.dumps(fresh)) != fresh  # the control: a round trip changes this tree
    first = bodies.cached_derivation(body)  # derived, written, returned as read back
    assert bodies.cached_derivation(body) == first  # read back by "another process"


def test_a_bodys_sliding_phase_is_kept_on_disk(tmp_path, monkeypatch):
    """``body:NAME+coulomb`` derives its sliding phase once (the egg's took minutes on every run) and reads it
    back; the same phase, and the one disk+coulomb derives for the thin disk's own contact vector."""
    from models import bodies, coulomb

    monkeypatch.setenv("HEYOKA_CACHE_DIR", str(tmp_path))
    coulomb._body_sliding.cache_clear()
    try:
        assert not coulomb.sliding_is_kept("body:disk+coulomb")  # what the command line warns of
        _, first, _ = coulomb.body("body:disk+coulomb")
        assert coulomb.sliding_is_kept("body:disk+coulomb") and coulomb.sliding_is_kept("disk+coulomb")
        (written,) = (tmp_path / "bodies").glob("disk-sliding-*.pickle")
        coulomb._body_sliding.cache_clear()
        _, again, _ = coulomb.body("body:disk+coulomb")
        assert again == first and again is not first
        whole = written.read_bytes()
        for damage in (b"not a pickle", whole[:-40] + bytes([whole[-40] ^ 1]) + whole[-39:]):  # garbage; one bit
            written.write_bytes(damage)  # damaged: derived again and rewritten, never trusted
            coulomb._body_sliding.cache_clear()
            assert coulomb.body("body:disk+coulomb")[1] == first
            assert written.read_bytes() == whole
        direct = coulomb.derive_sliding(*bodies.contact_vector(load("disk")))
        assert all(sp.simplify(a - b) == 0 for a, b in zip(direct.rhs, first.rhs))
        # a body file named like the shipped one in the working folder is not what body:disk+coulomb slides as
        monkeypatch.chdir(tmp_path)
        (tmp_path / "disk").write_text(to_toml(load("disk")).replace('radius = "1"', 'radius = "2"'))
        coulomb._body_sliding.cache_clear()
        assert coulomb.body("body:disk+coulomb")[1] == first
    finally:
        coulomb._body_sliding.cache_clear()  # leave no phase read from this temporary folder behind


def test_a_derived_body_is_kept_on_disk_and_read_back_as_the_same_model(tmp_path, monkeypatch):
    from models import bodies

    monkeypatch.setenv("HEYOKA_CACHE_DIR", str(tmp_path))
    body = load("routh-sphere")
    first = bodies.cached_derivation(body)  # derived, then written
    (written,) = (tmp_path / "bodies").glob("routh-sphere-*.pickle")
    again = bodies.cached_derivation(body)  # read back
    assert again == first and again is not first
    written.write_bytes(b"not a pickle")  # a damaged cache is derived again, not trusted
    assert bodies.cached_derivation(body) == first
