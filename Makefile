# Every target bootstraps .venv itself: `make demo` and `make test` are the contract.
PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed
DEVSTAMP := $(VENV)/.installed-dev
export MPLBACKEND ?= Agg

.PHONY: demo test test-all bench lint clean

$(PY):
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip

$(STAMP): pyproject.toml | $(PY)
	$(PY) -m pip install -q -e .
	@touch $@

$(DEVSTAMP): pyproject.toml | $(PY)
	$(PY) -m pip install -q -e ".[dev]"
	@touch $(STAMP) $@

demo: $(STAMP)
	$(VENV)/bin/mawdo demo --out out/demo

# CI (CI=true) runs the fast tier; `make test-all` adds the slow convergence and study tests.
test: $(DEVSTAMP)
	$(PY) -m pytest -q -m "not slow" --timeout=600

test-all: $(DEVSTAMP)
	$(PY) -m pytest -q --timeout=1800

bench: $(DEVSTAMP)
	$(PY) -m benchmarks

lint: $(DEVSTAMP)
	$(PY) -m ruff check src tests benchmarks
	$(PY) -m ruff format --check src tests benchmarks

clean:
	rm -rf $(VENV) out build *.egg-info src/*.egg-info
