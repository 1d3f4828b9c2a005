# Two commands set everything up: `make demo` and `make test`.
# Both create (or reuse) .venv and install the package with the exact
# versions in constraints.txt; only Python 3.11, pip and make are needed.

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PIP    := $(BIN)/python -m pip install --disable-pip-version-check -q -c constraints.txt

.PHONY: demo test lint bench docs wheel clean clean-cache

$(BIN)/python:
	$(PYTHON) -c 'import sys; assert sys.version_info[:2] == (3, 11), "gapath needs Python 3.11, found " + sys.version' 
	$(PYTHON) -m venv $(VENV)

$(VENV)/.installed: $(BIN)/python pyproject.toml constraints.txt
	$(PIP) -e .
	touch $@

$(VENV)/.docs-installed: $(VENV)/.installed
	$(PIP) -e '.[docs]'
	touch $@

# the suite builds the docs (tests/test_docs.py): dev includes the docs tools
$(VENV)/.dev-installed: $(VENV)/.installed
	$(PIP) -e '.[dev,docs]'
	touch $@ $(VENV)/.docs-installed

$(VENV)/.bench-installed: $(VENV)/.dev-installed
	$(PIP) -e '.[dev,bench]'
	touch $@

demo: $(VENV)/.installed
	$(BIN)/gapath demo

# lint (ruff), format check and types (mypy on the core modules, see pyproject.toml)
lint: $(VENV)/.dev-installed
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	$(BIN)/mypy

test: lint
	GAPATH_REQUIRE_DOCS=1 $(BIN)/python -m pytest

bench: $(VENV)/.bench-installed
	@for f in benchmarks/bench_*.py; do echo "== $$f"; $(BIN)/python $$f || exit 1; done

# Build the wheel and sdist, install the wheel into a clean venv (pinned
# dependencies) and run the demo from it, outside the source tree.
WHEEL_VENV := build/wheel-venv
wheel: $(VENV)/.dev-installed
	rm -rf dist $(WHEEL_VENV)
	$(BIN)/python -m build --outdir dist .
	$(PYTHON) -m venv $(WHEEL_VENV)
	$(WHEEL_VENV)/bin/python -m pip install --disable-pip-version-check -q -c constraints.txt dist/gapath-*.whl
	cd build && wheel-venv/bin/gapath demo --quiet --pop 40 --gen 5 --out wheel-demo
	test -s build/wheel-demo/front.csv && test -s build/wheel-demo/summary.json
	@echo "wheel ok: $$(ls dist)"

# the site, warnings as errors; open docs/_build/html/index.html
docs: $(VENV)/.docs-installed
	$(BIN)/python -m sphinx -W --keep-going -q -b html docs docs/_build/html

# numba's cache does not follow calls across modules: clear it after a branch switch or merge
clean-cache:
	find src -name '*.nbi' -delete -o -name '*.nbc' -delete

clean: clean-cache
	rm -rf $(VENV) gapath-demo .pytest_cache build dist docs/_build docs/api docs/notebooks
