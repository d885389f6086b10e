"""The report's Friction section: mu_req on the steady families two ways, the slip on the spin-down two
ways, the figure runs matched to their trajectories, and the section rendered from data only.

* the engine's friction cfunc and the closed form Omega_C^2 rho_C / g agree on steady states of
  every family, in double and quad, to AGREEMENT_FACTOR eps S (``agreement_bound`` argues S);
  a wrong rho_C, or a state off the family (a wrong rate), must fail the same bound;
* the scan's family states are the spin-down study's own;
* the slip tilt on the quasi-steady drift and in the damped run with the ``slips`` event agree to
  the run's departure from the drift, a(theta) plus the start's nutation (checked on a short
  run, a larger couple); the Eq. 45 family itself has no slip, so that agreement is not with it;
* every decimal number of the rendered section is in the data it is rendered from.
"""
from __future__ import annotations

import json
import re
from pathlib import Path

import mpmath
import pytest

from verify.precision import parse_precision
from verify.report.friction import render_markdown
from verify.studies import friction, spindown_slip, steady_friction
from verify.studies.summary import RING_PARAMS

RING = dict(RING_PARAMS)
RESULTS = Path(__file__).resolve().parent.parent / "reports" / "results.json"


def _family(model, family, theta, params):
    values = friction._values(model, params)
    with mpmath.workdps(steady_friction.DPS):
        th = mpmath.mpf(theta)
        phidot, psidot = friction.family_state(model, family, th, values)
    return th, phidot, psidot, values


CIRCLING = [("disk", "zero-vertical-spin", "0.5", {}), ("disk", "zero-vertical-spin", "1e-3", {}),
            ("ring", "zero-vertical-spin", "0.1", RING)]


@pytest.mark.parametrize("model,family,theta,params", CIRCLING + [("disk", "cm-at-rest", "0.1", {}),
                                                                  ("ring", "cm-at-rest", "0.3", RING)])
def test_cfunc_and_closed_form_agree_on_the_spindown_families(model, family, theta, params):
    th, phidot, psidot, values = _family(model, family, theta, params)
    row = friction.steady_point(model, family, th, phidot, psidot, values, theta)
    for precision in steady_friction.CFUNC_PRECISIONS:
        assert row["cfunc"][precision]["agrees"], (precision, row["cfunc"][precision])
        assert abs(float(row["cfunc"][precision]["normal"]) - 1) < 1e-10  # steady: N = M g
    if family == "zero-vertical-spin":
        assert float(row["mu_closed"]) > 1e-3  # a real circle: the check is not 0 = 0
    else:
        assert float(row["mu_closed"]) < 1e-30  # C at rest: rho_C = 0


@pytest.mark.parametrize("model,motion,rate", [("ring", "diameter-spin", "20"), ("hurricane", "precession", "40"),
                                               ("disk", "straight-line", "10")])
def test_cfunc_and_closed_form_agree_on_the_steady_motions(model, motion, rate):
    (row,) = friction.steady_motion_rows(model, motion, RING if model == "ring" else {}, (rate,))
    assert all(row["cfunc"][p]["agrees"] for p in steady_friction.CFUNC_PRECISIONS), row["cfunc"]


def _disagreement(model, th, phidot, psidot, values, precision, geometry=None):
    """|cfunc - closed form| over its bound (> 1: the check fails)."""
    eps = parse_precision(precision).eps
    with mpmath.workdps(steady_friction.DPS):
        closed = steady_friction.closed_form(model, th, phidot, psidot, values, geometry)
        _, mu = steady_friction.cfunc_value(model, th, phidot, psidot, values, precision)
        return float(abs(mu - closed)) / steady_friction.agreement_bound(phidot, psidot, values["g"], eps)


@pytest.mark.parametrize("model,family,theta,params", CIRCLING)
def test_a_wrong_circle_radius_fails(model, family, theta, params):
    """rho_C with the e3 part of r_P wrong (the disk given the ring's h = 0.1, the ring its h with
    the sign flipped): the closed form no longer matches the cfunc."""
    th, phidot, psidot, values = _family(model, family, theta, params)
    wrong = (-1, mpmath.mpf("-0.1")) if model == "disk" else (-1, values["h"])
    assert _disagreement(model, th, phidot, psidot, values, "quad") <= 1
    assert _disagreement(model, th, phidot, psidot, values, "quad", wrong) > 1e3


@pytest.mark.parametrize("model,family,theta,params", CIRCLING)
def test_a_state_off_the_family_fails(model, family, theta, params):
    """phidot 1e-6 relative off the family's rate (psidot by the family's ratio): not a steady
    motion, so thetaddot != 0 and the closed form, which assumes one, is wrong by far more than the bound."""
    th, phidot, psidot, values = _family(model, family, theta, params)
    off = 1 + mpmath.mpf("1e-6")
    assert _disagreement(model, th, phidot * off, psidot * off, values, "quad") > 1e3


@pytest.mark.parametrize("model,family,theta,params", [("disk", "cm-at-rest", "1e-4", {}),
                                                       ("disk", "zero-vertical-spin", "0.3", {}),
                                                       ("ring", "zero-vertical-spin", "0.01", RING)])
def test_the_scan_follows_the_spindown_study(model, family, theta, params):
    from verify.studies.spindown import spindown

    th, phidot, psidot, _ = _family(model, family, theta, params)
    s = spindown(model, theta, family, params)
    with mpmath.workdps(steady_friction.DPS):
        assert abs(phidot / s.phidot - 1) < mpmath.mpf(10) ** -40
        assert abs(psidot / s.psidot - 1) < mpmath.mpf(10) ** -40


def test_the_eq45_family_never_slips_and_the_other_family_does():
    eq45 = friction.family_slip("disk", "cm-at-rest", {})
    assert float(eq45["max_mu"]) < 1e-30 and not any(eq45["roots"].values())
    other = friction.family_slip("disk", "zero-vertical-spin", {})
    assert float(other["max_mu"]) > 0.5 and other["roots"]["0.1"]
    for level, roots in other["roots"].items():  # each root is a root
        values = friction._values("disk", {})
        mu = friction.family_mu("disk", "zero-vertical-spin", values)
        for r in roots:
            assert abs(float(mu(mpmath.mpf(r))) - float(level)) < 1e-8


@pytest.fixture(scope="module")
def short_spindown():
    """The contact-rate spin-down with a couple 100 times the study's: the drift's theta does not
    depend on c, its clock and the adiabatic parameter a scale with it, so the run is short."""
    from verify.studies.dissipation import STUDY_C

    drift = spindown_slip.transported_slip("contact-rate", repr(100 * float(STUDY_C["contact-rate"])))
    return drift, spindown_slip.slip_runs("contact-rate", drift)


def _within_departure(run_theta: float, drift_theta: float, adiabatic: float) -> bool:
    """The run departs from the quasi-steady drift by O(a(theta)) and the start's nutation (relative
    size a(theta0) < 1e-6, damped): agreement to a + 1e-6 is what to expect."""
    return abs(run_theta / drift_theta - 1) <= adiabatic + 1e-6


def test_the_damped_run_slips_where_the_quasi_steady_drift_says(short_spindown):
    drift, runs = short_spindown
    levels = {x["mu"]: x for x in drift["levels"]}
    assert [m for m in spindown_slip.MU_LEVELS if levels[m]["theta"] is None] == []
    assert [leg["mu"] for leg in runs["legs"]] == list(spindown_slip.MU_LEVELS)
    for leg in runs["legs"]:
        assert leg["outcome"] == "event:slips", leg
        d = levels[leg["mu"]]
        assert _within_departure(float(leg["theta"]), float(d["theta"]), float(d["adiabatic"])), (leg, d)
        assert float(leg["plain_max"]) < float(leg["mu"])  # no earlier slip hidden before the switch
        assert abs(float(leg["mu_at_event"]) - float(leg["mu"])) < 1e-9


def test_a_quasi_steady_family_with_the_wrong_rate_fails(short_spindown):
    """Negative control: the disk's other spin-down family (no vertical spin: omega3 tied to phidot,
    not transported) predicts slip tilts the run does not meet, and the same check says so."""
    drift, runs = short_spindown
    levels = {x["mu"]: x for x in drift["levels"]}
    other = friction.family_slip("disk", "zero-vertical-spin", {})
    for leg in runs["legs"]:
        for root in other["roots"][leg["mu"]]:
            assert not _within_departure(float(leg["theta"]), float(root), float(levels[leg["mu"]]["adiabatic"]))
    assert any(other["roots"][leg["mu"]] for leg in runs["legs"])  # not vacuous


def _numbers(text: str) -> set:
    return set(re.findall(r"(?<![\w.])-?\d+\.\d+(?:e[-+]?\d+)?|(?<![\w.])-?\d+e[-+]?\d+", text))


@pytest.fixture(scope="module")
def committed():
    results = json.loads(RESULTS.read_text())
    if "friction" not in results["studies"]:
        pytest.skip("the committed results.json has no friction section yet")
    return results


def _computed(studies) -> set:
    """The numbers the renderer computes from the data, as it formats them: run/drift - 1, t0 - t,
    the largest cfunc differences, the maxima over the families with mu_req = 0."""
    f = studies["friction"]
    fitted = {d["law"]: float(d["fit"]["t0"]) for d in studies.get("dissipation") or []}
    out = set()
    for law, v in f["slip"].items():
        drift = {d["mu"]: d for d in v["drift"]["levels"]}
        for leg in v["run"]["legs"]:
            d = drift.get(leg["mu"], {})
            if leg.get("theta") and d.get("theta"):
                out.add(f"{float(leg['theta']) / float(d['theta']) - 1:.2g}")
            if leg.get("t") and law in fitted:
                out.add(f"{fitted[law] - float(leg['t']):.4g}")
    rows = [r for r in f["steady"]["spindown"] + f["steady"]["motions"] if not r.get("none")]
    for p in f["steady"]["cfunc_precisions"]:
        out.add(f"{max(float(r['cfunc'][p]['difference_in_eps_scale']) for r in rows):g}")
        out.update(f"{float(r['cfunc'][p]['mu']):.1e}" for r in rows)
    out.update(f"{float(r['mu_closed']):.1e}" for r in rows)
    return out


def _typed_numbers(text: str, studies) -> list:
    """The decimal numbers of ``text`` that are neither in the data nor computed from it."""
    data = json.dumps([studies["friction"], studies.get("dissipation")])
    allowed = _computed(studies)
    return [n for n in _numbers(text) if n not in allowed and not re.search(rf"(?<![\d.]){re.escape(n)}(?!\d)", data)]


def test_the_section_renders_from_data_only(committed):
    """Every decimal number of the section is a string of the data, or one the renderer computes
    from it (:func:`_computed`): none is typed into the text."""
    studies = committed["studies"]
    text = "\n".join(render_markdown(studies["friction"], studies.get("dissipation")))
    assert len(_numbers(text)) > 100  # the tables are there
    assert not _typed_numbers(text, studies)
    assert _typed_numbers(text + "\nthe coin slips at theta = 0.0123457", studies) == ["0.0123457"]  # the check sees one


def test_a_changed_number_changes_the_section(committed):
    studies = json.loads(json.dumps(committed["studies"]))
    row = studies["friction"]["figures"][0]
    row["mu_max"] = "0.123456"
    text = "\n".join(render_markdown(studies["friction"], studies.get("dissipation")))
    assert "0.123456" in text


def test_figure_rows_run_the_figure_even_after_its_claims_were_evaluated_in_this_process():
    """The report's pool runs several jobs in one worker: a figure's claims may have been evaluated (and
    cached) by the claims' job before the friction job asks for the figure's runs."""
    from verify.report.figure_friction import figure_claims, figure_rows

    for claim in figure_claims(2):
        claim.evaluate()
    rows = figure_rows(2)
    assert rows and all("run" in r for r in rows)


def test_every_table_row_of_the_section_has_its_header_s_cells():
    """A '|' in a run's label (|psidot0|) must not split its cell, and no line may start a list."""
    import json
    import re
    from pathlib import Path

    from verify.report.friction import render_markdown

    results = json.loads(Path("reports/results.json").read_text())
    lines = render_markdown(results["studies"]["friction"], results["studies"].get("dissipation"))
    cells = lambda line: len(re.split(r"(?<!\\)\|", line.strip())) - 2  # noqa: E731
    header = None
    for line in lines:
        if not line.startswith("|"):
            header = None
            assert not re.match(r"^\d+\. ", line), line  # a wrapped sentence must not become a list item
            continue
        if header is None:
            header = cells(line)
        assert cells(line) == header, line
