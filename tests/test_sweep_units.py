"""Every axis and quantity a sweep can have says its unit on the map (verify.sweep.units, verify.sweep.plot).

The table is checked against what each name is (the models' own parameter descriptions and the run
files' units), every parameter of every model and body and every recordable quantity has one (a name
without one raises, so a new parameter or quantity cannot be drawn without a unit silently), and a map
drawn from a store carries them on both axes, the colour bar and a panel's title.
"""
from __future__ import annotations

import matplotlib.figure
import pytest

from models import ALL_NAMES, get_model
from models.bodies import shipped
from models.symbols import STATE_NAMES
from verify.sweep import Store, load, run_sweep
from verify.sweep.plot import render
from verify.sweep.spec import ALWAYS, QUANTITIES
from verify.sweep.units import axis_unit, label, parameter_unit, quantity_unit

from .test_sweep import small

MODELS = list(ALL_NAMES) + [f"body:{b}" for b in shipped()]


@pytest.mark.parametrize("model", MODELS)
def test_every_parameter_of_every_model_has_a_unit(model):
    for p in get_model(model).parameters:
        assert parameter_unit(model, p.name)


@pytest.mark.parametrize("model,name,unit,words", [
    ("disk", "k", "ratio", "I1/(m R^2)"), ("disk", "g", "1/s^2", "g/L in s^-2"), ("ring", "I1", "m R^2", "units of m R^2"),
    ("ring", "h", "R", "in units of R"), ("ring+air-drag", "w", "R", "in units of R"), ("disk+moffatt", "c", "1/s", "in s^-1"),
    ("disk+contact-rate", "c", "1/s", "in s^-1"), ("ring+rolling-friction", "c", "1/s", "tau = -c (omega"),
    ("ring+air-drag", "c", "ratio", "|omega_perp| omega_perp"),
    ("body:oblate-ellipsoid", "c", "L", None), ("body:tippe-top", "centre_height", "L", None),
    ("disk", "phidot", "1/s", None), ("disk", "tilt", "rad", None), ("disk", "x", "R", None), ("hurricane", "x", "a", None),
    ("disk", "friction", "ratio", None),
])
def test_units_say_what_the_names_are(model, name, unit, words):
    """Against the models' own words where a parameter has a description (k = I1/(m R^2); g is g/L in s^-2;
    the ring's h and w in units of R; Moffatt's c in s^-1; a couple per m R^2 (1/s^2) of -c omega_perp has c
    in 1/s and the air drag's -c A |omega_perp| omega_perp a pure number; a body file's c is a semi-axis, a
    length in its scale L), and the run files' units for the state."""
    assert axis_unit(model, name) == unit
    if words is not None:
        (description,) = [p.description for p in get_model(model).parameters if p.name == name]
        assert words in description


def test_every_quantity_has_a_unit_and_an_unknown_name_has_none():
    for q in QUANTITIES + ALWAYS:
        assert quantity_unit("disk", q)
    assert [quantity_unit("disk", f"final_{n}") for n in STATE_NAMES] == ["rad"] * 3 + ["1/s"] * 3 + ["R"] * 2
    for bad in (lambda: quantity_unit("disk", "nonsense"), lambda: axis_unit("disk", "zeta"),
                lambda: parameter_unit("disk", "zeta")):
        with pytest.raises(KeyError):
            bad()


def test_labels_are_written_as_the_run_pictures_write_them():
    assert label("tilt", "rad") == "tilt / rad"
    assert label("phidot", "1/s") == "phidot / (1/s)"
    assert label("I1", "m R^2") == "I1 / (m R^2)"
    assert label("growth", "ratio") == "growth (ratio)"


def test_a_drawn_map_says_its_units(tmp_path, monkeypatch):
    """The map of a small sweep (as tests/test_sweep.py runs it, with k as a third axis) over phidot and k,
    a panel per tilt: the labels read from the figure itself as it is written."""
    path = small(tmp_path)
    text = path.read_text().replace('y = "tilt"', 'y = "k"\npanels = "tilt"')
    path.write_text(text.replace("[record]", '[[axis]]\nname = "k"\nfrom = 0.2\nto = 0.3\ncount = 2\n\n[record]'))
    spec = load(path)
    run_sweep(spec, threads=1, progress=False)
    with Store(spec) as store:
        rows = store.rows()
    seen = []
    original = matplotlib.figure.Figure.savefig

    def keep(fig, *args, **kwargs):
        seen.append(fig)
        return original(fig, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", keep)
    render(spec, rows)
    (fig,) = seen
    labels = {a.get_xlabel() for a in fig.axes} | {a.get_ylabel() for a in fig.axes}
    assert {"phidot / (1/s)", "k (ratio)", "growth (ratio)"} <= labels
    titles = [a.get_title() for a in fig.axes if a.get_title()]
    assert titles and all(t.startswith("tilt = ") and t.endswith(" rad") for t in titles)
