# The two entry points: `make report` and `make test`.  Both create the virtual
# environment in .venv when it is missing and install the project into it.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed
export HEYOKA_CACHE_DIR ?= $(CURDIR)/.heyoka-cache
export MPLBACKEND := Agg

.PHONY: report test test-all bench engines clean

$(STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

report: $(STAMP)
	$(PY) -m verify report

# The lint (ruff: pyflakes and syntax rules, pyproject's [tool.ruff]), then the tests on every core
# (pytest-xdist): about 6 minutes on 2 cores.
test: $(STAMP)
	$(PY) -m ruff check .
	$(PY) -m pytest -q -n auto

test-all: $(STAMP)
	$(PY) -m pytest -q -n auto -m ''

bench: $(STAMP)
	$(PY) -m verify bench

# The other engines (Exudyn, MuJoCo, PyBullet, Drake) on the reference cases: reports/engines.json.
# Not part of `make report` or `make test`; needs the engines extra.
engines: $(STAMP)
	$(PY) -m pip install --quiet -e '.[engines]'
	$(PY) -m verify engines

clean:
	rm -rf $(VENV) .heyoka-cache .pytest_cache
