# Every target bootstraps .venv itself: `make demo` and `make test` are the contract.
PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed
DEVSTAMP := $(VENV)/.installed-dev
export MPLBACKEND ?= Agg

.PHONY: install demo readme-img test test-all test-rl bench lint docs clean

$(PY):
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip

$(STAMP): pyproject.toml | $(PY)
	$(PY) -m pip install -q -e .
	@touch $@

$(DEVSTAMP): pyproject.toml | $(PY)
	$(PY) -m pip install -q -e ".[dev]"
	@touch $(STAMP) $@

# Installing includes compiling the Numba kernels the first commands need (40-75 s of CPU by the machine,
# in 2 processes at once, with a progress line every 2 s), so that no first run waits for it.
# Numba caches them; later calls find them there and return in a second or two.
install: $(STAMP)
	$(PY) -m mawdo.jit --jobs 2

demo: install
	$(VENV)/bin/mawdo demo --out out/demo

# The README image is the demo's own figure (mawdo.planning.demo.write_figure), copied; it
# stores its title and caption as PNG text, which tests/planning/test_demo.py checks.
readme-img: demo
	cp out/demo/snapshots_mawdo.png docs/img/snapshots_mawdo.png
	@$(PY) -c "from mawdo.planning.demo import figure_text as t; \
	print('README caption:', t('docs/img/snapshots_mawdo.png')['Description'])"

# CI (CI=true) runs the fast tier; `make test-all` adds the slow convergence and study tests.
# The planner's kernels are compiled first, in 2 processes at once (the tests would compile
# them one after the other, on a fresh clone about a minute of waiting). The tests run in
# TEST_WORKERS processes (pytest-xdist), each test file whole in one of them: on 2 cores the
# fast tier takes about half the time of one process (a kernel that only tests need may be
# compiled in both).
TEST_WORKERS ?= 2
test: $(DEVSTAMP)
	$(PY) -m mawdo.jit --jobs 2
	$(PY) -m pytest -q -n $(TEST_WORKERS) --dist loadfile -m "not slow and not rl" --timeout=600

# The slow tier also computes stored runs of the official CEC studies again bit for bit. Some
# of them go through OpenBLAS (EA4eig's and the cmaes library's eigendecompositions), whose
# kernels differ by CPU, as NumPy's AVX-512 loops do (docs/deviations.md#d-cpu); the stores
# were made with OpenBLAS's Haswell kernels and without those loops, and test-all asks the same
# of any x86-64 CPU with AVX2 (a setting of your own in the environment wins).
CPU_PINS := $(shell grep -qs avx2 /proc/cpuinfo && echo OPENBLAS_CORETYPE=$${OPENBLAS_CORETYPE:-Haswell} \
	$$(grep -qs avx512f /proc/cpuinfo && echo NPY_DISABLE_CPU_FEATURES=$${NPY_DISABLE_CPU_FEATURES:-X86_V4}))
test-all: $(DEVSTAMP)
	$(CPU_PINS) $(PY) -m pytest -q -m "not rl" --timeout=1800

# The tests that train with stable-baselines3 (marker rl) need PyTorch, which the dev extras
# leave out: they run in a venv of their own with the rl extra (pip picks the PyTorch build).
RLVENV := .venv-rl
RLSTAMP := $(RLVENV)/.installed-rl
$(RLSTAMP): pyproject.toml
	$(PYTHON) -m venv $(RLVENV)
	$(RLVENV)/bin/python -m pip install -q --upgrade pip
	$(RLVENV)/bin/python -m pip install -q -e ".[dev,rl]"
	@touch $@

test-rl: $(RLSTAMP)
	$(RLVENV)/bin/python -m pytest -q -m rl --timeout=600

bench: $(DEVSTAMP)
	$(PY) -m benchmarks

# The documentation site into site/, warnings as errors; `mkdocs serve` previews it.
docs: $(DEVSTAMP)
	$(PY) -m mkdocs build --strict

lint: $(DEVSTAMP)
	$(PY) -m ruff check src tests benchmarks
	$(PY) -m ruff format --check src tests benchmarks

clean:
	rm -rf $(VENV) $(RLVENV) out build site *.egg-info src/*.egg-info
