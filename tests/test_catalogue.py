"""models.catalogue (the models as plain data, for listings and units) against the derived models."""
import subprocess
import sys

import pytest

from models import ALL_NAMES, get_model, sources
from models.catalogue import ALIASES, CATALOGUE, ENTRIES, entry


def test_every_model_has_one_entry():
    assert tuple(e.name for e in ENTRIES) == ALL_NAMES
    assert set(CATALOGUE) == set(ALL_NAMES)


@pytest.mark.parametrize("name", ALL_NAMES)
def test_entry_is_what_the_derivation_gives(name):
    m, e = get_model(name), CATALOGUE[name]
    assert e.title == m.title
    assert e.equations == sources(name)
    assert e.parameters == tuple((p.name, str(p.default), p.allowed(), p.description) for p in m.parameters)
    assert e.domain == (str(m.domain.theta_min), str(m.domain.theta_max), m.domain.below, m.domain.above)
    assert e.invariants == m.invariant_names()
    assert e.inertia_unit == m.units
    assert e.normal_force == (m.normal_force is not None)
    assert e.friction_required == (m.friction_required is not None)


def test_aliases_and_coulomb_bodies_resolve():
    model, params = ALIASES["hoop"]
    assert entry("hoop") is CATALOGUE[model] and float(params["k"]) == 0.5
    assert entry("disk+coulomb") is CATALOGUE["disk"] and entry("ring+coulomb") is CATALOGUE["ring"]
    assert entry("hurricane").length_unit == "a" and entry("ring").length_unit == "R"


def test_listing_imports_no_sympy():
    """The names and the catalogue come without the derivation (the listing answers at once)."""
    code = "import sys, models, models.catalogue; print('sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
