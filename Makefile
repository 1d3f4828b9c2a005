# Two commands set everything up: `make demo` and `make test`.
# Both create (or reuse) .venv and install the package with the exact
# versions in constraints.txt; only Python 3.11, pip and make are needed.

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PIP    := $(BIN)/python -m pip install --disable-pip-version-check -q -c constraints.txt

.PHONY: demo test bench clean

$(BIN)/python:
	$(PYTHON) -c 'import sys; assert sys.version_info[:2] == (3, 11), "gapath needs Python 3.11, found " + sys.version' 
	$(PYTHON) -m venv $(VENV)

$(VENV)/.installed: $(BIN)/python pyproject.toml constraints.txt
	$(PIP) -e .
	touch $@

$(VENV)/.dev-installed: $(VENV)/.installed
	$(PIP) -e '.[dev]'
	touch $@

$(VENV)/.bench-installed: $(VENV)/.dev-installed
	$(PIP) -e '.[dev,bench]'
	touch $@

demo: $(VENV)/.installed
	$(BIN)/gapath demo

test: $(VENV)/.dev-installed
	$(BIN)/python -m pytest

bench: $(VENV)/.bench-installed
	@for f in benchmarks/bench_*.py; do echo "== $$f"; $(BIN)/python $$f || exit 1; done

clean:
	rm -rf $(VENV) gapath-demo .pytest_cache
