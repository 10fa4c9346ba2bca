# paperlib: every command bootstraps .venv from pyproject.toml on first use.
#   make test        ruff, then pytest including the notebooks run through papermill (CI runs this)
#   make reproduce   every notebook at paper quality -> figures/ and figures/INDEX.md
#   make bench       speed measurements -> benchmarks/results.json
#   make strip       remove outputs from the notebook sources

PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
JOBS ?= 2

.PHONY: test lint reproduce reproduce-ci bench strip clean

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test,dask]"
	touch $(STAMP)

lint: $(STAMP)
	$(BIN)/ruff check paperlib tests benchmarks

test: lint
	$(BIN)/python -m pytest

reproduce: $(STAMP)
	$(BIN)/python -m paperlib reproduce --quality paper --jobs $(JOBS)

reproduce-ci: $(STAMP)
	$(BIN)/python -m paperlib reproduce --quality ci --jobs $(JOBS)

bench: $(STAMP)
	$(BIN)/python benchmarks/run.py

strip: $(STAMP)
	$(BIN)/jupyter nbconvert --clear-output --inplace notebooks/*.ipynb

clean:
	rm -rf build .pytest_cache
