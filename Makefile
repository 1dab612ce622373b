# Quickstart: `make report` then `make test`. Both bootstrap .venv on first use.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
TEST_STAMP := $(VENV)/.installed-test

.PHONY: report test check bench bench-build clean

# `make report` installs mechreport alone; `make test` adds the test tools (pytest, dask ...)
$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e .
	touch $(STAMP)

$(TEST_STAMP): $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(TEST_STAMP)

report: $(STAMP)
	$(BIN)/mechreport build specs -o out

test: $(TEST_STAMP)
	$(BIN)/lint-imports
	OPENBLAS_NUM_THREADS=1 $(BIN)/python -m pytest -n 2
	$(BIN)/mechreport check specs

check: $(STAMP)
	$(BIN)/mechreport check specs

bench: $(TEST_STAMP)
	$(BIN)/python bench/bench_methods.py
	$(BIN)/python bench/bench_build.py $(if $(AGAINST),--against $(AGAINST))

# `make bench-build AGAINST=bf87766`: this tree and that revision, measured in one run
bench-build: $(TEST_STAMP)
	$(BIN)/python bench/bench_build.py $(if $(AGAINST),--against $(AGAINST))

clean:
	rm -rf out/* $(VENV)
