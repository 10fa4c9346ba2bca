# paperlib: every command bootstraps .venv from pyproject.toml on first use.
#   make test        ruff, then pytest: the tests on $(JOBS) workers, then the notebooks through papermill (CI runs this)
#   make reproduce   every notebook at paper quality -> figures/ and figures/INDEX.md
#   make bench       speed measurements -> benchmarks/results.json
#   make fuzz        the full fuzz campaign (>= 10,000 Hypothesis inputs) -> build/fuzz/summary.md
#   make docs        the documentation site from the executed notebooks -> build/docs/html/index.html
#   make strip       remove outputs from the notebook sources

PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
JOBS ?= 2

.PHONY: test lint reproduce reproduce-ci bench fuzz docs strip clean

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test,dask,docs]"
	touch $(STAMP)

lint: $(STAMP)
	$(BIN)/ruff check paperlib tests benchmarks docs

# The tests that execute no notebook run on $(JOBS) workers (each test file on one worker: a file's
# fixtures, such as the documentation site, are built once); the notebook passes then run their
# notebooks $(JOBS) at a time. `pytest` alone runs everything in one process.
test: lint
	$(BIN)/python -m pytest -n $(JOBS) --dist loadfile -m "not notebooks"
	$(BIN)/python -m pytest -m notebooks

reproduce: $(STAMP)
	$(BIN)/python -m paperlib reproduce --quality paper --jobs $(JOBS)

reproduce-ci: $(STAMP)
	$(BIN)/python -m paperlib reproduce --quality ci --jobs $(JOBS)

bench: $(STAMP)
	$(BIN)/python benchmarks/run.py

# every public callable, 34 inputs each (>= 10,000 in all), 6 GiB and 20 s per case (tests/fuzz_harness.py)
fuzz: $(STAMP)
	$(BIN)/python tests/fuzz_harness.py --examples 34 --jobs $(JOBS) --out build/fuzz

# Executes nothing: pages show build/notebooks/ (left by `make reproduce`) or the sources' markdown, with the
# committed figures. -E rereads every page so that every warning is reported, and -W makes it an error.
docs: $(STAMP)
	$(BIN)/sphinx-build -E -W --keep-going -j $(JOBS) -b html docs build/docs/html
	@echo "open build/docs/html/index.html"

strip: $(STAMP)
	$(BIN)/jupyter nbconvert --clear-output --inplace notebooks/*.ipynb

clean:
	rm -rf build .pytest_cache
