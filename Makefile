# Quickstart: `make report` then `make test`. Both bootstrap .venv on first use.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: report test check bench bench-build clean

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

report: $(STAMP)
	$(BIN)/mechreport build specs -o out

test: $(STAMP)
	$(BIN)/lint-imports
	OPENBLAS_NUM_THREADS=1 $(BIN)/python -m pytest -n 2
	$(BIN)/mechreport check specs

check: $(STAMP)
	$(BIN)/mechreport check specs

bench: $(STAMP)
	$(BIN)/python bench/bench_methods.py

bench-build: $(STAMP)
	$(BIN)/python bench/bench_build.py

clean:
	rm -rf out/* $(VENV)
